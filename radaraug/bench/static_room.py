"""`radaraug bench static-room`: the room trace's cost and convergence, image method vs SBR rays.

The paper's corridor and a furnished mesh room; the baseline is the image-method trace in the same
process. The figures are described in docs/benchmarks.md.
"""

from __future__ import annotations

import platform
import time
from pathlib import Path
from typing import Any

import torch

from radaraug.bench import write_figures
from radaraug.files import atomic_savefig

SBR_RAYS = (128, 256, 512, 1024)


def furnished_room():
    """The mesh room of the benchmark and the convergence test: ``(room, pose)``."""
    from radaraug.scene.geometry import RadarPose
    from radaraug.scene.room import box, corridor, merge

    room = merge([
        corridor(15.0, 3.0, 2.6, materials={"floor": "floorboard", "ceiling": "ceiling_board",
                                            "left_wall": "concrete", "right_wall": "concrete",
                                            "near_wall": "concrete", "far_wall": "metal"}),
        box((4.0, 1.3, 0.4), (5.0, 1.45, 1.0), "metal"),       # radiator
        box((8.0, -1.5, 0.0), (8.1, -1.35, 2.1), "wood"),      # door frame
        box((11.0, -0.4, 0.0), (11.6, 0.2, 0.9), "wood"),      # cabinet
    ])
    return room, RadarPose.look_at((0.1, 0.0, 1.2), (15.0, 0.0, 1.2))


def _timed_trace(**kw: Any) -> tuple[Any, float, torch.Tensor, torch.Tensor]:
    """A fresh trace of ``kw``: the tracer, its seconds, and its static range profile ``(r, profile)``."""
    from radaraug.raytrace.convergence import static_range_profile
    from radaraug.raytrace.tracer import RayTracer

    t0 = time.perf_counter()
    tracer = RayTracer(cache=False, **kw)
    tracer.static_paths()
    t = time.perf_counter() - t0
    return tracer, t, *static_range_profile(tracer.static_paths(), kw["config"])


def run_static_room_benchmark(
    *, rays: tuple[int, ...] = SBR_RAYS, out: str | Path | None = None, figure: str | Path | None = None,
) -> dict[str, Any]:
    """Run the benchmark (docs/benchmarks.md); write JSON to ``out`` and a PNG to ``figure``."""
    from radaraug.raytrace.convergence import compare_profiles
    from radaraug.scene.scene import Scene

    scene = Scene.builtin("corridor")
    cfg = scene.config
    # The specular part (no diffuse clutter) is what SBR rays compute: compare like with like.
    base = {"room": scene.room, "radar": scene.radar, "config": cfg}
    default, t_default, _, prof_default = _timed_trace(**base, scattering=scene.scattering)
    *_, prof_default4 = _timed_trace(**base, scattering=scene.scattering, density=4.0)
    image, t_image, r, ref = _timed_trace(**base, diffuse=False)
    _, t_dense, _, ref_dense = _timed_trace(**base, density=4.0, diffuse=False)
    interval = (2.0, min(19.5, cfg.max_range_m))
    res: dict[str, Any] = {
        "benchmark": "static-room",
        "scene": "corridor (paper corridor, 20 m x 2 m x 2.7 m)",
        "config_max_range_m": round(cfg.max_range_m, 3),
        "default_trace_s": round(t_default, 3),
        "default_static_paths": default.static_paths().num_paths,
        "default_vs_density4": _cmp(compare_profiles(r, prof_default, prof_default4, interval_m=interval)),
        "image_trace_s": round(t_image, 3),
        "image_static_paths": image.static_paths().num_paths,
        "image_vs_density4": _cmp(compare_profiles(r, ref, ref_dense, interval_m=interval)),
        "image_density4_trace_s": round(t_dense, 3),
        "sbr": [],
    }
    profiles = {"default (image method + diffuse clutter)": prof_default, "image method": ref}
    for n in rays:
        sbr, t, _, prof = _timed_trace(**base, method="sbr", rays=n, max_bounces=3)
        profiles[f"SBR {n}x{n} rays"] = prof
        res["sbr"].append({"rays": n, "trace_s": round(t, 2), "ratio_to_image": round(t / t_image, 1),
                           "paths": sbr.static_paths().num_paths,
                           "vs_image": _cmp(compare_profiles(r, prof, ref, interval_m=interval))})
    room, pose = furnished_room()
    mesh, t_mesh, _, p1 = _timed_trace(room=room, radar=pose, config=cfg, diffuse=False)
    _, t_mesh4, _, p4 = _timed_trace(room=room, radar=pose, config=cfg, density=4.0, diffuse=False)
    res["mesh_room"] = {"trace_s": round(t_mesh, 3), "density4_trace_s": round(t_mesh4, 3),
                        "static_paths": mesh.static_paths().num_paths,
                        "vs_density4": _cmp(compare_profiles(r, p1, p4, interval_m=interval))}
    res.update(torch_version=torch.__version__, cpu=platform.machine(), threads=torch.get_num_threads())
    write_figures(out, res)
    if figure is not None:
        _plot(r, profiles, figure)
    return res


def _cmp(c: Any) -> dict[str, float]:
    return {"far_peak_range_m": round(c.far_peak_range_m, 2), "far_peak_error_dB": round(c.far_peak_error_dB, 2),
            "rms_error_dB": round(c.rms_error_dB, 2), "max_error_dB": round(c.max_error_dB, 2), "bins": c.bins}


def _plot(r: torch.Tensor, profiles: dict[str, torch.Tensor], path: str | Path) -> None:
    from radaraug._optional import pyplot

    plt = pyplot()

    fig, ax = plt.subplots(figsize=(8, 4.2))
    for name, prof in profiles.items():
        main = name == "image method"
        ax.plot(r.numpy(), prof.numpy(), lw=2.2 if main else 1.0, color="k" if main else None,
                ls=":" if name.startswith("default") else "-", label=name)
    ax.set_xlabel("range (m)")
    ax.set_ylabel("static range profile (dB, ideal receiver)")
    ax.set_title("Paper corridor: static room vs ray density")
    ax.set_ylim(max(float(min(p.min() for p in profiles.values())), -200), None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, path, dpi=110)
    plt.close(fig)
