"""Path variables of a particle moving on a space curve r(t): the Frenet frame.

Frame: the fixed Cartesian frame XYZ (+Z up); positions in m, time t in s. The
curve is typed as three formulas x(t), y(t), z(t) (see
:mod:`app.physics.math.expressions`), differentiated symbolically three times and
compiled once with ``sympy.lambdify``. At each instant:

* speed ``v = |r'|`` (m/s) and unit tangent ``T = r'/|r'|``;
* curvature ``κ = |r' × r''| / |r'|³`` (1/m), binormal ``B = (r' × r'')/|r' × r''|``,
  principal normal ``N = B × T``;
* torsion ``τ = (r' × r'')·r''' / |r' × r''|²`` (1/m);
* tangential and normal acceleration ``a_t = dv/dt = r'·r''/|r'|`` and
  ``a_n = |r' × r''|/|r'| = κ v²`` (m/s²), so ``r'' = a_t T + a_n N``;
* arc length ``s(t) = ∫₀ᵗ |r'| dt`` (m) by composite Gauss–Legendre quadrature.

Degenerate instants are reported, not drawn as garbage: where the speed is
zero the tangent (and everything after it) is undefined; where the curvature
is zero (the path is locally straight) the normal, binormal and torsion are
undefined. "Zero" means below a small fraction of the path's own scale
(:class:`ReferenceScales`), because a formula evaluated in floating point
leaves rounding noise of about 1e-16 of its size where the exact value is 0.
Undefined values are NaN.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
import sympy

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.curvilinear import curvilinear_series
from app.physics.math.expressions import MAX_LENGTH, check_expression, parse_expression
from app.physics.math.expressions import T as T_SYMBOL

#: Speeds below this fraction of the path's reference speed count as zero.
SPEED_TOLERANCE = 1e-9
#: Normal accelerations below this fraction of the path's reference acceleration count as zero.
CURVATURE_TOLERANCE = 1e-9
#: Largest expression tree (nodes) allowed for r', r'' and r''' in turn: each
#: order can multiply the size, and sympy's time to differentiate grows faster
#: than the size. These limits keep the slowest formulas we found compiling in
#: well under a second.
MAX_DERIVATIVE_NODES = (300, 600, 3000)
#: Largest component of r, r', r'' or r''' (m, m/s, m/s², m/s³) a curve may reach over the span it is
#: drawn on. The viewer draws in float32 (largest 3.4e38), and the path variables raise these to at most
#: the fourth power in float64 (|v|³ in κ, |v × a|² in τ: ≤ 1e122 ≪ 1.8e308), so nothing derived from a
#: curve under this bound overflows; ``exp(50*t)`` or ``t^100`` over a long span are refused instead.
MAX_CURVE_MAGNITUDE = 1e30
#: Times evaluated per call of the compiled formulas: each of sympy's common subexpressions becomes an
#: array of this length, so a formula's peak memory is bounded whatever the number of frames.
EVALUATION_CHUNK = 4096
#: Gauss–Legendre points per panel for the arc length, and the longest panel (s).
_ARC_NODES, _ARC_WEIGHTS = np.polynomial.legendre.leggauss(8)
ARC_PANEL_S = 0.05

COMPONENTS = ("x_of_t", "y_of_t", "z_of_t")


class CurveError(ValueError):
    """A curve formula is refused; ``component`` names which of x(t), y(t), z(t)."""

    def __init__(self, component: str, message: str) -> None:
        super().__init__(message)
        self.component = component


def _node_count(expr: sympy.Expr) -> int:
    return sum(1 for _ in sympy.preorder_traversal(expr))


@dataclass(frozen=True, eq=False)
class SpaceCurve:
    """A compiled parametric curve r(t) (m) on XYZ and its first three time derivatives.

    ``derivatives[k][i]`` is the sympy expression of d^k r_i/dt^k (k = 0..3,
    i = x, y, z). Build with :func:`compile_curve`.
    """

    texts: tuple[str, str, str]
    derivatives: tuple[tuple[sympy.Expr, sympy.Expr, sympy.Expr], ...]
    _evaluate: Callable[[np.ndarray], list]

    def jets(self, t_s: np.ndarray | float) -> np.ndarray:
        """r, r', r'', r''' at times ``t_s`` (s): shape (4, N, 3) in m, m/s, m/s², m/s³.

        Instants where a formula is undefined (sqrt of a negative number, log of
        zero, overflow) are NaN.
        """
        t = np.atleast_1d(np.asarray(t_s, dtype=float)).ravel()
        out = np.empty((4, t.size, 3))
        for start in range(0, t.size, EVALUATION_CHUNK):
            chunk = t[start : start + EVALUATION_CHUNK]
            with np.errstate(all="ignore"):
                values = self._evaluate(chunk)
                for column, value in enumerate(values):  # order k = column // 3, axis = column % 3
                    out[column // 3, start : start + chunk.size, column % 3] = np.broadcast_to(
                        np.asarray(value, dtype=float), chunk.shape
                    )
        out[~np.isfinite(out)] = np.nan
        return out

    def position(self, t_s: np.ndarray | float) -> np.ndarray:
        """Position (m) on XYZ, shape (N, 3)."""
        return self.jets(t_s)[0]


@lru_cache(maxsize=128)
def compile_curve(x_text: str, y_text: str, z_text: str) -> SpaceCurve:
    """Parse, differentiate (three times) and compile a curve typed as x(t), y(t), z(t) in m.

    Raises :class:`CurveError` naming the component that is refused.
    """
    texts = (x_text, y_text, z_text)
    orders: list[list[sympy.Expr]] = [[], [], [], []]
    for component, text in zip(COMPONENTS, texts):
        try:
            expr = parse_expression(text)
        except ValueError as exc:
            raise CurveError(component, str(exc)) from None
        orders[0].append(expr)
        for k in (1, 2, 3):
            expr = sympy.diff(expr, T_SYMBOL)
            if expr.has(sympy.zoo, sympy.nan, sympy.oo, sympy.I):
                raise CurveError(component, f"its derivative of order {k} is not a finite real function")
            limit = MAX_DERIVATIVE_NODES[k - 1]
            if _node_count(expr) > limit:
                raise CurveError(
                    component,
                    f"its derivative of order {k} is too long (more than {limit} terms and factors) "
                    "to evaluate quickly; please type a simpler formula",
                )
            orders[k].append(expr)
    flat = [expr for order in orders for expr in order]
    evaluate = sympy.lambdify(T_SYMBOL, flat, modules="numpy", cse=True)
    return SpaceCurve(texts, tuple(tuple(order) for order in orders), evaluate)


def check_curve_span(curve: SpaceCurve, t_s: np.ndarray) -> None:
    """Raise :class:`CurveError` if a component of r or a derivative exceeds :data:`MAX_CURVE_MAGNITUDE` at any of
    ``t_s`` (s).

    The error names the component and the first time it happens. Instants where a
    formula has no value (a pole, the root of a negative number) are not refused:
    they are reported as undefined where the curve is drawn.
    """
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    jets = curve.jets(t)  # (4, N, 3); NaN where undefined
    with np.errstate(invalid="ignore"):
        over = np.abs(jets) > MAX_CURVE_MAGNITUDE  # NaN compares False
    times = np.flatnonzero(over.any(axis=(0, 2)))
    if times.size == 0:
        return
    index = int(times[0])
    order, axis = (int(k[0]) for k in np.nonzero(over[:, index, :]))  # lowest derivative order first
    value = float(jets[order, index, axis])
    what = "xyz"[axis] + ("(t)", "′(t)", "″(t)", "‴(t)")[order]
    raise CurveError(
        COMPONENTS[axis],
        f"{what} reaches {value:.3g} at t = {t[index]:.4g} s, beyond the bound of {MAX_CURVE_MAGNITUDE:g} (SI units) "
        f"within the span 0 to {t[-1]:.4g} s it is drawn over: shorten the span or type a formula that grows "
        "more slowly",
    )


@dataclass(frozen=True)
class ReferenceScales:
    """Sizes of the motion over the span of interest, for deciding what counts as zero.

    ``length_m``: largest distance from the origin; ``speed_m_s`` and
    ``acceleration_m2``: largest speed and acceleration magnitude (each at
    least a tiny positive floor built from the others so a straight, uniform
    path still has a scale).
    """

    length_m: float
    speed_m_s: float
    acceleration_m_s2: float


def reference_scales(curve: SpaceCurve, t_end_s: float, *, samples: int = 1001) -> ReferenceScales:
    """Scales of ``curve`` sampled on [0, t_end_s] (s), ignoring undefined instants."""
    t = np.linspace(0.0, t_end_s, samples)
    r, v, a, _ = curve.jets(t)
    length = float(np.nanmax(np.linalg.norm(r, axis=1), initial=0.0))
    speed = float(np.nanmax(np.linalg.norm(v, axis=1), initial=0.0))
    accel = float(np.nanmax(np.linalg.norm(a, axis=1), initial=0.0))
    tiny = 1e-300
    speed = max(speed, length / max(t_end_s, tiny), tiny)
    accel = max(accel, speed**2 / max(length, tiny), tiny)
    return ReferenceScales(max(length, tiny), speed, accel)


@dataclass(frozen=True)
class PathVariables:
    """Path variables at N instants. Vectors are (N, 3) on XYZ; NaN where undefined.

    ``defined``: r and its derivatives are finite; ``moving``: the speed is not
    zero (tangent, a_t, a_n, κ defined); ``curving``: also the curvature is not
    zero (normal, binormal, torsion defined).
    """

    t_s: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    acceleration_m_s2: np.ndarray
    jerk_m_s3: np.ndarray
    speed_m_s: np.ndarray
    tangent: np.ndarray
    normal: np.ndarray
    binormal: np.ndarray
    curvature_1_m: np.ndarray
    torsion_1_m: np.ndarray
    a_tangential_m_s2: np.ndarray
    a_normal_m_s2: np.ndarray
    defined: np.ndarray
    moving: np.ndarray
    curving: np.ndarray


def path_variables(curve: SpaceCurve, t_s: np.ndarray | float, scales: ReferenceScales) -> PathVariables:
    """Speed, Frenet frame, curvature, torsion and the a_t/a_n split at times ``t_s`` (s)."""
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    r, v, a, j = curve.jets(t)
    defined = np.all(np.isfinite(np.concatenate([r, v, a, j], axis=1)), axis=1)
    with np.errstate(all="ignore"):
        speed = np.linalg.norm(v, axis=1)
        moving = defined & (speed > SPEED_TOLERANCE * scales.speed_m_s)
        v_cross_a = np.cross(v, a)
        cross_norm = np.linalg.norm(v_cross_a, axis=1)
        a_normal = np.where(moving, cross_norm / speed, np.nan)
        a_tangential = np.where(moving, np.einsum("ij,ij->i", v, a) / speed, np.nan)
        curving = moving & (a_normal > CURVATURE_TOLERANCE * scales.acceleration_m_s2)
        curvature = np.where(moving, cross_norm / speed**3, np.nan)
        tangent = np.where(moving[:, None], v / speed[:, None], np.nan)
        binormal = np.where(curving[:, None], v_cross_a / cross_norm[:, None], np.nan)
        normal = np.cross(binormal, tangent)
        torsion = np.where(curving, np.einsum("ij,ij->i", v_cross_a, j) / cross_norm**2, np.nan)
    speed = np.where(defined, speed, np.nan)
    return PathVariables(
        t_s=t,
        position_m=r,
        velocity_m_s=v,
        acceleration_m_s2=a,
        jerk_m_s3=j,
        speed_m_s=speed,
        tangent=tangent,
        normal=normal,
        binormal=binormal,
        curvature_1_m=curvature,
        torsion_1_m=torsion,
        a_tangential_m_s2=a_tangential,
        a_normal_m_s2=a_normal,
        defined=defined,
        moving=moving,
        curving=curving,
    )


def arc_length(curve: SpaceCurve, t_s: np.ndarray) -> np.ndarray:
    """Arc length s(t) = ∫₀ᵗ |r'| dt (m) at increasing times ``t_s`` (s, t ≥ 0).

    Composite 8-point Gauss–Legendre on panels of at most ``ARC_PANEL_S``
    between consecutive requested times (exact for polynomial speeds of degree
    ≤ 15 per panel); NaN from the first instant where the speed is undefined.
    """
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    if t.size and (t[0] < 0.0 or np.any(np.diff(t) < 0.0)):
        raise ValueError("arc_length needs increasing times t ≥ 0 s")
    starts = np.concatenate([[0.0], t[:-1]])
    widths = t - starts
    panels = np.maximum(1, np.ceil(widths / ARC_PANEL_S)).astype(int)
    interval = np.repeat(np.arange(t.size), panels)
    within = np.arange(interval.size) - np.repeat(np.cumsum(panels) - panels, panels)
    half = 0.5 * widths[interval] / panels[interval]
    left = starts[interval] + 2.0 * half * within
    nodes = (left[:, None] + half[:, None] * (1.0 + _ARC_NODES[None, :])).ravel()
    speed = np.concatenate(  # in chunks: the jets of every node at once would be 12 floats per node
        [
            np.linalg.norm(curve.jets(nodes[i : i + EVALUATION_CHUNK])[1], axis=1)
            for i in range(0, nodes.size, EVALUATION_CHUNK)
        ]
    ).reshape(interval.size, -1)
    pieces = np.bincount(interval, weights=half * (speed @ _ARC_WEIGHTS), minlength=t.size)
    return np.cumsum(pieces)


def undefined_reason(variables: PathVariables, index: int = 0) -> str:
    """A sentence saying what is undefined at instant ``index`` and why ('' if nothing is)."""
    t = float(variables.t_s[index])
    if not variables.defined[index]:
        return (
            f"At t = {t:.3g} s the curve's formula (or one of its derivatives) has no finite value, "
            "e.g. the square root of a negative number, log of zero or an overflow: nothing is drawn there."
        )
    if not variables.moving[index]:
        return (
            f"At t = {t:.3g} s the particle is momentarily at rest (speed 0): the tangent, and with it the "
            "whole Frenet frame, is undefined there."
        )
    if not variables.curving[index]:
        return (
            f"At t = {t:.3g} s the curvature is zero (the path is locally straight): the normal and binormal "
            "directions and the torsion are undefined there, and the acceleration is purely tangential."
        )
    return ""


# -- the typed curve as a model: inputs and the simulate report ---------------------------


def _check_curve(values: Mapping[str, Any]) -> None:
    """ParameterSet check: the three formulas must differentiate and compile together."""
    try:
        compile_curve(*(values[name] for name in COMPONENTS))
    except CurveError as exc:
        raise ParameterError(exc.component, str(exc)) from None


def curve_parameters() -> tuple[Parameter, ...]:
    """The three typed components x(t), y(t), z(t) (m, t in s)."""
    return tuple(
        Parameter(
            name,
            "m",
            default,
            kind="text",
            label=f"{axis}(t)",
            description=f"{axis} coordinate of the particle (m) as a formula in t (s): "
            "t, numbers, + - * / ^, ( ), sqrt sin cos tan exp log, pi",
            max_length=MAX_LENGTH,
            parse=check_expression,
        )
        for name, axis, default in zip(COMPONENTS, "xyz", DEFAULT_CURVE)
    )


#: A helix of radius 1 m rising 0.2 m per radian: the default curve.
DEFAULT_CURVE = ("cos(t)", "sin(t)", "0.2*t")
INPUTS = ParameterSet(curve_parameters(), check=_check_curve)

#: Events reported per kind of undefined instant (the first frame of each run).
MAX_EVENTS_PER_KIND = 10


class ParticleOnCurve(ClosedFormModel):
    """A particle whose position is the typed curve r(t): path, cylindrical and spherical variables."""

    parameters = INPUTS
    series_units = {
        "x": "m",
        "y": "m",
        "z": "m",
        "speed": "m/s",
        "arc_length": "m",
        "curvature": "1/m",
        "torsion": "1/m",
        "a_tangential": "m/s^2",
        "a_normal": "m/s^2",
        "R": "m",
        "theta": "rad",
        "v_R": "m/s",
        "v_theta": "m/s",
        "v_z": "m/s",
        "a_R": "m/s^2",
        "a_theta": "m/s^2",
        "a_z": "m/s^2",
        "r": "m",
        "phi": "rad",
        "v_r": "m/s",
        "v_phi": "m/s",
        "a_r": "m/s^2",
        "a_phi": "m/s^2",
    }
    description = (
        "the typed curve differentiated symbolically (sympy) and evaluated at each frame; "
        "arc length by composite 8-point Gauss–Legendre quadrature"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        curve = compile_curve(*(params[name] for name in COMPONENTS))
        try:
            check_curve_span(curve, t_s)
        except CurveError as exc:
            raise ParameterError(exc.component, str(exc)) from None
        scales = reference_scales(curve, float(t_s[-1]) if t_s[-1] > 0 else 1.0)
        path = path_variables(curve, t_s, scales)
        series = {
            "x": path.position_m[:, 0],
            "y": path.position_m[:, 1],
            "z": path.position_m[:, 2],
            "speed": path.speed_m_s,
            "arc_length": arc_length(curve, t_s),
            "curvature": path.curvature_1_m,
            "torsion": path.torsion_1_m,
            "a_tangential": path.a_tangential_m_s2,
            "a_normal": path.a_normal_m_s2,
            **curvilinear_series(
                path.position_m, path.velocity_m_s, path.acceleration_m_s2, length_scale_m=scales.length_m
            ),
        }
        return ClosedFormSolution(series=series, events=_degenerate_events(path))


def _degenerate_events(path: PathVariables) -> list[Event]:
    """The first frame of each run of frames where something is undefined, by kind."""
    kinds = (
        ("undefined", ~path.defined),
        ("at-rest", path.defined & ~path.moving),
        ("straight", path.moving & ~path.curving),
    )
    events: list[Event] = []
    for kind, mask in kinds:
        starts = np.flatnonzero(mask & ~np.concatenate([[False], mask[:-1]]))
        for index in starts[:MAX_EVENTS_PER_KIND]:
            events.append(Event(float(path.t_s[index]), kind, undefined_reason(path, int(index))))
    return sorted(events, key=lambda event: event.t_s)
