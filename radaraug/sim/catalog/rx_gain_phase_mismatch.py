"""Gain and phase offsets between the RX channels, on top of the receiver's own."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import RxGainPhaseMismatch
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect
from radaraug.sim.priors import span, uniform

MISMATCH_ANTENNAS = 16
"""Values are drawn for antenna numbers 1..16 (``radaraug.config.MAX_ANTENNAS``), whatever the config, so
that the draws do not depend on it; a config's RX channels take their antennas' values."""


@dataclass
class RxGainPhaseMismatchPrior(CatalogEffect):
    """Draws an :class:`~radaraug.sensor.effects.RxGainPhaseMismatch`.

    Args:
        probability: per-item chance.
        gain_dB: each antenna's gain offset, dB.
        phase_deg: each antenna's phase offset, degrees.
    """

    name = "rx_gain_phase_mismatch"
    probability: float = 0.3
    gain_dB: tuple[float, float] = span(-1.5, 1.5)
    phase_deg: tuple[float, float] = span(-30.0, 30.0, bounds=(-180.0, 180.0))

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """16 gains, then 16 phases (one per antenna number)."""
        gains = tuple(uniform(self.gain_dB, g) for _ in range(MISMATCH_ANTENNAS))
        phases = tuple(uniform(self.phase_deg, g) for _ in range(MISMATCH_ANTENNAS))
        return {"gain_dB": gains, "phase_deg": phases}

    @classmethod
    def record(cls, values: Mapping[str, Any], config: RadarConfig) -> dict[str, Any]:
        """The values of ``config``'s RX antennas."""
        return {"gain_dB": [values["gain_dB"][a - 1] for a in config.rx_antennas],
                "phase_deg": [values["phase_deg"][a - 1] for a in config.rx_antennas]}

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """One :class:`~radaraug.sensor.effects.RxGainPhaseMismatch` (phases in radians)."""
        rec = cls.record(values, config)
        return [RxGainPhaseMismatch(gain_dB=rec["gain_dB"], phase_rad=[math.radians(p) for p in rec["phase_deg"]])]

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """The fitted gains +-0.5 dB and phases +-10 degrees."""
        g_raw, ph_raw = fitted.get("gain_dB"), fitted.get("phase_rad")
        gains = [float(v) for v in (g_raw if isinstance(g_raw, list) else [0.0 if g_raw is None else g_raw])]
        phases = [math.degrees(float(v)) for v in
                  (ph_raw if isinstance(ph_raw, list) else [0.0 if ph_raw is None else ph_raw])]
        return {"probability": probability,
                "gain_dB": (max(min(gains) - 0.5, -6.0), min(max(gains) + 0.5, 6.0)),
                "phase_deg": (max(min(phases) - 10.0, -180.0), min(max(phases) + 10.0, 180.0))}
