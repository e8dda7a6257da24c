"""The kernels behind radaraug's transforms, as plain functions with explicit parameters.

Like ``torchvision.transforms.v2.functional``: for parameters of your own (a fixed floor, a known clip
range). Any leading batch dims, dtype and device kept, inputs never modified; type, dtype and rank are
checked (:class:`~radaraug.errors.InputTensorError`) but, unlike the classes, not NaN/Inf.

Examples:
    >>> import torch
    >>> from radaraug.transforms import functional as F
    >>> db = F.to_decibels(F.range_doppler(0.01 * torch.randn(4, 3, 64, 256)))
    >>> rgb = F.colormap(F.clip_normalize(F.combine_rx(F.dr_clamp(db, torch.tensor(-100.0)), db=True), -120, -40))
    >>> F.resize(rgb, (224, 224)).shape
    torch.Size([4, 3, 224, 224])
"""

from radaraug.transforms.functional._dr import calibrated_floor, dr_clamp, empirical_floor, random_floor
from radaraug.transforms.functional._floor import floor_relative, persistent_cells
from radaraug.transforms.functional._image import clip_normalize, colormap, colormap_lut, max_resize, resize
from radaraug.transforms.functional._spectral import (
    combine_rx,
    doppler_fft,
    interference_excision,
    range_doppler,
    range_fft,
    remove_mean,
    static_clutter_removal,
    to_decibels,
)

__all__ = [
    "remove_mean",
    "static_clutter_removal",
    "interference_excision",
    "range_fft",
    "doppler_fft",
    "range_doppler",
    "to_decibels",
    "combine_rx",
    "dr_clamp",
    "calibrated_floor",
    "empirical_floor",
    "random_floor",
    "floor_relative",
    "persistent_cells",
    "clip_normalize",
    "colormap",
    "colormap_lut",
    "max_resize",
    "resize",
]
