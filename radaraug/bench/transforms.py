"""`radaraug bench transforms`: the paper's RD chain in torch vs a straightforward NumPy version.

Same process, same batch of paper-size frames; the figure is the torch/NumPy frames/s ratio
(docs/benchmarks.md).
"""

from __future__ import annotations

import platform
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.bench import best_seconds, torch_threads, write_figures
from radaraug.bench.numpy_reference import numpy_rd_chain, numpy_rd_db
from radaraug.config import RadarConfig


def run_transforms_benchmark(
    *, batch: int = 32, repeats: int = 5, device: str = "cpu", out: str | Path | None = None
) -> dict[str, Any]:
    """Time both chains and return the figures (also written as JSON to ``out``).

    Args:
        batch: frames per call.
        repeats: timed repetitions (the best is kept, after one warm-up).
        device: torch device for the radaraug chain ("cpu", "cuda").
        out: optional JSON file to write.
    """
    from radaraug.transforms import CalibratedDR, ClipNormalize, Colormap, CombineRx, RangeDoppler, ToDecibels
    from radaraug.transforms._viridis import viridis_rgb

    cfg = RadarConfig.bgt60tr13c()
    gen = torch.Generator().manual_seed(0)
    shape = (batch, *cfg.frame_shape)
    # A plausible raw frame: DC offset + noise at ~1.4 counts RMS + a tone, in SDK floats.
    cube = 0.2 * torch.rand(shape, generator=gen) + 1.4 * 2 / 4095 * torch.randn(shape, generator=gen)
    t = torch.arange(cfg.num_samples_per_chirp) / cfg.sample_rate_Hz
    cube = cube + 0.01 * torch.cos(2 * torch.pi * 60e3 * t)
    dev = torch.device(device)
    x = cube.to(dev)

    mean_db, std_db, vmin, vmax = -100.0, 3.0, -110.0, -40.0
    chain = torch.nn.Sequential(
        RangeDoppler(),
        ToDecibels(),
        CalibratedDR(mean_db, std_db, generator=torch.Generator(device=dev).manual_seed(1)),
        CombineRx("mean_power", db=True),
        ClipNormalize(vmin, vmax),
        Colormap("viridis"),
    ).to(dev)

    def run_torch() -> None:
        with torch.inference_mode():
            chain(x)
        if dev.type == "cuda":
            torch.cuda.synchronize()

    x_np = cube.numpy().astype(np.float64)
    lut = np.asarray(viridis_rgb(), dtype=np.float64)
    rng = np.random.default_rng(1)

    def run_numpy() -> None:
        numpy_rd_chain(x_np, mean_db=mean_db, std_db=std_db, vmin=vmin, vmax=vmax, lut=lut, rng=rng)

    # The two chains must compute the same thing: compare them without the random clamp.
    with torch.inference_mode():
        ref_chain = torch.nn.Sequential(RangeDoppler(), ToDecibels()).to(dev)
        torch_db = ref_chain(x[:2]).double().cpu().numpy()
    np_db = numpy_rd_db(x_np[:2])
    max_diff_db = float(np.abs(np_db - torch_db)[np_db > -150].max())

    run_numpy()  # warm-up (plans, caches), as for each torch run below
    t_numpy = best_seconds(run_numpy, repeats)
    # Torch at its default thread count and single-threaded (NumPy's FFT is single-threaded, and on
    # a busy 2-core machine torch's intra-op threads contend with other processes).
    default_threads = torch.get_num_threads()
    per_threads = {}
    for n in sorted({1, default_threads}):
        with torch_threads(n):
            run_torch()
            per_threads[n] = best_seconds(run_torch, repeats)
    t_torch = per_threads[default_threads]
    result = {
        "benchmark": "transforms",
        "chain": "RangeDoppler(hann,hann) -> ToDecibels -> CalibratedDR -> CombineRx(mean_power) -> ClipNormalize -> Colormap(viridis)",
        "frame_shape": list(shape[1:]),
        "batch": batch,
        "device": str(dev),
        "torch_frames_per_s": round(batch / t_torch, 1),
        "numpy_frames_per_s": round(batch / t_numpy, 1),
        "speedup_vs_numpy": round(t_numpy / t_torch, 2),
        "max_abs_diff_db_vs_numpy": max_diff_db,
        "torch_threads": default_threads,
        "torch_frames_per_s_by_threads": {str(n): round(batch / t, 1) for n, t in per_threads.items()},
        "speedup_vs_numpy_by_threads": {str(n): round(t_numpy / t, 2) for n, t in per_threads.items()},
        "torch_version": torch.__version__,
        "numpy_version": np.__version__,
        "cpu": platform.processor() or platform.machine(),
    }
    if dev.type == "cuda":
        result["gpu"] = torch.cuda.get_device_name(dev)
    write_figures(out, result)
    return result
