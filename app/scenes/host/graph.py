"""The graphs of a session's kept motion: every series, invariant and energy part against simulated time.

The host hands over the frames it kept for the scrubber (:class:`~.history.MotionHistory`);
they are stacked and the model evaluates its series, invariants and energy budget on
all of them at once (vectorised, after the frame, never inside the frame loop), then
the answer is thinned evenly to at most ``max_points`` frames, the latest always kept.
Non-finite numbers become None: nothing non-finite reaches a client.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from app.physics.core.energy import ENERGY_LABELS
from app.physics.solvers.integrated_model import IntegratedModel
from app.scenes.kit import Scene

#: Most and fewest points a graph answer may hold, and its default.
MAX_POINTS_RANGE = (10, 2000)
DEFAULT_MAX_POINTS = 600
#: The energy bars' order (a model gives either the two kinetic parts or ``kinetic_J``).
ENERGY_BAR_ORDER = ("translational_kinetic_J", "rotational_kinetic_J", "kinetic_J", "potential_J", "dissipated_J")
ENERGY_PREFIX = "energy_"

_GREEK = {
    "alpha": "α",
    "beta": "β",
    "gamma": "γ",
    "delta": "δ",
    "theta": "θ",
    "phi": "φ",
    "psi": "ψ",
    "omega": "ω",
    "mu": "μ",
    "lambda": "λ",
    "tau": "τ",
    "sigma": "σ",
    "kappa": "κ",
    "xi": "ξ",
    "rho": "ρ",
    "eta": "η",
    "epsilon": "ε",
    "zeta": "ζ",
}
_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
#: Unit words at the end of a name (``crank_speed_rad_s``), dropped from its label: the unit column says them.
_UNIT_WORDS = {"rad", "s", "s2", "m", "N", "J", "kg", "deg", "Hz", "W", "kg_m2", "m2"}


def check_graph_request(*, since_s: float, max_points: int) -> None:
    """Raise ValueError naming the field for a ``since_s`` that is NaN or +∞, or ``max_points`` out of range."""
    if isinstance(since_s, bool) or not isinstance(since_s, int | float) or math.isnan(since_s) or since_s == math.inf:
        raise ValueError(f"since_s: a simulated time in s (or none for the whole kept motion), got {since_s!r}")
    low, high = MAX_POINTS_RANGE
    if isinstance(max_points, bool) or not isinstance(max_points, int) or not low <= max_points <= high:
        raise ValueError(f"max_points: a whole number from {low} to {high}, got {max_points!r}")


def readable_label(name: str) -> str:
    """A name as a student reads it: unit words dropped, Greek letters and subscripts written (``theta1_rad``
    → ``θ₁``)."""
    words = name.split("_")
    while len(words) > 1 and (words[-1] in _UNIT_WORDS or "_".join(words[-2:]) in _UNIT_WORDS):
        words.pop()
    out = []
    for word in words:
        match = re.fullmatch(r"([a-z]+)(\d*)", word)
        if match and match.group(1) in _GREEK:
            word = _GREEK[match.group(1)] + match.group(2).translate(_SUBSCRIPT)
        out.append(word)
    return " ".join(out)


def decimated(count: int, max_points: int) -> np.ndarray:
    """Indices of at most ``max_points`` of ``count`` frames, evenly spread, the first and the last always in."""
    if count <= max_points:
        return np.arange(count)
    return np.unique(np.round(np.linspace(0.0, count - 1, max_points)).astype(int))


def _finite_list(values: np.ndarray) -> list[float | None]:
    values = np.asarray(values, dtype=float)
    return [float(v) if math.isfinite(v) else None for v in values.tolist()]


def _finite(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def empty_graph(scene_id: str, note: str) -> dict[str, Any]:
    """A graph with nothing in it, and why."""
    return {
        "scene_id": scene_id,
        "t_s": [],
        "quantities": [],
        "values": {},
        "energy": None,
        "span_s": None,
        "note": note,
    }


def no_graph_note(scene_cls: type[Scene]) -> str | None:
    """Why a scene of this class has no graph (None: it has one)."""
    if not scene_cls.animated:
        return (
            "this scene does not move in time: there is nothing to graph against time (its numbers are in the readout)"
        )
    model = scene_cls.model
    if model is None or not model.integrated:
        return (
            "this scene's motion is a closed form in time, not integrated: "
            "its graph is not kept (its numbers are in the readout)"
        )
    return None


def motion_graph(
    scene_id: str,
    model: IntegratedModel,
    params: Mapping[str, Any],
    frames: Sequence[tuple[float, Mapping[str, Any]]],
    latest: tuple[float, Mapping[str, Any]] | None,
    *,
    max_points: int,
) -> dict[str, Any]:
    """The graph answer for ``frames`` (``(t_s, motion)`` with ``motion["y"]`` the state) of an integrated model.

    Series, invariants and the energy budget are evaluated on every frame, then
    thinned to ``max_points``; the energy bars are the ``latest`` kept frame's
    (``frames[-1]``, or the last kept before them when ``frames`` is empty).
    """
    quantities: list[dict[str, str]] = []
    values: dict[str, list[float | None]] = {}
    t_s = np.array([t for t, _ in frames], dtype=float)
    budget: Mapping[str, np.ndarray] | None = None
    with np.errstate(all="ignore"):
        if frames:
            states = np.array([np.asarray(motion["y"], dtype=float) for _, motion in frames])
            keep = decimated(len(frames), max_points)
            labels = model.series_labels
            groups = (
                ("series", model.series(params, t_s, states), model.series_units),
                ("invariant", model.invariants(params, states), model.invariant_units),
            )
            for kind, named, units in groups:
                for name, series in named.items():
                    quantities.append(
                        {
                            "name": name,
                            "label": labels.get(name) or readable_label(name),
                            "unit": units.get(name, ""),
                            "kind": kind,
                        }
                    )
                    values[name] = _finite_list(np.broadcast_to(np.asarray(series, dtype=float), t_s.shape)[keep])
            budget = model.energy_budget(params, states, t_s=t_s)
            for key, series in (budget or {}).items():
                name = ENERGY_PREFIX + key
                quantities.append(
                    {"name": name, "label": ENERGY_LABELS.get(key, readable_label(key)), "unit": "J", "kind": "energy"}
                )
                values[name] = _finite_list(np.asarray(series)[keep])
            t_s = t_s[keep]
        if not frames and latest is not None:  # nothing new: the bars still show the last kept frame
            latest_t_s, latest_motion = latest
            budget = model.energy_budget(
                params, np.asarray(latest_motion["y"], dtype=float)[None, :], t_s=np.array([latest_t_s])
            )
        energy = None if budget is None else _energy_bars(model, params, budget)
    span = [float(t_s[0]), float(t_s[-1])] if len(t_s) else None
    return {
        "scene_id": scene_id,
        "t_s": t_s.tolist(),
        "quantities": quantities,
        "values": values,
        "energy": energy,
        "span_s": span,
        "note": None,
    }


def _energy_bars(model: IntegratedModel, params: Mapping[str, Any], budget: Mapping[str, np.ndarray]) -> dict[str, Any]:
    """The energy bars at the budget's last frame: parts in :data:`ENERGY_BAR_ORDER`, the total and the model's note."""
    parts = [
        {"name": ENERGY_PREFIX + key, "label": ENERGY_LABELS[key], "value_J": _finite(float(budget[key][-1]))}
        for key in ENERGY_BAR_ORDER
        if key in budget
    ]
    return {"parts": parts, "total_J": _finite(float(budget["total_J"][-1])), "note": model.energy_note(params)}


#: How a unit is spelled at the end of a name (``kg·m²/s`` → ``kg_m2_s``, as in ``p_theta_kg_m2_s``).
_UNIT_SPELLING = str.maketrans({"·": "_", "/": "_", " ": "_", "*": "_", "²": "2", "³": "3", "°": "deg"})


def name_carries_unit(name: str, unit: str) -> bool:
    """Whether ``name`` ends with ``unit`` spelled as names spell it (``energy_total_J`` and J, ``spin_rate_rad_s``
    and rad/s, ``driving_torque_N_m`` and N·m); never for no unit."""
    spelled = unit.translate(_UNIT_SPELLING)
    return bool(spelled) and (name == spelled or name.endswith("_" + spelled))


def csv_column(name: str, unit: str) -> str:
    """A CSV column's heading: the name with its unit once: ``theta (rad)``, but ``energy_total_J`` as it is (its
    name already says J; ``energy_total_J (J)`` wrote the unit twice), and a unitless name alone."""
    return f"{name} ({unit})" if unit and not name_carries_unit(name, unit) else name


def graph_csv(answer: Mapping[str, Any]) -> str:
    """A graph answer as CSV: header ``t_s`` then each quantity's :func:`csv_column`, one row per time; empty cells
    for missing values."""
    names = [q["name"] for q in answer["quantities"]]
    header = ["t_s"] + [csv_column(q["name"], q["unit"]) for q in answer["quantities"]]
    lines = [",".join(header)]
    for i, t in enumerate(answer["t_s"]):
        cells = [repr(float(t))] + [
            "" if (v := answer["values"][name][i]) is None else repr(float(v)) for name in names
        ]
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"
