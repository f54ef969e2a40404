"""Analytical mechanics as data: derivations over sympy.physics.mechanics (the home of chapters 7-9)."""
