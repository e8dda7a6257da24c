"""Moved: the floor fit lives in :mod:`radaraug.calibration.floor_fit` (this path keeps working)."""

from radaraug.calibration.floor_fit import QUANTILES, floor_statistics, floor_values, matched_floor_quantiles
from radaraug.transforms._motion import MotionWarning

__all__ = ["QUANTILES", "MotionWarning", "floor_statistics", "floor_values", "matched_floor_quantiles"]
