"""Frame-to-frame drift of the receiver's gain and DC level (temperature, supply)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import FrameDrift
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect, fit_band
from radaraug.sim.priors import span, uniform


@dataclass
class FrameDriftPrior(CatalogEffect):
    """Draws a :class:`~radaraug.sensor.effects.FrameDrift`.

    Args:
        probability: per-item chance.
        gain_rms_dB: its per-frame gain RMS, dB.
        dc_rms_counts: its per-RX DC shift RMS, counts.
    """

    name = "frame_drift"
    probability: float = 0.3
    gain_rms_dB: tuple[float, float] = span(0.1, 1.0, bounds=(0.0, float("inf")))
    dc_rms_counts: tuple[float, float] = span(0.2, 4.0, bounds=(0.0, float("inf")))

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """Gain RMS, then DC RMS."""
        return {"gain_rms_dB": uniform(self.gain_rms_dB, g), "dc_rms_counts": uniform(self.dc_rms_counts, g)}

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """One :class:`~radaraug.sensor.effects.FrameDrift`."""
        return [FrameDrift(**values)]

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """Bands of 2x around the fitted gain and DC RMS."""
        return {"probability": probability,
                "gain_rms_dB": fit_band(fitted, "gain_rms_dB", 0.1, 0.0, 3.0),
                "dc_rms_counts": fit_band(fitted, "dc_rms_counts", 0.5, 0.0, 20.0)}
