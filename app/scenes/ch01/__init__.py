"""Chapter 1 scenes: the robotic arm and cable, radar tracking, a projectile with drag."""
