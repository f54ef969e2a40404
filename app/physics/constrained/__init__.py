"""Constrained generalized coordinates (chapter 8): equations with multipliers and the algorithms that integrate them.

A :class:`~.system.ConstrainedSystem` states ``M(q) q̈ = f(t, q, q̇) + Cᵀ λ`` with
holonomic constraints ``g(q) = 0`` and nonholonomic ``A(q) q̇ = 0``; the
algorithm modules turn it into something an integrator can advance
(uncorrected index reduction, Baumgarte stabilisation, coordinate projection,
coordinate partitioning) and find consistent initial conditions.
"""
