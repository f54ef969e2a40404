"""The Ritz series for a uniform Euler–Bernoulli cantilever: natural frequencies from above, and the basis's
conditioning.

Frame and names (m, s): the beam lies along x from the clamp (x = 0) to the free
end (x = L); its deflection w(x, t) is transverse (drawn along +Z). ``ξ = x/L``
is the dimensionless position. Length L, flexural rigidity EI (N·m²) and mass
per length ρA (kg/m) are uniform, and every frequency is a dimensionless number
λ times the beam's scale ``Ω = √(EI / (ρA L⁴))`` (rad/s).

**Exact.** Separating ``w = φ(ξ) cos ωt`` in ``EI w'''' + ρA ẅ = 0`` with
``φ(0) = φ'(0) = 0`` and ``φ''(1) = φ'''(1) = 0`` leaves ``cos β cosh β = −1``
for ``β = β_n L``, and ``ω_n = β_n² Ω``. We solve the cosh-free form
``cos β + sech β = 0`` (one root in each ``((n−1)π, nπ)``) to rounding, and
write the mode shape ``cosh u − cos u − σ (sinh u − sin u)`` (``u = βξ``) with
every exponential as ``e^{−u}`` or ``e^{u−β}``, so nothing overflows or cancels
for high modes.

**Ritz.** Hamilton's principle restricted to ``w = L Σ q_k(t) φ_k(ξ)`` with
admissible functions (``φ_k(0) = φ_k'(0) = 0``; the free-end conditions are
left to the principle) gives ``K q + M q̈ = 0``, with the dimensionless

    K_ij = ∫₀¹ φ_i'' φ_j'' dξ   (× EI/L),      M_ij = ∫₀¹ φ_i φ_j dξ   (× ρA L³),

and ``K v = λ² M v``. Because the trial space is a subspace of the true one,
every Ritz frequency is an upper bound of the exact one of the same index
(Rayleigh–Ritz), and adding a term can only lower it.

**Bases.** ``monomial``: ``φ_k = ξ^{k+1}``, k = 1…N, integrals in closed form
(``M_ij = 1/(i+j+3)``, ``K_ij = i(i+1)j(j+1)/(i+j−1)``): Hilbert-like matrices
whose condition number grows about 40-fold per term, so with N ≈ 7 rounding
already costs more digits than the series gains, and by N ≈ 11 the computed
frequencies fall below the exact ones (which exact arithmetic forbids) and some
ω² turn negative. ``orthogonal`` (the default): ``φ_k'' = √(2k+1) P̃_k(ξ)``,
the shifted Legendre polynomials, k = 0…N−1, integrated twice from the clamp.
Then ``K = I`` exactly (the P̃_k are orthogonal), ``M`` comes from Gauss–Legendre
with N + 3 points (exact for its polynomials of degree ≤ 2N + 2), and the
pencil reduces to the symmetric standard problem ``M v = μ v`` with
``μ = 1/λ²``: its only ill-conditioning is the physics' own spread of
frequencies, cond(M) = (λ_N / λ_1)². Both bases are solved the same way:
factor K (Cholesky) and find ``μ`` (``scipy.linalg.eigh(M, K)``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache, cached_property
from typing import Any, Literal

import numpy as np
import scipy.linalg
from numpy.polynomial import Legendre, legendre
from scipy.optimize import brentq

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

Basis = Literal["orthogonal", "monomial"]
BASES: tuple[Basis, ...] = ("orthogonal", "monomial")
MAX_TERMS = 14
#: Unit roundoff of a double.
UNIT_ROUNDOFF = float(np.finfo(float).eps) / 2.0
#: Rounding can move the frequencies by about u·cond(M) (relative); above this the readout warns
#: (fewer than six digits can be trusted).
TRUSTED_ROUNDING = 1e-6
#: A Ritz frequency more than this fraction below the exact one breaks the upper bound: exact
#: arithmetic forbids it, so it is rounding. The well-conditioned basis stays within 1e-15 of its
#: bound (eigh's rounding of the converged, largest μ is a few u), so 1e-12 flags only real failures.
BOUND_SLACK = 1e-12


# -- the exact solution ---------------------------------------------------------------------------


def frequency_equation(beta_L: np.ndarray | float) -> np.ndarray | float:
    """``cos β + sech β`` (zero at the cantilever's ``β_n L``): ``cos β cosh β + 1`` divided by ``cosh β``."""
    b = np.asarray(beta_L, dtype=float)
    return np.cos(b) + 2.0 * np.exp(-b) / (1.0 + np.exp(-2.0 * b))


@cache
def _exact_beta_L(modes: int) -> tuple[float, ...]:
    return tuple(
        brentq(
            frequency_equation,
            (n - 1) * math.pi,
            n * math.pi,
            xtol=1e-300,
            rtol=4.0 * float(np.finfo(float).eps),
            maxiter=200,
        )
        for n in range(1, modes + 1)
    )


def exact_beta_L(modes: int) -> np.ndarray:
    """The first ``modes`` roots ``β_n L`` of ``cos β cosh β = −1`` (dimensionless, shape (modes,)), to rounding."""
    if not 1 <= modes <= 200:
        raise ValueError(f"modes must be between 1 and 200 (got {modes})")
    return np.array(_exact_beta_L(modes))


def _exact_shape_terms(beta_L: float) -> tuple[float, float, float]:
    """``(A, B, σ)`` with ``φ(ξ) = A e^{−u} + B e^{u−β} − cos u + σ sin u`` (``u = βξ``), free of cosh."""
    b = beta_L
    decay = math.exp(-b)
    denominator = 1.0 - decay * decay + 2.0 * decay * math.sin(b)  # (sinh β + sin β)·2e^{−β}
    a_coefficient = (1.0 + decay * (math.sin(b) + math.cos(b))) / denominator
    b_coefficient = (math.sin(b) - math.cos(b) - decay) / denominator
    sigma = (1.0 + decay * decay + 2.0 * decay * math.cos(b)) / denominator
    return a_coefficient, b_coefficient, sigma


def exact_mode_shape(beta_L: float, xi: np.ndarray, *, derivative: int = 0) -> np.ndarray:
    """Mode shape ``φ = cosh u − cos u − σ(sinh u − sin u)`` or its ξ-derivative (0 or 2) at ``xi`` (shape (P,)).

    Unnormalised (``φ(1) = ±2``); ``u = β ξ``; every exponential is bounded by 1.
    """
    a, b_, sigma = _exact_shape_terms(beta_L)
    u = beta_L * np.asarray(xi, dtype=float)
    if derivative == 0:
        return a * np.exp(-u) + b_ * np.exp(u - beta_L) - np.cos(u) + sigma * np.sin(u)
    if derivative == 2:
        return beta_L**2 * (a * np.exp(-u) + b_ * np.exp(u - beta_L) + np.cos(u) - sigma * np.sin(u))
    raise ValueError(f"derivative must be 0 or 2 (got {derivative})")


# -- the two bases --------------------------------------------------------------------------------


@dataclass(frozen=True)
class RitzBasis:
    """N admissible functions on ξ ∈ [0, 1] with their dimensionless Ritz matrices.

    ``stiffness`` K (N, N) = ∫ φ_i'' φ_j'' dξ and ``mass`` M (N, N) = ∫ φ_i φ_j dξ;
    ``values(xi)`` (N, P) and ``curvatures(xi)`` (N, P) evaluate φ_k and φ_k'' (ξ-derivatives).
    """

    name: Basis
    terms: int
    stiffness: np.ndarray
    mass: np.ndarray

    def values(self, xi: np.ndarray) -> np.ndarray:
        return _evaluate(self.name, self.terms, np.asarray(xi, dtype=float), derivative=0)

    def curvatures(self, xi: np.ndarray) -> np.ndarray:
        return _evaluate(self.name, self.terms, np.asarray(xi, dtype=float), derivative=2)


@cache
def _orthogonal_functions(k: int) -> tuple[Legendre, Legendre]:
    """``φ_k`` and ``φ_k''`` (``√(2k+1) P̃_k``) as Legendre series on [0, 1]; ``φ_k(0) = φ_k'(0) = 0``."""
    curvature = math.sqrt(2 * k + 1) * Legendre.basis(k, domain=[0.0, 1.0])
    return curvature.integ(2, lbnd=0.0), curvature


def _evaluate(name: Basis, terms: int, xi: np.ndarray, *, derivative: int) -> np.ndarray:
    if name == "monomial":
        powers = np.arange(2, terms + 2)[:, None]  # ξ², ξ³, …, ξ^{N+1}
        if derivative == 0:
            return xi[None, :] ** powers
        return powers * (powers - 1) * xi[None, :] ** np.maximum(powers - 2, 0)
    return np.array([_orthogonal_functions(k)[1 if derivative == 2 else 0](xi) for k in range(terms)])


def _check_terms(terms: int) -> None:
    if not 1 <= terms <= MAX_TERMS:
        raise ParameterError("terms", f"must be between 1 and {MAX_TERMS} (got {terms})")


def monomial_basis(terms: int) -> RitzBasis:
    """``φ_k = ξ^{k+1}`` (k = 1…N) with K and M in closed form (each entry rounded once)."""
    _check_terms(terms)
    i = np.arange(1, terms + 1, dtype=float)
    I, J = np.meshgrid(i, i, indexing="ij")
    return RitzBasis("monomial", terms, I * (I + 1) * J * (J + 1) / (I + J - 1), 1.0 / (I + J + 3))


def orthogonal_basis(terms: int) -> RitzBasis:
    """``φ_k'' = √(2k+1) P̃_k(ξ)`` (k = 0…N−1): K = I exactly, M by (N+3)-point Gauss–Legendre (exact)."""
    _check_terms(terms)
    nodes, weights = legendre.leggauss(terms + 3)
    xi, w = 0.5 * (nodes + 1.0), 0.5 * weights
    values = _evaluate("orthogonal", terms, xi, derivative=0)
    mass = (values * w) @ values.T
    return RitzBasis("orthogonal", terms, np.eye(terms), 0.5 * (mass + mass.T))


def ritz_basis(name: Basis, terms: int) -> RitzBasis:
    """The basis ``name`` (``"orthogonal"`` or ``"monomial"``) with ``terms`` functions."""
    if name == "orthogonal":
        return orthogonal_basis(terms)
    if name == "monomial":
        return monomial_basis(terms)
    raise ParameterError("basis", f"must be one of {', '.join(BASES)} (got {name!r})")


# -- the Ritz eigenproblem ------------------------------------------------------------------------


@dataclass(frozen=True)
class RitzModes:
    """What ``K v = λ² M v`` gave, in ascending λ.

    ``lambda_squared`` (N,) dimensionless ω²/Ω² (NaN where the computed μ = 1/λ² was not
    positive: an imaginary frequency, which only rounding produces); ``vectors`` (N, N), column
    n the generalized coordinates of mode n+1; ``factorized`` False when the Cholesky factor of K
    could not be formed (then nothing else is meaningful); cond(M), cond(K) in the 2-norm.
    """

    lambda_squared: np.ndarray
    vectors: np.ndarray
    factorized: bool
    condition_mass: float
    condition_stiffness: float

    @property
    def nonphysical(self) -> int:
        """How many computed ω² were not positive (imaginary frequencies)."""
        return int(np.count_nonzero(~np.isfinite(self.lambda_squared))) if self.factorized else 0


def solve_ritz(basis: RitzBasis) -> RitzModes:
    """Factor K and solve ``M v = μ K v`` (``μ = 1/λ²``, scipy.linalg.eigh); largest μ first = lowest mode."""
    n = basis.terms
    condition_mass = float(np.linalg.cond(basis.mass))
    condition_stiffness = float(np.linalg.cond(basis.stiffness))
    try:
        mu, vectors = scipy.linalg.eigh(basis.mass, basis.stiffness)
    except np.linalg.LinAlgError:
        return RitzModes(np.full(n, np.nan), np.full((n, n), np.nan), False, condition_mass, condition_stiffness)
    order = np.argsort(-mu)  # positive μ first, largest (lowest frequency) first; non-positive last
    mu, vectors = mu[order], vectors[:, order]
    with np.errstate(divide="ignore"):
        lambda_squared = np.where(mu > 0.0, 1.0 / np.where(mu > 0.0, mu, 1.0), np.nan)
    return RitzModes(lambda_squared, vectors, True, condition_mass, condition_stiffness)


# -- the cantilever and its Ritz approximation ----------------------------------------------------


@dataclass(frozen=True)
class Cantilever:
    """A uniform Euler–Bernoulli cantilever: length (m), flexural rigidity EI (N·m²), mass per length ρA (kg/m)."""

    length_m: float
    flexural_rigidity_N_m2: float
    mass_per_length_kg_m: float

    def __post_init__(self) -> None:
        for name in ("length_m", "flexural_rigidity_N_m2", "mass_per_length_kg_m"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ParameterError(name, f"must be a positive finite number (got {value!r})")

    @property
    def frequency_scale_rad_s(self) -> float:
        """``Ω = √(EI / (ρA L⁴))`` (rad/s): every natural frequency is a number times this."""
        return math.sqrt(self.flexural_rigidity_N_m2 / (self.mass_per_length_kg_m * self.length_m**4))

    def exact_omega_rad_s(self, modes: int) -> np.ndarray:
        """``ω_n = (β_n L)² Ω`` (rad/s, shape (modes,))."""
        return exact_beta_L(modes) ** 2 * self.frequency_scale_rad_s

    def exact_shape(self, mode: int, xi: np.ndarray) -> np.ndarray:
        """Exact mode ``mode`` (1-based) at ``xi`` (shape (P,)), scaled to a unit tip deflection (dimensionless)."""
        beta = float(exact_beta_L(mode)[-1])
        return exact_mode_shape(beta, xi) / float(exact_mode_shape(beta, np.array([1.0]))[0])

    def exact_root_curvature(self, mode: int) -> float:
        """``w''(0)`` (1/m) of exact mode ``mode`` with a unit tip deflection (m): ``φ''(0) / (L φ(1))``."""
        beta = float(exact_beta_L(mode)[-1])
        tip = float(exact_mode_shape(beta, np.array([1.0]))[0])
        return float(exact_mode_shape(beta, np.array([0.0]), derivative=2)[0]) / (tip * self.length_m**2)


@dataclass(frozen=True)
class RitzCantilever:
    """The cantilever approximated by ``terms`` functions of ``basis``, with the exact solution beside it."""

    beam: Cantilever
    basis: RitzBasis
    modes: RitzModes

    @classmethod
    def build(cls, beam: Cantilever, *, basis: Basis, terms: int) -> RitzCantilever:
        functions = ritz_basis(basis, terms)
        return cls(beam, functions, solve_ritz(functions))

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> RitzCantilever:
        beam = Cantilever(params["length_m"], params["flexural_rigidity_N_m2"], params["mass_per_length_kg_m"])
        return cls.build(beam, basis=params["basis"], terms=params["terms"])

    @property
    def terms(self) -> int:
        return self.basis.terms

    @cached_property
    def ritz_omega_rad_s(self) -> np.ndarray:
        """Ritz natural frequencies (rad/s, shape (N,), ascending; NaN where none could be computed)."""
        return np.sqrt(self.modes.lambda_squared) * self.beam.frequency_scale_rad_s

    @cached_property
    def exact_omega_rad_s(self) -> np.ndarray:
        """Exact natural frequencies of the same indices (rad/s, shape (N,))."""
        return self.beam.exact_omega_rad_s(self.terms)

    @cached_property
    def relative_error(self) -> np.ndarray:
        """``(ω_Ritz − ω_exact) / ω_exact`` (shape (N,)); ≥ 0 in exact arithmetic, NaN where ω_Ritz is."""
        return (self.ritz_omega_rad_s - self.exact_omega_rad_s) / self.exact_omega_rad_s

    @property
    def below_exact(self) -> np.ndarray:
        """Modes (bool, shape (N,)) whose Ritz frequency broke the upper bound by more than :data:`BOUND_SLACK`."""
        return np.nan_to_num(self.relative_error, nan=0.0) < -BOUND_SLACK

    @property
    def rounding_estimate(self) -> float:
        """``u · cond(M)``: about how far rounding alone can move a computed frequency (relative)."""
        return UNIT_ROUNDOFF * self.modes.condition_mass

    def mode_available(self, mode: int) -> bool:
        """Whether mode ``mode`` (1-based) has a real Ritz frequency and shape."""
        return self.modes.factorized and bool(np.isfinite(self.modes.lambda_squared[mode - 1]))

    def ritz_shape(self, mode: int, xi: np.ndarray) -> np.ndarray:
        """Ritz mode ``mode`` at ``xi`` (shape (P,)), scaled to a unit tip deflection; NaN if unavailable."""
        if not self.mode_available(mode):
            return np.full(np.shape(xi), np.nan)
        coordinates = self.modes.vectors[:, mode - 1]
        return (coordinates @ self.basis.values(xi)) / float(coordinates @ self.basis.values(np.array([1.0]))[:, 0])

    def ritz_root_curvature(self, mode: int) -> float:
        """``w''(0)`` (1/m) of Ritz mode ``mode`` with a unit tip deflection (m); NaN if unavailable."""
        if not self.mode_available(mode):
            return math.nan
        coordinates = self.modes.vectors[:, mode - 1]
        tip = float(coordinates @ self.basis.values(np.array([1.0]))[:, 0])
        return float(coordinates @ self.basis.curvatures(np.array([0.0]))[:, 0]) / (tip * self.beam.length_m**2)

    def modal_energy_J(self, mode: int, amplitude_m: float, t_s: np.ndarray) -> np.ndarray:
        """``T + V`` (J, shape (P,)) of Ritz mode ``mode`` with tip amplitude ``amplitude_m`` at times ``t_s``:
        ``V = ½ qᵀKq·EI/L``, ``T = ½ q̇ᵀMq̇·ρA L³`` with ``q = a v cos ωt / (L tip)`` — constant if Kv = ω²Mv."""
        beam = self.beam
        coordinates = self.modes.vectors[:, mode - 1]
        tip = float(coordinates @ self.basis.values(np.array([1.0]))[:, 0])
        q = amplitude_m * coordinates / (beam.length_m * tip)
        omega = float(self.ritz_omega_rad_s[mode - 1])
        stiffness = float(q @ self.basis.stiffness @ q) * beam.flexural_rigidity_N_m2 / beam.length_m
        mass = float(q @ self.basis.mass @ q) * beam.mass_per_length_kg_m * beam.length_m**3
        t = np.asarray(t_s, dtype=float)
        return 0.5 * stiffness * np.cos(omega * t) ** 2 + 0.5 * mass * omega**2 * np.sin(omega * t) ** 2

    def warning(self) -> str:
        """Why the numbers cannot be trusted, in words (empty when they can)."""
        modes = self.modes
        conditioning = f"cond(M) = {modes.condition_mass:.1e}"
        if not modes.factorized:
            return (
                f"The {self.basis.name} basis with {self.terms} terms failed: the Cholesky factor of K could not "
                "be formed "
                f"({conditioning}, cond(K) = {modes.condition_stiffness:.1e}). No Ritz frequencies."
            )
        words = []
        if modes.nonphysical:
            words.append(
                f"{modes.nonphysical} computed ω² came out negative (imaginary frequencies), which exact "
                "arithmetic forbids."
            )
        below = np.flatnonzero(self.below_exact) + 1
        if below.size:
            listed = ", ".join(str(n) for n in below)
            words.append(
                f"Mode{'s' if below.size > 1 else ''} {listed} fell below the exact frequency: the Ritz upper "
                "bound is broken."
            )
        if words or self.rounding_estimate > TRUSTED_ROUNDING:
            digits = max(0, int(math.floor(-math.log10(self.rounding_estimate)))) if self.rounding_estimate < 1.0 else 0
            words.append(
                f"{conditioning}: rounding alone can move the frequencies by about {self.rounding_estimate:.0e} "
                f"(about {digits} trustworthy digits). Do not trust these numbers; use the orthogonal basis."
            )
        return " ".join(words)


@dataclass(frozen=True)
class ConvergenceRow:
    """One N of the convergence table: Ritz and exact ω (rad/s, shape (N,)), relative errors, cond(M)."""

    terms: int
    ritz_omega_rad_s: np.ndarray
    exact_omega_rad_s: np.ndarray
    relative_error: np.ndarray
    condition_mass: float
    factorized: bool


def convergence_table(beam: Cantilever, *, basis: Basis, max_terms: int = MAX_TERMS) -> tuple[ConvergenceRow, ...]:
    """The Ritz solution for N = 1…``max_terms`` of ``basis`` (one row per N)."""
    _check_terms(max_terms)
    rows = []
    for terms in range(1, max_terms + 1):
        ritz = RitzCantilever.build(beam, basis=basis, terms=terms)
        rows.append(
            ConvergenceRow(
                terms,
                ritz.ritz_omega_rad_s,
                ritz.exact_omega_rad_s,
                ritz.relative_error,
                ritz.modes.condition_mass,
                ritz.modes.factorized,
            )
        )
    return tuple(rows)


# -- parameters and the simulate model ------------------------------------------------------------


def _check(params: Mapping[str, Any]) -> None:
    if params["mode"] > params["terms"]:
        raise ParameterError(
            "mode", f"mode {params['mode']} needs at least {params['mode']} Ritz terms (terms = {params['terms']})"
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "length_m", "m", 1.0, 0.05, 50.0, "Length L of the cantilever, clamp to free end", "length L", scale="log"
        ),
        Parameter(
            "flexural_rigidity_N_m2",
            "N·m²",
            50.0,
            1e-3,
            1e9,
            "Flexural rigidity EI of the cross-section",
            "flexural rigidity EI",
            scale="log",
        ),
        Parameter(
            "mass_per_length_kg_m", "kg/m", 1.0, 1e-3, 1e4, "Mass per unit length ρA", "mass per length ρA", scale="log"
        ),
        Parameter(
            "terms",
            "",
            6,
            1,
            MAX_TERMS,
            "Number N of admissible functions in the Ritz series",
            "Ritz terms N",
            kind="int",
            step=1,
        ),
        Parameter(
            "basis",
            "",
            "orthogonal",
            kind="choice",
            choices=BASES,
            label="basis",
            description=(
                "Admissible functions: 'orthogonal' (second derivatives are shifted Legendre "
                "polynomials) or 'monomial' (ξ², ξ³, …)"
            ),
        ),
        Parameter(
            "mode", "", 1, 1, MAX_TERMS, "Which Ritz mode n to animate (at most N)", "mode n", kind="int", step=1
        ),
        Parameter(
            "amplitude_m",
            "m",
            0.2,
            0.0,
            10.0,
            "Tip amplitude of the animated mode (linear theory: frequencies do not depend on it)",
            "tip amplitude",
            step=0.01,
        ),
    ),
    check=_check,
)


