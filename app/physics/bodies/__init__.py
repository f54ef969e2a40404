"""Rigid bodies as data: inertia (the one home for tensors and principal axes), composite bodies, the body about a fixed
point."""
