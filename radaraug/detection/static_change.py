"""A person changes the room's static return: a zero-Doppler change detector fitted on an empty room.

People slower than a Doppler bin vanish with the blanked zero Doppler of an RD map, but they change
the zero-Doppler range profile, which is stable in an empty room. :class:`StaticChangeDetector` scores
that change in units of the empty room's own spread; nothing is trained and it runs one frame at a
time. See ``docs/static_change.md``.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.transforms import functional as F

if TYPE_CHECKING:
    from radaraug.io.base import CaptureReader

DEFAULT_MARGIN_DB = 3.0
"""Added to the calibration's largest leave-one-out score (room for the drift between calibration and test)."""
DEFAULT_MIN_RANGE_M = 0.5
"""Range bins nearer than this are left out (TX-RX leakage and the DC residue live there)."""
CHUNK_FRAMES = 256
"""Frames read from a capture at a time (a long recording is never held whole)."""


def zero_doppler_profile(frames: torch.Tensor) -> torch.Tensor:
    """Complex zero-Doppler range profile of raw frames: the mean over chirps, DC removed, Hann range FFT.

    Args:
        frames: ``(frames, rx, chirps, samples)`` raw samples (counts or SDK floats).

    Returns:
        ``(frames, rx, samples // 2)`` complex128 (range FFT divided by the window sum).

    Raises:
        ConfigError: ``frames`` is not 4-D.
    """
    if frames.ndim != 4:
        raise ConfigError(f"zero_doppler_profile: frames must be (frames, rx, chirps, samples), got {tuple(frames.shape)}")
    # the chirp mean is the zero-Doppler bin (a rectangular Doppler window); then the project's range FFT
    x = frames.to(torch.float64).mean(dim=-2, keepdim=True)
    return F.range_fft(F.remove_mean(x), "hann").squeeze(-2)


