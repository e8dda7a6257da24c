"""Plausibility summary of a capture (``radaraug info``): DC, noise, clipping, floor, static return, motion.

It runs the RD chain, so it lives here rather than in ``io``.
"""

from __future__ import annotations

import collections
import numbers
from typing import Any

import numpy as np
import torch

from radaraug.errors import RadarAugError
from radaraug.io.summary import noise_floor_db
from radaraug.transforms._motion import WARN_FRACTION, cells_motion_fraction, off_zero_doppler
from radaraug.transforms.spectral import RangeDoppler, ToDecibels
from radaraug.units import DB_CONVENTION, counts_to_float

MAX_SUMMARY_SAMPLES = 2**24
"""Most ADC samples ``summarize_capture`` analyses (frames beyond this are left out)."""


def summarize_capture(reader: Any, *, max_frames: int = 256) -> dict[str, Any]:
    """Summarize a capture opened with :func:`radaraug.io.open_capture` as a JSON-able dict.

    Args:
        reader: an open capture reader.
        max_frames: frames read from the start (at most :data:`MAX_SUMMARY_SAMPLES` samples in all).

    Raises:
        RadarAugError: ``max_frames`` is not a positive integer.
    """
    if isinstance(max_frames, bool) or not isinstance(max_frames, numbers.Integral) or max_frames < 1:
        raise RadarAugError(f"{reader.path}: max_frames must be a positive integer, got {max_frames!r}")
    cfg = reader.config
    frame_samples = cfg.num_rx * cfg.num_chirps_per_frame * cfg.num_samples_per_chirp
    # The statistics hold a few float64 copies of the frames read: cap them, whatever max_frames says.
    n = min(reader.num_frames, int(max_frames), max(1, MAX_SUMMARY_SAMPLES // frame_samples))
    raw = reader.read(0, n, as_float=False)  # (F, rx, chirps, samples) int32 codes, read once
    counts = raw.to(torch.float64)
    full = cfg.adc_full_scale_counts
    dc = counts.mean(dim=(0, 2, 3))
    # Slow-time noise per sample: std over chirps, after removing each sample's mean over chirps
    # (static returns cancel); the median over samples ignores the few moving bins.
    slow_std = counts.std(dim=2).median(dim=-1).values.median(dim=0).values
    clipped = ((counts <= 0) | (counts >= full)).double().mean(dim=(0, 2, 3))

    x = counts_to_float(raw, cfg.adc_bits)  # the same SDK floats read(as_float=True) gives
    db = ToDecibels()(RangeDoppler()(x))  # (F, rx, range, doppler)
    static = db[..., cfg.num_chirps_per_frame // 2].mean(dim=0)  # (rx, range) at zero Doppler
    # Skip range bin 0 (residual DC after mean removal).
    k = int(static[:, 1:].max(dim=0).values.argmax()) + 1
    floor = noise_floor_db(db)
    frac = cells_motion_fraction(off_zero_doppler(db, guard_bins=2))
    motion = None if frac is None else {
        "motion": frac > WARN_FRACTION,
        "fraction": frac,
        "explanation": f"{100 * frac:.3f} % of off-zero-Doppler cells > 15 dB above their median over frames; "
        f"noise alone gives ~0 %, flagged above {100 * WARN_FRACTION:.1f} %",
    }

    return {
        "path": str(reader.path),
        "config": cfg.to_dict(),
        "summary": cfg.describe(),
        "shape": list(reader.shape),
        "num_frames": reader.num_frames,
        "duration_s": reader.duration_s,
        "labels": {k2: _label_summary(v) for k2, v in reader.labels.items()},
        "frames_analysed": n,
        "dc_offset_counts": [round(float(v), 1) for v in dc],
        "slow_time_noise_rms_counts": [round(float(v), 3) for v in slow_std],
        "clipped_fraction": [float(v) for v in clipped],
        "noise_floor_db": None if floor is None else round(floor, 2),
        "strongest_static_return": {
            "range_m": round(cfg.range_axis_m()[k], 3),
            "range_bin": k,
            "level_db": round(float(static[:, k].max()), 2),
        },
        "motion": motion,
        "db_convention": DB_CONVENTION,
    }


def _label_summary(values: np.ndarray) -> dict[str, Any]:
    """``{value as text: frame count}`` of one label."""
    arr = np.asarray(values)
    if arr.dtype.kind in "biufU":
        uniq, cnt = np.unique(arr, return_counts=True)
        return {str(u): int(c) for u, c in zip(uniq.tolist(), cnt.tolist())}
    # The readers only serve numbers, bools and strings; anything else (a reader from elsewhere)
    # is summarized by its text, never sorted (mixed types cannot be).
    counts = collections.Counter(str(v) for v in arr.reshape(-1).tolist())
    return dict(sorted(counts.items()))
