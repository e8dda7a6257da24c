"""Throughput of the receiver: ``fast`` vs ``exact`` synthesis, same process, same paths."""

from __future__ import annotations

import time

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.paths import Paths
from radaraug.sensor.point_target import point_target_paths
from radaraug.sensor.receiver import FMCWReceiver


def random_scene_paths(
    config: RadarConfig,
    num_paths: int,
    *,
    moving_fraction: float = 0.3,
    max_speed_m_s: float = 5.0,
    device: torch.device | str = "cpu",
    dtype: torch.dtype = torch.float32,
    generator: torch.Generator | None = None,
) -> Paths:
    """A scene-like path set: point scatterers at 0.5-20 m in the field of view, RCS -30..0 dBsm.

    ``moving_fraction`` of them move (walker-like speeds up to ``max_speed_m_s``), the rest are static.
    """
    g = generator if generator is not None else torch.Generator().manual_seed(0)
    r = 0.5 + 19.5 * torch.rand(num_paths, generator=g, dtype=torch.float64)
    az = (torch.rand(num_paths, generator=g, dtype=torch.float64) - 0.5) * 2.0
    el = (torch.rand(num_paths, generator=g, dtype=torch.float64) - 0.5) * 1.0
    pos = torch.stack([r * torch.sin(az) * torch.cos(el), r * torch.sin(el), r * torch.cos(az) * torch.cos(el)], -1)
    speed = (torch.rand(num_paths, generator=g, dtype=torch.float64) * 2 - 1) * max_speed_m_s
    speed = speed * (torch.rand(num_paths, generator=g, dtype=torch.float64) < moving_fraction)
    vel = pos / r[:, None] * speed[:, None]
    rcs = 10 ** (-3 * torch.rand(num_paths, generator=g, dtype=torch.float64))
    paths = point_target_paths(config, pos, vel, rcs)
    cdt = torch.complex64 if dtype == torch.float32 else torch.complex128
    return Paths(paths.delay_s.to(device, dtype), paths.delay_rate.to(device, dtype), paths.amplitude.to(device, cdt))


def _frames_per_s(receiver: FMCWReceiver, paths: Paths, num_frames: int, generator: torch.Generator) -> float:
    dev = paths.delay_s.device
    sync = torch.cuda.synchronize if dev.type == "cuda" else (lambda _: None)
    receiver(paths, generator=generator)  # warm-up (allocator, kernels)
    sync(dev)
    t0 = time.perf_counter()
    for i in range(num_frames):
        receiver(paths, generator=generator, frame_start_s=i * receiver.config.frame_repetition_time_s)
    sync(dev)
    return num_frames / (time.perf_counter() - t0)


@torch.no_grad()
def benchmark_receiver(
    config: RadarConfig,
    num_paths: int,
    num_frames: int,
    device: torch.device | str = "cpu",
    *,
    dtype: torch.dtype = torch.float32,
    exact_frames: int | None = None,
    moving_fraction: float = 0.3,
    max_speed_m_s: float = 5.0,
) -> dict:
    """Frames/s of the full default receiver (noise, filters, ADC) with ``fast`` and ``exact`` synthesis.

    One frame at a time (the on-the-fly DataLoader case), on ``device``. Also reports the
    agreement of the two syntheses on the same paths with the ideal receiver (relative RMS
    error, and max abs error relative to the peak).

    Args:
        config: radar configuration.
        num_paths: paths per frame.
        num_frames: frames timed for ``fast``.
        device: where to run.
        dtype: float32 or float64.
        exact_frames: frames timed for ``exact`` (default ``max(1, num_frames // 20)``).
        moving_fraction: share of moving scatterers.
        max_speed_m_s: speed bound of the moving scatterers.

    Returns:
        dict with ``fast_frames_per_s``, ``exact_frames_per_s``, ``speedup``, ``rel_rms_error``,
        ``max_abs_error_rel_peak``, and the settings.
    """
    device = torch.device(device)
    paths = random_scene_paths(config, num_paths, moving_fraction=moving_fraction,
                               max_speed_m_s=max_speed_m_s, device=device, dtype=dtype)
    gen = torch.Generator(device=device).manual_seed(0)
    fast = FMCWReceiver(config, synthesis="fast")
    exact = FMCWReceiver(config, synthesis="exact")
    fps_fast = _frames_per_s(fast, paths, num_frames, gen)
    fps_exact = _frames_per_s(exact, paths, exact_frames or max(1, num_frames // 20), gen)
    # Accuracy of the synthesis itself: the ideal receiver (no effects) on the same paths.
    xf = FMCWReceiver(config, effects=[], synthesis="fast")(paths).double()
    xe = FMCWReceiver(config, effects=[], synthesis="exact")(paths).double()
    err = xf - xe
    return {
        "device": str(device),
        "dtype": str(dtype).replace("torch.", ""),
        "threads": torch.get_num_threads(),
        "num_paths": num_paths,
        "num_frames": num_frames,
        "shape": list(config.frame_shape),
        "fast_frames_per_s": fps_fast,
        "exact_frames_per_s": fps_exact,
        "speedup": fps_fast / fps_exact,
        "rel_rms_error": float(err.pow(2).mean().sqrt() / xe.pow(2).mean().sqrt()),
        "max_abs_error_rel_peak": float(err.abs().max() / xe.abs().max()),
    }
