"""Deterministic per-item seeds: a simulated item is a pure function of (seed, index).

The seed of item ``i`` does not depend on which worker, process or DDP rank computes it, so a
dataset gives the same items however it is split. SplitMix64 mixes the pair so that nearby
(seed, index) pairs give unrelated streams.
"""

from __future__ import annotations

import torch

_MASK = (1 << 64) - 1


def splitmix64(x: int) -> int:
    """One SplitMix64 step (Steele, Lea & Flood 2014) on a 64-bit integer."""
    x = (x + 0x9E3779B97F4A7C15) & _MASK
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & _MASK
    return x ^ (x >> 31)


def item_seed(seed: int, index: int, stream: int = 0) -> int:
    """A 63-bit seed for item ``index`` of a dataset seeded ``seed`` (``stream`` separates uses)."""
    return splitmix64(splitmix64(splitmix64(seed & _MASK) ^ (index & _MASK)) ^ stream) >> 1


def item_generator(seed: int, index: int, stream: int = 0, device: torch.device | str = "cpu") -> torch.Generator:
    """A fresh ``torch.Generator`` for (seed, index, stream)."""
    g = torch.Generator(device=device)
    g.manual_seed(item_seed(seed, index, stream))
    return g
