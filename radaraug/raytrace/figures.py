"""Figures of the ray tracer's documentation; matplotlib is imported only when a figure is made."""

from __future__ import annotations

import math
from pathlib import Path

import torch

from radaraug.files import atomic_savefig
from radaraug.raytrace.shadow import ellipse_obstacle_transmission, knife_edge, shadow_transmission
from radaraug.scene.people import SEGMENT_NAMES, Walker
from radaraug.scene.people.person import Person


def _walker_wall_curves(walker: Person, times: torch.Tensor, wall_m: float, radar_height_m: float,
                        lateral_axis: int, wavelength: float) -> dict[str, torch.Tensor]:
    """Model and torso-only estimates (two passes, dB) of a metal wall's return with a walker."""
    vertices = torch.tensor([[[0.0, 0.0, radar_height_m], [wall_m, 0.0, radar_height_m],
                              [0.0, 0.0, radar_height_m]]], dtype=torch.float64)
    ell = walker.ellipsoids(times)
    model = 20 * torch.log10(shadow_transmission(vertices, ell, wavelength)[:, 0].abs())
    k = SEGMENT_NAMES.index("torso")
    tc = ell.centers[:, k]
    xs = tc[:, 0]
    offset = torch.stack([tc[:, 1], tc[:, 2] - radar_height_m], -1)
    lat, vert = float(ell.semi_axes[0, k, lateral_axis]), float(ell.semi_axes[0, k, 2])
    po = torch.stack([
        ellipse_obstacle_transmission(offset[i:i + 1], (lat, vert), float(xs[i]), wall_m - float(xs[i]), wavelength)[0]
        for i in range(xs.shape[0])
    ])
    scale = torch.sqrt(2.0 / wavelength * (1 / xs + 1 / (wall_m - xs)))
    h_edge = torch.minimum(lat - offset[:, 0].abs(), vert - offset[:, 1].abs())
    return {"x": xs, "y": tc[:, 1], "model": model, "po": 40 * torch.log10(po.abs()),
            "knife_edge": 40 * torch.log10(knife_edge(h_edge * scale).abs()), "covered": h_edge > 0}


def plot_walker_shadowing(path: str | Path, *, wall_m: float = 8.0, radar_height_m: float = 1.25,
                          frames: int = 241) -> dict[str, float]:
    """Figure ``docs/img/twin/walker_shadowing.png``: a metal wall's return vs a walker's position.

    The shadowing model (all segments, both passes) against the torso's knife edge and physical-optics
    estimates, for a walk along the radar-wall line and a crossing at ``wall_m / 2`` (``docs/shadowing.md``).

    Args:
        path: PNG file to write.
        wall_m: distance to the wall, metres.
        radar_height_m: height of the radar and of the wall's foot point, metres.
        frames: walker positions per panel.

    Returns:
        Summary numbers (dB): along the line, the means over the middle half; crossing, the values at the
        closest pass and the means while the torso covers the line.
    """
    from radaraug._optional import pyplot

    plt = pyplot()

    lam = 299792458.0 / 61e9
    speed = 1.4
    along = _walker_wall_curves(
        Walker(speed_m_s=speed, start=(wall_m - 0.5, 0.0), heading_rad=math.pi),
        torch.linspace(0.0, (wall_m - 1.0) / speed, frames, dtype=torch.float64), wall_m, radar_height_m, 1, lam)
    cross = _walker_wall_curves(
        Walker(speed_m_s=speed, start=(wall_m / 2, -1.5), heading_rad=math.pi / 2),
        torch.linspace(0.0, 3.0 / speed, frames, dtype=torch.float64), wall_m, radar_height_m, 0, lam)

    fig, axes = plt.subplots(1, 2, figsize=(11, 3.9), sharey=True)
    for ax, cur, key, xlabel in ((axes[0], along, "x", "walker (torso centre) x along the radar-wall line, m"),
                                 (axes[1], cross, "y", f"torso centre y, crossing the line at x = {wall_m / 2:g} m")):
        ax.plot(cur[key], cur["model"], label="model: knife edge per person, 2 passes", lw=1.8)
        ax.plot(cur[key], cur["knife_edge"].clamp(min=-80), "--", label="knife edge, torso's nearer edge")
        ax.plot(cur[key], cur["po"], ":", label="physical optics, torso ellipse")
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("wall return vs unshadowed, dB")
    axes[0].set_title(f"Walking along the line (metal wall at {wall_m:g} m, 61 GHz)", fontsize=10)
    axes[1].set_title("Crossing the line (side view of the torso)", fontsize=10)
    axes[1].legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, path, dpi=120)
    plt.close(fig)
    xs = along["x"]
    middle = (xs > wall_m / 4) & (xs < 3 * wall_m / 4)
    i = int(torch.argmin(cross["y"].abs()))
    on = cross["covered"]
    return {
        "along_model_db_mean": float(along["model"][middle].mean()),
        "along_knife_edge_db_mean": float(along["knife_edge"][middle].mean()),
        "along_po_db_mean": float(along["po"][middle].mean()),
        "cross_model_db_closest": float(cross["model"][i]),
        "cross_knife_edge_db_closest": float(cross["knife_edge"][i]),
        "cross_po_db_closest": float(cross["po"][i]),
        "cross_model_db_mean_covered": float(cross["model"][on].mean()),
        "cross_knife_edge_db_mean_covered": float(cross["knife_edge"][on].mean()),
        "cross_po_db_mean_covered": float(cross["po"][on].mean()),
        "cross_model_db_max_off_line": float(cross["model"][cross["y"].abs() > 1.0].abs().max()),
    }


__all__ = ["plot_walker_shadowing"]
