"""Chapter 10, gyroscopic effects: free bodies and their references, the heavy top, gyroscopes, the equinoxes."""
