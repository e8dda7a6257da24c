"""The exceptions radaraug raises for bad input.

Each derives from :class:`RadarAugError` and from :class:`ValueError` (so ``except ValueError`` keeps
working), with a message naming the file, if any, and the problem. The CLI turns them into exit status 3.
"""

from __future__ import annotations


class RadarAugError(ValueError):
    """Base class of every error radaraug raises for bad input."""


class ConfigError(RadarAugError):
    """A radar configuration is invalid, missing, or does not match the data."""


class CaptureError(RadarAugError):
    """A capture file or folder is missing, truncated, corrupted, empty, or does not match its config."""


class InputTensorError(RadarAugError):
    """A tensor given to radaraug has the wrong rank, dtype or shape, or holds NaN/Inf."""


class CalibrationError(RadarAugError):
    """A calibration (CalibratedDR JSON, twin profile) is unreadable or does not fit the data it is applied to."""


class SceneError(RadarAugError):
    """A scene description, mesh or motion file is invalid."""


class DependencyNotFoundError(ModuleNotFoundError):
    """A feature needs a package that is not installed (the message names it and how to install it).

    A ``ModuleNotFoundError`` (``except ImportError`` catches it), not a :class:`RadarAugError`: the input
    is fine, the environment lacks something. Raised by :func:`radaraug._optional.lazy_import`.
    """


class DeviceError(RadarAugError):
    """A radar board cannot be found, opened, configured or read (no USB backend or permission, unplugged)."""


class CheckpointError(RadarAugError):
    """A classifier file is missing, truncated, foreign, unsafe to load, or does not match the data given to it."""
