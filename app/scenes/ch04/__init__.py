"""Chapter 4 scenes: the four-bar, the slider-crank, the cardan joint, rolling without slip."""
