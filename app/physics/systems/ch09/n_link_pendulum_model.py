"""The N-link pendulum swinging under gravity, integrated as a plain ODE from the engine's generated equations.

State ``(q, q̇)`` (2n,): the coordinates of :mod:`.n_link_pendulum` (planar: θ_k, each link's angle from the one
before, rad; spatial: α_k then β_k per universal joint, rad) and their rates. The chain has no constraints, so the
equations are M(q) q̈ = f(q, q̇) with M solved by LU at each call: the engine's generated ``dynamics`` kernel (Kane's
method, :mod:`app.physics.mechanics.multibody`) compiled by numba inside a small right-hand side written beside it
on disk (:data:`_ODE_MODULE`). The step rule picks RK4 or Dormand–Prince at the 1e-6 target, like the catalogue's
derived models.

Preparing a member (derive, generate, numba compile) takes from 0.3 s (2 links) to about 12 s (20 links), so it is
done by the whole-set check in a bounded child process (:func:`prepared_chain`); this process then only reads it
from disk.

The start: a normal mode at ``amplitude_deg`` (its largest link angle from the vertical), the chain straight at that
angle, or bent in a zigzag. The normal modes come from the engine's own linearisation
(:func:`~app.physics.mechanics.multibody.linearise.state_matrix`) about hanging at rest; a spatial chain has each
planar frequency twice, once per swing plane. The model stops where a spatial joint's β passes ±85° (the universal
joint locks at 90°: its two axes would line up).
"""

from __future__ import annotations

import functools
import math
import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import scipy.linalg

from app.physics.core.bounded import BoundedRunner, WorkBusy, WorkInterrupted, WorkRefused
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations.sequences import elementary_rotation_matrix
from app.physics.mechanics.engine import load_generated
from app.physics.mechanics.multibody.compiled import CompiledSystem, compiled
from app.physics.mechanics.multibody.linearise import state_matrix
from app.physics.solvers.integrated_model import IntegratedModel, ModelLimit
from app.physics.solvers.kernels import Kernel
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch09.n_link_pendulum import MAX_LINKS, MAX_SPATIAL_LINKS, MIN_LINKS, PHYSICAL, chain

#: Beyond this β (deg) a universal joint is about to lock (its axes line up at 90°): the spatial chain stops.
JOINT_LOCK_DEG = 85.0
JOINT_LOCK = "joint_lock"
#: The small-oscillation picture holds while the quadratic energy is within this fraction of the true energy above
#: rest, and a started mode keeps at least 1 − this of the linear energy.
LINEAR_TOLERANCE = 0.01
PLANES = ("x–z", "y–z")
PHYSICAL_NAMES = tuple(p.name for p in PHYSICAL)


def check_chain(values: Mapping[str, Any]) -> None:
    """The whole-set check: a start that can exist (naming the field at fault), then the member prepared (derived,
    generated and compiled in a bounded child: :func:`prepared_chain`)."""
    links, planar = member_key(values)
    if not planar and links > MAX_SPATIAL_LINKS:
        raise ParameterError(
            "links", f"a spatial chain has at most {MAX_SPATIAL_LINKS} links (twice the coordinates of a planar one)"
        )
    count = links if planar else 2 * links
    if values["start"] == "mode":
        if int(values["mode"]) > count:
            raise ParameterError(
                "mode",
                f"a {links}-link {'planar' if planar else 'spatial'} chain has {count} normal modes; choose 1 to "
                f"{count}",
            )
        if float(values["gravity_m_s2"]) <= 0.0:
            raise ParameterError(
                "start",
                "with g = 0 nothing pulls the hanging chain back, so it has no normal modes: start it straight or "
                "bent, or give g > 0",
            )
    if not planar:
        amplitude = float(values["amplitude_deg"])
        largest = amplitude if values["start"] != "bend" else 2.0 * amplitude
        if values["start"] != "mode" and largest >= JOINT_LOCK_DEG:
            raise ParameterError(
                "amplitude_deg",
                f"a spatial chain's joints lock at β = 90° and the model stops at {JOINT_LOCK_DEG:g}°: this start "
                f"bends a joint by {largest:g}°",
            )
    try:
        prepared_chain(links, planar)
    except (ParameterError, WorkBusy, WorkInterrupted):  # busy or stopped from outside: "try again"
        raise
    except (WorkRefused, ValueError) as error:
        raise ParameterError("links", f"this chain could not be prepared: {error}") from None


