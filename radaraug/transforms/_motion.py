"""The motion check of ``CalibratedDR.fit``: is the "empty" capture empty? (docs/transforms.md, "Motion warning")."""

from __future__ import annotations

import torch

MIN_FRAMES = 16
DEFAULT_THRESHOLD_DB = 15.0
WARN_FRACTION = 1e-3


class MotionWarning(UserWarning):
    """An empty-room capture shows motion (own category: ``radaraug calibrate`` refuses on it)."""


def off_zero_doppler(maps_db: torch.Tensor, guard_bins: int) -> torch.Tensor:
    """The cells of ``(..., doppler)`` dB maps (Doppler centred) more than ``guard_bins`` from zero Doppler."""
    doppler = maps_db.shape[-1]
    keep = (torch.arange(doppler, device=maps_db.device) - doppler // 2).abs() > guard_bins
    return maps_db[..., keep]


def cells_motion_fraction(cells: torch.Tensor, threshold_db: float = DEFAULT_THRESHOLD_DB) -> float | None:
    """Fraction of dB ``cells`` ``(frames, ...)`` off zero Doppler above their median over frames + ``threshold_db``.

    None with fewer than :data:`MIN_FRAMES` frames or no Doppler bins.
    """
    if cells.shape[0] < MIN_FRAMES or cells.shape[-1] == 0:
        return None
    median = cells.median(dim=0).values
    return float((cells > median + threshold_db).double().mean())
