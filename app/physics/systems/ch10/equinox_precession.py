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
from app.physics.core.solution import Plot, PlotSeries, Solution, Step, WorkedExample

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
)