PARAMETERS = ParameterSet(
    (
        Parameter("links", "", 6, MIN_LINKS, MAX_LINKS, "How many links (2 to 20; spatial: 2 to 10)", "N", kind="int"),
        Parameter("planar", "", "planar", kind="choice", choices=("planar", "spatial"), label="motion",
                  description="planar: hinges about one axis; spatial: universal joints, the links swing anywhere"),
        *PHYSICAL,
        Parameter("start", "", "mode", kind="choice", choices=("mode", "straight", "bend"), label="start",
                  description="mode: one normal mode's shape; straight: the chain in line, tilted; bend: a zigzag"),
        Parameter("mode", "", 1, 1, MAX_LINKS, "Which normal mode to start (1: the slowest)", "mode", kind="int"),
        Parameter("amplitude_deg", "deg", 5.0, 0.0, 175.0,
                  "The start's largest link angle from the vertical (straight: the whole chain's tilt)", "A"),
    ),
    check=check_chain,
)  # fmt: skip


def member_key(params: Mapping[str, Any]) -> tuple[int, bool]:
    """(links, planar) of the chain ``params`` choose."""
    return int(params["links"]), params["planar"] == "planar"


def physical(params: Mapping[str, Any]) -> dict[str, float]:
    """m (kg), l (m) and g (m/s²) by the system's parameter names."""
    return {name: float(params[name]) for name in PHYSICAL_NAMES}


# --- preparing a member: derive and generate (the engine), then compile its ODE right-hand side -------------------

#: The right-hand side ẏ = (q̇, M⁻¹ f) over the generated ``dynamics``, written beside the generated module: numba
#: caches both there, so a process that finds them on disk loads them in a few hundredths of a second.
_ODE_MODULE = '''"""{title} as an ODE: q̈ = M(q)⁻¹ f(q, q̇), M solved by LU at each call (no constraints).

Generated by app.physics.systems.ch09.n_link_pendulum_model over {module}. Do not edit."""

import math

import numba
import numpy as np

from app.physics.mechanics.linear import solve_small
from app.physics.solvers.kernels import RHS_SIGNATURE
from {module} import dynamics as dynamics_python

N = {n}
dynamics = numba.njit(cache=True, nogil=True, error_model="numpy")(dynamics_python)


def rhs_python(t, y, p, dydt):
    M = np.empty((N, N))
    f = np.empty(N)
    dynamics(t, y[:N], y[N:], p, M, f)
    if not solve_small(M, f):
        for i in range(2 * N):
            dydt[i] = math.nan
        return
    for i in range(N):
        dydt[i] = y[N + i]
        dydt[N + i] = f[i]


rhs = numba.cfunc(RHS_SIGNATURE, cache=True, nopython=True, error_model="numpy")(rhs_python)
'''


def _ode_module(equations: CompiledSystem):
    """The member's ODE module (written once beside the generated one; importing it compiles or loads ``rhs``)."""
    module = equations.dynamics.__module__
    generated = Path(equations.dynamics.__code__.co_filename)
    path = generated.with_name(f"{generated.stem}_ode.py")
    source = _ODE_MODULE.format(title=equations.system.title, module=module, n=equations.n)
    if not path.exists() or path.read_text() != source:
        temporary = path.with_suffix(f".{threading.get_ident()}.{time.monotonic_ns()}.tmp")
        temporary.write_text(source)
        temporary.replace(path)
    return load_generated(path)


def _prepare_in_child(links: int, planar: bool) -> dict[str, Any]:
    """In a bounded child: derive and generate the member (or find it on disk) and compile its right-hand side, so
    both are on disk for the parent; what each took (s)."""
    equations = compiled(chain(links, planar))
    start = time.perf_counter()
    rhs = _ode_module(equations).rhs
    return {
        "from_cache": bool(equations.from_cache),
        "derive_s": float(equations.derive_s),
        "generate_s": float(equations.generate_s),
        "numba_s": time.perf_counter() - start,
        "numba_from_cache": bool(rhs.cache_hits),
    }


