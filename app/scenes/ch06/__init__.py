"""Chapter 6 scenes: the unbalanced rotor, a mechanism driven by a torque, the sliding ladder, collisions."""
