"""Deterministic per-item seeds: a simulated item is a pure function of (seed, index).

The seed of item ``i`` does not depend on which worker, process or DDP rank computes it, so a
dataset gives the same items however it is split. SplitMix64 mixes the pair so that nearby
(seed, index) pairs give unrelated streams (:mod:`radaraug._seeding`, the mixer the transforms
use too).
"""

from __future__ import annotations

import torch

from radaraug._seeding import mix, splitmix64

__all__ = ["splitmix64", "item_seed", "item_generator"]


def item_seed(seed: int, index: int, stream: int = 0) -> int:
    """A 63-bit seed for item ``index`` of a dataset seeded ``seed`` (``stream`` separates uses).

    ``splitmix64(splitmix64(splitmix64(seed) ^ index) ^ stream) >> 1``: :func:`radaraug._seeding.mix`
    of the three (the values every recorded simulation was made with).
    """
    return mix(seed, index, stream)


def item_generator(seed: int, index: int, stream: int = 0, device: torch.device | str = "cpu") -> torch.Generator:
    """A fresh ``torch.Generator`` for (seed, index, stream)."""
    g = torch.Generator(device=device)
    g.manual_seed(item_seed(seed, index, stream))
    return g
