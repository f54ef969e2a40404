"""``/api/scenes/{scene_id}/sessions/{session_id}/graph``: a session's kept motion as graphs and energy bars."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, Field


class GraphQuantity(BaseModel):
    """One quantity that can be graphed: its name (a key of ``values``), what a student reads, its unit and kind."""

    name: str = Field(
        description=(
            'A series or invariant name of the model, or "energy_" + an energy key (e.g. energy_rotational_kinetic_J)'
        )
    )
    label: str = Field(description="The symbol or words a student sees (θ, ω₃, kinetic, rotational)")
    unit: str
    kind: Literal["series", "invariant", "energy"]


class EnergyPart(BaseModel):
    """One energy bar at the latest kept frame."""

    name: str = Field(description='"energy_" + the energy key, as in quantities')
    label: str
    value_J: float | None = Field(description="J; null if not finite")


class EnergyBars(BaseModel):
    """The energy bars at the latest kept frame: translational and rotational kinetic (or kinetic), potential,
    dissipated."""

    parts: list[EnergyPart]
    total_J: float | None = Field(description="Kinetic + potential (J); null if not finite")
    note: str | None = Field(
        description="What the budget leaves out (a drive whose work is not tracked, a reduced model)"
    )


class GraphAnswer(BaseModel):
    """Every series, invariant and energy part of the session's kept motion against simulated time."""

    scene_id: str
    t_s: list[float] = Field(
        description="Simulated times (s), ascending, at most max_points, the latest kept frame last"
    )
    quantities: list[GraphQuantity]
    values: dict[str, list[float | None]] = Field(
        description="Per quantity name, one value per time; null where not finite"
    )
    energy: EnergyBars | None
    span_s: list[float] | None = Field(description="[first, last] of t_s (s); null when t_s is empty")
    note: str | None = Field(
        description="Why the graph is empty (a scene that is not integrated, no viewer yet), or null"
    )
