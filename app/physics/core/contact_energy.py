"""The energy account of a rigid body whose contacts slide with friction and strike with impacts (chapters 6 and 8:
the sliding ladder, the bar sliding on a rough floor): kinetic, potential, and what friction and impacts took."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.physics.core.energy import EnergyParts


@dataclass(frozen=True)
class ContactEnergyBudget:
    """Energies along N states (J, arrays (N,)): their sum ``total_J`` stays at the initial energy.

    Kinetic energy split as ½ m v_G² (translational) and ½ I_G ω² (rotational); ``friction_work_J`` and
    ``impact_loss_J`` are what the contacts have taken since t = 0 (≥ 0)."""

    translational_kinetic_J: np.ndarray
    rotational_kinetic_J: np.ndarray
    potential_J: np.ndarray
    friction_work_J: np.ndarray
    impact_loss_J: np.ndarray

    @property
    def kinetic_J(self) -> np.ndarray:
        return self.translational_kinetic_J + self.rotational_kinetic_J

    @property
    def total_J(self) -> np.ndarray:
        return self.kinetic_J + self.potential_J + self.friction_work_J + self.impact_loss_J

    def parts(self) -> EnergyParts:
        """The mechanical energies, for the model's energy budget (friction and impacts show up as dissipated)."""
        return EnergyParts(
            self.potential_J,
            translational_kinetic_J=self.translational_kinetic_J,
            rotational_kinetic_J=self.rotational_kinetic_J,
        )
