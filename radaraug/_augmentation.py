"""Per-item reproducible augmentation: the random draws of item ``i`` from ``(seed, i, epoch)``.

A low-level module below ``io``, ``sim`` and ``transforms``: datasets scope their transform call with
:func:`transform_item`, random transforms read :func:`scoped_generator`. The public names and the two
modes are in :mod:`radaraug.transforms.per_item`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

import numpy as np
import torch

from radaraug._seeding import mix
from radaraug.errors import ConfigError

AUGMENTATION_MODES = ("stream", "per_item")
_TAG = 0x41554721  # separates these seeds from every other use of (seed, index)

_SCOPED: ContextVar[torch.Generator | None] = ContextVar("radaraug_scoped_generator", default=None)


@contextmanager
def use_generator(generator: torch.Generator) -> Iterator[torch.Generator]:
    """Inside the block, every random radaraug transform draws from ``generator``.

    It takes precedence over a transform's own ``generator``/``seed`` and the global RNG, for any nesting
    of transforms, in the current thread / context only.

    Example:
        >>> with use_generator(torch.Generator().manual_seed(7)):  # doctest: +SKIP
        ...     y = pipeline(x)   # CalibratedDR / RandomDR noise drawn from that generator
    """
    if not isinstance(generator, torch.Generator):
        raise TypeError(f"use_generator needs a torch.Generator, got {type(generator).__name__}")
    token = _SCOPED.set(generator)
    try:
        yield generator
    finally:
        _SCOPED.reset(token)


def scoped_generator() -> torch.Generator | None:
    """The generator of the innermost :func:`use_generator` block (None outside any)."""
    return _SCOPED.get()


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
    """The 63-bit seed of item ``index``'s augmentation in ``epoch``: :func:`radaraug._seeding.mix` of the three.

    A fourth, tag word keeps it apart from the simulated items' seeds.
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
