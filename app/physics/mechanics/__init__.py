"""Analytical mechanics as data: one system description, six formulations, generated code (chapters 7–9).

* :mod:`.description` — a system as data (coordinates, speeds, particles, bodies, springs, forces, reactions);
* :mod:`.kinematics` — velocities, accelerations and energies from it; :mod:`.algebra` — shared symbolic steps;
* one module per formulation — :mod:`.newton_euler`, :mod:`.lagrange` (sympy's ``LagrangesMethod``),
  :mod:`.hamilton`, :mod:`.routh`, :mod:`.gibbs_appell`, :mod:`.kane` — each returning a
  :class:`~.derivation.Derivation`: equations, steps, and a recipe for the state derivative;
* :mod:`.codegen` and :mod:`.engine` — recipes turned into Python source, cached on disk by fingerprint and
  compiled by numba for live scenes; :mod:`.linear` — the small solve the generated code calls;
* :mod:`.agreement` — the formulations compared numerically and symbolically;
* :mod:`.model` — an integrated model driven by a derivation; :mod:`.typed` — a Lagrangian a student types.
"""
