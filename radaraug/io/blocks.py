"""Simulated captures in blocks of frames: the block size, the block arithmetic and the one block writer.

Continuously played scenes (``radaraug simulate``, the virtual sensor, the held-out proxy) are simulated
:data:`BLOCK_FRAMES` frames at a time, one noise generator per block: the block size is part of every
such frame's identity, never change it. See ``docs/captures.md``, "Simulated captures".
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.io.hdf5_writer import CaptureWriter

BLOCK_FRAMES = 16
"""Frames per simulated block (one twin call and one noise generator each)."""

COUNT_LABELS = {"count": "int64", "occupancy": "int64"}
"""Per-frame labels of a simulated capture: people in view, and whether there is anyone."""


def block_of(frame: int, block_frames: int = BLOCK_FRAMES) -> int:
    """The block that holds frame ``frame``."""
    return frame // block_frames


def blocks_covering(start: int, stop: int, block_frames: int = BLOCK_FRAMES) -> range:
    """The blocks that hold frames ``[start, stop)``."""
    return range(start // block_frames, -(-stop // block_frames))


def frame_times(start: int, stop: int, period_s: float) -> torch.Tensor:
    """Start times of frames ``[start, stop)`` played continuously, ``k * period_s``, float64 seconds."""
    return torch.arange(start, stop, dtype=torch.float64) * period_s


class BlockWriter:
    """Frames with ``count``/``occupancy`` labels written to a capture, one flushed (crash-safe) append per block.

    Args:
        writer: an open :class:`CaptureWriter` whose per-frame labels are :data:`COUNT_LABELS`.
    """

    def __init__(self, writer: CaptureWriter) -> None:
        self.writer = writer

    @classmethod
    def create(
        cls,
        path: str | os.PathLike,
        config: RadarConfig,
        *,
        attrs: dict[str, Any] | None = None,
        expected_frames: int | None = None,
        publish: str = "first_append",
    ) -> BlockWriter:
        """A new capture at ``path`` (see :class:`CaptureWriter` for ``expected_frames`` and ``publish``)."""
        return cls(CaptureWriter(path, config, labels_schema=COUNT_LABELS, attrs=attrs,
                                 expected_frames=expected_frames, publish=publish))

    @classmethod
    def resume(cls, path: str | os.PathLike, config: RadarConfig, *, expected_frames: int | None = None) -> BlockWriter:
        """Append to the capture at ``path`` (:meth:`CaptureWriter.resume`)."""
        return cls(CaptureWriter.resume(path, config, expected_frames=expected_frames))

    @property
    def num_frames(self) -> int:
        """Frames written (and flushed) so far."""
        return self.writer.num_frames

    def write(self, counts: np.ndarray | torch.Tensor, timestamps: np.ndarray | torch.Tensor,
              count: np.ndarray | torch.Tensor) -> None:
        """Append one block of ``k`` frames in one append (so one flush).

        Args:
            counts: ``(k, rx, chirps, samples)`` ADC counts.
            timestamps: ``(k,)`` frame times, seconds.
            count: ``(k,)`` people counts; ``occupancy`` is ``count > 0``.
        """
        ts = timestamps.detach().cpu().numpy() if isinstance(timestamps, torch.Tensor) else np.asarray(timestamps)
        c = count.detach().cpu().numpy() if isinstance(count, torch.Tensor) else np.asarray(count)
        c = c.astype(np.int64)
        self.writer.append(counts, timestamp=ts, labels={"count": c, "occupancy": (c > 0).astype(np.int64)})

    def close(self) -> None:
        """Close the capture (:meth:`CaptureWriter.close`)."""
        self.writer.close()

    def __enter__(self) -> BlockWriter:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.writer.__exit__(*exc)

    def __repr__(self) -> str:
        return f"BlockWriter({self.writer!r})"


__all__ = ["BLOCK_FRAMES", "COUNT_LABELS", "BlockWriter", "block_of", "blocks_covering", "frame_times"]
