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


def _frames(manifest: Path, config: RadarConfig, mount: room_mod.Mount, image: tuple[int, int]) -> dict[str, list]:
    """Per test frame, in test order (the manifest's test files'): what it holds.

    ``kind``: the episode's kind (:func:`kind_of`, as the gate's figure sorts them). ``moving``: how many
    people move off the blanked zero Doppler in this frame (a walker whose torso's radial speed at the
    frame's start is >= 1.5 Doppler bins). For frames of two people, ``apart``: their torsos >= 1 pixel of
    the network's input apart in range or in Doppler; ``gap_dB``: their received powers apart (radar
    equation: mean RCS, antenna pattern, range); None for other frames.
    """
    fields = set(walkers.Person.__dataclass_fields__)
    vres = config.velocity_resolution_m_s
    px_range = config.range_resolution_m * config.num_range_bins / image[0]
    px_speed = vres * config.num_chirps_per_frame / image[1]
    dt = walkers.DERIVATIVE_STEP_S
    out: dict[str, list] = {"kind": [], "moving": [], "apart": [], "gap_dB": []}
    for entry in load_json(manifest)["files"]["tests"]:
        for ep in entry["episodes"]:
            n = int(ep["frames"])
            t = float(ep["t0_s"]) + np.arange(n) * config.frame_repetition_time_s
            ranges, rates, speeds, levels = [], [], [], []
            for p in ep["people"]:
                person = walkers.Person(**{k: v for k, v in p.items() if k in fields})
                r, u = room_mod.look(walkers.positions(person, t)[0], mount)  # the torso's range (F,)
                rate = (room_mod.look(walkers.positions(person, t + dt)[0], mount)[0]
                        - room_mod.look(walkers.positions(person, t - dt)[0], mount)[0]) / (2 * dt)
                ranges.append(r)
                rates.append(np.zeros(n) if p["standing"] else rate)  # signed: toward and away differ
                speeds.append(np.abs(rates[-1]))
                levels.append(room_mod.level_dB(10 ** (p["rcs_dBsm"] / 10), r, u, config.wavelength_m))
            out["kind"] += [kind_of(ep["people"], vres)] * n
            out["moving"] += [int(sum(v[k] >= 1.5 * vres for v in speeds)) for k in range(n)]
            if len(ep["people"]) == 2:
                apart = (np.abs(ranges[0] - ranges[1]) >= px_range) | (np.abs(rates[0] - rates[1]) >= px_speed)
                out["apart"] += [bool(x) for x in apart]
                out["gap_dB"] += [float(g) for g in np.abs(levels[0] - levels[1])]
            else:
                out["apart"] += [None] * n
                out["gap_dB"] += [None] * n
    return out


def _world_manifests(run: Path) -> dict[str, Path]:
    """World name -> its manifest, for every held-out world the run generated."""
    out = {}
    for path in sorted(run.rglob("manifest.json")):
        data = load_json(path)
        if data.get("format") == "radaraug-heldout-world":
            out[data["world"]["name"]] = path
    return out


def _suite_std(report: dict, worlds: dict, task: str, method: str, key: str) -> float:
    """The std over seeds of the suite mean (each seed's mean over the worlds)."""
    per_world = [report["test_sets"][w]["results"][task][method][key]["per_seed"] for w in worlds]
    return float(np.std([np.mean(seed) for seed in zip(*per_world)]))


def main() -> None:
    """Score every run of the design suite by kind of frame and write the record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path, help="the reproduce run's output folder")
    ap.add_argument("-o", "--output", type=Path, required=True)
    ap.add_argument("--method", default="randomdr")
    ap.add_argument("--margin-db", type=float, default=3.0)
    ap.add_argument("--context-frames", type=int, default=None, help="default: the run's (its report.json)")
    ap.add_argument("--note", default=None, help="a note to keep in the record")
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
        world = draw_world(data["world"]["suite"], int(data["world"]["index"]))
        frames_of = _frames(manifest, config, world.room.mount, image)
        kinds, moving, apart, gaps = (frames_of[k] for k in ("kind", "moving", "apart", "gap_dB"))
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
                                gap_bin = next(nm for nm, lo, hi in gap_bins if lo <= gap < hi)
                                by_gap[how][gap_bin][int(pred[i])] += 1
        per_world[name] = {"frames": dict(Counter(kinds)), "occupancy_errors_summed_over_seeds":
                           {how: dict(c) for how, c in row.items()},
                           "gate_threshold_db": det.threshold_db}
    n = max(len(seeds), 1)
    interference = report["settings"].get("excise_interference_db")  # absent from runs before the option: none
    resample = report["settings"].get("resample") or "bilinear"  # absent from runs before the option: bilinear
    record = {
        "benchmark": "heldout_design_errors", "kind": "validation (the design suite is looked at)",
        "command": "radaraug reproduce --quick --seeds 3 --methods randomdr --test-sets design --worlds 8 --no-ablation "
                   f"--excise-interference-db {'off' if interference is None else interference} "
                   + ("--resample max " if resample == "max" else "")
                   + "-o RUN; python scripts/design_errors.py RUN -o FILE",
        "excise_interference_db": interference, "resample": resample, "note": args.note,
        "method": args.method, "worlds": len(worlds), "seeds": sorted(seeds), "context_frames": context,
        "gate_margin_db": args.margin_db,
        "kinds": "per episode (scripts/static_change_figure.py kind_of): empty: nobody; walking: a walker whose "
                 "speed along its track times |cos(track yaw)| is >= 1.5 Doppler bins; slow: every walker under "
                 "that; standing: only standing people",
        "moving": "per frame: walkers whose torso's radial speed at the frame's start is >= 1.5 Doppler bins",
        "occupancy_frames_per_seed": {k: frames[k] // n for k in KINDS},
        "occupancy_error_share": {how: {k: (missed[how][k] / frames[k] if frames[k] else None) for k in KINDS}
                                  for how in missed},
        "counting_confusion_true_by_predicted_summed_over_seeds": {how: cm.tolist() for how, cm in confusion.items()},
        "counting_confusion_by_moving_people_summed_over_seeds": {
            how: {f"{k}_moving": cm[k].tolist() for k in range(3)} for how, cm in by_moving.items()},
        "run_results": {task: {**{k: r[k] for k in ("mean", "worst", "worst_world", "gated_mean", "gated_worst",
                                                      "single_frame_mean", "val_mean", "per_world")},
                               "gated_per_world": {w: report["test_sets"][w]["results"][task][name]
                                                   ["static_gate_balanced_accuracy"]["mean"] for w in r["per_world"]},
                               "mean_std_over_seeds": _suite_std(report, r["per_world"], task, name,
                                                                 "balanced_accuracy"),
                               "gated_mean_std_over_seeds": _suite_std(report, r["per_world"], task, name,
                                                                       "static_gate_balanced_accuracy")}
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
