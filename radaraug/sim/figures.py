"""Figures of the twin's checks (docs/simulation.md), beside the checks they show."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import torch

from radaraug._optional import lazy_import
from radaraug.files import atomic_savefig
from radaraug.scene.geometry import Ellipsoids
from radaraug.scene.people import Walker
from radaraug.scene.people.skeleton import without_turn
from radaraug.scene.scene import Scene
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.twin import DigitalTwin
from radaraug.transforms import RangeDoppler


def doppler_profiles_db(x: torch.Tensor) -> torch.Tensor:
    """Per-frame Doppler profiles ``(T, chirps)``, dB, of frames ``(T, RX, chirps, samples)`` (zero Doppler centred)."""
    p = RangeDoppler()(x).abs().square().mean(dim=1).sum(dim=1)
    return 10 * torch.log10(p.clamp_min(1e-30))


def traced_at_every_chirp(scene_name: str, people: list, times: torch.Tensor) -> torch.Tensor:
    """The people's frames ``(T, RX, chirps, samples)`` built without any rate model (the empty room's subtracted).

    One-chirp frames, each traced at its own chirp's time, stacked (ideal receiver, no multipath,
    float64): the reference the twin's motion inside a frame is checked against.
    """
    single = Scene.builtin(scene_name)
    cfg = single.config
    single.config = cfg.replace(num_chirps_per_frame=1)
    m = cfg.num_chirps_per_frame
    tc = (times[:, None] + torch.arange(m, dtype=torch.float64) * cfg.chirp_repetition_time_s).reshape(-1)
    stacked = _people_only(_ideal_twin(single, intra_frame=0), people, tc)  # (T M, RX, 1, samples)
    return stacked.reshape(len(times), m, *stacked.shape[1:]).squeeze(3).transpose(1, 2)


def plot_limb_doppler_check(path: str | os.PathLike, frames: int = 4) -> Path:
    """A walker's Doppler profiles: traced per chirp vs the twin, echo at the centre (old) or specular point."""
    lazy_import("matplotlib.pyplot", feature="figures")  # a missing matplotlib fails before the simulation
    scene = Scene.builtin("corridor")
    walker = Walker(start=(2.0, 0.3), heading_rad=0.0)
    times = torch.arange(frames, dtype=torch.float64) * (1.1 / frames)
    now = _people_only(_ideal_twin(scene), [walker], times)
    with without_turn():
        before = _people_only(_ideal_twin(scene), [walker], times)
    ref = traced_at_every_chirp("corridor", [walker], times)
    curves = {"a trace at every chirp (reference)": doppler_profiles_db(ref),
              "twin, echo at the centre's velocity (before)": doppler_profiles_db(before),
              "twin, echo at the specular point (now)": doppler_profiles_db(now)}
    return _plot_doppler_profiles(path, curves, times)


def _ideal_twin(scene: Scene, **options: Any) -> DigitalTwin:
    """A float64 twin of ``scene`` with an ideal receiver (no effects) and no multipath."""
    return DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), multipath=False, dtype=torch.float64,
                       **options)


def _people_only(twin: DigitalTwin, people: list, times: torch.Tensor) -> torch.Tensor:
    """The people's frames: ``twin``'s frames with them less those of the empty room."""
    return twin.simulate(people, times) - twin.simulate([], times)


def _plot_doppler_profiles(path: str | os.PathLike, curves: dict[str, torch.Tensor], times: torch.Tensor) -> Path:
    """One panel per frame: the profiles ``(T, chirps)`` dB of ``curves`` (the first is the reference, black)."""
    plt = lazy_import("matplotlib.pyplot", feature="figures")
    ref = next(iter(curves.values()))
    m = ref.shape[-1]
    bins = torch.arange(m) - m // 2  # RangeDoppler centres zero Doppler
    fig, axes = plt.subplots(1, ref.shape[0], figsize=(3.2 * ref.shape[0], 3.0), sharey=True)
    for k, ax in enumerate(axes):
        top = float(ref[k].max())
        for (label, c), style in zip(curves.items(), ("k-", "C3--", "C0:")):
            ax.plot(bins, c[k] - top, style, label=label, lw=1.4)
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


class TurningRod:
    """A thin rigid ellipsoid (0.6 m x 0.1 m) that turns at ``omega`` rad/s about the vertical as it moves.

    The harshest case for the twin's per-frame models (its specular point and its shadow on the
    room change fastest): the check of :meth:`~radaraug.sim.twin.DigitalTwin.shadow_knots`.
    """

    def __init__(self, start: tuple[float, float, float] = (3.0, 0.2, 1.0), velocity_m_s: float = 1.2,
                 omega: float = 6.0) -> None:
        self.start = torch.tensor(start, dtype=torch.float64)
        self.velocity = torch.tensor([velocity_m_s, 0.0, 0.0], dtype=torch.float64)
        self.omega = omega

    def ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        """The rod at times ``t`` ``(T,)``: ``(T, 1)`` ellipsoids with their velocities and spin."""
        t = t.to(torch.float64).reshape(-1)
        n = t.shape[0]
        ang = self.omega * t
        cos, sin, zero, one = ang.cos(), ang.sin(), torch.zeros_like(ang), torch.ones_like(ang)
        rot = torch.stack([torch.stack([cos, -sin, zero], -1), torch.stack([sin, cos, zero], -1),
                           torch.stack([zero, zero, one], -1)], -2)
        axes = torch.tensor([0.3, 0.05, 0.05], dtype=torch.float64).expand(n, 1, 3)
        spin = torch.tensor([0.0, 0.0, self.omega], dtype=torch.float64).expand(n, 1, 3)
        return Ellipsoids((self.start + t[:, None] * self.velocity)[:, None], axes.clone(), rot[:, None],
                          self.velocity.expand(n, 1, 3).clone(), "skin", spin.clone())


def rod_frame_times(frames: int) -> torch.Tensor:
    """Start times ``(frames,)`` of the turning-rod check's frames: 0.14 s apart (the rod turns 0.84 rad)."""
    return torch.arange(frames, dtype=torch.float64) * 0.14


def shadow_in_frame_profiles(frames: int = 6, intervals: tuple[int, ...] = (0, 2)) -> dict[str, torch.Tensor]:
    """Doppler profiles ``(T, chirps)`` dB of a :class:`TurningRod`: traced per chirp vs the twin per ``intervals``."""
    scene = Scene.builtin("corridor")
    rod = TurningRod()
    times = rod_frame_times(frames)
    out = {"reference": doppler_profiles_db(traced_at_every_chirp("corridor", [rod], times))}
    for k in intervals:
        twin = _ideal_twin(scene, shadow_intervals=k)
        out[f"shadow_intervals={k}"] = doppler_profiles_db(_people_only(twin, [rod], times))
    return out


def plot_shadow_in_frame_check(path: str | os.PathLike, frames: int = 4) -> Path:
    """A turning rod's Doppler profiles: a trace at every chirp vs the twin with its shadow held or moving."""
    lazy_import("matplotlib.pyplot", feature="figures")  # a missing matplotlib fails before the simulation
    curves = shadow_in_frame_profiles(frames, intervals=(0, 2))
    labels = {"reference": "a trace at every chirp (reference)",
              "shadow_intervals=0": "twin, shadow held for the frame (default)",
              "shadow_intervals=2": "twin, shadow_intervals=2"}
    return _plot_doppler_profiles(path, {labels[k]: c for k, c in curves.items()}, rod_frame_times(frames))
