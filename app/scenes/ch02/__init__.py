"""Chapter 2 scenes: a particle on a typed space curve."""
