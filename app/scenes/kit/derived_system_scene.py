"""Base for scenes of catalogue systems integrated from derived equations: the formulations' agreement readout.

Every available formulation's right-hand side is evaluated on the running
state and compared with the one driving the motion (the model's
``agreement``). That costs a few plain-Python evaluations, so it is sampled
every :data:`AGREEMENT_EVERY_FRAMES` frames, never per frame.
"""

from __future__ import annotations

from abc import abstractmethod

from app.physics.core.readout import Quantity
from app.physics.mechanics.derivation import FORMULATIONS
from app.physics.mechanics.model import DerivedModel
from app.scenes.kit.integrated import IntegratedScene

#: The agreement is re-evaluated at 2 Hz (every 15th frame at 30 Hz).
AGREEMENT_EVERY_FRAMES = 15


class DerivedSystemScene(IntegratedScene):
    """An integrated scene whose model is a :class:`~app.physics.mechanics.model.DerivedModel`."""

    run_model: DerivedModel

    @abstractmethod
    def _draw(self) -> None:
        """Move the drawing to :attr:`run`'s current state (called after each successful frame)."""

    def restart(self) -> None:
        super().restart()
        self._agreement: dict[str, float] = {}
        self._agreement_frame = -AGREEMENT_EVERY_FRAMES

    def formulation_agreement(self) -> dict[str, float]:
        """Per formulation, |ẏ_f − ẏ_running| / |ẏ_running| on the current state (sampled, see module doc)."""
        if self._frames - self._agreement_frame >= AGREEMENT_EVERY_FRAMES:
            self._agreement = self.run_model.agreement(self.physical_params(), self.run.y, self.run.t_s)
            self._agreement_frame = self._frames
        return self._agreement

    def agreement_quantities(self) -> list[Quantity]:
        """One readout row per other formulation, and the worst of them, dimensionless."""
        running = self.params["formulation"]
        agreement = self.formulation_agreement()
        rows = [
            Quantity(f"agreement_{f.replace('-', '_')}", f"{f} vs {running}: relative difference of ẏ", agreement[f])
            for f in FORMULATIONS
            if f in agreement and f != running
        ]
        worst = max((agreement[f] for f in agreement if f != running), default=0.0)
        return [Quantity("formulation_agreement", "largest difference between formulations", worst), *rows]

    def drift_quantity(self, invariant: str, label: str) -> Quantity:
        """The invariant's drift since the start, relative to its scale (dimensionless)."""
        return Quantity(f"{invariant}_drift", label, self.current_drift()[invariant])
