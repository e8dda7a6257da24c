"""Receiver levels from wide ranges: a gain, a noise figure and an ADC floor far from the datasheet's."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import torch

from radaraug.sim.catalog.base import CatalogEffect
from radaraug.sim.priors import span, uniform


@dataclass
class WideLevelsPrior(CatalogEffect):
    """Draws the item's levels from wide ranges; they replace the ``levels`` section's offsets.

    Args:
        probability: per-item chance.
        system_gain_offset_dB, noise_figure_offset_dB: the wide ranges of the receiver's gain and noise
            figure offsets, dB.
        adc_noise_offset_dB: offset on the ``adc_noise`` stage's RMS, dB (with the wide levels only).
    """

    name = "wide_levels"
    probability: float = 0.3
    system_gain_offset_dB: tuple[float, float] = span(-12.0, 12.0)
    noise_figure_offset_dB: tuple[float, float] = span(-4.0, 8.0)
    adc_noise_offset_dB: tuple[float, float] = span(-3.0, 3.0)

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """Gain, noise figure and ADC noise offsets, in that order."""
        return {"system_gain_offset_dB": uniform(self.system_gain_offset_dB, g),
                "noise_figure_offset_dB": uniform(self.noise_figure_offset_dB, g),
                "adc_noise_offset_dB": uniform(self.adc_noise_offset_dB, g)}
