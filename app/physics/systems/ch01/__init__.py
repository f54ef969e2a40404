"""Chapter 1, basic considerations: the robotic arm and cable, radar tracking, a projectile with drag."""
