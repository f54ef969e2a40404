"""Chapter 2, particle kinematics: a particle on a typed space curve."""
