"""Per-item reproducible augmentation (public home of :mod:`radaraug._augmentation`; docs/transforms.md)."""

from __future__ import annotations

from radaraug._augmentation import (
    AUGMENTATION_MODES,
    augmentation_generator,
    augmentation_seed,
    check_augmentation,
    check_epoch,
    transform_item,
)

__all__ = [
    "AUGMENTATION_MODES",
    "augmentation_generator",
    "augmentation_seed",
    "check_augmentation",
    "check_epoch",
    "transform_item",
]
