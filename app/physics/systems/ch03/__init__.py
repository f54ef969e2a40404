"""Chapter 3, relative motion: the moving-frame acceleration, the Foucault pendulum, eastward deflection."""
