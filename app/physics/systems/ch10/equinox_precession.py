"""Worked example: the precession of the equinoxes from the Sun's and the Moon's torques.

The Earth is an oblate rigid body: principal moments A = B < C about its centre,
spinning at ω about its figure axis, which is tilted by the obliquity ε from the
normal of the ecliptic (the plane of the Earth's orbit). A distant point mass M at
position r from the Earth's centre exerts the gravity-gradient moment
(MacCullagh)::

    M_O = (3 G M / r⁵) r × ([I] r) = (3 G M / r⁵) (C − A) (s · r) (r × s),

with s the unit figure axis. Averaged over an orbit of semi-major axis a and
eccentricity e, and (for the Moon) over the 18.6-year regression of its orbit's
nodes, the moment is horizontal, perpendicular to s in the ecliptic, of size::

    ⟨M⟩ = (3 G M / (2 a³ (1 − e²)^{3/2})) (C − A) sin ε cos ε · P₂(cos i),

i the orbit's inclination to the ecliptic, P₂(x) = (3x² − 1)/2. The spin angular
momentum C ω s is far larger than the rest, so the axis precesses (gyroscopic
approximation) about the ecliptic normal at Ω = ⟨M⟩ / (C ω sin ε), westward, i.e.
opposite to the Earth's spin: the equinoxes regress. Kepler's third law gives
G M / a³ without G or the masses: n² (the Sun: the Earth's mass neglected beside
it) and n² μ/(1 + μ) for the Moon (μ = M_moon / M_earth), n = 2π / orbital period.

Units: rates in rad/s internally; outputs per Julian year (365.25 d) in
arcseconds (1296000″ per turn). The result is the lunisolar precession; the
planets' pull on the Earth's orbit adds a small planetary part (about −0.1″/yr)
that this model leaves out.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Plot, PlotSeries, Solution, Step, WorkedExample

DAY_S = 86_400.0
JULIAN_YEAR_S = 365.25 * DAY_S
ARCSEC_PER_RAD = 180.0 * 3600.0 / math.pi
ARCSEC_PER_TURN = 360.0 * 3600.0

INPUTS = ParameterSet(
    (
        Parameter(
            "dynamical_ellipticity",
            "",
            0.0032738,
            1e-6,
            0.1,
            "Dynamical ellipticity H = (C − A)/C of the Earth",
            "H",
            scale="log",
        ),
        Parameter(
            "obliquity_deg",
            "deg",
            23.439,
            0.0,
            89.0,
            "Obliquity ε: tilt of the spin axis from the ecliptic normal",
            "ε",
            step=0.1,
        ),
        Parameter(
            "earth_spin_rad_s",
            "rad/s",
            7.292115e-5,
            1e-7,
            1e-2,
            "Earth's spin rate ω relative to the stars (one sidereal day)",
            "ω",
            scale="log",
        ),
        Parameter(
            "sun_orbital_period_days",
            "d",
            365.25636,
            1.0,
            1e5,
            "Sidereal year: period of the Earth's orbit about the Sun",
            "T_sun",
            scale="log",
        ),
        Parameter(
            "moon_orbital_period_days",
            "d",
            27.321662,
            0.1,
            1e4,
            "Sidereal month: period of the Moon's orbit about the Earth",
            "T_moon",
            scale="log",
        ),
        Parameter(
            "moon_mass_ratio", "", 0.0123000371, 0.0, 1.0, "Moon's mass over the Earth's mass, μ", "μ", step=0.0001
        ),
        Parameter(
            "earth_orbit_eccentricity", "", 0.0167, 0.0, 0.9, "Eccentricity of the Earth's orbit", "e_sun", step=0.0001
        ),
        Parameter(
            "moon_orbit_eccentricity", "", 0.0549, 0.0, 0.9, "Eccentricity of the Moon's orbit", "e_moon", step=0.0001
        ),
        Parameter(
            "moon_inclination_deg",
            "deg",
            5.145,
            0.0,
            30.0,
            "Inclination of the Moon's orbit to the ecliptic",
            "i",
            step=0.01,
        ),
    )
)


@dataclass(frozen=True)
class EquinoxPrecession:
    """Precession rates (rad/s, magnitudes; the motion is westward) and their split."""

    sun_rate_rad_s: float
    moon_rate_rad_s: float

    @property
    def rate_rad_s(self) -> float:
        return self.sun_rate_rad_s + self.moon_rate_rad_s

    @property
    def rate_arcsec_per_year(self) -> float:
        return self.rate_rad_s * JULIAN_YEAR_S * ARCSEC_PER_RAD

    @property
    def period_years(self) -> float:
        return ARCSEC_PER_TURN / self.rate_arcsec_per_year if self.rate_rad_s > 0.0 else math.inf


#: The gyroscopic (averaged) model needs the precession far slower than the spin, so the spin angular
#: momentum C ω s dominates; beyond this ratio Ω/ω the model's answer is outside its assumptions.
GYROSCOPIC_RATIO_LIMIT = 1e-2


def averaged_model_warning(inputs: Mapping[str, Any], result: EquinoxPrecession) -> str:
    """The sentence a student reads when Ω/ω exceeds :data:`GYROSCOPIC_RATIO_LIMIT` ('' when the model holds)."""
    ratio = result.rate_rad_s / inputs["earth_spin_rad_s"]
    if ratio <= GYROSCOPIC_RATIO_LIMIT:
        return ""
    return (
        f"Outside the model: the precession rate is {ratio:.3g} times the spin rate. The gyroscopic, orbit-averaged "
        f"model assumes precession far slower than spin (Ω/ω below {GYROSCOPIC_RATIO_LIMIT:g}), so these numbers "
        "are the "
        "formula's, not the motion such a body would have."
    )


def mean_motion_rad_s(period_days: float) -> float:
    return 2.0 * math.pi / (period_days * DAY_S)


def orbit_factor(eccentricity: float, inclination_rad: float = 0.0) -> float:
    """(1 − e²)^{−3/2} P₂(cos i): the orbit-averaged 1/r³ and the node-averaged tilt of the orbit."""
    return (1.0 - eccentricity**2) ** -1.5 * (1.0 - 1.5 * math.sin(inclination_rad) ** 2)


def precession_rate_rad_s(
    *, gm_over_a3: float, factor: float, ellipticity: float, obliquity_rad: float, spin_rad_s: float
) -> float:
    """Ω = (3/2)(GM/a³)(H/ω) cos ε × factor (rad/s), the gyroscopic precession from one body."""
    return 1.5 * gm_over_a3 * factor * ellipticity * math.cos(obliquity_rad) / spin_rad_s


def equinox_precession(inputs: Mapping[str, Any]) -> EquinoxPrecession:
    """Sun's and Moon's contributions for validated ``inputs`` (see :data:`INPUTS`)."""
    H, eps, omega = inputs["dynamical_ellipticity"], math.radians(inputs["obliquity_deg"]), inputs["earth_spin_rad_s"]
    mu = inputs["moon_mass_ratio"]
    n_sun = mean_motion_rad_s(inputs["sun_orbital_period_days"])
    n_moon = mean_motion_rad_s(inputs["moon_orbital_period_days"])
    sun = precession_rate_rad_s(
        gm_over_a3=n_sun**2,
        factor=orbit_factor(inputs["earth_orbit_eccentricity"]),
        ellipticity=H,
        obliquity_rad=eps,
        spin_rad_s=omega,
    )
    moon = precession_rate_rad_s(
        gm_over_a3=n_moon**2 * mu / (1.0 + mu),
        factor=orbit_factor(inputs["moon_orbit_eccentricity"], math.radians(inputs["moon_inclination_deg"])),
        ellipticity=H,
        obliquity_rad=eps,
        spin_rad_s=omega,
    )
    return EquinoxPrecession(sun_rate_rad_s=sun, moon_rate_rad_s=moon)


#: Points of the true anomaly (and of the Moon's node longitude) at which :func:`summed_moment_per_C` evaluates the
#: instantaneous moment. Weighted by the time spent there, the moment is a trigonometric polynomial of low degree in
#: each angle (degree 3 in the true anomaly, 2 in the node), so an equally spaced sum of this many points is its exact
#: average up to rounding.
AVERAGE_POINTS = 64


def _rotation_x(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rotation_z(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def summed_moment_per_C(
    *, gm_over_a3: float, eccentricity: float, inclination_rad: float, ellipticity: float, obliquity_rad: float
) -> float:
    """|⟨M⟩|/C (rad/s²) of one body, from the instantaneous moment (MacCullagh) summed over its orbit.

    Ecliptic frame: Z the ecliptic normal, the figure axis s = (sin ε, 0, cos ε). The body's position is
    r = a (1 − e²)/(1 + e cos f) (cos f, sin f, 0) turned by the inclination i about the node line and by the node
    longitude about Z; each point is weighted by the fraction of the period spent there,
    dt/T = (r/a)² df / (2π √(1 − e²)). The moment per unit polar moment C is
    M/C = 3 (GM/a³) H (a/r)³ (s·r̂)(r̂ × s), with GM/a³ = ``gm_over_a3``. With i > 0 the node longitude is averaged
    too (the Moon's nodes regress once in 18.6 years).
    """
    e = eccentricity
    s = np.array([math.sin(obliquity_rad), 0.0, math.cos(obliquity_rad)])
    f = 2.0 * math.pi * np.arange(AVERAGE_POINTS) / AVERAGE_POINTS
    radius = (1.0 - e * e) / (1.0 + e * np.cos(f))  # r/a
    weight = radius**2 / (AVERAGE_POINTS * math.sqrt(1.0 - e * e))
    in_plane = np.stack([np.cos(f), np.sin(f), np.zeros_like(f)], axis=1)
    nodes = 2.0 * math.pi * np.arange(AVERAGE_POINTS) / AVERAGE_POINTS if inclination_rad != 0.0 else np.zeros(1)
    total = np.zeros(3)
    for node in nodes:
        unit = in_plane @ (_rotation_z(float(node)) @ _rotation_x(inclination_rad)).T
        along = unit @ s
        moment = 3.0 * gm_over_a3 * ellipticity * (along / radius**3)[:, None] * np.cross(unit, s)
        total += weight @ moment
    return float(np.linalg.norm(total / len(nodes)))


def _check_step(inputs: Mapping[str, Any]) -> Step:
    """The orbit-averaged moment of the formula beside the instantaneous moment summed over the orbit, per unit C."""
    H, eps = inputs["dynamical_ellipticity"], math.radians(inputs["obliquity_deg"])
    mu = inputs["moon_mass_ratio"]
    bodies = {
        "sun": (mean_motion_rad_s(inputs["sun_orbital_period_days"]) ** 2, inputs["earth_orbit_eccentricity"], 0.0),
        "moon": (
            mean_motion_rad_s(inputs["moon_orbital_period_days"]) ** 2 * mu / (1.0 + mu),
            inputs["moon_orbit_eccentricity"],
            math.radians(inputs["moon_inclination_deg"]),
        ),
    }
    values: dict[str, float] = {}
    for name, (gm_over_a3, e, incl) in bodies.items():
        values[f"M_{name}/C (formula)"] = 1.5 * gm_over_a3 * orbit_factor(e, incl) * H * math.sin(eps) * math.cos(eps)
        values[f"M_{name}/C (summed)"] = summed_moment_per_C(
            gm_over_a3=gm_over_a3, eccentricity=e, inclination_rad=incl, ellipticity=H, obliquity_rad=eps
        )
    return Step(
        "Check: the formula's averaged moment against the instantaneous moment summed over the orbit",
        r"\frac{\langle M\rangle}{C} = \sum_k \frac{\Delta t_k}{T}\;3\,\frac{GM}{a^3}\,H\left(\frac{a}{r_k}\right)^3"
        r"(\bar s\cdot\hat r_k)\,(\hat r_k\times\bar s),\qquad \frac{\Delta t_k}{T} = "
        r"\frac{(r_k/a)^2\,\Delta f}{2\pi\sqrt{1-e^2}}",
        values,
        {name: "rad/s²" for name in values},
    )


def solve(inputs: Mapping[str, Any]) -> Solution:
    result = equinox_precession(inputs)
    H, eps_deg, omega = inputs["dynamical_ellipticity"], inputs["obliquity_deg"], inputs["earth_spin_rad_s"]
    mu = inputs["moon_mass_ratio"]
    n_sun = mean_motion_rad_s(inputs["sun_orbital_period_days"])
    n_moon = mean_motion_rad_s(inputs["moon_orbital_period_days"])
    per_year = JULIAN_YEAR_S * ARCSEC_PER_RAD
    total = result.rate_rad_s
    sun_share = result.sun_rate_rad_s / total if total > 0.0 else 0.0
    outputs = {
        "rate_arcsec_per_year": result.rate_arcsec_per_year,
        "period_years": result.period_years,
        "sun_share": sun_share,
        "moon_share": 1.0 - sun_share if total > 0.0 else 0.0,
        "sun_rate_arcsec_per_year": result.sun_rate_rad_s * per_year,
        "moon_rate_arcsec_per_year": result.moon_rate_rad_s * per_year,
        "rate_rad_s": total,
    }
    steps: tuple[Step, ...] = (
        Step(
            "Moment of a distant mass on the oblate Earth, averaged over an orbit",
            r"\langle M \rangle = \frac{3GM}{2a^3(1-e^2)^{3/2}}\,(C-A)\sin\varepsilon\cos\varepsilon\;P_2(\cos i)",
            {"ε": eps_deg, "H = (C−A)/C": H},
            {"ε": "deg", "H = (C−A)/C": ""},
        ),
        Step(
            "GM/a³ from Kepler's third law (no G, no masses needed)",
            r"\frac{GM_\odot}{a_\odot^3} = n_\odot^2, \qquad \frac{GM_{☾}}{a_{☾}^3} = "
            r"n_{☾}^2\,\frac{\mu}{1+\mu}, \qquad n = \frac{2\pi}{T}",
            {"n_sun": n_sun, "n_moon": n_moon, "μ/(1+μ)": mu / (1.0 + mu)},
            {"n_sun": "rad/s", "n_moon": "rad/s", "μ/(1+μ)": ""},
        ),
        Step(
            "Gyroscopic precession: the moment turns the spin angular momentum Cω about the ecliptic normal",
            r"\Omega = \frac{\langle M\rangle}{C\,\omega\sin\varepsilon} = "
            r"\frac{3}{2}\,\frac{GM}{a^3}\,\frac{H}{\omega}\cos\varepsilon\;\frac{P_2(\cos i)}{(1-e^2)^{3/2}}",
            {"Ω_sun": result.sun_rate_rad_s, "Ω_moon": result.moon_rate_rad_s, "ω": omega},
            {"Ω_sun": "rad/s", "Ω_moon": "rad/s", "ω": "rad/s"},
        ),
        Step(
            "Per year, and the time for the axis to sweep its whole cone",
            r"\Omega_{\mathrm{yr}} = (\Omega_\odot + \Omega_{☾})\times 365.25\,\mathrm{d} \times "
            r"206265''/\mathrm{rad}, \qquad T = \frac{1296000''}{\Omega_{\mathrm{yr}}}",
            {
                "Ω": outputs["rate_arcsec_per_year"],
                "T": outputs["period_years"],
                "Sun's share": outputs["sun_share"],
                "Moon's share": outputs["moon_share"],
            },
            {"Ω": "arcsec/yr", "T": "yr", "Sun's share": "", "Moon's share": ""},
        ),
    )
    steps += (_check_step(inputs),)
    warning = averaged_model_warning(inputs, result)
    if warning:
        steps += (
            Step(
                f"Warning. {warning}",
                r"\frac{\Omega}{\omega} \ll 1 \quad\text{(gyroscopic approximation)}",
                {"Ω/ω": total / omega, "limit": GYROSCOPIC_RATIO_LIMIT},
                {"Ω/ω": "", "limit": ""},
            ),
        )
    obliquities = np.linspace(0.0, 89.0, 90)
    sweep = np.array(
        [equinox_precession({**inputs, "obliquity_deg": float(e)}).rate_arcsec_per_year for e in obliquities]
    )
    plot = Plot(
        "Precession rate against obliquity (other inputs as set)",
        "obliquity ε (deg)",
        "rate (arcsec/yr)",
        (PlotSeries("Sun + Moon", obliquities, sweep),),
    )
    return Solution(outputs=outputs, steps=steps, plots=(plot,))


EXAMPLE = WorkedExample(
    id="equinox-precession",
    title="Precession of the equinoxes",
    chapter=10,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "rate_arcsec_per_year": "arcsec/yr",
        "period_years": "yr",
        "sun_share": "",
        "moon_share": "",
        "sun_rate_arcsec_per_year": "arcsec/yr",
        "moon_rate_arcsec_per_year": "arcsec/yr",
        "rate_rad_s": "rad/s",
    },
    section="10.2",
    story=ExampleStory(
        situation=(
            "The Earth spins once a sidereal day about an axis tilted $\\varepsilon \\approx 23.4°$ from the normal "
            "to its orbit. It is not a sphere: its polar moment $C$ exceeds its equatorial moment $A$ by the fraction "
            "$H = (C - A)/C \\approx 0.00327$. The Sun, and the Moon on its orbit tilted $5.1°$ to the ecliptic, "
            "pull harder on the near side of this equatorial bulge than on the far side. We know the orbital periods, "
            "the eccentricities, the Moon-to-Earth mass ratio and the spin rate."
        ),
        wanted=(
            "The rate at which the spin axis swings round the ecliptic normal, in arcseconds per year, the time it "
            "takes to go once round its cone (about 26 000 years), and how that rate divides between the Sun and "
            "the Moon."
        ),
        approach=(
            "The torque wobbles over a month and a year, while the axis moves only about $50''$ a year, so we average "
            "the gravity-gradient moment over each orbit (and over the Moon's 18.6-year node cycle) before using it. "
            "The spin angular momentum $C\\omega$ is some ten million times the rest of $\\bar H_G$, so the "
            "averaged moment simply turns $\\bar H_G$ sideways: $\\Omega = \\langle M\\rangle/(C\\omega\\sin"
            "\\varepsilon)$, the gyroscopic approximation of a fast top. Kepler's third law replaces $GM/a^3$ by the "
            "square of the orbital rate, so neither $G$ nor a mass in kilograms is needed. Integrating Euler's "
            "equations with the real torque instead would need time steps well under a day over thousands of years "
            "to find a drift the averaging gives in one line."
        ),
        check=(
            "The first step's formula for the averaged moment comes from integrating by hand. The check builds the "
            "same average a second way: it places the Sun (or the Moon) at 64 points round its orbit, evaluates the "
            "instantaneous moment $3(GM/r^5)(C - A)(\\bar s\\cdot\\bar r)(\\bar r\\times\\bar s)$ at each, "
            "weights each point by the time the body spends there, and sums (for the Moon, over 64 node positions "
            "too). Both sides, per unit $C$ in rad/s², must agree to rounding, because the weighted moment is a "
            "short trigonometric sum that equally spaced points average exactly."
        ),
        what_if=(
            "Move the **obliquity ε**. The rate goes as $\\cos\\varepsilon$, so a smaller tilt gives a slightly "
            "faster precession, and the plot under the steps shows the whole curve. The torque itself goes as "
            "$\\sin\\varepsilon\\cos\\varepsilon$ and vanishes at $0°$: with no tilt nothing pulls the "
            "bulge, and both sides of the check fall to zero. In the scene, watch the cone the axis sweeps narrow "
            "or widen and the torque arrows shrink as the tilt goes to zero. Then set the Moon's mass ratio to 0 "
            "and see the Sun alone give about a third of the rate."
        ),
    ),
)
