"""Chapter 6, Newton–Euler equations: bearing reactions of an unbalanced rotor, a mechanism's kinetics, the sliding
ladder and impacts.

One concept per module: :mod:`.unbalanced_rotor`, :mod:`.mechanism_kinetics`,
:mod:`.sliding_ladder`, :mod:`.impact` (the impulse law) with
:mod:`.planar_collision` and :mod:`.bouncing_bar`.
"""
