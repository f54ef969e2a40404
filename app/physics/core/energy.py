"""A model's energy budget along its motion: kinetic (translational and rotational), potential, total, dissipated.

A model states its energies as :class:`EnergyParts` along states (N, n);
:func:`energy_budget` turns them, with the same parts at t = 0, into the named
arrays the graphs show. Translational kinetic energy is ½ m v_G² summed over
the bodies, rotational ½ ω·I_G ω (König's split); where a model cannot split
its kinetic energy (a student-typed T) it gives ``kinetic_J`` alone.
``dissipated_J`` is E(0) + W(t) − E(t), W the work the drives have done since
t = 0 where the state tracks it: the energy friction, impacts and damping
removed, and for a conservative model the integration's drift (reported, not
zeroed). A dissipation within round-off of zero (:data:`DISSIPATION_ROUND_OFF`
of the motion's energy scale) is 0: a geometric integrator keeps a heavy top's
energy to 1e-10 of it or better, and that showed as "dissipated −1.1e-11 J", a
loss that never happened.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["DISSIPATION_ROUND_OFF", "ENERGY_LABELS", "EnergyParts", "energy_budget", "energy_scale_J"]

#: A dissipation whose magnitude is at most this fraction of the motion's energy scale (:func:`energy_scale_J`) is
#: shown as 0: round-off, or the bounded energy error of a geometric integrator, never a loss. Measured on the heavy
#: top (18 J): −1.65e-9 J (9e-11 of it) 3 s into a live run (the fixed step rule, before the step choice's pilot
#: answered) and at most 5.7e-12 of it over a minute of its chosen splitting (order 8, 1 step/frame). Integrations
#: that drift (RK4, Dormand–Prince) reach 1e-8 of their scale and more, and stay reported. Every bar shows 4
#: significant figures, so a billionth of the scale is on no bar.
DISSIPATION_ROUND_OFF = 1e-9

#: What a student reads for each key of :func:`energy_budget`, in the order the energy bars show them.
ENERGY_LABELS = {
    "translational_kinetic_J": "kinetic, translational",
    "rotational_kinetic_J": "kinetic, rotational",
    "kinetic_J": "kinetic",
    "potential_J": "potential",
    "dissipated_J": "dissipated",
    "total_J": "total",
}


@dataclass(frozen=True)
class EnergyParts:
    """Energies (J) along N states, arrays (N,).

    Either both ``translational_kinetic_J`` and ``rotational_kinetic_J``, or
    ``kinetic_J`` alone (only where the split is not defined). ``potential_J``:
    gravity and springs. ``drive_work_J``: work done on the system by its drives
    since t = 0, where the state tracks it (None: no drive, or one not tracked —
    the model's ``energy_note`` says which).
    """

    potential_J: np.ndarray
    translational_kinetic_J: np.ndarray | None = None
    rotational_kinetic_J: np.ndarray | None = None
    kinetic_J: np.ndarray | None = None
    drive_work_J: np.ndarray | None = None

    def __post_init__(self) -> None:
        split = (self.translational_kinetic_J is not None, self.rotational_kinetic_J is not None)
        if split[0] != split[1] or all(split) == (self.kinetic_J is not None):
            raise ValueError("energy parts: give translational_kinetic_J with rotational_kinetic_J, or kinetic_J alone")

    @property
    def kinetic_total_J(self) -> np.ndarray:
        """All the kinetic energy (J), (N,)."""
        if self.kinetic_J is not None:
            return np.asarray(self.kinetic_J, dtype=float)
        return np.asarray(self.translational_kinetic_J, dtype=float) + np.asarray(
            self.rotational_kinetic_J, dtype=float
        )

    @property
    def total_J(self) -> np.ndarray:
        """Kinetic + potential (J), (N,)."""
        return self.kinetic_total_J + np.asarray(self.potential_J, dtype=float)

    @property
    def work_J(self) -> np.ndarray:
        """The drives' work (J), (N,): zero where none is tracked."""
        return np.zeros_like(self.total_J) if self.drive_work_J is None else np.asarray(self.drive_work_J, dtype=float)


def energy_budget(parts: EnergyParts, start: EnergyParts) -> dict[str, np.ndarray]:
    """The named energies (J, arrays (N,)) of ``parts``, with ``start`` the same parts at t = 0 (arrays (1,)).

    Keys: ``translational_kinetic_J`` and ``rotational_kinetic_J`` (or ``kinetic_J``),
    ``potential_J``, ``total_J`` (kinetic + potential) and ``dissipated_J``
    (E(0) − W(0) − (E(t) − W(t)), exactly 0 where within :data:`DISSIPATION_ROUND_OFF` of the energy scale).
    """
    total = parts.total_J
    out: dict[str, np.ndarray] = {}
    if parts.kinetic_J is not None:
        out["kinetic_J"] = np.asarray(parts.kinetic_J, dtype=float)
    else:
        out["translational_kinetic_J"] = np.asarray(parts.translational_kinetic_J, dtype=float)
        out["rotational_kinetic_J"] = np.asarray(parts.rotational_kinetic_J, dtype=float)
    out["potential_J"] = np.broadcast_to(np.asarray(parts.potential_J, dtype=float), total.shape).copy()
    out["total_J"] = total
    dissipated = (float(start.total_J[0]) - float(start.work_J[0])) - (total - parts.work_J)
    round_off = np.abs(dissipated) <= DISSIPATION_ROUND_OFF * energy_scale_J(parts, start)
    out["dissipated_J"] = np.where(round_off, 0.0, dissipated)
    return out


def energy_scale_J(parts: EnergyParts, start: EnergyParts) -> np.ndarray:
    """The energy scale of the motion at each of N states (J, (N,)): the largest magnitude of any part there (each
    kinetic part, the potential, the total, the drives' work) or of the total and work at t = 0. What E(t) is
    computed from, so its round-off is a few ulps of this."""
    total = parts.total_J
    magnitudes = [np.abs(total), np.abs(parts.work_J), np.abs(np.broadcast_to(parts.potential_J, total.shape))]
    if parts.kinetic_J is not None:
        magnitudes.append(np.abs(np.asarray(parts.kinetic_J, dtype=float)))
    else:
        magnitudes.append(np.abs(np.asarray(parts.translational_kinetic_J, dtype=float)))
        magnitudes.append(np.abs(np.asarray(parts.rotational_kinetic_J, dtype=float)))
    at_start = max(abs(float(start.total_J[0])), abs(float(start.work_J[0])))
    return np.maximum(np.maximum.reduce([np.broadcast_to(m, total.shape) for m in magnitudes]), at_start)
