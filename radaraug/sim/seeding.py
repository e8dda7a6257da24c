"""Deterministic per-item seeds: a simulated item is a pure function of (seed, index).

The seed of item ``i`` does not depend on the worker, process or DDP rank that computes it;
SplitMix64 (:mod:`radaraug._seeding`) mixes the pair so that nearby pairs give unrelated streams.
"""

from __future__ import annotations

from enum import IntEnum

import torch

from radaraug._seeding import mix, splitmix64

__all__ = ["Stream", "splitmix64", "item_seed", "item_generator"]


class Stream(IntEnum):
    """The registry of generator streams: every ``stream=`` of :func:`item_seed` / :func:`item_generator`.

    A stream separates two uses of the same ``(seed, index)``, so that one never shifts another's
    draws. The values are mixed into every recorded simulation's seeds: never renumber a member; give
    a new use a new value. ``index`` means what each member's docstring says.
    """

    SCENARIO = 0
    """Dataset item ``index``: its scenario (people, paths, speeds) from the scenario sampler."""
    ITEM_NOISE = 1
    """Dataset item ``index``: its receiver noise (and the catalog's receiver-side draws)."""
    BLOCK_NOISE = 2
    """Receiver noise of frame block ``index`` of a continuously played scene (``simulate``, virtual sensor, proxy)."""
    ITEM_DRAWS = 3
    """Twin randomization of item ``index``: room variant, gain, noise figure, RCS per person (in that order)."""
    ROOM_POOL = 4
    """Twin randomization: room variant ``index`` of the room pool."""
    SCATTERERS = 5
    """Twin randomization of item ``index``: its static scatterers and phase noise."""
    EFFECTS = 6
    """Twin randomization of item ``index``: its effect catalog (spur, interference, fan, mismatch, drift, levels)."""
    NOISE_FIT = 7
    """Noise-figure fit: receiver noise of empty-room frame ``index``."""
    PROXY_WALKS = 30
    """Held-out proxy: the walks of the file of ``index - 1`` people."""
    PROXY_NOISE = 31
    """Held-out proxy: noise base seed of a file (``index`` 0: calibration, ``c + 1``: ``c`` people)."""


def item_seed(seed: int, index: int, stream: int = Stream.SCENARIO) -> int:
    """A 63-bit seed for item ``index`` of a dataset seeded ``seed`` (``stream``, a :class:`Stream`, separates uses).

    ``splitmix64(splitmix64(splitmix64(seed) ^ index) ^ stream) >> 1``: :func:`radaraug._seeding.mix`
    of the three (the values every recorded simulation was made with).
    """
    return mix(seed, index, stream)


def item_generator(seed: int, index: int, stream: int = Stream.SCENARIO, device: torch.device | str = "cpu") -> torch.Generator:
    """A fresh ``torch.Generator`` for (seed, index, stream)."""
    g = torch.Generator(device=device)
    g.manual_seed(item_seed(seed, index, stream))
    return g
