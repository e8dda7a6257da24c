"""A spur tone at the ADC: a line at one beat frequency in every chirp (a clock, a switching supply)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import SpurTone
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect, band, first, fit_band
from radaraug.sim.priors import log_uniform, span, uniform


@dataclass
class SpurTonePrior(CatalogEffect):
    """Draws a :class:`~radaraug.sensor.effects.SpurTone`.

    Args:
        probability: per-item chance.
        freq_nyquist: its frequency as a fraction of Nyquist (``freq_Hz = freq_nyquist * fs / 2``), so
            that the draw does not depend on the config.
        amplitude_counts: its peak amplitude at the ADC, counts (drawn in the logarithm).
    """

    name = "spur_tone"
    probability: float = 0.3
    freq_nyquist: tuple[float, float] = span(0.01, 0.99, bounds=(0.0, 1.0))
    amplitude_counts: tuple[float, float] = span(0.3, 5.0, positive=True)

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """Frequency (fraction of Nyquist), amplitude (log), phase, in that order."""
        return {"freq_nyquist": uniform(self.freq_nyquist, g), "amplitude_counts": log_uniform(self.amplitude_counts, g),
                "phase_rad": uniform((-math.pi, math.pi), g)}

    @classmethod
    def record(cls, values: Mapping[str, Any], config: RadarConfig) -> dict[str, Any]:
        """The frequency in Hz at ``config``'s sample rate."""
        return {"freq_Hz": values["freq_nyquist"] * float(config.sample_rate_Hz) / 2,
                "amplitude_counts": values["amplitude_counts"], "phase_rad": values["phase_rad"]}

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """One :class:`~radaraug.sensor.effects.SpurTone`."""
        return [SpurTone(**cls.record(values, config))]

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """A band of +-0.02 Nyquist around the fitted frequency, 2x around its amplitude."""
        if "freq_Hz" not in fitted:
            return None
        frac = first(fitted["freq_Hz"]) / (float(config.sample_rate_Hz) / 2)
        return {"probability": probability, "freq_nyquist": band(frac, 0.02, 0.0, 1.0),
                "amplitude_counts": fit_band(fitted, "amplitude_counts", 1.0, 0.05, 200.0)}
