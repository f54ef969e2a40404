"""Rigid bodies as data: principal inertia checks and the body about a fixed point (chapter 5 adds inertia tensors)."""
