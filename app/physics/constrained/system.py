"""A mechanical system in constrained generalized coordinates, as the DAE algorithms see it.

Coordinates ``q`` (n,) and their rates ``v = q̇`` (n,). The equations of motion
with Lagrange multipliers ``λ`` (m,) are

    M(q) v̇ = f(t, q, v) + Cᵀ(q) λ,

subject to ``m = m_h + m_n`` constraints, all scleronomic (no explicit time):

* ``m_h`` holonomic ``g(q) = 0``, whose velocity form is ``G(q) v = 0`` with ``G = ∂g/∂q``;
* ``m_n`` nonholonomic ``A(q) v = 0`` (rolling without slip).

``C = [G; A]`` (m, n) stacks the velocity-level rows, holonomic first. Differentiated
once more they read ``C v̇ = c`` with ``c = −Ċ v``: that is what the index-reduced
equations impose. ``λ`` is then the generalized constraint force per unit of each
constraint's residual (N for a residual in m, N·m for one in rad).

Two kernels describe a system (numba C callbacks with a pure-Python twin, see
:mod:`app.physics.solvers.kernels`):

* ``dynamics(t, q, v, p, M_out, f_out)``: mass matrix ``M`` (n, n) and generalized
  forces ``f`` (n,) — applied, gravity and velocity (Coriolis) terms, everything but
  the constraint forces;
* ``constraints(q, v, p, g_out, C_out, c_out)``: the holonomic residuals ``g`` (m_h,),
  the stacked velocity rows ``C`` (m, n) and ``c = −Ċ v`` (m,).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.physics.solvers.kernels import Kernel


@dataclass(frozen=True)
class ConstrainedSystem:
    """``M v̇ = f + Cᵀ λ`` with ``g(q) = 0`` (m_h rows) and ``A v = 0`` (m_n rows); see the module docstring.

    ``parameters`` is the flat float array ``p`` handed to both kernels.
    ``independent`` names the coordinates coordinate partitioning integrates
    (n − m of them); ``None`` lets the algorithm choose them from ``C`` by pivoting.
    """

    dynamics: Kernel
    constraints: Kernel
    parameters: np.ndarray
    coordinate_names: tuple[str, ...]
    n_holonomic: int
    n_nonholonomic: int = 0
    independent: tuple[int, ...] | None = None

    def __post_init__(self) -> None:
        n = len(self.coordinate_names)
        if n < 1:
            raise ValueError("a constrained system needs at least one coordinate")
        if self.n_holonomic < 0 or self.n_nonholonomic < 0 or self.n_constraints < 1:
            raise ValueError(
                f"constraint counts must be ≥ 0 with at least one constraint (got {self.n_holonomic}, "
                f"{self.n_nonholonomic})"
            )
        if self.n_constraints >= n:
            raise ValueError(f"{self.n_constraints} constraints on {n} coordinates leave no freedom to move")
        if self.independent is not None:
            if len(self.independent) != n - self.n_constraints or len(set(self.independent)) != len(self.independent):
                raise ValueError(
                    f"independent must name {n - self.n_constraints} distinct coordinates (got {self.independent})"
                )
            if any(not 0 <= i < n for i in self.independent):
                raise ValueError(f"independent coordinates must be indices in [0, {n}) (got {self.independent})")

    @property
    def n_coordinates(self) -> int:
        return len(self.coordinate_names)

    @property
    def n_constraints(self) -> int:
        return self.n_holonomic + self.n_nonholonomic

    @property
    def degrees_of_freedom(self) -> int:
        """Independent velocities: n − m."""
        return self.n_coordinates - self.n_constraints

    def mass_and_forces(self, t: float, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``M`` (n, n) and ``f`` (n,) at one state, with the pure-Python kernel."""
        n = self.n_coordinates
        mass, forces = np.empty((n, n)), np.empty(n)
        self.dynamics.python(float(t), _vector(q), _vector(v), self.parameters, mass, forces)
        return mass, forces

    def constraint_terms(self, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``g`` (m_h,), ``C`` (m, n) and ``c = −Ċ v`` (m,) at one state, with the pure-Python kernel."""
        g = np.empty(self.n_holonomic)
        jacobian = np.empty((self.n_constraints, self.n_coordinates))
        convective = np.empty(self.n_constraints)
        self.constraints.python(_vector(q), _vector(v), self.parameters, g, jacobian, convective)
        return g, jacobian, convective


def _vector(x: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(x, dtype=float)
