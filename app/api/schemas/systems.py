"""``/api/systems``: the derivation engine's catalogue, derivations and right-hand sides."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

from app.api.schemas.parameters import ParameterSpec

Formulation = Literal["lagrange", "hamilton", "routh", "gibbs-appell", "kane", "newton-euler"]


class CoordinateSpec(BaseModel):
    name: str
    latex: str
    unit: str


class SystemSummary(BaseModel):
    """A catalogue system: its coordinates and speeds, which formulations apply (and why not), its parameters."""

    id: str
    title: str
    chapter: int
    coordinates: list[CoordinateSpec]
    speeds: list[CoordinateSpec]
    formulations: list[str] = Field(description="The formulations that apply to this system")
    unavailable: dict[str, str] = Field(description="Formulation → why it does not apply here")
    parameters: list[ParameterSpec]
    assumptions: str


class DeriveRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    formulation: Formulation = "lagrange"
    params: dict[str, Any] = Field(
        default_factory=dict, description="Parameters by name (validated; the equations are symbolic in them)"
    )


class DeriveStep(BaseModel):
    title: str
    latex: str


class DeriveAnswer(BaseModel):
    system_id: str
    formulation: str
    coordinates: list[str]
    speeds: list[str]
    variables: str = Field(description="The variables this formulation's equations are written in")
    equations_latex: list[str]
    mass_matrix_latex: str
    forcing_latex: str
    steps: list[DeriveStep]
    derive_s: float = Field(description="Seconds spent deriving for this request (0 when the derivation was cached)")
    compile_s: float = Field(description="Seconds spent generating and loading the right-hand side for this request")
    cached: bool
    params: dict[str, Any] = Field(default_factory=dict)


class RhsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    formulation: Formulation = "lagrange"
    params: dict[str, Any] = Field(default_factory=dict)
    state: list[float] = Field(
        description="The coordinates, then their time derivatives, in the listed order (SI)", max_length=64
    )
    t: float = Field(0.0, description="Time, s")


class RhsAnswer(BaseModel):
    state_derivative: list[float] = Field(
        description="d(state)/dt: the coordinates' rates, then their second derivatives (SI)"
    )


class CustomDeriveRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    coordinates: list[str] = Field(description="['q1'], ['q1', 'q2'] or ['q1', 'q2', 'q3']", max_length=3)
    kinetic_energy: str = Field(description="T in q1…q3, q1d…q3d, t and the named parameters, J", max_length=400)
    potential_energy: str = Field(description="V in q1…q3, t and the named parameters, J", max_length=400)
    parameters: dict[str, float] = Field(default_factory=dict, description="Named constants and their values")


class RhsCheck(BaseModel):
    state: list[float]
    t: float
    state_derivative: list[float]


class CustomDeriveAnswer(DeriveAnswer):
    rhs_check: RhsCheck
