"""The exceptions radaraug raises for bad input.

Every problem with user input (a file, a config, a tensor, a calibration) surfaces as one of
these types, with a message that names the file (when there is one) and what is wrong. All of
them derive from :class:`RadarAugError`, and from :class:`ValueError` so that generic
``except ValueError`` handlers keep working.

=================================  ==========================================================
exception                          raised when
=================================  ==========================================================
:class:`ConfigError`               a radar configuration is invalid, missing or inconsistent
:class:`CaptureError`              a capture file/folder is missing, truncated, corrupted,
                                   empty, or its data does not match its configuration
:class:`InputTensorError`          a tensor has the wrong rank/dtype/shape or holds NaN/Inf
:class:`CalibrationError`          a calibration (CalibratedDR JSON, twin profile) is
                                   unreadable or does not fit the data it is applied to
:class:`SceneError`                a scene description or mesh is invalid
:class:`DeviceError`               a radar board cannot be found, opened or read (USB backend
                                   missing, no permission, SDK not installed, board unplugged)
=================================  ==========================================================

One error is about the environment, not the input: :class:`DependencyNotFoundError` (a
``ModuleNotFoundError``, so ``except ImportError`` catches it; not a ``RadarAugError``) is raised
when a feature needs a package that is not installed, and names the package and the ``pip``
command that installs it.
"""

from __future__ import annotations


class RadarAugError(ValueError):
    """Base class of every error radaraug raises for bad input."""


class ConfigError(RadarAugError):
    """A radar configuration is invalid, missing, or does not match the data."""


class CaptureError(RadarAugError):
    """A capture file or recording folder cannot be read as what it claims to be."""


class InputTensorError(RadarAugError):
    """A tensor given to radaraug has the wrong rank, dtype or shape, or holds NaN/Inf."""


class CalibrationError(RadarAugError):
    """A calibration file is unreadable or does not match the data it is applied to."""


class SceneError(RadarAugError):
    """A scene description, mesh or motion file is invalid."""


class DependencyNotFoundError(ModuleNotFoundError):
    """A feature needs a package that is not installed (the message names it and how to install it).

    Raised by :func:`radaraug._optional.lazy_import`. A ``ModuleNotFoundError`` (so generic
    ``except ImportError`` handlers keep working), not a :class:`RadarAugError`: the input is
    fine, the environment lacks something.
    """


class DeviceError(RadarAugError):
    """A radar board cannot be found, opened, configured or read (live capture)."""
