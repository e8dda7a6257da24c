"""Per-item reproducible augmentation: random transforms of item ``i`` drawn from ``(seed, i, epoch)``.

Two modes, chosen with the ``augmentation`` argument of
:class:`~radaraug.sim.dataset.SimulatedRadarDataset` and :class:`~radaraug.io.RadarCaptureDataset`:

``"stream"`` (default)
    A random transform draws from its own source (its ``generator``/``seed``, else torch's global
    RNG), one stream per DataLoader worker (:mod:`radaraug.transforms._rng`). Reproducible for a
    fixed DataLoader setup, but item ``i`` gets other noise with another ``num_workers``, batch
    order or sampler.
``"per_item"``
    The dataset calls its transform inside :func:`~radaraug.transforms._rng.use_generator` with
    :func:`augmentation_generator` ``(seed, index, epoch)``: item ``i`` gets the same augmentation
    with any ``num_workers``, start method, sampler or process, and another one when the epoch
    changes (``dataset.set_epoch(epoch)`` before each epoch, as with a ``DistributedSampler``).

The implementation lives in :mod:`radaraug._augmentation`, a module below ``io``, ``sim`` and
``transforms`` (so that :class:`~radaraug.io.RadarCaptureDataset` scopes its transform without
importing ``radaraug.transforms``); this module is its public home.
"""

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
