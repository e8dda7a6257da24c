"""`radaraug bench micro-doppler`: a walker's micro-Doppler as a PNG.

One snapshot per frame vs motion inside the frame (:mod:`radaraug.sim.intra_frame`); docs/benchmarks.md.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import torch

from radaraug.files import atomic_savefig


def doppler_spectrogram(frames: torch.Tensor) -> torch.Tensor:
    """Doppler power in dB (peak 0 dB) ``(T, M)`` of frames ``(T, RX, M, N)``.

    Zero Doppler is centred (bin ``M // 2``); the range FFT power is summed over range and RX.
    """
    m = frames.shape[-2]
    rng = torch.fft.rfft(frames.double(), dim=-1)
    win = torch.hann_window(m, periodic=False, dtype=torch.float64)[:, None]
    spec = torch.fft.fftshift(torch.fft.fft(rng * win, dim=-2), dim=-2)
    power = spec.abs().pow(2).sum(dim=(1, 3))
    return 10 * torch.log10(power / power.max() + 1e-30)


def micro_doppler_before_after(
    out: str | os.PathLike | None = None, *, seconds: float = 1.0, speed_m_s: float = 1.4,
) -> dict[str, Any]:
    """Simulate the walk both ways and write the two spectrograms side by side to ``out`` (PNG).

    Returns the numbers behind the figure (window length, knot intervals used per window).
    """
    from radaraug.scene.people import Walker
    from radaraug.scene.scene import Scene
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.sensor.synthesis import ChirpTiming
    from radaraug.sim.intra_frame import chirp_times
    from radaraug.sim.twin import DigitalTwin

    scene = Scene.builtin("corridor")
    cfg = scene.config
    walker = Walker(height_m=1.8, speed_m_s=speed_m_s, start=(2.0 + speed_m_s * seconds, 0.1), heading_rad=math.pi)
    timing = ChirpTiming.from_config(cfg)
    window = float(chirp_times(timing)[-1]) + timing.prt
    times = torch.arange(0.0, seconds, window, dtype=torch.float64)
    spectra = {}
    knots: list[int] = []  # intervals per frame of the intra-frame twin
    modes: tuple[tuple[str, int | str], ...] = (("one snapshot per frame", 0), ("motion inside the frame", "auto"))
    for label, mode in modes:
        twin = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=[]), multipath=False,
                           tracer_options={"rays": 16}, intra_frame=mode)
        blocks = []
        for i in range(0, len(times), 16):
            blocks.append(twin.receiver(twin.paths([walker], times[i:i + 16])))
            if mode == "auto" and twin.last_intervals is not None:
                knots.extend(int(k) for k in twin.last_intervals)
        spectra[label] = doppler_spectrogram(torch.cat(blocks))
    v_bin = cfg.wavelength_m / (2 * timing.num_chirps * timing.prt)
    m = timing.num_chirps
    if out is not None:
        from radaraug._optional import pyplot

        plt = pyplot()

        fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True, constrained_layout=True)
        extent = [0.0, float(times[-1] + window), -m // 2 * v_bin, (m // 2 - 1) * v_bin]
        for ax, (label, s) in zip(axes, spectra.items()):
            im = ax.imshow(s.T.numpy(), origin="lower", aspect="auto", extent=extent, vmin=-40, vmax=0, cmap="viridis")
            ax.set_title(label)
            ax.set_xlabel("time (s)")
        axes[0].set_ylabel("radial velocity (m/s, + = receding)")
        fig.colorbar(im, ax=axes, label="Doppler power (dB)")
        fig.suptitle(f"Walker approaching at {speed_m_s} m/s, one {window * 1e3:.0f} ms frame per column")
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        atomic_savefig(fig, out, dpi=110)
        plt.close(fig)
    return {
        "figure": None if out is None else str(out),
        "windows": len(times),
        "window_s": window,
        "doppler_bin_m_s": v_bin,
        "knot_intervals_mean": sum(knots) / len(knots),
        "knot_intervals_max": max(knots),
    }
