"""Validation of raw ADC counts and timestamps handed to the capture writers."""

from __future__ import annotations

from typing import Any

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, InputTensorError
from radaraug.files import safe_repr


def as_counts(data: Any, config: RadarConfig, where: str) -> np.ndarray:
    """Validate ADC counts ``(rx, chirps, samples)`` or ``(k, rx, chirps, samples)`` -> uint16 4-D.

    Args:
        data: integer numpy array or torch tensor of raw ADC codes (any device).
        config: the radar configuration the counts must match.
        where: the file being written, for error messages.

    Raises:
        InputTensorError: not an integer array, wrong rank/shape, or codes outside
            ``0..2**adc_bits-1``.
    """
    if isinstance(data, torch.Tensor):
        if data.is_floating_point() or data.is_complex() or data.dtype == torch.bool:
            raise InputTensorError(
                f"{where}: frames must be integer ADC counts, got a {data.dtype} tensor "
                "(convert SDK floats with radaraug.units.float_to_counts)"
            )
        data = data.detach().to("cpu", torch.int64).numpy()
    arr = np.asarray(data)
    if arr.dtype.kind not in "ui":
        raise InputTensorError(
            f"{where}: frames must be integer ADC counts, got dtype {arr.dtype} "
            "(convert SDK floats with radaraug.units.float_to_counts)"
        )
    if arr.ndim == 3:
        arr = arr[None]
    frame_shape = config.frame_shape
    if arr.ndim != 4 or arr.shape[1:] != frame_shape:
        raise InputTensorError(
            f"{where}: frames have shape {tuple(np.shape(data))}, expected (rx, chirps, samples) = "
            f"{frame_shape} or a block (k, {', '.join(map(str, frame_shape))}) for this radar config"
        )
    if arr.shape[0] == 0:
        raise InputTensorError(f"{where}: empty block of frames")
    full = config.adc_full_scale_counts
    lo, hi = int(arr.min()), int(arr.max())
    if lo < 0 or hi > full:
        raise InputTensorError(
            f"{where}: ADC counts span {lo}..{hi}, outside the {config.adc_bits}-bit code range 0..{full}"
        )
    return arr.astype(np.uint16, copy=False)


def as_timestamps(value: Any, frames: int, where: str) -> np.ndarray:
    """``frames`` finite Unix times in seconds (a number for one frame) as float64 ``(frames,)``.

    Raises:
        CaptureError: another number of values, or a NaN or Inf among them (``where`` starts the message).
    """
    ts = np.asarray(value, dtype=np.float64).reshape(-1)
    if ts.shape != (frames,) or not np.all(np.isfinite(ts)):
        raise CaptureError(
            f"{where}: need {frames} finite timestamps (one per frame), got {safe_repr(value)}"
        )
    return ts
