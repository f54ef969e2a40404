"""Chapter 4, constrained rigid bodies: linkages solved by loop closure (no integration anywhere) and rolling.

One concept per module: :mod:`.planar_loop` (the 2×2 linear solves and
continuous angles every planar loop needs), :mod:`.crank_drive` (the input
crank's angle in time), :mod:`.four_bar`, :mod:`.slider_crank` and
:mod:`.cardan_joint`; :mod:`.rolling` for a disk or cone rolling without slip. Positions come from closed-form loop
closure; velocities
and accelerations from the once- and twice-differentiated loop equations,
which are linear in the unknown rates.
"""
