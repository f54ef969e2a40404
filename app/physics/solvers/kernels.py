"""Compiled kernels with a pure-Python twin.

Every hot loop in the integrators is written once, as plain Python over numpy
arrays, and compiled by numba with an explicit signature and ``cache=True``.
The uncompiled function is kept beside it: running the same source without
numba is how the tests check that the compiled path computes what it says
(results agree to the last bit or two), and it is the fallback a debugger can
step through.

Model functions (right-hand sides, projections, torques, events, reset maps,
constraints) are passed to
the integrator kernels as first-class function values of a fixed signature, so
each integrator is compiled once and cached, whatever the model.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numba
from numba import types

Backend = Literal["numba", "python"]

_vector = types.float64[::1]
_matrix = types.float64[:, ::1]

#: ``rhs(t, y, p, dydt_out)``: time derivative of the state ``y`` at time ``t`` (s).
RHS_SIGNATURE = types.void(types.float64, _vector, _vector, _vector)
#: ``project(y, p)``: move ``y`` back onto the model's constraint manifold in place.
PROJECT_SIGNATURE = types.void(_vector, _vector)
#: ``torque(q_world_body, p, torque_body_out)``: external torque (N·m, body frame).
TORQUE_SIGNATURE = types.void(_vector, _vector, _vector)
#: ``events(t, y, p, g_out)``: the values of all m event functions; event i happens where ``g_out[i]`` changes sign.
EVENTS_SIGNATURE = types.void(types.float64, _vector, _vector, _vector)
#: ``reset(t, y, p, index)``: change ``y`` in place at event ``index`` (an impact, a mode switch).
RESET_SIGNATURE = types.void(types.float64, _vector, _vector, types.int64)
#: ``constraint(y, p, g_out, G_out)``: residuals ``g(q)`` (m,) and Jacobian ``∂g/∂q`` (m, n_positions).
CONSTRAINT_SIGNATURE = types.void(_vector, _vector, _vector, _matrix)
#: ``dynamics(t, q, v, p, M_out, f_out)``: mass matrix (n, n) and generalized forces (n,) of a constrained system.
DYNAMICS_SIGNATURE = types.void(types.float64, _vector, _vector, _vector, _matrix, _vector)
#: ``constraints(q, v, p, g_out, C_out, c_out)``: holonomic residuals (m_h,), velocity rows ``C`` (m, n), ``c = −Ċ v``
#: (m,).
MULTIPLIER_CONSTRAINTS_SIGNATURE = types.void(_vector, _vector, _vector, _vector, _matrix, _vector)

RHS_TYPE = types.FunctionType(RHS_SIGNATURE)
PROJECT_TYPE = types.FunctionType(PROJECT_SIGNATURE)
TORQUE_TYPE = types.FunctionType(TORQUE_SIGNATURE)
EVENTS_TYPE = types.FunctionType(EVENTS_SIGNATURE)
RESET_TYPE = types.FunctionType(RESET_SIGNATURE)
CONSTRAINT_TYPE = types.FunctionType(CONSTRAINT_SIGNATURE)
DYNAMICS_TYPE = types.FunctionType(DYNAMICS_SIGNATURE)
MULTIPLIER_CONSTRAINTS_TYPE = types.FunctionType(MULTIPLIER_CONSTRAINTS_SIGNATURE)

VECTOR = _vector
MATRIX = _matrix
INDEX_VECTOR = types.int64[::1]

_MODEL_SIGNATURES = (
    RHS_SIGNATURE,
    PROJECT_SIGNATURE,
    TORQUE_SIGNATURE,
    EVENTS_SIGNATURE,
    RESET_SIGNATURE,
    CONSTRAINT_SIGNATURE,
    DYNAMICS_SIGNATURE,
    MULTIPLIER_CONSTRAINTS_SIGNATURE,
)


@dataclass(frozen=True)
class Kernel:
    """One function in two forms: numba-compiled and the plain Python source."""

    compiled: Any
    python: Callable[..., Any]

    @property
    def name(self) -> str:
        return self.python.__name__

    def get(self, backend: Backend) -> Callable[..., Any]:
        if backend == "numba":
            return self.compiled
        if backend == "python":
            return self.python
        raise ValueError(f"unknown backend {backend!r}; use 'numba' or 'python'")


def kernel(signature: Any) -> Callable[[Callable[..., Any]], Kernel]:
    """Decorator: compile ``fn`` for ``signature`` (cached on disk) and keep its source twin.

    Model functions (the ``*_SIGNATURE`` types above: right-hand sides,
    projections, torques, events, reset maps, constraints) become C callbacks (``numba.cfunc``): an
    integrator receives them as function pointers, which costs about 3× less
    per call from Python than passing a dispatcher. Everything else is an
    ordinary ``njit`` function.
    """
    model_function = signature in _MODEL_SIGNATURES

    def wrap(fn: Callable[..., Any]) -> Kernel:
        if model_function:
            compiled = numba.cfunc(  # type: ignore[call-arg]  # numba's stub omits cfunc's nopython option
                signature, cache=True, nopython=True, error_model="numpy"
            )(fn)
        else:
            compiled = numba.njit(signature, cache=True, nogil=True, error_model="numpy")(fn)
        return Kernel(compiled=compiled, python=fn)

    return wrap


@kernel(PROJECT_SIGNATURE)
def no_projection(y, p):  # pragma: no cover - trivial
    """The identity projection, for models without constraints."""
    return None


@kernel(EVENTS_SIGNATURE)
def no_events(t, y, p, g_out):  # pragma: no cover - trivial
    """No event functions (``g_out`` has length 0)."""
    return None


@kernel(RESET_SIGNATURE)
def no_reset(t, y, p, index):  # pragma: no cover - trivial
    """The identity reset map."""
    return None


@kernel(CONSTRAINT_SIGNATURE)
def no_constraint(y, p, g_out, G_out):  # pragma: no cover - trivial
    """No constraints (``g_out`` has length 0)."""
    return None
