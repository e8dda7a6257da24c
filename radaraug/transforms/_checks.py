"""Cheap input checks shared by the transforms (rank, dtype, one finiteness test per call)."""

from __future__ import annotations

import torch

from radaraug.errors import InputTensorError


def check_tensor(
    x: object,
    what: str,
    *,
    min_ndim: int = 3,
    allow_complex: bool = False,
    finite: bool = True,
) -> torch.Tensor:
    """``x`` if it is a floating (or, with ``allow_complex``, complex) tensor of rank >= ``min_ndim``.

    Also refuses an empty event and, with ``finite``, NaN/Inf; raises InputTensorError naming ``what``.
    """
    if not isinstance(x, torch.Tensor):
        raise InputTensorError(f"{what}: expected a torch.Tensor, got {type(x).__name__}")
    if not (x.is_floating_point() or (allow_complex and x.is_complex())):
        kinds = "a real or complex floating" if allow_complex else "a real floating"
        hint = " (convert ADC counts with radaraug.units.counts_to_float)" if not x.is_complex() else ""
        raise InputTensorError(f"{what}: expected {kinds} tensor, got dtype {x.dtype}{hint}")
    if x.ndim < min_ndim:
        raise InputTensorError(f"{what}: expected at least {min_ndim} dims, got shape {tuple(x.shape)}")
    if min_ndim and 0 in x.shape[x.ndim - min_ndim :]:
        # Empty leading (batch) dims are fine; an empty event (0 rx, chirps or samples) is not.
        raise InputTensorError(f"{what}: got an empty event, shape {tuple(x.shape)}")
    # A sum is NaN/Inf whenever any element is (one cheap reduction, no bool temporary); only a
    # non-finite sum -- which a huge but finite input can also give -- pays for the exact test.
    # Meta tensors (shape/device tracing) hold no values to test.
    if (
        finite
        and x.numel()
        and x.device.type != "meta"
        and not bool(torch.isfinite(x.sum()))
        and not bool(torch.isfinite(x).all())
    ):
        raise InputTensorError(f"{what}: input holds NaN or Inf values")
    return x
