"""The fit behind the default chain's noise constants, reproducible on any set of recordings.

Thermal noise (amplified by the IF gain) and ADC-side noise (not) set the RD floor; recordings at
several IF gains separate them. :func:`fit_noise_defaults` grid-searches the front-end gain and the
ADC-side RMS so that the default twin's floor matches every recording's, minimizing the worst
difference; :func:`check_defaults` reports the floors per recording. Results:
``docs/diagnosis.md``, "Default constants".
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.views import rd_noise_floor_db
from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS, FRONT_END_GAIN_DB, default_effects
from radaraug.sensor.effects import TxRxLeakage
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver


def capture_floor_db(path: str | os.PathLike, max_frames: int = 64) -> tuple[RadarConfig, float]:
    """A recording's config and RD noise floor (dBFS, :func:`radaraug.diagnosis.noise_fit.capture_noise_floor_db`)."""
    from radaraug.diagnosis.noise_fit import capture_noise_floor_db
    from radaraug.io import open_capture

    with open_capture(path) as reader:
        return reader.config, capture_noise_floor_db(reader, max_frames)


@torch.no_grad()
def twin_floor_db(config: RadarConfig, front_end_gain_dB: float = FRONT_END_GAIN_DB,
                  adc_noise_rms_counts: float = ADC_NOISE_RMS_COUNTS, frames: int = 8, seed: int = 0) -> float:
    """RD noise floor (dBFS) of the default chain's empty frames with the given two constants.

    Raises:
        CalibrationError: ``config`` has too few chirps (<= 4) to measure a floor off zero Doppler.
    """
    effects = default_effects(config, adc_noise_rms_counts=adc_noise_rms_counts)
    leak = next(e for e in effects if isinstance(e, TxRxLeakage))
    leak.coupling_dB.add_(FRONT_END_GAIN_DB - front_end_gain_dB)  # keep the leakage's ADC level
    rx = FMCWReceiver(config, effects=effects, front_end_gain_dB=front_end_gain_dB)
    z = torch.zeros(frames, 0, config.num_rx, dtype=torch.float64)
    x = rx(Paths(z, z.clone(), z.to(torch.complex128)), generator=torch.Generator().manual_seed(seed))
    return rd_noise_floor_db(x)


def check_defaults(paths: Sequence[str | os.PathLike], **twin_kw: Any) -> list[dict[str, Any]]:
    """Per recording: IF gain, capture floor, default-twin floor and their difference (dB)."""
    rows = []
    for p in paths:
        cfg, cap = capture_floor_db(p)
        tw = twin_floor_db(cfg, **twin_kw)
        rows.append({"recording": str(p), "if_gain_dB": cfg.if_gain_dB, "chirps": cfg.num_chirps_per_frame,
                     "samples": cfg.num_samples_per_chirp, "capture_floor_db": round(cap, 2),
                     "twin_floor_db": round(tw, 2), "difference_db": round(tw - cap, 2)})
    return rows


#: The default grids of :func:`fit_noise_defaults`: 20-40 dB in 0.5 dB steps, 0.5-4 counts in 0.25.
FRONT_END_GAIN_GRID_DB = tuple(x / 2 for x in range(40, 81))
ADC_RMS_GRID_COUNTS = tuple(0.25 * k for k in range(2, 17))


def fit_noise_defaults(paths: Sequence[str | os.PathLike],
                       front_end_gains_dB: Sequence[float] = FRONT_END_GAIN_GRID_DB,
                       adc_rms_counts: Sequence[float] = ADC_RMS_GRID_COUNTS) -> dict[str, Any]:
    """Grid-search (front-end gain, ADC-side RMS) minimizing the worst floor difference.

    Returns:
        ``{"front_end_gain_dB", "adc_noise_rms_counts", "worst_difference_db", "rows"}``.
    """
    caps = [capture_floor_db(p) for p in paths]
    best: tuple[float, float, float] | None = None
    for g in front_end_gains_dB:
        for a in adc_rms_counts:
            worst = max(abs(twin_floor_db(cfg, g, a) - f) for cfg, f in caps)
            if best is None or worst < best[0]:
                best = (worst, g, a)
    assert best is not None
    worst, g, a = best
    return {"front_end_gain_dB": g, "adc_noise_rms_counts": a, "worst_difference_db": round(worst, 3),
            "rows": check_defaults(paths, front_end_gain_dB=g, adc_noise_rms_counts=a)}
