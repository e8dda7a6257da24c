"""Twin vs recording: the room's zero-Doppler clutter with and without diffuse scattering.

The fitting script of :data:`radaraug.scene.scattering.DIFFUSE_DEFAULTS` and its figure
(docs/diffuse_clutter.md); its functions are imported from this file (``sys.path`` to ``scripts/``). Profiles are
the mean over frames and RX of the zero-Doppler power per range bin, in dBFS (:data:`radaraug.units.DB_CONVENTION`),
as the calibration's ``range_profile``.

Run as a script, it measures every figure of the page's "Fit and before / after" table and "Cost" section and
writes them as one JSON record::

    python scripts/diffuse_clutter_fit.py REAL_DIR -o benchmarks/diffuse_clutter_fit_cpu.json

``REAL_DIR`` is the shared real-data folder (the two 48 dB recordings of ``jjustin__ec-international-2022``).
The twin runs at the first recording's config; specular only means the tracer without diffuse scattering
(smooth surfaces); "+ diffuse, S" the default tracer with every room finish at ``S`` and the
scatterers drawn with the seed (the seed also seeds the receiver noise).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.files import atomic_savefig
from radaraug.raytrace.diffuse import diffuse_paths, occluder_faces
from radaraug.scene.scattering import FALLBACK, DiffuseScattering, get_scattering
from radaraug.scene.scene import Scene
from radaraug.transforms import RangeDoppler

RECORDINGS = {
    "18_48_07": "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_48_07",
    "18_52_43": "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_52_43",
}
"""The real 48 dB recordings, under the real-data folder (the twin runs at the first one's config)."""

SEEDS = (0, 1, 2)
DEFAULT_S = 0.7
FIT_S = {"corridor": (0.4, DEFAULT_S), "corridor_furnished": (DEFAULT_S,)}
"""The room finishes' ``S`` simulated per built-in scene (0.4: the first guess, 0.7: the default)."""

BAND_M = (1.0, 5.0)
SUB_BANDS_M = ((1.0, 2.5), (3.0, 5.0))
"""Parts of the band (m) whose band means the record holds too (twin: the empty corridor, default S, seed 0)."""
COST_REPEATS = 3


@torch.no_grad()
def zero_doppler_profile_db(frames: torch.Tensor) -> torch.Tensor:
    """Mean zero-Doppler power per range bin (dBFS) of raw frames ``(F, rx, chirps, samples)``."""
    x = RangeDoppler()(frames.to(torch.float64))
    p = x[..., x.shape[-1] // 2].abs().square().mean(dim=(0, 1))
    return 10 * torch.log10(p.clamp_min(1e-30))


def finish_scattering(scene: Scene, S: float) -> dict[str, DiffuseScattering]:
    """Overrides that set every room finish of ``scene`` (a material at the fitted finish value) to ``S``.

    Glass, metal, skin and the absorber keep theirs; ``scene.scattering`` is the base.
    """
    out: dict[str, DiffuseScattering] = {}
    for key in scene.room.materials:
        base = get_scattering(key, scene.scattering)
        if base == FALLBACK:
            out[key] = DiffuseScattering(float(S), base.pattern, base.alpha_R)
    return out


def make_twin(
    scene: Scene,
    config: RadarConfig,
    *,
    diffuse: bool = True,
    gain_dB: float = 0.0,
    scattering: Mapping[str, Any] | None = None,
    seed: int = 0,
    receiver: Any = None,
) -> Any:
    """The empty room's twin at ``config``: specular only (``diffuse=False``) or with diffuse scattering.

    Args:
        scene: the room (its people are ignored).
        config: radar config to simulate.
        diffuse: trace the diffuse scattering (the specular reflections then keep ``sqrt(1 - S^2)``).
        gain_dB: the tracer's ``diffuse_gain_dB``.
        scattering: overrides over ``scene.scattering``.
        seed: seed of the diffuse scatterers.
        receiver: a receiver to share (None: the config's default).
    """
    from radaraug.sim.twin import DigitalTwin

    options: dict[str, Any] = {"diffuse": diffuse, "cache": False}
    if diffuse:
        options.update(scattering={**scene.scattering, **(scattering or {})}, diffuse_seed=int(seed),
                       diffuse_gain_dB=float(gain_dB))
    return DigitalTwin(scene, config=config, receiver=receiver, tracer_options=options)


@torch.no_grad()
def simulated_profile_db(twin: Any, seed: int = 0, frames: int = 16) -> torch.Tensor:
    """Zero-Doppler profile (dBFS) of ``frames`` frames of the empty room, receiver noise seeded by ``seed``."""
    times = twin.frame_times(range(frames))
    return zero_doppler_profile_db(twin.simulate(None, times, generators=torch.Generator().manual_seed(seed)))


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
        gain_dB: the tracer's ``diffuse_gain_dB``.
        scattering: overrides over ``scene.scattering`` (e.g. :func:`finish_scattering`).
        seed: seed of the diffuse cells and of the receiver noise.
        frames: frames simulated per profile.

    Returns:
        ``{"range_m", "specular_db", "diffuse_db", "diffuse_paths"}`` (the last a 0-d count).
    """
    spec = make_twin(scene, config, diffuse=False)
    both = make_twin(scene, config, gain_dB=gain_dB, scattering=scattering, seed=seed, receiver=spec.receiver)
    n = config.num_samples_per_chirp // 2
    return {
        "range_m": torch.arange(n, dtype=torch.float64) * config.range_resolution_m,
        "specular_db": simulated_profile_db(spec, seed, frames),
        "diffuse_db": simulated_profile_db(both, seed, frames),
        "diffuse_paths": torch.tensor(both.tracer.static_paths("diffuse").num_paths),
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




def range_axis_m(config: RadarConfig, bins: int) -> torch.Tensor:
    """Range (m) of the first ``bins`` range bins at ``config``."""
    return torch.arange(bins, dtype=torch.float64) * config.range_resolution_m


def diffuse_cost(scene: Scene, config: RadarConfig, *, repeats: int = COST_REPEATS) -> dict[str, Any]:
    """What :func:`diffuse_paths` does with ``scene``'s room at the defaults (seed 0), and how long it takes.

    Returns:
        triangles, area, faces that can occlude (shadow rays), visible cells (no merge), paths after the default
        merge and after a 1 cm / 0.5 m merge, and the wall time of each of ``repeats`` default calls (s).
    """
    tr = make_twin(scene, config, diffuse=False).tracer
    tri = scene.room.triangles.to(torch.float64)
    area = 0.5 * torch.linalg.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]).norm(dim=-1).sum()
    occ = occluder_faces(tri.to(tr.radar.centre.dtype), tr.radar.centre)

    def call(**kw: Any) -> int:
        paths, _ = diffuse_paths(scene.room, tr.radar, tr.antenna, tr.bvh, frequency_Hz=tr.frequency_Hz, seed=0,
                                 scattering=scene.scattering, **kw)
        return paths.num_paths

    seconds = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        paths = call()
        seconds.append(round(time.perf_counter() - t0, 3))
    return {"triangles": int(tri.shape[0]), "area_m2": round(float(area), 2),
            "occluding_faces": int(occ.sum()) if occ is not None else int(tri.shape[0]),
            "visible_cells": call(merge_bin_m=None), "paths_default_merge": paths,
            "paths_merge_1cm_0.5m": call(merge_bin_m=0.01, merge_voxel_m=0.5), "diffuse_paths_seconds": seconds}


def main(argv: Sequence[str] | None = None) -> None:
    """Measure the page's fit table and cost figures and write the JSON record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("real_dir", type=Path, help="the real-data folder (e.g. ../shared/real)")
    ap.add_argument("-o", "--output", type=Path, required=True, help="JSON record (overwritten)")
    ap.add_argument("--frames", type=int, default=16, help="frames simulated per twin profile")
    ap.add_argument("--capture-frames", type=int, default=64, help="first frames of each recording")
    ap.add_argument("--threads", type=int, default=1, help="torch threads")
    ap.add_argument("--figure", type=Path, help="also draw the profiles of seed 0 (empty corridor) to this image")
    args = ap.parse_args(argv)
    torch.set_num_threads(args.threads)
    missing = [rel for rel in RECORDINGS.values() if not (args.real_dir / rel).is_dir()]
    if missing:
        ap.error(f"not under {args.real_dir}: {missing}")
    start = time.perf_counter()

    real: dict[str, float] = {}
    real_profiles: dict[str, torch.Tensor] = {}
    config: RadarConfig | None = None
    for name, rel in RECORDINGS.items():
        cfg, prof = capture_profile(args.real_dir / rel, args.capture_frames)
        config = config or cfg
        real_profiles[name] = prof
        real[name] = round(band_mean_db(prof, range_axis_m(cfg, prof.numel()), *BAND_M), 3)
        print(f"real {name}: {real[name]:.2f} dBFS", flush=True)
    assert config is not None
    r = range_axis_m(config, config.num_samples_per_chirp // 2)

    twin: dict[str, dict[str, list[float]]] = {}
    paths: dict[str, dict[str, Any]] = {}
    seed0: dict[str, torch.Tensor] = {}
    for name, values in FIT_S.items():
        scene = Scene.builtin(name)
        spec = make_twin(scene, config, diffuse=False)
        rows: dict[str, list[float]] = {"specular": []}
        paths[name] = {"specular": spec.tracer.static_paths().num_paths}
        for seed in SEEDS:
            prof = simulated_profile_db(spec, seed, args.frames)
            rows["specular"].append(round(band_mean_db(prof, r, *BAND_M), 3))
            if name == "corridor" and seed == 0:
                seed0["specular_db"] = prof
        for S in values:
            key = f"diffuse_S{S}"
            rows[key], paths[name][key] = [], []
            for seed in SEEDS:
                both = make_twin(scene, config, scattering=finish_scattering(scene, S), seed=seed,
                                 receiver=spec.receiver)
                prof = simulated_profile_db(both, seed, args.frames)
                rows[key].append(round(band_mean_db(prof, r, *BAND_M), 3))
                paths[name][key].append(both.tracer.static_paths("diffuse").num_paths)
                if name == "corridor" and seed == 0 and S == DEFAULT_S:
                    seed0["diffuse_db"] = prof
        print(f"{name}: {rows}", flush=True)
        twin[name] = rows
    # Where the band mean comes from: the near and the far part of the band, the figure's curves.
    sub_bands = {f"{lo:g}-{hi:g} m": {
        "real_48dB": {k: round(band_mean_db(p[: r.numel()], r, lo, hi), 3) for k, p in real_profiles.items()},
        f"corridor_S{DEFAULT_S}_seed0": round(band_mean_db(seed0["diffuse_db"], r, lo, hi), 3),
    } for lo, hi in SUB_BANDS_M}
    print(f"sub-bands: {sub_bands}", flush=True)

    cost = {}
    for name in FIT_S:
        cost[name] = diffuse_cost(Scene.builtin(name), config)
        print(f"cost {name}: {cost[name]}", flush=True)

    if args.figure is not None:
        seed0["range_m"] = r
        plot_diffuse_range_profile(seed0, [(f"real 48 dB, {k}", p) for k, p in real_profiles.items()], args.figure)

    out = args.output.name if args.output.is_absolute() else args.output.as_posix()  # no machine path in the record
    record = {
        "benchmark": "diffuse-clutter-fit",
        "command": f"python scripts/diffuse_clutter_fit.py REAL_DIR -o {out}",
        "what": "docs/diffuse_clutter.md, 'Fit and before / after' and 'Cost': band_mean_db = power mean over "
                f"{BAND_M[0]:g}-{BAND_M[1]:g} m of the mean zero-Doppler power per range bin (dBFS) of the two real 48 dB "
                f"recordings (first {args.capture_frames} frames) and of the empty built-in scenes' twin at the first "
                f"recording's config ({args.frames} frames per profile; per seed {list(SEEDS)}, which seeds the diffuse "
                "scatterers and the receiver noise): specular only = tracer without diffuse scattering; diffuse_S<S> = "
                "the default tracer with every room finish at S. sub_band_mean_db: the same statistic over parts of "
                f"the band (twin: empty corridor, S {DEFAULT_S}, seed 0). static_paths: the twins' specular paths and "
                "diffuse paths per seed. cost: diffuse_paths at the defaults, seed 0, wall time of each call",
        "machine": f"{os.cpu_count()}-core {platform.machine().replace('_', '-')} CPU, torch {torch.__version__}",
        "threads": torch.get_num_threads(),
        "wall_seconds": round(time.perf_counter() - start, 1),
        "band_mean_db": {"real_48dB": real, **twin},
        "sub_band_mean_db": sub_bands,
        "static_paths": paths,
        "cost": cost,
    }
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(record, indent=1) + "\n", encoding="utf-8")
    print("wrote", args.output, f"({record['wall_seconds']} s)")


__all__ = ["band_mean_db", "capture_profile", "diffuse_cost", "finish_scattering", "make_twin",
           "plot_diffuse_range_profile", "range_axis_m", "simulated_profile_db", "twin_profiles",
           "zero_doppler_profile_db"]


if __name__ == "__main__":
    main()
