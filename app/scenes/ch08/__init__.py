"""Chapter 8 scenes: constrained generalized coordinates, DAE algorithms, Coulomb friction."""
