"""Chapter 10 scenes: free bodies, the heavy top, gyroscopes, the precession of the equinoxes."""
