"""Chapter 5, inertial effects for a rigid body: composite bodies' mass properties, momentum and its rate of change.

One concept per module: :mod:`.composite_body` (the worked example
``inertia-of-composite-body``), :mod:`.angular_momentum` (a body spun about a
fixed axis that is not principal, and a particle system's momenta). The inertia
algebra itself lives in :mod:`app.physics.bodies.inertia`.
"""
