"""A vibrating scatterer (a fan, a pump, a swinging lamp): Doppler sidebands at its range."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import VibratingClutter
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect, band, first, fit_band
from radaraug.sim.item_signal import SCATTERER_ANTENNA_GAIN_DBI
from radaraug.sim.priors import log_uniform, span, uniform


def radar_equation_dB(config: RadarConfig, range_m: float, rcs_dBsm: float) -> float:
    """Received over transmitted power of a point scatterer, dB: ``G^2 lambda^2 sigma / ((4 pi)^3 R^4)``.

    With the static scatterers' antenna gain (:data:`~radaraug.sim.item_signal.SCATTERER_ANTENNA_GAIN_DBI`),
    as :func:`~radaraug.sensor.point_target.point_target_paths` gives them.
    """
    lam = float(config.wavelength_m)
    return (2 * SCATTERER_ANTENNA_GAIN_DBI + rcs_dBsm + 20 * math.log10(lam) - 30 * math.log10(4 * math.pi)
            - 40 * math.log10(range_m))


def rcs_dBsm(config: RadarConfig, range_m: float, level_dB: float) -> float:
    """Inverse of :func:`radar_equation_dB`: the RCS of a scatterer received at ``level_dB``."""
    lam = float(config.wavelength_m)
    return (level_dB - 2 * SCATTERER_ANTENNA_GAIN_DBI - 20 * math.log10(lam) + 30 * math.log10(4 * math.pi)
            + 40 * math.log10(max(range_m, 1e-3)))


@dataclass
class VibratingClutterPrior(CatalogEffect):
    """Draws a :class:`~radaraug.sensor.effects.VibratingClutter` at a drawn range and RCS.

    Args:
        probability: per-item chance.
        range_m: its range, m.
        rcs_dBsm: its RCS, dBsm (its level follows from :func:`radar_equation_dB`).
        displacement_m: its peak displacement, m (drawn in the logarithm).
        vibration_Hz: its vibration frequency, Hz (drawn in the logarithm).
    """

    name = "vibrating_clutter"
    probability: float = 0.3
    range_m: tuple[float, float] = span(0.5, 10.0, positive=True)
    rcs_dBsm: tuple[float, float] = span(-20.0, 5.0)
    displacement_m: tuple[float, float] = span(0.1e-3, 3e-3, positive=True)
    vibration_Hz: tuple[float, float] = span(5.0, 60.0, positive=True)

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """Range, RCS, displacement (log), frequency (log), phase, in that order."""
        return {"range_m": uniform(self.range_m, g), "rcs_dBsm": uniform(self.rcs_dBsm, g),
                "displacement_m": log_uniform(self.displacement_m, g), "vibration_Hz": log_uniform(self.vibration_Hz, g),
                "phase_rad": uniform((-math.pi, math.pi), g)}

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """One :class:`~radaraug.sensor.effects.VibratingClutter` at the radar equation's level."""
        params = dict(values)
        level = radar_equation_dB(config, params["range_m"], params.pop("rcs_dBsm"))
        return [VibratingClutter(level_dB=level, **params)]

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """+-1 m around the fitted range, +-6 dB around its RCS, 2x and 1.5x around the rest."""
        if "range_m" not in fitted:
            return None
        r = first(fitted["range_m"])
        rcs = rcs_dBsm(config, r, first(fitted.get("level_dB", -80.0)))
        nyquist_Hz = 1 / (2 * float(config.chirp_repetition_time_s))
        return {"probability": probability, "range_m": band(r, 1.0, 0.3, 30.0), "rcs_dBsm": band(rcs, 6.0, -40.0, 20.0),
                "displacement_m": fit_band(fitted, "displacement_m", 1e-3, 1e-5, 5e-3),
                "vibration_Hz": fit_band(fitted, "vibration_Hz", 20.0, 0.5, nyquist_Hz, 1.5)}
