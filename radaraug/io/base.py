"""`CaptureReader`: the interface shared by every kind of radar capture radaraug reads.

A capture is a sequence of raw frames ``(rx, chirps, samples)`` of ADC counts with one
:class:`~radaraug.config.RadarConfig`. Concrete readers (radaraug HDF5 files, Infineon
recording folders) only implement :meth:`CaptureReader._read_counts` and fill the metadata;
slicing, ADC-range checks and the conversion to SDK floats live here so every format behaves
the same.
"""

from __future__ import annotations

import abc
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError
from radaraug.units import counts_to_float


class CaptureWarning(UserWarning):
    """A capture is readable but some optional part of it was ignored (e.g. timestamps)."""


class CaptureReader(abc.ABC):
    """Read-only access to one capture: metadata up front, frames on demand.

    Subclasses set ``path``, ``config``, ``num_frames``, ``timestamps``, ``labels`` and
    ``attrs`` in their constructor and implement :meth:`_read_counts` and :meth:`close`.

    Attributes:
        path: the file or folder the capture was opened from.
        config: the radar configuration the frames were recorded with.
        num_frames: number of frames ``F``.
        timestamps: per-frame Unix time in seconds, float64 ``(F,)``, or ``None``.
        labels: label name -> per-frame ``np.ndarray`` of length ``F`` (file-level labels are
            broadcast to every frame).
        attrs: free-form metadata of the file (decoded to plain Python values).
    """

    path: Path
    config: RadarConfig
    num_frames: int
    timestamps: np.ndarray | None
    labels: dict[str, np.ndarray]
    attrs: dict[str, Any]

    # ------------------------------------------------------------------ to implement
    @abc.abstractmethod
    def _read_counts(self, start: int, stop: int) -> np.ndarray:
        """Frames ``start:stop`` (already validated, ``start < stop``) as an integer array."""

    @abc.abstractmethod
    def close(self) -> None:
        """Release file handles. Reading after ``close`` raises :class:`CaptureError`."""

    # ------------------------------------------------------------------ common interface
    @property
    def shape(self) -> tuple[int, int, int, int]:
        """``(frames, rx, chirps, samples)``."""
        c = self.config
        return (self.num_frames, *c.frame_shape)

    @property
    def duration_s(self) -> float:
        """Length of the capture in seconds.

        From the timestamps when there are any (last - first + one frame period, so a capture
        of ``F`` evenly spaced frames lasts ``F`` periods), else nominal ``F * frame period``.
        """
        period = self.config.frame_repetition_time_s
        if self.timestamps is not None and len(self.timestamps) > 1:
            return float(self.timestamps[-1] - self.timestamps[0]) + period
        return self.num_frames * period

    def read(self, start: int = 0, stop: int | None = None, *, as_float: bool = True) -> torch.Tensor:
        """Frames ``start:stop`` as a tensor ``(stop - start, rx, chirps, samples)``.

        Args:
            start: first frame (negative counts from the end, as in Python slicing).
            stop: one past the last frame; ``None`` reads to the end.
            as_float: ``True`` gives float32 Infineon SDK 3.6 floats ``2*c/(2**bits-1) - 1``;
                ``False`` gives the raw counts as an int32 tensor.

        Raises:
            CaptureError: the range is empty or outside the capture, the data cannot be read,
                or a value lies outside the ADC code range ``0..2**adc_bits-1``.
        """
        start, stop = self._normalise_range(start, stop)
        counts = self._read_counts(start, stop)
        full = self.config.adc_full_scale_counts
        # Codes above full scale cannot come from the ADC: the file is corrupt or was written
        # with another bit depth. Converting them would give floats outside [-1, 1] silently.
        lo, hi = int(counts.min()), int(counts.max())
        if hi > full or lo < 0:
            bad_value = hi if hi > full else lo
            bad = np.flatnonzero((counts == bad_value).reshape(len(counts), -1).any(axis=1))
            raise CaptureError(
                f"{self.path}: frame {start + int(bad[0])} holds ADC code {bad_value} outside "
                f"0..{full} ({self.config.adc_bits}-bit ADC); the capture is corrupt or its "
                "adc_bits is wrong"
            )
        x = torch.from_numpy(np.ascontiguousarray(counts, dtype=np.int32))
        return counts_to_float(x, self.config.adc_bits) if as_float else x

    def __getitem__(self, index: int | slice) -> torch.Tensor:
        """``capture[i]`` -> one frame ``(rx, chirps, samples)``; ``capture[a:b]`` -> frames (floats)."""
        if isinstance(index, slice):
            if index.step not in (None, 1):
                raise CaptureError(f"{self.path}: frame slices must have step 1, got {index.step}")
            start, stop, _ = index.indices(self.num_frames)
            return self.read(start, max(start, stop))
        if isinstance(index, (int, np.integer)):
            i = int(index)
            if not -self.num_frames <= i < self.num_frames:
                raise IndexError(f"{self.path}: frame {i} out of range for {self.num_frames} frames")
            i %= self.num_frames
            return self.read(i, i + 1)[0]
        raise TypeError(f"capture indices must be int or slice, not {type(index).__name__}")

    def __len__(self) -> int:
        return self.num_frames

    def __enter__(self) -> CaptureReader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({str(self.path)!r}, shape={self.shape})"

    # ------------------------------------------------------------------ helpers
    def _normalise_range(self, start: int, stop: int | None) -> tuple[int, int]:
        n = self.num_frames
        s = int(start) + n if start < 0 else int(start)
        e = n if stop is None else (int(stop) + n if stop < 0 else int(stop))
        if not 0 <= s < e <= n:
            raise CaptureError(f"{self.path}: cannot read frames {start}:{stop} of a capture with {n} frames")
        return s, e


