"""Chapter 7 scenes: analytical mechanics."""