#: The children that prepare members: the largest, cold, took 12 s and about 600 MB (20 links planar).
runner = BoundedRunner(
    max_jobs=2,
    timeout_s=120.0,
    memory_mb=2048.0,
    wait_s=30.0,
    # The typed derivations' preload and this module: the process has one forkserver, whoever starts it.
    preload=("app.physics.core.bounded", "numpy", "sympy", "app.physics.mechanics.typed", __name__),
)


@dataclass(frozen=True)
class PreparedChain:
    """One member ready to run: its generated equations, its compiled right-hand side and how they were obtained."""

    equations: CompiledSystem
    kernel: Kernel
    #: The child's report (:func:`_prepare_in_child`): from_cache, derive_s, generate_s, numba_s, numba_from_cache.
    child: Mapping[str, Any]
    #: Seconds this process waited for the child, and then to load from disk.
    waited_s: float
    load_s: float

    @property
    def preparation(self) -> str:
        """How the member was obtained, in words for the readout."""
        child = self.child
        if child["from_cache"] and child["numba_from_cache"]:
            return f"read from the disk cache ({self.load_s:.2f} s)"
        parts = []
        if not child["from_cache"]:
            parts.append(f"derived in {child['derive_s']:.2f} s, generated in {child['generate_s']:.2f} s")
        else:
            parts.append("equations read from the disk cache")
        parts.append(
            f"compiled by numba in {child['numba_s']:.2f} s"
            if not child["numba_from_cache"]
            else "compiled code read from the disk cache"
        )
        return ", ".join(parts) + f", in a separate process (then read here in {self.load_s:.2f} s)"


_prepared: dict[tuple[int, bool], PreparedChain] = {}
_prepared_lock = threading.Lock()
_member_locks: dict[tuple[int, bool], threading.Lock] = {}
#: Members being prepared in this process now, and since when (time.monotonic()).
_in_preparation: dict[tuple[int, bool], float] = {}


def member_name(links: int, planar: bool) -> str:
    return f"{links}-link {'planar' if planar else 'spatial'} chain"


def members_in_preparation() -> list[str]:
    """The members being prepared in this process now, with how long so far ("12-link planar chain, 3 s so far")."""
    now = time.monotonic()
    with _prepared_lock:
        return [f"{member_name(*key)}, {now - since:.0f} s so far" for key, since in sorted(_in_preparation.items())]


def prepared_chain(links: int, planar: bool) -> PreparedChain:
    """The member ready to run: from this process's memory, or prepared in a bounded child (which reads the disk cache
    when it can) and then read from disk here. Raises the runner's refusals (WorkBusy, WorkTimeout, …)."""
    key = (int(links), bool(planar))
    with _prepared_lock:
        found = _prepared.get(key)
        if found is not None:
            return found
        lock = _member_locks.setdefault(key, threading.Lock())
    with lock:
        with _prepared_lock:
            found = _prepared.get(key)
            if found is not None:
                return found
            _in_preparation[key] = time.monotonic()
        try:
            start = time.perf_counter()
            child = runner.run(_prepare_in_child, key, what=f"preparing the {member_name(*key)}")
            loading = time.perf_counter()
            equations = compiled(chain(*key))
            kernel = Kernel(compiled=_ode_module(equations).rhs, python=equations.rhs)
            ready = PreparedChain(equations, kernel, child, loading - start, time.perf_counter() - loading)
        finally:
            with _prepared_lock:
                _in_preparation.pop(key, None)
        with _prepared_lock:
            _prepared[key] = ready
        return ready


