"""Chapter 9 scenes: alternative formulations."""