class RitzCantileverModel(ClosedFormModel):
    """Free vibration of the cantilever in one Ritz mode, beside the exact mode of the same index."""

    parameters = PARAMETERS
    series_units = {
        "tip_deflection_m": "m",
        "exact_tip_deflection_m": "m",
        "root_bending_moment_N_m": "N·m",
        "exact_root_bending_moment_N_m": "N·m",
    }
    invariant_units = {"energy_J": "J"}
    description = (
        "Ritz series (Hamilton's principle on N admissible functions): one mode, w = a φ_n(x) cos ω_n "
        "t, beside the exact mode"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        ritz = RitzCantilever.from_params(params)
        mode, amplitude = params["mode"], params["amplitude_m"]
        beam = ritz.beam
        t = np.asarray(t_s, dtype=float)
        omega = float(ritz.ritz_omega_rad_s[mode - 1])
        exact_omega = float(ritz.exact_omega_rad_s[mode - 1])
        exact_phase = np.cos(exact_omega * t)
        exact_tip = amplitude * exact_phase
        exact_moment = beam.flexural_rigidity_N_m2 * amplitude * beam.exact_root_curvature(mode) * exact_phase
        warning = ritz.warning()
        if ritz.mode_available(mode):
            phase = np.cos(omega * t)
            series = {
                "tip_deflection_m": amplitude * phase,
                "exact_tip_deflection_m": exact_tip,
                "root_bending_moment_N_m": beam.flexural_rigidity_N_m2
                * amplitude
                * ritz.ritz_root_curvature(mode)
                * phase,
                "exact_root_bending_moment_N_m": exact_moment,
            }
            return ClosedFormSolution(series, {"energy_J": ritz.modal_energy_J(mode, amplitude, t)}, warning=warning)
        undefined = np.full(t.shape, np.nan)
        series = {
            "tip_deflection_m": undefined,
            "exact_tip_deflection_m": exact_tip,
            "root_bending_moment_N_m": undefined,
            "exact_root_bending_moment_N_m": exact_moment,
        }
        message = f"Ritz mode {mode} has no real frequency. {warning}"
        return ClosedFormSolution(
            series, {"energy_J": undefined}, [Event(0.0, "ritz-failed", message)], warning=message
        )

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        values = invariants["energy_J"]
        return {"energy_J": max(abs(float(values[0])), 1e-300) if np.isfinite(values[0]) else 1.0}