# --- normal modes -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class NormalModes:
    """The small oscillations about hanging at rest: M₀ q̈ + K q = 0.

    ``frequencies_rad_s`` (k,) ascending (a spatial chain: each twice, x–z plane first); ``shapes`` (k, n) in the
    joint coordinates, M₀-normalised (φᵀ M₀ φ = 1); ``planes`` (k,) the swing plane of each; ``mass_matrix`` M₀ (n, n,
    kg·m²) and ``stiffness`` K (n, n, N·m/rad)."""

    frequencies_rad_s: np.ndarray
    shapes: np.ndarray
    planes: tuple[str, ...]
    mass_matrix: np.ndarray
    stiffness: np.ndarray

    def modal_energies_J(self, states: np.ndarray) -> np.ndarray:
        """½ (η̇² + ω² η²) per mode (N, k) along ``states`` (N, 2n), η = Φᵀ M₀ q."""
        states = np.atleast_2d(states)
        n = self.mass_matrix.shape[0]
        project = self.shapes @ self.mass_matrix
        eta, eta_rate = states[:, :n] @ project.T, states[:, n:] @ project.T
        return 0.5 * (eta_rate**2 + (self.frequencies_rad_s * eta) ** 2)


def plane_coordinates(links: int, planar: bool) -> list[list[int]]:
    """The coordinates swinging in each plane: planar, all (x–z); spatial, the β's (x–z) then the α's (y–z)."""
    if planar:
        return [list(range(links))]
    return [list(range(1, 2 * links, 2)), list(range(0, 2 * links, 2))]


@functools.lru_cache(maxsize=64)
def _normal_modes(links: int, planar: bool, m: float, l: float, g: float) -> NormalModes:
    equations = prepared_chain(links, planar).equations
    params = dict(zip(PHYSICAL_NAMES, (m, l, g)))
    system = equations.system
    n = equations.n
    p = equations.parameter_array(params)
    M0, forces = np.empty((n, n)), np.empty(n)
    equations.dynamics(0.0, np.zeros(n), np.zeros(n), p, M0, forces)
    assert system.reference is not None  # every member hangs at rest as its reference
    A = state_matrix(equations, params, system.reference)
    K = -M0 @ A[n:, :n]
    K = 0.5 * (K + K.T)
    per_plane = []
    for plane, indices in zip(PLANES, plane_coordinates(links, planar)):
        block = np.ix_(indices, indices)
        values, vectors = scipy.linalg.eigh(K[block], M0[block])
        rows = []
        for value, vector in zip(values, vectors.T):
            shape = np.zeros(n)
            shape[indices] = vector
            rows.append((math.sqrt(max(float(value), 0.0)), plane, shape))
        per_plane.append(rows)
    # The two planes' frequencies are equal (to rounding): mode by mode, the x–z swing first.
    rows = [row for pair in zip(*per_plane) for row in pair]
    return NormalModes(
        frequencies_rad_s=np.array([r[0] for r in rows]),
        shapes=np.array([r[2] for r in rows]),
        planes=tuple(r[1] for r in rows),
        mass_matrix=M0,
        stiffness=K,
    )


def normal_modes(params: Mapping[str, Any]) -> NormalModes:
    """The member's normal modes for ``params`` (kept per member and m, l, g)."""
    return _normal_modes(*member_key(params), *(float(params[k]) for k in PHYSICAL_NAMES))


def link_angles(params: Mapping[str, Any], shape: np.ndarray) -> np.ndarray:
    """Each link's angle from the vertical in its swing plane (rad, (links,)) for small joint angles ``shape`` (n,)
    of one plane: the running sum of the joint angles."""
    links, planar = member_key(params)
    planes = plane_coordinates(links, planar)
    own = max(planes, key=lambda indices: float(np.max(np.abs(shape[indices]))))
    return np.cumsum(shape[own])


def mode_start(params: Mapping[str, Any], mode: int, amplitude_rad: float) -> np.ndarray:
    """q (n,) of mode ``mode`` (1-based) with its largest link angle from the vertical ``amplitude_rad``, that angle
    positive."""
    shape = normal_modes(params).shapes[mode - 1]
    angles = link_angles(params, shape)
    largest = int(np.argmax(np.abs(angles)))
    return shape * (amplitude_rad / angles[largest])


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """(2n,) at rest: a mode's shape, the chain straight at the amplitude, or bent in a zigzag (each link's angle
    from the vertical alternately ±amplitude; spatial: in the x–z plane, the first link also turned sideways by half
    the amplitude)."""
    links, planar = member_key(params)
    n = links if planar else 2 * links
    amplitude = math.radians(float(params["amplitude_deg"]))
    q = np.zeros(n)
    swing = plane_coordinates(links, planar)[0]
    if params["start"] == "mode":
        q = mode_start(params, int(params["mode"]), amplitude)
    elif params["start"] == "straight":
        q[swing[0]] = amplitude
    else:
        absolute = amplitude * (-1.0) ** np.arange(links)
        q[swing] = np.diff(absolute, prepend=0.0)
        if not planar:
            q[0] = 0.5 * amplitude
    return np.concatenate([q, np.zeros(n)])


