"""Which frames the classifiers miss on the design suite: by kind of person, and the counting confusions.

Reads a finished ``radaraug reproduce --test-sets design`` run (its ``runs/*/test_scores.pt`` and the
worlds' manifests), scores each frame with the run's frame context and with the static-change gate fused
in, and sorts the errors by what the frame holds: nobody, walkers (one at least 1.5 Doppler bins of radial
speed), slow walkers (every walker under that), standing people. Validation numbers: the design suite is
looked at. docs/static_change.md and docs/training.md quote the record.

    radaraug reproduce --quick --seeds 3 --methods randomdr --test-sets design --worlds 8 --no-ablation -o RUN
    python scripts/design_errors.py RUN -o benchmarks/heldout_design_errors_cpu.json
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
from collections import Counter
from pathlib import Path

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.detection import StaticChangeDetector
from radaraug.errors import ConfigError
from radaraug.files import atomic_write_json
from radaraug.files import load_json as _load_json
from radaraug.testsets.independent import room as room_mod
from radaraug.testsets.independent import walkers
from radaraug.testsets.independent.worlds import draw_world
from radaraug.training.metrics import context_predictions, gated_predictions

_spec = importlib.util.spec_from_file_location("static_change_figure", Path(__file__).with_name("static_change_figure.py"))
assert _spec is not None and _spec.loader is not None
_figure = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_figure)
kind_of = _figure.kind_of  # one definition of the kinds, shared with the gate's figure

KINDS = ("empty", "walking", "slow", "standing")


def load_json(path: Path) -> dict:
    """A run's or a world's JSON (its path named in the error)."""
    return _load_json(path, error=ConfigError)


def _moving(people: list[dict], velocity_resolution_m_s: float) -> int:
    """How many of ``people`` walk at >= 1.5 Doppler bins of radial speed (off the blanked zero Doppler)."""
    return sum(not p["standing"] and p["speed_m_s"] * abs(math.cos(p.get("track_yaw_rad", 0.0)))
               >= 1.5 * velocity_resolution_m_s for p in people)


def _frames(manifest: Path, velocity_resolution_m_s: float) -> tuple[list[str], list[int]]:
    """Every test frame's kind and number of moving people, in test order (the manifest's test files')."""
    kinds: list[str] = []
    moving: list[int] = []
    for entry in load_json(manifest)["files"]["tests"]:
        for ep in entry["episodes"]:
            kinds += [kind_of(ep["people"], velocity_resolution_m_s)] * int(ep["frames"])
            moving += [_moving(ep["people"], velocity_resolution_m_s)] * int(ep["frames"])
    return kinds, moving


def _pairs(manifest: Path, config: RadarConfig, mount: room_mod.Mount,
           image: tuple[int, int]) -> tuple[list[bool | None], list[float | None]]:
    """Per test frame of two people: whether their torsos sit >= 1 image pixel apart, and their level gap (dB).

    The pixel: the network's input (resized from the range-Doppler map) in range or in Doppler. The gap:
    the two people's received power by the radar equation (their mean RCS, the antenna pattern, range).
    None for other frames.
    """
    fields = set(walkers.Person.__dataclass_fields__)
    px_range = config.range_resolution_m * config.num_range_bins / image[0]
    px_speed = config.velocity_resolution_m_s * config.num_chirps_per_frame / image[1]
    out: list[bool | None] = []
    gaps: list[float | None] = []
    for entry in load_json(manifest)["files"]["tests"]:
        for ep in entry["episodes"]:
            n = int(ep["frames"])
            if len(ep["people"]) != 2:
                out += [None] * n
                gaps += [None] * n
                continue
            t = float(ep["t0_s"]) + np.arange(n) * config.frame_repetition_time_s
            dt = walkers.DERIVATIVE_STEP_S
            rv, level = [], []
            for p in ep["people"]:
                person = walkers.Person(**{k: v for k, v in p.items() if k in fields})
                r, u = room_mod.look(walkers.positions(person, t)[0], mount)  # the pelvis' range (F,)
                level.append(room_mod.level_dB(10 ** (p["rcs_dBsm"] / 10), r, u, config.wavelength_m))
                rate = (room_mod.look(walkers.positions(person, t + dt)[0], mount)[0]
                        - room_mod.look(walkers.positions(person, t - dt)[0], mount)[0]) / (2 * dt)
                rv.append((r, rate))
            apart = (np.abs(rv[0][0] - rv[1][0]) >= px_range) | (np.abs(rv[0][1] - rv[1][1]) >= px_speed)
            out += [bool(a) for a in apart]
            gaps += [float(g) for g in np.abs(level[0] - level[1])]
    return out, gaps


def _world_manifests(run: Path) -> dict[str, Path]:
    """World name -> its manifest, for every held-out world the run generated."""
    out = {}
    for path in sorted(run.rglob("manifest.json")):
        data = load_json(path)
        if data.get("format") == "radaraug-heldout-world":
            out[data["world"]["name"]] = path
    return out


