"""Chapter 3 scenes: rotation sequences, the moving-frame acceleration, the Foucault pendulum, eastward deflection."""
