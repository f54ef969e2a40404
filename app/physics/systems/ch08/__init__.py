"""Chapter 8 systems: constrained generalized coordinates with multipliers, integrated as DAEs; Coulomb friction."""
