"""Twin vs recording: the room's zero-Doppler clutter with and without diffuse scattering.

The fitting script of :data:`radaraug.scene.scattering.DIFFUSE_DEFAULTS` and its figure
(docs/diffuse_clutter.md); its functions are imported from this file (``sys.path`` to ``scripts/``). Profiles are the mean over frames and RX of the zero-Doppler power per
range bin, in dBFS (:data:`radaraug.units.DB_CONVENTION`), as the calibration's ``range_profile``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.files import atomic_savefig
from radaraug.raytrace.diffuse import diffuse_paths
from radaraug.scene.scene import Scene
from radaraug.sensor.paths import Paths
from radaraug.transforms import RangeDoppler


@torch.no_grad()
def zero_doppler_profile_db(frames: torch.Tensor) -> torch.Tensor:
    """Mean zero-Doppler power per range bin (dBFS) of raw frames ``(F, rx, chirps, samples)``."""
    x = RangeDoppler()(frames.to(torch.float64))
    p = x[..., x.shape[-1] // 2].abs().square().mean(dim=(0, 1))
    return 10 * torch.log10(p.clamp_min(1e-30))


@torch.no_grad()
def twin_profiles(
    scene: Scene,
    config: RadarConfig,
    *,
    gain_dB: float = 0.0,
    scattering: Mapping[str, Any] | None = None,
    seed: int = 0,
    frames: int = 16,
) -> dict[str, torch.Tensor]:
    """Zero-Doppler profiles (dBFS) of the empty scene: specular only and specular + diffuse.

    Args:
        scene: the room (its people are ignored).
        config: radar config to simulate (e.g. a recording's).
        gain_dB: passed to :func:`~radaraug.raytrace.diffuse.diffuse_paths`.
        scattering: passed to it too, over ``scene.scattering``.
        seed: seed of the diffuse cells and of the receiver noise.
        frames: frames simulated per profile.

    Returns:
        ``{"range_m", "specular_db", "diffuse_db", "diffuse_paths"}`` (the last a 0-d count).
    """
    from radaraug.sim.twin import DigitalTwin

    twin = DigitalTwin(scene, config=config)
    tr = twin.tracer
    over = {**scene.scattering, **(scattering or {})}
    diffuse, _ = diffuse_paths(scene.room, tr.radar, tr.antenna, tr.bvh, frequency_Hz=tr.frequency_Hz,
                               seed=seed, scattering=over, gain_dB=gain_dB)
    times = twin.frame_times(range(frames))
    spec = twin.simulate(None, times, generators=torch.Generator().manual_seed(seed))
    both = DigitalTwin(scene, config=config, receiver=twin.receiver,
                       static_signal=twin.receiver.static_signal(Paths.cat([tr.static_paths(), diffuse])))
    with_diffuse = both.simulate(None, times, generators=torch.Generator().manual_seed(seed))
    n = config.num_samples_per_chirp // 2
    return {
        "range_m": torch.arange(n, dtype=torch.float64) * config.range_resolution_m,
        "specular_db": zero_doppler_profile_db(spec),
        "diffuse_db": zero_doppler_profile_db(with_diffuse),
        "diffuse_paths": torch.tensor(diffuse.num_paths),
    }


def capture_profile(path: str | os.PathLike, max_frames: int = 64) -> tuple[RadarConfig, torch.Tensor]:
    """A recording's config and zero-Doppler profile (dBFS) over its first ``max_frames`` frames."""
    from radaraug.io import open_capture

    with open_capture(path) as reader:
        return reader.config, zero_doppler_profile_db(reader.read(0, min(reader.num_frames, max_frames)))


def band_mean_db(profile_db: torch.Tensor, range_m: torch.Tensor, lo_m: float = 1.0, hi_m: float = 5.0) -> float:
    """Power mean (dB of the mean linear power) of a profile over ``lo_m <= range <= hi_m``."""
    sel = (range_m >= lo_m) & (range_m <= hi_m)
    return float(10 * torch.log10((10 ** (profile_db[sel] / 10)).mean()))


def plot_diffuse_range_profile(
    profiles: dict[str, torch.Tensor],
    captures: Sequence[tuple[str, torch.Tensor]],
    path: str | os.PathLike,
    *,
    title: str = "Corridor zero-Doppler range profile",
) -> None:
    """Figure: specular-only twin, twin with diffuse clutter and real recordings (dBFS).

    Args:
        profiles: output of :func:`twin_profiles`.
        captures: ``(label, profile_db)`` of recordings with the same range axis.
        path: output image file.
        title: figure title.
    """
    from radaraug._optional import pyplot

    plt = pyplot()

    r = profiles["range_m"].numpy()
    fig, ax = plt.subplots(figsize=(7.5, 4.2), dpi=120)
    ax.plot(r, profiles["specular_db"].numpy(), label="twin, specular only", lw=1.5)
    ax.plot(r, profiles["diffuse_db"].numpy(), label="twin + diffuse clutter", lw=1.5)
    for label, prof in captures:
        ax.plot(r[: prof.numel()], prof.numpy()[: r.size], label=label, lw=1.0, alpha=0.8)
    ax.axvspan(1.0, 5.0, color="0.9", zorder=0, label="fit band 1-5 m")
    ax.set_xlabel("range (m)")
    ax.set_ylabel("zero-Doppler power (dBFS)")
    ax.text(0.01, 0.01, "dBFS: 20 log10|X|, FFTs divided by their window sums; mean over frames and RX",
            transform=ax.transAxes, fontsize=7, color="0.35")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    atomic_savefig(fig, path)
    plt.close(fig)


__all__ = ["band_mean_db", "capture_profile", "plot_diffuse_range_profile", "twin_profiles",
           "zero_doppler_profile_db"]