def main() -> None:
    """Score every run of the design suite by kind of frame and write the record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path, help="the reproduce run's output folder")
    ap.add_argument("-o", "--output", type=Path, required=True)
    ap.add_argument("--method", default="randomdr")
    ap.add_argument("--margin-db", type=float, default=3.0)
    ap.add_argument("--context-frames", type=int, default=None, help="default: the run's (its report.json)")
    args = ap.parse_args()
    report = load_json(args.run / "report.json")
    context = args.context_frames or int(report["settings"]["context_frames"])
    worlds = _world_manifests(args.run)
    missed: dict[str, Counter] = {"network": Counter(), "gated": Counter()}
    frames: Counter = Counter()
    confusion = {"network": torch.zeros(3, 3, dtype=torch.long), "gated": torch.zeros(3, 3, dtype=torch.long)}
    # counting: true count x predicted count, split by how many people move off zero Doppler
    by_moving = {how: torch.zeros(3, 3, 3, dtype=torch.long) for how in confusion}
    # two-person frames: predicted count, split by whether the two sit apart in the network's image
    pairs = {how: {"apart": Counter(), "same_pixel": Counter()} for how in confusion}
    gap_bins = (("gap_under_6_dB", 0.0, 6.0), ("gap_6_to_15_dB", 6.0, 15.0), ("gap_over_15_dB", 15.0, math.inf))
    by_gap = {how: {name: Counter() for name, *_ in gap_bins} for how in confusion}
    image = tuple(int(v) for v in report["settings"]["image_size"])
    per_world: dict[str, dict] = {}
    seeds: set[int] = set()
    for name, manifest in worlds.items():
        data = load_json(manifest)
        world_dir = manifest.parent
        config = RadarConfig.from_dict(data["config"])
        kinds, moving = _frames(manifest, config.velocity_resolution_m_s)
        world = draw_world(data["world"]["suite"], int(data["world"]["index"]))
        apart, gaps = _pairs(manifest, config, world.room.mount, image)
        det = StaticChangeDetector.from_capture(world_dir / data["files"]["calibration"]["path"], margin_db=args.margin_db)
        gate = torch.cat([det.detect_capture(world_dir / e["path"]) for e in data["files"]["tests"]])
        row: dict[str, dict] = {}
        for task in ("occupancy", "counting"):
            for scores_file in sorted((args.run / "runs" / name).glob(f"{task}_{args.method}_seed*/test_scores.pt")):
                seeds.add(int(scores_file.parent.name.rsplit("seed", 1)[1]))
                s = torch.load(scores_file, weights_only=True)
                probs, labels, starts = s["probs"], s["labels"], s["recording_starts"]
                if len(probs) != len(kinds):
                    raise SystemExit(f"{scores_file}: {len(probs)} frames, the manifest has {len(kinds)}")
                net = context_predictions(probs, starts, context)
                fused = gated_predictions(net, gate, starts, context)
                for how, pred in (("network", net), ("gated", fused)):
                    if task == "occupancy":
                        wrong = pred != labels
                        for k in KINDS:
                            idx = [i for i, kk in enumerate(kinds) if kk == k]
                            missed[how][k] += int(wrong[idx].sum())
                            if how == "network":
                                frames[k] += len(idx)
                            row.setdefault(how, Counter())[k] += int(wrong[idx].sum())
                    else:
                        confusion[how] += torch.bincount(labels * 3 + pred, minlength=9).reshape(3, 3)
                        m = torch.tensor(moving)
                        by_moving[how] += torch.bincount(m * 9 + labels * 3 + pred, minlength=27).reshape(3, 3, 3)
                        for i, a in enumerate(apart):
                            if a is not None and moving[i] == 2:
                                pairs[how]["apart" if a else "same_pixel"][int(pred[i])] += 1
                                gap = gaps[i]
                                assert gap is not None
                                name = next(nm for nm, lo, hi in gap_bins if lo <= gap < hi)
                                by_gap[how][name][int(pred[i])] += 1
        per_world[name] = {"frames": dict(Counter(kinds)), "occupancy_errors_summed_over_seeds":
                           {how: dict(c) for how, c in row.items()},
                           "gate_threshold_db": det.threshold_db}
    n = max(len(seeds), 1)
    record = {
        "benchmark": "heldout_design_errors", "kind": "validation (the design suite is looked at)",
        "command": "radaraug reproduce --quick --seeds 3 --methods randomdr --test-sets design --worlds 8 --no-ablation "
                   "-o RUN; python scripts/design_errors.py RUN -o FILE",
        "method": args.method, "worlds": len(worlds), "seeds": sorted(seeds), "context_frames": context,
        "gate_margin_db": args.margin_db,
        "kinds": "empty: nobody; walking: a walker at >= 1.5 Doppler bins of radial speed; slow: every walker "
                 "under 1.5 bins; standing: only standing people",
        "occupancy_frames_per_seed": {k: frames[k] // n for k in KINDS},
        "occupancy_error_share": {how: {k: (missed[how][k] / frames[k] if frames[k] else None) for k in KINDS}
                                  for how in missed},
        "counting_confusion_true_by_predicted_summed_over_seeds": {how: cm.tolist() for how, cm in confusion.items()},
        "counting_confusion_by_moving_people_summed_over_seeds": {
            how: {f"{k}_moving": cm[k].tolist() for k in range(3)} for how, cm in by_moving.items()},
        "run_results": {task: {k: r[k] for k in ("mean", "worst", "worst_world", "gated_mean", "gated_worst",
                                                   "single_frame_mean", "val_mean")}
                        for task, methods in report["suites"]["design"]["results"].items()
                        for name, r in methods.items() if name == args.method},
        "counting_two_moving_people_by_image_separation_summed_over_seeds": {
            how: {where: [c[k] for k in range(3)] for where, c in d.items()} for how, d in pairs.items()},
        "counting_two_moving_people_by_level_gap_summed_over_seeds": {
            how: {name: [c[k] for k in range(3)] for name, c in d.items()} for how, d in by_gap.items()},
        "level_gap": "the two people's received power apart (radar equation: mean RCS, antenna pattern, range), dB",
        "image_separation": "apart: the two torsos >= 1 pixel of the network's image apart in range or in Doppler "
                            "(pixel = map bins x map size / image size)",
        "worlds_detail": per_world,
    }
    atomic_write_json(args.output, record, indent=1)
    print(json.dumps({k: v for k, v in record.items() if k != "worlds_detail"}, indent=1))


if __name__ == "__main__":
    main()
