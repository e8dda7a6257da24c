"""radaraug: trainable FMCW radar perception from simulation.

A torch digital twin of an FMCW radar scene, range-Doppler transforms, calibrated domain
randomization (CDR) and real-capture Datasets for the Infineon BGT60TR13C.
"""

from radaraug.config import RadarConfig
from radaraug.errors import (
    CalibrationError,
    CaptureError,
    ConfigError,
    InputTensorError,
    RadarAugError,
    SceneError,
)

__version__ = "0.1.0"

__all__ = [
    "RadarConfig",
    "RadarAugError",
    "ConfigError",
    "CaptureError",
    "InputTensorError",
    "CalibrationError",
    "SceneError",
    "__version__",
]
