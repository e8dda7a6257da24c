"""`radaraug bench diagnose`: `radaraug diagnose` on a 100-frame paper-config capture vs simulating it.

The capture is made in the same process by the library's receiver; see docs/benchmarks.md.
"""

from __future__ import annotations

import math
import platform
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.bench import write_figures
from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.sensor import FMCWReceiver, Paths
from radaraug.sensor.effects import FrameDrift, SpurTone, insert_in_order


def _capture_frames(cfg: RadarConfig, frames: int) -> torch.Tensor:
    rx = FMCWReceiver(cfg)
    effects = insert_in_order(list(rx.effects), SpurTone(freq_Hz=187.3e3, amplitude_counts=3.0))
    effects = insert_in_order(effects, FrameDrift(gain_rms_dB=0.3, dc_rms_counts=3.0))
    rx = FMCWReceiver(cfg, effects=effects)
    ranges = torch.tensor([1.5, 3.2, 7.9], dtype=torch.float64)
    d = (2 * ranges / SPEED_OF_LIGHT)[:, None].expand(3, cfg.num_rx)
    amp = torch.tensor([1e-4, 5e-5, 3e-5], dtype=torch.complex128)[:, None].expand(3, cfg.num_rx)
    paths = Paths(d[None].expand(frames, -1, -1).contiguous(), torch.zeros(frames, 3, cfg.num_rx, dtype=torch.float64),
                  amp[None].expand(frames, -1, -1).contiguous())
    times = torch.arange(frames, dtype=torch.float64) * cfg.frame_repetition_time_s
    return rx.to_counts(paths, generator=torch.Generator().manual_seed(0), frame_start_s=times)


def run_diagnose_benchmark(*, frames: int = 100, out: str | Path | None = None) -> dict[str, Any]:
    """Seconds to diagnose a ``frames``-frame capture at the paper's config, and the ratio to simulating it."""
    from radaraug.diagnosis import diagnose
    from radaraug.io import write_capture

    cfg = RadarConfig.bgt60tr13c()
    t0 = time.perf_counter()
    counts = _capture_frames(cfg, frames)
    t_sim = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.h5"
        write_capture(path, counts.numpy().astype(np.uint16), cfg)
        t1 = time.perf_counter()
        diag = diagnose(path, max_frames=frames)
        t_diag = time.perf_counter() - t1
    r = diag.result
    result = {
        "config": cfg.describe(),
        "frames": frames,
        "diagnose_s": round(t_diag, 2),
        "simulate_capture_s": round(t_sim, 3),
        "ratio_diagnose_to_simulate": round(t_diag / t_sim, 1) if t_sim > 0 else math.inf,
        "evaluations": r.evaluations,
        "effects_added": [s["effect"] for s in r.steps],
        "error_before_dB": round(r.before.overall, 3),
        "error_after_dB": round(r.after.overall, 3),
        "target_s": 120,
        "device": "cpu",
        "threads": torch.get_num_threads(),
        "torch": torch.__version__,
        "machine": platform.machine(),
    }
    write_figures(out, result)
    return result