def frames_problem(shape: tuple[int, ...], config: RadarConfig, config_name: str) -> str | None:
    """Why frames of ``shape`` cannot be a capture's ``(F, rx, chirps, samples)`` in ``config``, or None.

    Not 4-D, an axis ``config`` (named ``config_name`` in the message) does not match, or no frame.
    """
    if len(shape) != 4:
        return f"shape {shape}, expected 4-D (frames, rx, chirps, samples)"
    for axis, name, want in (
        (1, "rx", config.num_rx),
        (2, "chirps", config.num_chirps_per_frame),
        (3, "samples", config.num_samples_per_chirp),
    ):
        if shape[axis] != want:
            return f"{shape[axis]} {name} (shape {shape}) but {config_name} says {want}"
    return "no frames (empty capture)" if shape[0] == 0 else None


def timestamp_problem(ts: np.ndarray) -> str | None:
    """Why per-frame timestamps cannot be used (NaN/Inf, or going backwards), or None."""
    if not np.isfinite(ts).all():
        return "timestamps hold NaN or Inf"
    back = np.flatnonzero(np.diff(ts) < 0)
    if len(back):
        # A negative duration or frame interval is never right; which stamps are wrong is unknowable.
        return f"timestamps go backwards (frame {int(back[0]) + 1} is earlier than frame {int(back[0])})"
    return None


_LABEL_SCALARS = (bool, int, float, str, np.bool_, np.integer, np.floating, np.str_)


def broadcast_label(name: str, value: Any, num_frames: int, source: Path) -> np.ndarray:
    """A file-level label value as a per-frame array (scalars repeat; arrays must fit).

    A label is a number, a bool or a string, or ``num_frames`` of them of one kind. Anything else
    (null, objects, nested or mixed lists, an empty HDF5 attribute) is a :class:`CaptureError`:
    a training label must never be guessed.
    """
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    if isinstance(value, (list, tuple)) and not all(isinstance(v, _LABEL_SCALARS) for v in value):
        kinds = sorted({type(v).__name__ for v in value})
        raise CaptureError(f"{source}: label {name!r} holds {kinds} values; labels must be numbers, bools or strings")
    if isinstance(value, (list, tuple)) and len({type(v) for v in value}) > 1 and not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in value
    ):
        raise CaptureError(f"{source}: label {name!r} mixes kinds of values ({sorted({type(v).__name__ for v in value})})")
    if not isinstance(value, (*_LABEL_SCALARS, list, tuple, np.ndarray)):
        raise CaptureError(
            f"{source}: label {name!r} is {type(value).__name__}; labels must be numbers, bools or strings"
        )
    try:
        arr = np.asarray(value)
    except (ValueError, OverflowError) as e:
        raise CaptureError(f"{source}: label {name!r} is not a usable value ({e})") from None
    if arr.dtype.kind not in "biufU":
        raise CaptureError(f"{source}: label {name!r} has dtype {arr.dtype}; labels must be numbers, bools or strings")
    if arr.ndim == 0:
        return np.full(num_frames, arr.item() if arr.dtype.kind != "U" else str(arr), dtype=arr.dtype)
    if arr.shape != (num_frames,):
        raise CaptureError(
            f"{source}: label {name!r} has shape {arr.shape}, expected a scalar or ({num_frames},)"
        )
    return arr
