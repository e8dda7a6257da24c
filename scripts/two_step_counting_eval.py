"""Counting decided in two steps, from a finished ``reproduce`` run: occupancy says nobody, else counting's 1 vs 2.

The occupancy network (with its context and the static-change gate) decides 0 against >= 1 person; the
counting network's probabilities of 1 and 2, renormalized, with the same causal context, decide between
those. Scored beside the counting network with the gate (docs/training.md, issue 34's decision table).

    python scripts/two_step_counting_eval.py RUN_DIR [--method randomdr] [--out FILE]
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
    gated_predictions,
)


def main() -> None:
    """Score every test set and seed of RUN_DIR both ways and write the JSON table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir", type=Path)
    ap.add_argument("--method", default="randomdr")
    ap.add_argument("--context", type=int, default=8)
    ap.add_argument("--margin-db", type=float, default=3.0)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    report = json.loads((args.run_dir / "report.json").read_text())
    per: dict[str, dict[str, list[float]]] = {"counting+gate": {}, "two_step": {}}
    for name, ts in report["test_sets"].items():
        det = StaticChangeDetector.from_capture(ts["calibration"], margin_db=args.margin_db)
        gate = torch.cat([det.detect_capture(e["path"]) for e in ts["test"]])
        for occ_file in sorted((args.run_dir / "runs" / name).glob(f"occupancy_{args.method}_seed*/test_scores.pt")):
            seed = occ_file.parent.name.rsplit("seed", 1)[1]
            o = torch.load(occ_file, weights_only=True)
            c = torch.load(args.run_dir / "runs" / name / f"counting_{args.method}_seed{seed}" / "test_scores.pt",
                           weights_only=True)
            if not torch.equal(o["labels"], (c["labels"] > 0).long()):
                raise SystemExit(f"{name} seed {seed}: the two tasks' test frames differ")
            starts = c["recording_starts"]
            occupied = gated_predictions(context_predictions(o["probs"], starts, args.context), gate, starts,
                                         args.context)
            counted = gated_predictions(context_predictions(c["probs"], starts, args.context), gate, starts,
                                        args.context)
            one_or_two = c["probs"][:, 1:] / c["probs"][:, 1:].sum(1, keepdim=True)
            two_step = torch.where(occupied == 0, 0, context_predictions(one_or_two, starts, args.context) + 1)
            for key, pred in (("counting+gate", counted), ("two_step", two_step)):
                per[key].setdefault(name, []).append(balanced_accuracy(confusion_matrix(pred, c["labels"], 3)))
    out: dict[str, Any] = {"run": str(args.run_dir.name), "method": args.method, "context_frames": args.context,
                           "static_gate_margin_db": args.margin_db, "variants": {}}
    for key, by_set in per.items():
        means = {n: statistics.fmean(v) for n, v in by_set.items()}
        seeds = min(len(v) for v in by_set.values())
        suite = [statistics.fmean(by_set[n][i] for n in by_set) for i in range(seeds)]  # the suite mean per seed
        out["variants"][key] = {"mean": round(statistics.fmean(means.values()), 3),
                                "std_over_seeds": round(statistics.pstdev(suite), 3) if seeds > 1 else 0.0,
                                "worst": round(min(means.values()), 3), "seeds": seeds,
                                "per_test_set": {n: round(m, 3) for n, m in means.items()}}
        v = out["variants"][key]
        print(f"{key:14s} {v['mean']:.3f} ± {v['std_over_seeds']:.3f} (worst {v['worst']:.3f})")
    dest = args.out or args.run_dir / "two_step_counting.json"
    dest.write_text(json.dumps(out, indent=1) + "\n")
    print("wrote", dest)


if __name__ == "__main__":
    main()
