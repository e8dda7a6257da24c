"""The motion check of `CalibratedDR.fit`: is the "empty" capture really empty?

Statistic: for every RD cell away from zero Doppler, compare each frame's dB value with that
cell's own median over frames, and count how often it exceeds the median by more than
``threshold_db`` (default 15 dB). For noise alone ``|X|**2`` is exponential in every cell, so
``P(dB > median + T) = 2**(-10**(T/10))``: ``3e-10`` at 15 dB -- essentially never. Static
clutter sits at zero Doppler (excluded, with its window main lobe), and whatever it leaks into
other Doppler bins (phase-noise skirt) is stationary, so it does not exceed its own median
either. A moving person changes cells from frame to frame and exceeds it by tens of dB.

Measured with the default chain on public BGT60TR13C recordings: 0 (static 3-RX reflector scene,
128 frames; near-static breathing scene, 256 frames) against 0.7-0.9 % (a person walking,
31 and 232 frames). Warn above 1e-3. Limitations: motion that stays in the same cells for the
whole capture (a fan, a person standing still) is not flagged; fewer than
:data:`MIN_FRAMES` frames are not checked (the median over frames is too noisy).
"""

from __future__ import annotations

import torch

MIN_FRAMES = 16
DEFAULT_THRESHOLD_DB = 15.0
WARN_FRACTION = 1e-3


class MotionWarning(UserWarning):
    """The capture a floor is fitted on should be an empty scene but shows motion.

    Its own category so that callers can act on it (``radaraug calibrate`` refuses instead of
    warning) without matching the message text.
    """


def off_zero_doppler(maps_db: torch.Tensor, guard_bins: int) -> torch.Tensor:
    """The cells of ``(..., doppler)`` dB maps (Doppler centred) more than ``guard_bins`` from zero Doppler."""
    doppler = maps_db.shape[-1]
    keep = (torch.arange(doppler, device=maps_db.device) - doppler // 2).abs() > guard_bins
    return maps_db[..., keep]


def cells_motion_fraction(cells: torch.Tensor, threshold_db: float = DEFAULT_THRESHOLD_DB) -> float | None:
    """Fraction of cells above their median over frames + ``threshold_db``.

    Args:
        cells: ``(frames, ...)`` dB values off zero Doppler, e.g. ``off_zero_doppler(maps_db, guard_bins)``
            of ``(frames, rx, range, doppler)`` maps with ``guard_bins`` Doppler bins on each side of zero
            left out (static clutter's main lobe).
        threshold_db: excess over the cell's median that counts as motion.

    Returns:
        The fraction, or None when there are too few frames or no Doppler bins left.
    """
    if cells.shape[0] < MIN_FRAMES or cells.shape[-1] == 0:
        return None
    median = cells.median(dim=0).values
    return float((cells > median + threshold_db).double().mean())