@dataclass
class StaticChangeDetector:
    """Zero-Doppler change against an empty room, in units of the empty room's own spread.

    Attributes:
        reference: ``(rx, range)`` complex mean zero-Doppler profile of the calibration frames.
        spread: ``(rx, range)`` their per-cell variance (unbiased).
        first_bin: first range bin scored (:data:`DEFAULT_MIN_RANGE_M` and up).
        threshold_db: a frame whose score exceeds this is called occupied.
        calibration_scores_db: the calibration frames' leave-one-out scores (the threshold's source).
        margin_db: what the threshold adds to their maximum.
    """

    reference: torch.Tensor
    spread: torch.Tensor
    first_bin: int
    threshold_db: float
    calibration_scores_db: torch.Tensor
    margin_db: float

    @classmethod
    def fit(cls, frames: torch.Tensor, config: RadarConfig, *, margin_db: float = DEFAULT_MARGIN_DB,
            min_range_m: float = DEFAULT_MIN_RANGE_M) -> StaticChangeDetector:
        """Fit on empty-room frames.

        Args:
            frames: ``(frames, rx, chirps, samples)`` raw empty-room frames, at least 3.
            config: their radar configuration (range bins).
            margin_db: added to the largest leave-one-out score.
            min_range_m: nearer range bins are not scored.

        Raises:
            ConfigError: fewer than 3 frames, a shape that does not match ``config``, or a bad margin/range.
        """
        shape = (config.num_rx, config.num_chirps_per_frame, config.num_samples_per_chirp)
        if frames.ndim != 4 or tuple(frames.shape[1:]) != shape:
            raise ConfigError(f"StaticChangeDetector: calibration frames of shape {tuple(frames.shape)} do not match "
                              f"the config's (frames, {', '.join(map(str, shape))})")
        return cls.fit_profiles(zero_doppler_profile(frames), config, margin_db=margin_db, min_range_m=min_range_m)

    @classmethod
    def fit_profiles(cls, p: torch.Tensor, config: RadarConfig, *, margin_db: float = DEFAULT_MARGIN_DB,
                     min_range_m: float = DEFAULT_MIN_RANGE_M) -> StaticChangeDetector:
        """:meth:`fit` on empty-room frames' :func:`zero_doppler_profile` ``(frames, rx, range)``."""
        if not math.isfinite(margin_db):
            raise ConfigError(f"StaticChangeDetector: margin_db must be finite, got {margin_db!r}")
        n = int(p.shape[0])
        if n < 3:
            raise ConfigError(f"StaticChangeDetector: needs at least 3 empty-room frames to fit, got {n}")
        if not (math.isfinite(min_range_m) and min_range_m >= 0) or \
                math.ceil(min_range_m / config.range_resolution_m) >= p.shape[-1]:
            raise ConfigError(f"StaticChangeDetector: min_range_m {min_range_m!r} leaves no range bin to score")
        first = max(1, math.ceil(min_range_m / config.range_resolution_m))
        ref = p.mean(dim=0)
        power = p.abs().square()
        spread = (power.sum(0) - n * ref.abs().square()).clamp_min(0) / (n - 1)
        floor = _floor(spread)
        # Leave-one-out: frame k against the mean and spread of the other n - 1 (closed form, all k at once).
        ref_k = (n * ref - p) / (n - 1)
        spread_k = (power.sum(0) - power - (n - 1) * ref_k.abs().square()).clamp_min(0) / (n - 2)
        loo = _score_db((p - ref_k).abs().square() / torch.maximum(spread_k, floor), first)
        return cls(ref, torch.maximum(spread, floor), first, float(loo.max()) + float(margin_db), loo, float(margin_db))

    @classmethod
    def from_capture(cls, path: str | os.PathLike, *, max_frames: int | None = None,
                     margin_db: float = DEFAULT_MARGIN_DB, min_range_m: float = DEFAULT_MIN_RANGE_M) -> StaticChangeDetector:
        """Fit on an empty-room capture (radaraug HDF5 or an Infineon recording; its first ``max_frames``).

        Raises:
            CaptureError: the capture cannot be read (named).
            ConfigError: as :meth:`fit`.
        """
        from radaraug.io import open_capture

        cap = open_capture(path)
        stop = len(cap) if max_frames is None else min(int(max_frames), len(cap))
        return cls.fit_profiles(_capture_profiles(cap, stop), cap.config, margin_db=margin_db, min_range_m=min_range_m)

    def score(self, frames: torch.Tensor) -> torch.Tensor:
        """``(frames,)`` score in dB: the largest mean-over-RX change over range, in empty-room spreads."""
        p = zero_doppler_profile(frames)
        if tuple(p.shape[1:]) != tuple(self.reference.shape):
            raise ConfigError(f"StaticChangeDetector: frames of shape {tuple(frames.shape)} do not match the "
                              f"calibration's ({tuple(self.reference.shape)} zero-Doppler profile)")
        ref = self.reference.to(p.device)
        return _score_db((p - ref).abs().square() / self.spread.to(p.device), self.first_bin).cpu()

    def detect(self, frames: torch.Tensor) -> torch.Tensor:
        """``(frames,)`` bool: True where the frame's score exceeds :attr:`threshold_db`."""
        return self.score(frames) > self.threshold_db

    def detect_capture(self, path: str | os.PathLike) -> torch.Tensor:
        """:meth:`detect` over every frame of a capture, read a chunk at a time.

        Raises:
            CaptureError: the capture cannot be read (named).
            ConfigError: its frames do not match the calibration's shape.
        """
        from radaraug.io import open_capture

        cap = open_capture(path)
        return torch.cat([self.detect(cap.read(i, min(i + CHUNK_FRAMES, len(cap)), as_float=False))
                          for i in range(0, len(cap), CHUNK_FRAMES)])


def _capture_profiles(cap: CaptureReader, stop: int) -> torch.Tensor:
    """Zero-Doppler profiles of a capture's first ``stop`` frames, a chunk at a time."""
    return torch.cat([zero_doppler_profile(cap.read(i, min(i + CHUNK_FRAMES, stop), as_float=False))
                      for i in range(0, stop, CHUNK_FRAMES)]) if stop else torch.zeros(0)


def _score_db(z: torch.Tensor, first_bin: int) -> torch.Tensor:
    """``(frames, rx, range)`` normalized change -> ``(frames,)`` dB of the largest RX-mean over range."""
    return 10 * torch.log10(z.mean(dim=1)[:, first_bin:].amax(dim=-1).clamp_min(1e-30))


def _floor(spread: torch.Tensor) -> torch.Tensor:
    """A tiny per-cell spread floor: a noiseless (simulated) cell would otherwise divide by zero."""
    return (spread.mean() * 1e-12).clamp_min(torch.finfo(torch.float64).tiny)
