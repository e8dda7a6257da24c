"""Figures of the twin's checks (docs/simulation.md), beside the checks they show."""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import torch

from radaraug._files import atomic_savefig
from radaraug._optional import lazy_import


def _doppler_db(x: torch.Tensor) -> torch.Tensor:
    from radaraug.transforms import RangeDoppler

    p = RangeDoppler()(x).abs().square().mean(dim=1).sum(dim=1)
    return 10 * torch.log10(p.clamp_min(1e-30))


def plot_limb_doppler_check(path: str | os.PathLike, frames: int = 4) -> Path:
    """A walker's Doppler profiles: a trace at every chirp vs the twin's frames.

    The twin with the echo's velocity at the segment centre (before issue 22) and at the specular
    point (now). Paper corridor, walker only, ideal receiver, no multipath; one panel per frame.
    """
    plt = lazy_import("matplotlib.pyplot", feature="figures")
    from radaraug.scene.people import Walker
    from radaraug.scene.people.skeleton import Skeleton
    from radaraug.scene.scene import Scene
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.sim.twin import DigitalTwin

    scene = Scene.builtin("corridor")
    cfg = scene.config
    walker = Walker(start=(2.0, 0.3), heading_rad=0.0)
    times = torch.arange(frames, dtype=torch.float64) * (1.1 / frames)

    def twin_frames() -> torch.Tensor:
        twin = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=[]), multipath=False, dtype=torch.float64)
        return twin.simulate([walker], times) - twin.simulate([], times)

    now = twin_frames()
    with_turn = Skeleton.ellipsoids
    Skeleton.ellipsoids = lambda self, *a, **kw: dataclasses.replace(  # type: ignore[method-assign]
        with_turn(self, *a, **kw), angular_velocities=None)
    try:
        before = twin_frames()
    finally:
        Skeleton.ellipsoids = with_turn  # type: ignore[method-assign]
    one = cfg.replace(num_chirps_per_frame=1)
    single = Scene.builtin("corridor")
    single.config = one
    chirp = DigitalTwin(single, config=one, receiver=FMCWReceiver(one, effects=[]), multipath=False, intra_frame=0,
                        dtype=torch.float64)
    m = cfg.num_chirps_per_frame
    tc = (times[:, None] + torch.arange(m, dtype=torch.float64) * cfg.chirp_repetition_time_s).reshape(-1)
    ref = chirp.simulate([walker], tc) - chirp.simulate([], tc)
    ref = ref.reshape(frames, m, *ref.shape[1:]).squeeze(3).transpose(1, 2)
    curves = {"a trace at every chirp (reference)": _doppler_db(ref), "twin, echo at the centre's velocity (before)":
              _doppler_db(before), "twin, echo at the specular point (now)": _doppler_db(now)}
    bins = torch.arange(m) - m // 2
    fig, axes = plt.subplots(1, frames, figsize=(3.2 * frames, 3.0), sharey=True)
    for k, ax in enumerate(axes):
        top = float(curves["a trace at every chirp (reference)"][k].max())
        for (label, c), style in zip(curves.items(), ("k-", "C3--", "C0:")):
            ax.plot(bins, c[k] - top, style, label=label, lw=1.4)  # RangeDoppler centres zero Doppler
        ax.set_title(f"t = {float(times[k]):.2f} s", fontsize=9)
        ax.set_xlabel("Doppler bin")
        ax.set_ylim(-45, 3)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("power re reference peak (dB)")
    axes[0].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    out = atomic_savefig(fig, path, dpi=110)
    plt.close(fig)
    return out
