"""The room's strongest returns carry the item's phase noise (a skirt around strong static lines)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import torch

from radaraug.sim.catalog.base import CatalogEffect


@dataclass
class StaticPhaseNoisePrior(CatalogEffect):
    """Passes the room's strongest returns to the receiver's ``phase_noise`` stage.

    Args:
        probability: per-item chance.
        paths: how many of the room's strongest returns carry it.
    """

    name = "static_phase_noise"
    probability: float = 0.5
    paths: int = 4

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """The number of paths (nothing is drawn)."""
        return {"paths": self.paths}
