"""Another radar's chirps crossing ours: bursts in a fraction of the chirps."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import Interference
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect, fit_band
from radaraug.sim.priors import log_uniform, span, uniform


@dataclass
class InterferencePrior(CatalogEffect):
    """Draws an :class:`~radaraug.sensor.effects.Interference`.

    Args:
        probability: per-item chance.
        chirp_probability: the fraction of chirps it hits (the stage's ``probability``).
        amplitude_counts: peak burst amplitude after the IF gain, counts (drawn in the logarithm).
        duration_s: burst length, s (drawn in the logarithm).
    """

    name = "interference"
    probability: float = 0.3
    chirp_probability: tuple[float, float] = span(0.01, 0.3, bounds=(0.0, 1.0))
    amplitude_counts: tuple[float, float] = span(5.0, 1000.0, positive=True)
    duration_s: tuple[float, float] = span(0.5e-6, 20e-6, positive=True)

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """Chirp fraction, amplitude (log), duration (log), in that order."""
        return {"probability": uniform(self.chirp_probability, g),
                "amplitude_counts": log_uniform(self.amplitude_counts, g),
                "duration_s": log_uniform(self.duration_s, g)}

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """One :class:`~radaraug.sensor.effects.Interference`."""
        return [Interference(**values)]

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """Bands of 2x around the fitted chirp fraction, amplitude and duration."""
        return {"probability": probability,
                "chirp_probability": fit_band(fitted, "probability", 0.05, 1e-3, 1.0),
                "amplitude_counts": fit_band(fitted, "amplitude_counts", 100.0, 1.0, 2000.0),
                "duration_s": fit_band(fitted, "duration_s", 5e-6, 0.2e-6, 30e-6)}
