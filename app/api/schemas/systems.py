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


class ReferenceSpec(BaseModel):
    about: str = Field(description="The reference motion, in words")
    states: list[str] = Field(description="The linear model's states: coordinates, then their rates (name_d)")


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
    dependent_coordinates: list[str] = Field(
        default_factory=list, description="Coordinates the configuration constraints fix (a system built of parts)"
    )
    dependent_speeds: list[str] = Field(
        default_factory=list, description="Rates the velocity (rolling) constraints fix (a system built of parts)"
    )
    reference: ReferenceSpec | None = Field(
        None, description="The motion its linear model is about (POST …/eigenvalues), if it has one"
    )


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
    operations: dict[str, int] | None = Field(
        None,
        description=(
            "A system built of parts: its generated code's size, operations written out in full (before_cse) and "
            "after common subexpressions are shared (after_cse), with its speeds and constraint rows"
        ),
    )


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


class SweepRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    parameter: str = Field(description="The parameter to vary (one of the system's, e.g. speed_m_s)")
    low: float = Field(description="From this value (the parameter's unit)")
    high: float = Field(description="To this value (the parameter's unit)")
    points: int = Field(51, ge=2, le=201, description="How many values, evenly spaced, ends included")


class EigenvaluesRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Parameters by name (the rest: defaults)")
    sweep: SweepRequest | None = Field(
        None, description="Also the eigenvalues as one parameter varies, and where stability changes"
    )


class Eigenvalue(BaseModel):
    re: float = Field(description="Real part, 1/s: the growth (> 0) or decay (< 0) rate")
    im: float = Field(description="Imaginary part, rad/s: the angular frequency of an oscillating pair")


class StabilityCrossing(BaseModel):
    value: float = Field(description="Where the largest real part crosses zero (the parameter's unit), to 1e-12")
    becomes: Literal["stable", "unstable"] = Field(description="What the motion becomes as the parameter grows past it")
    oscillating: bool = Field(description="The crossing eigenvalue is one of an oscillating pair (a bicycle's weave)")


class SweepAnswer(BaseModel):
    parameter: str
    unit: str
    values: list[float]
    eigenvalues: list[list[Eigenvalue]] = Field(description="At each value, sorted by real part, then imaginary part")
    crossings: list[StabilityCrossing]


class EigenvaluesAnswer(BaseModel):
    eigenvalues: list[Eigenvalue] = Field(description="Sorted by real part, then imaginary part")
    states: list[str] = Field(description="The linear model's states: coordinates, then their rates (name_d)")
    about: str = Field(description="The motion the model is linearised about")
    stable: bool = Field(description="Every eigenvalue's real part is negative: a small push dies out")
    unit: str = "1/s"
    params: dict[str, Any]
    sweep: SweepAnswer | None = None


class DescribeRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    description: dict[str, Any] | None = Field(
        None, description="The system's parts as JSON (app/physics/mechanics/multibody/data.py): give this or toml"
    )
    toml: str | None = Field(None, description="The same as TOML text (at most 20 kB)", max_length=20_000)
    params: dict[str, Any] = Field(
        default_factory=dict, description="Values for the described parameters, by name (the rest: their values)"
    )
    state: list[float] | None = Field(
        None,
        description="The coordinates, then their rates, in the listed order (SI); must meet the constraints",
        max_length=48,
    )
    linearise: bool = Field(
        False,
        description=(
            "Also the eigenvalues about the description's reference motion, or (without one) about rest at the "
            "state's configuration (zero if no state), which must be an equilibrium"
        ),
    )


class DegreesOfFreedom(BaseModel):
    configuration: int = Field(description="Coordinates less configuration constraints (a count)")
    speeds: int = Field(description="Speeds less velocity constraints (a count)")


class Operations(BaseModel):
    speeds: int = Field(description="How many speeds (one per coordinate)")
    constraints: int = Field(description="How many velocity-constraint rows")
    before_cse: int = Field(description="Arithmetic operations in M, f, A and b written out in full (a count)")
    after_cse: int = Field(description="Operations in the generated code, subexpressions shared (a count)")


class Energies(BaseModel):
    kinetic_J: float
    potential_J: float = Field(description="Gravity's, zero at z = 0, J")
    translational_J: float = Field(description="½ Σ m v_G², J")
    rotational_J: float = Field(description="½ Σ ω·I_G ω, J")
    total_J: float


class LinearModel(BaseModel):
    about: str = Field(description="The motion the model is linearised about")
    states: list[str] = Field(description="The linear model's states: coordinates, then their rates (name_d)")
    eigenvalues: list[Eigenvalue] = Field(description="Sorted by real part, then imaginary part")
    stable: bool = Field(description="Every eigenvalue's real part is negative")
    unit: str = "1/s"


class DescribeAnswer(BaseModel):
    id: str
    title: str
    coordinates: list[CoordinateSpec]
    dependent_coordinates: list[str]
    dependent_speeds: list[str]
    degrees_of_freedom: DegreesOfFreedom
    operations: Operations
    derive_s: float = Field(description="Seconds sympy took to derive the equations (when first derived)")
    generate_s: float = Field(description="Seconds the code generator took (when first derived)")
    load_s: float = Field(description="Seconds this server took to load the generated code")
    cached: bool = Field(description="The generated code was already on disk or in memory: nothing derived now")
    parameters: list[ParameterSpec] = Field(description="The described parameters, with their units")
    params: dict[str, Any] = Field(description="The parameter values used (their units in `parameters`)")
    state: list[float] = Field(description="The state the energies are at: q, then q̇ (units in state_units)")
    state_units: list[str]
    state_is: str = Field(description="Where the state came from: given, or rest at the zero configuration")
    energies: Energies
    state_derivative: list[float] | None = Field(None, description="d(state)/dt at the given state")
    state_derivative_units: list[str] | None = None
    linear: LinearModel | None = Field(None, description="With linearise: the linear model's eigenvalues")
