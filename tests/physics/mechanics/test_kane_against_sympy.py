"""Our Kane's method against sympy.physics.mechanics' KanesMethod, built independently from the same positions.

Our Kane forms partial velocities from the description's position vectors; sympy's is given the same points
(their velocities taken by its own vector calculus in frame N) and gravity as loads. Their mass matrices and
forcing must be the same functions: compared at random states to 1e-12 relative.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy
from sympy.physics.mechanics import KanesMethod, Particle, Point, ReferenceFrame, dynamicsymbols

from app.physics.mechanics.description import TIME
from app.physics.mechanics.kane import derive_kane
from app.physics.systems import analytical_systems


def _sympy_kane(system):
    """(M, f) of sympy's KanesMethod with u = q̇, as functions of our plain symbols."""
    t = dynamicsymbols._t
    q = [dynamicsymbols(c.name) for c in system.coordinates]
    u = [dynamicsymbols(f"u_{c.name}") for c in system.coordinates]
    N = ReferenceFrame("N")
    origin = Point("O")
    origin.set_vel(N, 0)
    to_dynamic = {TIME: t, **{c.symbol: qi for c, qi in zip(system.coordinates, q)}}
    particles, loads = [], []
    for particle in system.particles:
        r = particle.position.xreplace(to_dynamic)
        point = origin.locatenew(particle.name, r[0] * N.x + r[1] * N.y + r[2] * N.z)
        velocity = point.pos_from(origin).dt(N).subs({qi.diff(t): ui for qi, ui in zip(q, u)})
        point.set_vel(N, velocity)
        particles.append(Particle(particle.name, point, particle.mass))
        g = system.gravity
        loads.append((point, particle.mass * (g[0] * N.x + g[1] * N.y + g[2] * N.z)))
    method = KanesMethod(N, q_ind=q, u_ind=u, kd_eqs=[qi.diff(t) - ui for qi, ui in zip(q, u)])
    method.kanes_equations(particles, loads)
    back = {t: TIME}
    for c, qi, ui in zip(system.coordinates, q, u):
        back[ui.diff(t)] = c.acceleration
        back[ui] = c.rate
        back[qi] = c.symbol
    return method.mass_matrix.xreplace(back), method.forcing.xreplace(back)


@pytest.mark.parametrize("system_id", ["simple-pendulum", "double-pendulum", "spherical-pendulum", "bead-on-rotating-hoop"])
def test_our_kane_equals_sympys_kanes_method(system_id):
    system = analytical_systems()[system_id]
    ours = derive_kane(system)
    M_sympy, f_sympy = _sympy_kane(system)
    arguments = [TIME, *system.q, *system.qd, *system.parameter_symbols]
    functions = [sympy.lambdify(arguments, e, "numpy") for e in (ours.mass_matrix, ours.forcing, M_sympy, f_sympy)]
    p = system.parameter_array(system.parameters.defaults())
    rng = np.random.default_rng(3)
    for _ in range(50):
        state = list(rng.uniform(0.3, 2.0, 2 * len(system.q)))
        M1, f1, M2, f2 = (np.array(fn(0.4, *state, *p), dtype=float) for fn in functions)
        assert M1 == pytest.approx(M2, rel=1e-12, abs=1e-12 * np.abs(M2).max())
        assert f1 == pytest.approx(f2, rel=1e-12, abs=1e-12 * max(np.abs(f2).max(), 1.0))
