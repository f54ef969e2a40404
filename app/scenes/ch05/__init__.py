"""Chapter 5 scenes: the inertia explorer and angular momentum about a non-principal axis."""
