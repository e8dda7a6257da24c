"""Range-Doppler processing and noise-floor domain randomization as torch transforms.

Transforms take tensors or torchvision-v2-style samples; their kernels are plain functions in
:mod:`radaraug.transforms.functional`. dB values follow ``radaraug.units.DB_CONVENTION`` (dBFS).
See docs/transforms.md.
"""

from radaraug.transforms import functional
from radaraug.transforms._motion import MotionWarning
from radaraug.transforms._rng import use_generator
from radaraug.transforms.base import RadarTransform, RandomRadarTransform
from radaraug.transforms.compose import RadarCompose
from radaraug.transforms.dr import CalibratedDR, RandomDR
from radaraug.transforms.floor import FloorRelative
from radaraug.transforms.image import ClipNormalize, Colormap, MaxResize, Resize
from radaraug.transforms.per_item import augmentation_generator
from radaraug.transforms.spectral import (
    CombineRx,
    DopplerFFT,
    InterferenceExcision,
    RangeDoppler,
    RangeFFT,
    RemoveMean,
    StaticClutterRemoval,
    ToDecibels,
)
from radaraug.transforms.windows import WINDOWS, get_window, noise_power_gain

__all__ = [
    "functional",
    "use_generator",
    "augmentation_generator",
    "RadarTransform",
    "RandomRadarTransform",
    "RadarCompose",
    "RemoveMean",
    "StaticClutterRemoval",
    "InterferenceExcision",
    "RangeFFT",
    "DopplerFFT",
    "RangeDoppler",
    "ToDecibels",
    "CombineRx",
    "RandomDR",
    "CalibratedDR",
    "MotionWarning",
    "FloorRelative",
    "ClipNormalize",
    "Colormap",
    "MaxResize",
    "Resize",
    "WINDOWS",
    "get_window",
    "noise_power_gain",
]
