"""Turn the sources `CalibratedDR.fit` accepts into batches of frames."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.errors import CalibrationError, CaptureError


def _as_tensor(item: Any, where: str) -> torch.Tensor:
    if isinstance(item, (tuple, list)):
        if not item:
            raise CalibrationError(f"CalibratedDR.fit: {where} yielded an empty sample")
        item = item[0]  # (cube, label) samples: the cube
    if isinstance(item, np.ndarray):
        item = torch.from_numpy(item)
    if not isinstance(item, torch.Tensor):
        raise CalibrationError(f"CalibratedDR.fit: {where} yielded {type(item).__name__}, expected a tensor")
    return item


def _frames(t: torch.Tensor, where: str) -> torch.Tensor:
    """A tensor of one frame ``(a, b, c)`` or many ``(..., a, b, c)`` as ``(F, a, b, c)``."""
    if t.ndim < 3:
        raise CalibrationError(
            f"CalibratedDR.fit: {where} has shape {tuple(t.shape)}; need (frames, rx, ., .)"
        )
    return t.reshape(-1, *t.shape[-3:])


def iter_source(
    source: Any, *, max_frames: int | None, batch_size: int
) -> tuple[Iterator[torch.Tensor], str | None, Any]:
    """Batches of frames ``(F, rx, ., .)`` from a path, a capture reader, a tensor or a Dataset.

    Returns:
        (batch iterator, source name for the record, radar config of the capture or None).
    """
    limit = None if max_frames is None else int(max_frames)
    if isinstance(source, (str, os.PathLike)):
        from radaraug.io import open_capture

        try:
            reader = open_capture(source)
        except CaptureError:
            raise
        except OSError as e:
            raise CaptureError(f"cannot open capture {source}: {e}") from None
        return _iter_reader(reader, limit, batch_size, close=True), Path(source).name, reader.config
    if hasattr(source, "read") and hasattr(source, "num_frames"):
        name = Path(str(source.path)).name if getattr(source, "path", None) else None
        return _iter_reader(source, limit, batch_size, close=False), name, getattr(source, "config", None)
    if isinstance(source, torch.Tensor):
        return iter(_frames(source, "the tensor")[:limit].split(batch_size)), None, None
    if hasattr(source, "__getitem__") and hasattr(source, "__len__"):
        return (
            _iter_dataset(source, limit, batch_size),
            type(source).__name__,
            getattr(source, "config", None),
        )
    if hasattr(source, "__iter__"):
        return _iter_iterable(source, limit, batch_size), type(source).__name__, None
    raise CalibrationError(
        f"CalibratedDR.fit: unsupported source {type(source).__name__}; give a capture path, a capture "
        "reader, a tensor of frames, or a Dataset"
    )


def _iter_reader(reader: Any, limit: int | None, batch_size: int, close: bool) -> Iterator[torch.Tensor]:
    try:
        n = int(reader.num_frames) if limit is None else min(limit, int(reader.num_frames))
        for start in range(0, n, batch_size):
            yield _frames(
                reader.read(start, min(n, start + batch_size)), f"capture {getattr(reader, 'path', '')}"
            )
    finally:
        if close:
            reader.close()


def _iter_dataset(ds: Any, limit: int | None, batch_size: int) -> Iterator[torch.Tensor]:
    n = len(ds) if limit is None else min(limit, len(ds))
    pending: list[torch.Tensor] = []
    count = 0
    for i in range(n):
        pending.append(_frames(_as_tensor(ds[i], f"dataset item {i}"), f"dataset item {i}"))
        count += pending[-1].shape[0]
        if count >= batch_size:
            yield torch.cat(pending)
            pending, count = [], 0
    if pending:
        yield torch.cat(pending)


def _iter_iterable(it: Any, limit: int | None, batch_size: int) -> Iterator[torch.Tensor]:
    seen = 0
    for k, item in enumerate(it):
        frames = _frames(_as_tensor(item, f"item {k}"), f"item {k}")
        if limit is not None:
            frames = frames[: limit - seen]
        seen += frames.shape[0]
        if frames.shape[0]:
            yield frames
        if limit is not None and seen >= limit:
            return
