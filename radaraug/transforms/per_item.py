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
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import torch

from radaraug._seeding import mix
from radaraug.errors import ConfigError
from radaraug.transforms._rng import use_generator

AUGMENTATION_MODES = ("stream", "per_item")
_TAG = 0x41554721  # separates these seeds from every other use of (seed, index)


def check_augmentation(mode: Any, where: str) -> str:
    """``mode`` if it is one of :data:`AUGMENTATION_MODES`, else :class:`ConfigError`."""
    if mode not in AUGMENTATION_MODES:
        raise ConfigError(f"{where}: augmentation must be 'stream' or 'per_item', got {mode!r}")
    return mode


def check_epoch(epoch: Any, where: str) -> int:
    """A non-negative integer epoch, else :class:`ConfigError`."""
    if isinstance(epoch, bool) or not isinstance(epoch, (int, np.integer)) or epoch < 0:
        raise ConfigError(f"{where}: epoch must be a non-negative integer, got {epoch!r}")
    return int(epoch)


def augmentation_seed(seed: int, index: int, epoch: int = 0) -> int:
    """The 63-bit seed of item ``index``'s augmentation in ``epoch`` (a pure function of the three).

    :func:`radaraug._seeding.mix` of ``(seed, index, epoch, tag)``: the same SplitMix64 mixer as the
    simulated items' seeds, with a fourth word so that the two never coincide.
    """
    return mix(seed, index, epoch, _TAG)


def augmentation_generator(
    seed: int, index: int, epoch: int = 0, device: torch.device | str = "cpu"
) -> torch.Generator:
    """A fresh generator seeded with :func:`augmentation_seed` on ``device``."""
    g = torch.Generator(device=device)
    g.manual_seed(augmentation_seed(seed, index, epoch))
    return g


def transform_item(
    transform: Callable[[Any], Any],
    x: Any,
    *,
    mode: str,
    seed: int,
    index: int,
    epoch: int,
    device: torch.device | str = "cpu",
) -> Any:
    """``transform(x)``, with its random draws from ``(seed, index, epoch)`` in ``"per_item"`` mode."""
    if mode != "per_item":
        return transform(x)
    with use_generator(augmentation_generator(seed, index, epoch, device=device)):
        return transform(x)
