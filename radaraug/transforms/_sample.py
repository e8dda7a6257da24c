"""Samples like torchvision v2: a tensor, or any nesting of tuples, lists and dicts (a pytree).

Its radar leaves are the first eligible floating tensor and every other of exactly that shape; the rest
passes through (docs/transforms.md, "Samples").
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import torch
from torch import nn
from torch.utils import _pytree as pytree

from radaraug.errors import InputTensorError


def as_sample(inputs: tuple[Any, ...]) -> Any:
    """The sample of a call ``t(*inputs)``: the one argument, or the tuple of several."""
    if not inputs:
        raise InputTensorError("a transform needs a sample: a tensor, or a tuple/list/dict holding one")
    return inputs if len(inputs) > 1 else inputs[0]


def eligible(leaf: Any, min_ndim: int, allow_complex: bool) -> bool:
    """Whether ``leaf`` can be a radar tensor (see the module docstring)."""
    return (
        isinstance(leaf, torch.Tensor)
        and (leaf.is_floating_point() or (allow_complex and leaf.is_complex()))
        and leaf.ndim >= min_ndim
    )


def radar_leaves(flat: list[Any], accepts: Callable[[Any], bool]) -> list[int]:
    """Indices of the radar leaves of a flattened sample (empty when none is eligible)."""
    first = next((i for i, leaf in enumerate(flat) if accepts(leaf)), None)
    if first is None:
        return []
    shape = flat[first].shape
    return [first] + [i for i in range(first + 1, len(flat)) if accepts(flat[i]) and flat[i].shape == shape]


def most_likely_radar_leaf(flat: list[Any], min_ndim: int) -> Any:
    """For an error message: the first tensor with at least ``min_ndim`` dims, else the first tensor."""
    tensors = [leaf for leaf in flat if isinstance(leaf, torch.Tensor)]
    return next((t for t in tensors if t.ndim >= min_ndim), tensors[0] if tensors else None)


def is_sample_aware(module: Any) -> bool:
    """Whether ``module`` takes a whole sample, not each radar tensor of it.

    True for torchvision v2 transforms, ``nn.Sequential``s of such modules, and radaraug's modules, which
    say so with ``takes_samples = True`` (read here: importing their classes would import this module).
    """
    if getattr(module, "takes_samples", False) is True:
        return True
    if isinstance(module, nn.Sequential):
        return all(is_sample_aware(m) for m in module)
    # torchvision v2 transforms flatten samples themselves; checked by name so that radaraug
    # does not import torchvision here.
    return any(c.__module__.startswith("torchvision.transforms.v2") for c in type(module).__mro__)


def apply_to_radar_leaves(fn: Callable[[torch.Tensor], Any], sample: Any, min_ndim: int = 2) -> Any:
    """``fn`` applied to a plain tensor, or to each radar leaf (floating, >= ``min_ndim`` dims) of ``sample``."""
    if isinstance(sample, torch.Tensor):
        return fn(sample)
    flat, spec = pytree.tree_flatten(sample)
    chosen = radar_leaves(flat, lambda leaf: eligible(leaf, min_ndim, True))
    if not chosen:
        raise InputTensorError(
            f"{type(fn).__name__}: the sample ({type(sample).__name__}) holds no floating tensor with at least "
            f"{min_ndim} dims to transform"
        )
    for i in chosen:
        flat[i] = fn(flat[i])
    return pytree.tree_unflatten(flat, spec)