# --- geometry -----------------------------------------------------------------------------------------------------


def joint_positions_m(params: Mapping[str, Any], q: np.ndarray) -> np.ndarray:
    """(links + 1, 3) m in frame N (z up): the top hinge at the origin, then each link's far end."""
    links, planar = member_key(params)
    length = float(params["link_length_m"])
    q = np.asarray(q, dtype=float)
    if planar:
        turns = elementary_rotation_matrix(1, q)
    else:
        turns = elementary_rotation_matrix(0, q[0::2]) @ elementary_rotation_matrix(1, q[1::2])
    points = np.zeros((links + 1, 3))
    R = np.eye(3)
    down = np.array([0.0, 0.0, -length])
    for k in range(links):
        R = R @ turns[k]
        points[k + 1] = points[k] + R @ down
    return points


def beta_deg(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """(N, links) each universal joint's β (deg) along ``states`` (spatial chains only)."""
    return np.degrees(np.atleast_2d(states)[:, 1 : 2 * int(params["links"]) : 2])


class NLinkPendulumMotion(IntegratedModel):
    """N uniform rods hinged end to end, hanging under gravity: started in one normal mode it swings in that shape
    at its frequency while the swing is small; larger, the modes trade energy; released from high, it is chaotic."""

    parameters = PARAMETERS
    methods = ("rk4", "dopri5")
    default_method = "rk4"
    accuracy_target = AccuracyTarget(
        1e-6, "", "state (q, q̇): largest component error relative to the largest component"
    )
    series_units = {
        "tip_x_m": "m",
        "tip_y_m": "m",
        "tip_z_m": "m",
        "energy_J": "J",
        "energy_above_rest_J": "J",
        "linear_energy_J": "J",
        "started_mode_share": "",
    }
    invariant_units = {"energy": "J"}

    def prepared(self, params: Mapping[str, Any]) -> PreparedChain:
        return prepared_chain(*member_key(params))

    def prepare(self, params: Mapping[str, Any]) -> None:
        """Prepare the member now (a worker warms the default at start-up)."""
        self.prepared(params)

    def parameter_array(self, params: Mapping[str, Any]) -> np.ndarray:
        return self.prepared(params).equations.parameter_array(physical(params))

    def system(self, params: Mapping[str, Any]) -> OdeSystem:
        ready = self.prepared(params)
        names = [c.name for c in ready.equations.system.coordinates]
        return OdeSystem(
            rhs=ready.kernel,
            parameters=ready.equations.parameter_array(physical(params)),
            state_names=(*names, *(f"{name}_rate" for name in names)),
        )

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return initial_state(params)

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The highest normal-mode frequency (0 for g = 0) plus the fastest joint rate now, at least 1 rad/s."""
        highest = float(normal_modes(params).frequencies_rad_s[-1]) if float(params["gravity_m_s2"]) > 0 else 0.0
        n = len(state) // 2
        return max(1.0, highest + float(np.max(np.abs(state[n:]), initial=0.0)))

    def energy_parts(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> EnergyParts:
        """½ Σ m v_G², ½ Σ ω·I_G ω and Σ m g z_G (J) along ``states`` (N, 2n); V = 0 with every centre at the hinge's
        height."""
        equations = self.prepared(params).equations
        p, n = equations.parameter_array(physical(params)), equations.n
        parts = np.array([equations.energy_parts(s[:n], s[n:], p) for s in np.atleast_2d(states)])
        return EnergyParts(parts[:, 2], translational_kinetic_J=parts[:, 0], rotational_kinetic_J=parts[:, 1])

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 2n)."""
        return self.energy_parts(params, states).total_J

    def rest_energy_J(self, params: Mapping[str, Any]) -> float:
        """V hanging at rest, −m g l Σ (k − ½) = −m g l N² / 2 (J)."""
        links = int(params["links"])
        return (
            -float(params["link_mass_kg"])
            * float(params["gravity_m_s2"])
            * float(params["link_length_m"])
            * (links**2 / 2.0)
        )

    def linear_energy_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The small-oscillation energy ½ q̇ᵀ M₀ q̇ + ½ qᵀ K q (J) at ``state`` (2n,)."""
        modes = normal_modes(params)
        n = modes.mass_matrix.shape[0]
        q, rates = state[:n], state[n:]
        return float(0.5 * rates @ modes.mass_matrix @ rates + 0.5 * q @ modes.stiffness @ q)

    def started_mode_share(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """(N,) the started mode's share of the linear energy (1 while the small-oscillation picture holds; NaN for
        a start that is not a mode, or at rest)."""
        states = np.atleast_2d(states)
        if params["start"] != "mode" or float(params["gravity_m_s2"]) <= 0:
            return np.full(len(states), np.nan)
        energies = normal_modes(params).modal_energies_J(states)
        total = energies.sum(axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(total > 0, energies[:, int(params["mode"]) - 1] / total, np.nan)

    def linear_verdict(self, params: Mapping[str, Any], state: np.ndarray) -> tuple[bool, str]:
        """Whether the small-oscillation picture holds at ``state`` (2n,), and why, in words."""
        if float(params["gravity_m_s2"]) <= 0:
            return False, "no: with g = 0 there is nothing to oscillate about"
        above = float(self.energy_J(params, state[None, :])[0]) - self.rest_energy_J(params)
        if above <= 0:
            return True, "at rest"
        mismatch = abs(self.linear_energy_J(params, state) - above) / above
        share = float(self.started_mode_share(params, state[None, :])[0])
        kept = math.isnan(share) or share >= 1.0 - LINEAR_TOLERANCE
        holds = mismatch <= LINEAR_TOLERANCE and kept
        detail = f"the quadratic energy is off by {100 * mismatch:.2g}%"
        if not math.isnan(share):
            detail += f", the started mode holds {100 * share:.4g}% of it"
        return holds, ("holds: " if holds else "breaks: ") + detail

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        tips = np.array([joint_positions_m(params, s[: len(s) // 2])[-1] for s in states])
        energy = self.energy_J(params, states)
        return {
            "tip_x_m": tips[:, 0],
            "tip_y_m": tips[:, 1],
            "tip_z_m": tips[:, 2],
            "energy_J": energy,
            "energy_above_rest_J": energy - self.rest_energy_J(params),
            "linear_energy_J": np.array([self.linear_energy_J(params, s) for s in states])
            if float(params["gravity_m_s2"]) > 0
            else np.full(len(states), np.nan),
            "started_mode_share": self.started_mode_share(params, states),
        }

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        return {"energy": self.energy_J(params, states)}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """The energy above rest at the start (J), at least 1e-9 of m g l N² / 2 (a chain started at rest)."""
        above = float(self.energy_J(params, state[None, :])[0]) - self.rest_energy_J(params)
        floor = 1e-9 * max(abs(self.rest_energy_J(params)), float(params["link_mass_kg"]), 1e-12)
        return {"energy": max(above, floor)}

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where a spatial joint's β passes ±85° (status ``joint_lock``)."""
        if params["planar"] == "planar":
            return None
        beta = beta_deg(params, states)
        locked = np.nonzero(np.max(np.abs(beta), axis=1) > JOINT_LOCK_DEG)[0]
        if not locked.size:
            return None
        first = int(locked[0])
        joint = int(np.argmax(np.abs(beta[first])))
        return ModelLimit(
            max(first, 1),
            JOINT_LOCK,
            f"At t = {float(t_s[first]):.2f} s joint {joint + 1}'s β reached {float(beta[first, joint]):.1f}°: at 90° "
            "the universal joint's two axes line up and it locks (its coordinates fail there), so the motion stops "
            f"at {JOINT_LOCK_DEG:g}°.",
        )
