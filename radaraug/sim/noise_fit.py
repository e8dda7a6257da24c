"""Moved: the twin's noise fit lives in :mod:`radaraug.calibration.noise_fit` (this path keeps working)."""

from radaraug.calibration.noise_fit import (
    NOISE_FIGURE_LIMITS_DB,
    capture_noise_floor_db,
    fit_noise_figure,
    noise_fit_receiver,
)

__all__ = ["NOISE_FIGURE_LIMITS_DB", "capture_noise_floor_db", "fit_noise_figure", "noise_fit_receiver"]
