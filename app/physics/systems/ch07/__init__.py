"""Chapter 7 systems: virtual work, generalized coordinates and forces, Lagrange's equations."""
