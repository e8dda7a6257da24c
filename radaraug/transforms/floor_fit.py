"""Fitting the calibrated noise floor (``CalibratedDR.fit`` delegates here).

Only submodules are imported, never the package or :mod:`.dr`, so that no import cycle forms.
"""

from __future__ import annotations

import numbers
import warnings
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import
from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError
from radaraug.transforms._fit_sources import iter_source
from radaraug.transforms._motion import (
    DEFAULT_THRESHOLD_DB,
    WARN_FRACTION,
    MotionWarning,
    cells_motion_fraction,
    off_zero_doppler,
)
from radaraug.transforms.compose import RadarCompose
from radaraug.transforms.dsp_spec import chain_of, doppler_window_of
from radaraug.transforms.spectral import RangeDoppler, ToDecibels
from radaraug.transforms.windows import MAIN_LOBE_HALF_WIDTH_BINS

#: Quantiles recorded for the empirical floor (probabilities 0, 1/1024, ..., 1): the top step
#: holds 0.1 % of the cells, a few per map, so the per-map maximum keeps the real floor's level.
QUANTILES = 1025


def floor_statistics(
    source: Any,
    *,
    pipeline: Any = None,
    config: RadarConfig | None = None,
    max_frames: int | None = None,
    input: str = "raw",
    batch_size: int = 32,
    motion_threshold_db: float = DEFAULT_THRESHOLD_DB,
    progress: bool = False,
) -> dict[str, Any]:
    """The keyword arguments of a CalibratedDR fitted on ``source`` (see ``CalibratedDR.fit``).

    Returns:
        ``mean_db``, ``std_db``, ``chain``, ``config``, ``map_shape``, ``source``, ``num_frames``,
        ``motion`` and ``quantiles_db`` (:data:`QUANTILES` quantiles off the zero-Doppler main lobe).
    """
    if input not in ("raw", "db"):
        raise CalibrationError(f"CalibratedDR.fit: input must be 'raw' or 'db', got {input!r}")
    # max_frames=None (no limit) is checked as a valid stand-in.
    for name, value in (("max_frames", 1 if max_frames is None else max_frames), ("batch_size", batch_size)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 1:
            raise CalibrationError(f"CalibratedDR.fit: {name} must be a positive integer, got {value!r}")
    if pipeline is None:
        pipeline = RadarCompose([RangeDoppler(), ToDecibels()])
    chain = chain_of(pipeline)
    if chain is None:
        warnings.warn(
            "CalibratedDR.fit: the pipeline has no chain_spec(); the chain cannot be recorded or checked",
            UserWarning,
            stacklevel=3,
        )
    batches, source_name, capture_config = iter_source(source, max_frames=max_frames, batch_size=batch_size)
    if capture_config is not None:
        if config is not None and config != capture_config:
            raise CalibrationError(
                f"CalibratedDR.fit: the config given differs from the config of {source_name}"
            )
        config = capture_config
    where = f"capture {source_name}" if source_name else "the calibration data"
    if progress:
        tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

        batches = tqdm(batches, desc="fit CalibratedDR", unit="batch", leave=False)
    maps = []
    with torch.no_grad():
        for batch in batches:
            out = batch if input == "db" else pipeline(batch)
            if not isinstance(out, torch.Tensor) or out.ndim != 4 or out.is_complex():
                raise CalibrationError(
                    f"CalibratedDR.fit: the pipeline must map frames to real dB maps (frames, rx, range, "
                    f"doppler); got {getattr(out, 'shape', type(out).__name__)} from {where}"
                )
            if not bool(torch.isfinite(out).all()):
                raise CalibrationError(f"CalibratedDR.fit: NaN/Inf in the RD maps of {where}")
            maps.append(out)
    if not maps or sum(m.shape[0] for m in maps) == 0:
        raise CalibrationError(f"CalibratedDR.fit: {where} has no frames")
    shapes = {tuple(m.shape[1:]) for m in maps}
    if len(shapes) > 1:
        raise CalibrationError(f"CalibratedDR.fit: frames of {where} have different shapes {sorted(shapes)}")
    all_maps = torch.cat(maps)
    values = all_maps.double()
    mean, std = float(values.mean()), float(values.std(correction=0))
    window = doppler_window_of(chain) or "hann"
    # The cells off zero Doppler serve the motion check and the empirical floor's distribution: the
    # static clutter in the zero-Doppler main lobe is the room's (the twin makes its own), not the
    # receiver's floor; drawn i.i.d. into every cell, its high values would be spikes no floor has.
    off = off_zero_doppler(all_maps, MAIN_LOBE_HALF_WIDTH_BINS.get(window, 1) + 1)
    motion = cells_motion_fraction(off, motion_threshold_db)
    floor = floor_values(all_maps, window)
    quantiles = torch.from_numpy(np.quantile(floor.cpu().numpy(), np.linspace(0.0, 1.0, QUANTILES)))
    if motion is not None and motion > WARN_FRACTION:
        warnings.warn(
            f"CalibratedDR.fit: {where} should be an empty scene but shows motion: {100 * motion:.2f} % of the cells "
            f"off zero Doppler are > {motion_threshold_db:g} dB above their own median over frames (noise "
            f"and static clutter alone give ~0 %). The fitted floor includes it; record the empty scene.",
            MotionWarning,
            stacklevel=3,
        )
    return {
        "mean_db": mean,
        "std_db": std,
        "chain": chain,
        "config": config,
        "map_shape": tuple(all_maps.shape[1:]),
        "source": source_name,
        "num_frames": int(all_maps.shape[0]),
        "motion": motion,
        "quantiles_db": quantiles,
    }


def floor_values(maps_db: torch.Tensor, window: str = "hann") -> torch.Tensor:
    """The dB values of ``(..., doppler)`` maps off the zero-Doppler main lobe, flattened (float64)."""
    off = off_zero_doppler(maps_db, MAIN_LOBE_HALF_WIDTH_BINS.get(window, 1) + 1)
    return (off if off.numel() else maps_db).double().flatten()


def matched_floor_quantiles(
    capture_quantiles_db: torch.Tensor, twin_values_db: torch.Tensor, points: int = QUANTILES
) -> torch.Tensor:
    """Quantiles of a clamp floor ``N`` such that ``max(S, N)`` has the capture's floor distribution.

    For independent ``S`` (the twin's own floor) and ``N``, ``F_N = F_capture / F_S``, made a CDF by its
    largest non-decreasing minorant and clipped to [0, 1]: where the twin already sits above the capture,
    ``N`` stays below it. Why: drawing ``N`` from the capture alone stacks a second floor on a twin whose
    floor is near the capture's (docs/transforms.md).

    Args:
        capture_quantiles_db: ``(K,)`` non-decreasing capture quantiles at probabilities ``0, ..., 1``.
        twin_values_db: dB values of the twin's own empty-room floor (any shape).
        points: quantiles returned.

    Returns:
        ``(points,)`` non-decreasing quantiles in dB (float64) for ``F.empirical_floor``.
    """
    q_cap = torch.as_tensor(capture_quantiles_db, dtype=torch.float64).flatten().cpu()
    s = torch.as_tensor(twin_values_db, dtype=torch.float64).flatten().cpu()
    s = s[torch.isfinite(s)]
    if q_cap.numel() < 2 or s.numel() == 0:
        raise CalibrationError("matched_floor_quantiles: needs >= 2 capture quantiles and some twin values")
    lo = float(torch.minimum(q_cap[0], s.min())) - 1.0
    hi = float(torch.maximum(q_cap[-1], s.max()))
    grid = torch.linspace(lo, hi, 4096, dtype=torch.float64)
    p_cap = torch.linspace(0.0, 1.0, q_cap.numel(), dtype=torch.float64)
    f_cap = torch.from_numpy(np.interp(grid.numpy(), q_cap.numpy(), p_cap.numpy(), left=0.0, right=1.0))
    s_sorted = s.sort().values
    f_s = torch.searchsorted(s_sorted, grid, right=True).double() / s.numel()
    ratio = torch.where(f_s > 0, f_cap / f_s.clamp_min(1e-300), torch.ones_like(f_s)).clamp(0.0, 1.0)
    # running minimum from the right: the largest non-decreasing function below the ratio
    f_n = ratio.flip(0).cummin(0).values.flip(0)
    f_n[-1] = 1.0
    probs = torch.linspace(0.0, 1.0, points, dtype=torch.float64)
    # q(p) = the first grid point where F_N >= p (below F_N(lo): N sits below every S value)
    idx = torch.searchsorted(f_n.contiguous(), probs, right=False).clamp(max=grid.numel() - 1)
    return grid[idx]


__all__ = ["QUANTILES", "MotionWarning", "floor_statistics", "floor_values", "matched_floor_quantiles"]
