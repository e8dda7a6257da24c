"""Balanced accuracy at an operating point set on the empty room, from a finished ``reproduce`` run.

Each run's ``test_scores.pt`` holds the network's probabilities on its test frames and on the test
set's empty-room capture. This script scores every run three ways (the argmax, the threshold at the
empty room's largest "somebody" score, and that threshold never below 0.5), each alone and with the
static-change gate fused in, and writes per test set and variant the mean over seeds, and per
suite/variant the mean over test sets and the worst one (docs/training.md, "Issue 34, third round").

    python scripts/operating_point_eval.py RUN_DIR [--context 8] [--out RUN_DIR/operating_point.json]
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path
from typing import Any

import torch

from radaraug.detection import StaticChangeDetector
from radaraug.training.metrics import (
    balanced_accuracy,
    confusion_matrix,
    context_predictions,
    empty_room_threshold,
    gated_predictions,
    operating_point_predictions,
)

VARIANTS = ("argmax", "empty_room", "empty_room_at_least_half")


def predictions(scores: dict[str, Any], context: int) -> dict[str, torch.Tensor]:
    """Each variant's predicted classes of one run's test frames."""
    probs, starts, cal = scores["probs"], scores["recording_starts"], scores["calibration_probs"]
    thr = empty_room_threshold(cal, context)
    return {"argmax": context_predictions(probs, starts, context),
            "empty_room": operating_point_predictions(probs, starts, context, thr),
            "empty_room_at_least_half": operating_point_predictions(probs, starts, context, max(0.5, thr))}


def main() -> None:
    """Score every run of RUN_DIR and write the JSON table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir", type=Path)
    ap.add_argument("--context", type=int, default=8, help="the classifier's context frames (the recipes': 8)")
    ap.add_argument("--margin-db", type=float, default=3.0, help="the static gate's margin")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    report = json.loads((args.run_dir / "report.json").read_text())
    table: dict[str, Any] = {}
    for name, ts in report["test_sets"].items():
        det = StaticChangeDetector.from_capture(ts["calibration"], margin_db=args.margin_db)
        gate = torch.cat([det.detect_capture(e["path"]) for e in ts["test"]])
        for run in sorted((args.run_dir / "runs" / name).glob("*/test_scores.pt")):
            task, variant = run.parent.name.split("_")[0], run.parent.name.split("_")[1]
            scores = torch.load(run, weights_only=True)
            if scores.get("calibration_probs") is None:
                continue
            k = scores["probs"].shape[1]
            for v, pred in predictions(scores, args.context).items():
                for gated in (False, True):
                    p = gated_predictions(pred, gate, scores["recording_starts"], args.context) if gated else pred
                    key = f"{variant}/{v}" + ("+gate" if gated else "")
                    bacc = balanced_accuracy(confusion_matrix(p, scores["labels"], k))
                    table.setdefault(task, {}).setdefault(key, {}).setdefault(name, []).append(bacc)
    out: dict[str, Any] = {"context_frames": args.context, "static_gate_margin_db": args.margin_db, "tasks": {}}
    for task, by_key in table.items():
        for key, by_set in by_key.items():
            means = {n: statistics.fmean(b) for n, b in by_set.items()}
            seeds = min(len(b) for b in by_set.values())
            suite = [statistics.fmean(by_set[n][i] for n in by_set) for i in range(seeds)]
            out["tasks"].setdefault(task, {})[key] = {
                "mean": statistics.fmean(means.values()), "std_over_seeds": statistics.pstdev(suite) if seeds > 1 else 0.0,
                "worst": min(means.values()), "seeds": seeds, "per_test_set": means}
            print(f"{task:9s} {key:40s} {out['tasks'][task][key]['mean']:.3f} "
                  f"(worst {out['tasks'][task][key]['worst']:.3f}) ", " ".join(f"{m:.2f}" for m in means.values()))
    dest = args.out or args.run_dir / "operating_point.json"
    dest.write_text(json.dumps(out, indent=1))
    print("wrote", dest)


if __name__ == "__main__":
    main()
