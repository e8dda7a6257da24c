"""Figure and figures of the zero-Doppler change gate on the design suite (docs/static_change.md).

Generates the design worlds (or reuses them under OUT/worlds), fits a StaticChangeDetector on each
world's empty-room capture and scores every test frame; writes OUT/static_change_design.png (score
per frame: empty, walkers, slow walkers, standing people, with the threshold) and
OUT/static_change_design.json (per world: threshold, false alarms, detections by kind).

    python scripts/static_change_figure.py OUT [--worlds 6] [--margin-db 3]
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

from radaraug.detection import StaticChangeDetector
from radaraug.io import open_capture
from radaraug.testsets.independent.worlds import make_suite


def kind_of(people: list[dict], velocity_resolution_m_s: float) -> str:
    """``empty``, ``standing``, ``slow`` (every walker under 1.5 Doppler bins of radial speed) or ``walking``."""
    if not people:
        return "empty"
    if all(p["standing"] for p in people):
        return "standing"
    radial = [p["speed_m_s"] * abs(math.cos(p.get("track_yaw_rad", 0.0))) for p in people if not p["standing"]]
    return "slow" if max(radial) / velocity_resolution_m_s < 1.5 else "walking"


def main() -> None:
    """Generate (or reuse) the design worlds, score them and write the figure and the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--worlds", type=int, default=6)
    ap.add_argument("--margin-db", type=float, default=3.0)
    args = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    args.out.mkdir(parents=True, exist_ok=True)
    suite = make_suite(args.out / "worlds", "design", worlds=args.worlds, frames_per_count=60, progress=False)
    cols = 3
    rows = math.ceil(len(suite) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.0 * rows), squeeze=False)
    colors = {"empty": "tab:gray", "walking": "tab:blue", "slow": "tab:orange", "standing": "tab:red"}
    record = {}
    for ax, (world, made) in zip(axes.flat, suite):
        det = StaticChangeDetector.from_capture(made.calibration, margin_db=args.margin_db)
        manifest = json.loads(Path(made.manifest).read_text())
        vres = world.config.velocity_resolution_m_s
        by_kind: dict[str, list[float]] = {k: [] for k in colors}
        for entry in manifest["files"]["tests"]:
            scores = det.score(open_capture(Path(made.manifest).parent / entry["path"]).read(as_float=False)).tolist()
            i = 0
            for ep in entry["episodes"]:
                by_kind[kind_of(ep["people"], vres)] += scores[i:i + ep["frames"]]
                i += ep["frames"]
        x0 = 0
        for kind, vals in by_kind.items():
            ax.scatter(range(x0, x0 + len(vals)), vals, s=3, color=colors[kind], label=kind)
            x0 += len(vals)
        ax.axhline(det.threshold_db, color="k", lw=0.8, ls="--")
        ax.set_title(f"{world.name} (Doppler bin {vres:.2f} m/s)", fontsize=9)
        ax.set_ylabel("score (dB)")
        record[world.name] = {
            "threshold_db": det.threshold_db, "calibration_max_db": float(det.calibration_scores_db.max()),
            "disturbances": list(world.disturbances), "velocity_resolution_m_s": vres,
            **{f"fired_{kind}": (sum(v > det.threshold_db for v in vals) / len(vals) if vals else None)
               for kind, vals in by_kind.items()},
            **{f"frames_{kind}": len(vals) for kind, vals in by_kind.items()}}
    for ax in list(axes.flat)[len(suite):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7, markerscale=3)
    fig.suptitle("Zero-Doppler change vs each world's empty room (dashed: threshold); design suite, validation")
    fig.tight_layout()
    fig.savefig(args.out / "static_change_design.png", dpi=110)
    (args.out / "static_change_design.json").write_text(json.dumps(
        {"kind": "validation (design suite)", "margin_db": args.margin_db, "worlds": record}, indent=1))
    for name, r in record.items():
        print(name, {k: round(v, 3) if isinstance(v, float) else v for k, v in r.items()})


if __name__ == "__main__":
    main()
