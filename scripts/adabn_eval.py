"""Test-time BatchNorm statistics (AdaBN) rescored on a finished ``reproduce`` run that kept its classifiers.

Each kept classifier (RandomDR, every world and seed) is scored on its world's test captures as trained,
then with its BatchNorm running statistics recomputed (cumulative average, train-mode forward passes, no
gradient) on: the world's empty-room capture alone; the test frames themselves (transductive: every class,
in the test sets' proportions); both. Balanced accuracy with 8 frames of causal context, alone and with
the static-change gate fused in (docs/training.md, issue 34's decision table).

    python scripts/adabn_eval.py RUN_DIR [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path
from typing import Any

import torch
from torch import nn

from radaraug.inference import RadarClassifier
from radaraug.io import open_capture
from radaraug.training.metrics import (
    balanced_accuracy,
    confusion_matrix,
    context_predictions,
    gated_predictions,
)

VARIANTS = ("base", "adabn_calibration", "adabn_test", "adabn_cal+test")
METHOD, CONTEXT = "randomdr", 8


def frames_of(path: str) -> torch.Tensor:
    """Every frame of a capture, SDK floats."""
    with open_capture(path) as cap:
        return cap.read()


@torch.no_grad()
def adapted(clf: RadarClassifier, x: torch.Tensor, batch: int = 64) -> list[tuple[Any, Any, Any]]:
    """Recompute ``clf``'s BatchNorm statistics on frames ``x``; returns what :func:`restore` puts back."""
    bns = [m for m in clf.net.modules() if isinstance(m, nn.modules.batchnorm._BatchNorm)]
    saved = [(m.running_mean.clone(), m.running_var.clone(), m.momentum) for m in bns]
    for m in bns:
        m.reset_running_stats()
        m.momentum = None  # a cumulative average over every batch
    clf.net.train()
    order = torch.randperm(len(x), generator=torch.Generator().manual_seed(0))
    for i in range(0, len(x), batch):
        clf.net(clf.transforms()(x[order[i:i + batch]]))
    clf.net.eval()
    return saved


def restore(clf: RadarClassifier, saved: list[tuple[Any, Any, Any]]) -> None:
    """Put the trained statistics back."""
    bns = [m for m in clf.net.modules() if isinstance(m, nn.modules.batchnorm._BatchNorm)]
    for m, (mean, var, momentum) in zip(bns, saved):
        m.running_mean.copy_(mean)
        m.running_var.copy_(var)
        m.momentum = momentum


def score(probs: torch.Tensor, labels: torch.Tensor, starts: torch.Tensor, gate: torch.Tensor | None,
          classes: int) -> tuple[float, float]:
    """Balanced accuracy with context, and with context and the gate."""
    pred = context_predictions(probs, starts, CONTEXT)
    gated = pred if gate is None else gated_predictions(pred, gate, starts, CONTEXT)
    return (balanced_accuracy(confusion_matrix(pred, labels, classes)),
            balanced_accuracy(confusion_matrix(gated, labels, classes)))


def main() -> None:
    """Rescore every kept RandomDR classifier of RUN_DIR four ways and write the JSON table."""
    torch.set_num_threads(1)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir", type=Path)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    run = args.run_dir
    rep = json.loads((run / "report.json").read_text())
    out: dict[str, dict[str, dict[str, Any]]] = {}
    for name, ts in rep["test_sets"].items():
        cal = frames_of(ts["calibration"])
        x = torch.cat([frames_of(e["path"]) for e in ts["test"]])
        sources = {"adabn_calibration": cal, "adabn_test": x, "adabn_cal+test": torch.cat([cal, x])}
        for task, classes in (("occupancy", 2), ("counting", 3)):
            for d in sorted((run / "runs" / name).glob(f"{task}_{METHOD}_seed*")):
                recorded = torch.load(d / "test_scores.pt", weights_only=True)
                labels, starts = recorded["labels"], recorded["recording_starts"]
                clf = RadarClassifier.load(d / "classifier.pt")
                gate = clf.gate_detections(x)
                base = clf.probabilities(x)
                res: dict[str, Any] = {"base": score(base, labels, starts, gate, classes),
                                       "base_vs_recorded": float((base - recorded["probs"]).abs().max())}
                for variant, frames in sources.items():
                    saved = adapted(clf, frames)
                    res[variant] = score(clf.probabilities(x), labels, starts, gate, classes)
                    restore(clf, saved)
                out.setdefault(task, {}).setdefault(name, {})[d.name] = res
                print(task, name, d.name, {k: v for k, v in res.items()}, flush=True)
    summary: dict[str, dict[str, Any]] = {}
    for task, worlds in out.items():
        seeds = sorted({run_name.rsplit("seed", 1)[1] for runs in worlds.values() for run_name in runs})
        for variant in VARIANTS:
            for j, kind in enumerate(("context", "context+gate")):
                per_world = {w: statistics.mean(r[variant][j] for r in runs.values()) for w, runs in worlds.items()}
                per_seed = [statistics.mean(runs[f"{task}_{METHOD}_seed{s}"][variant][j] for runs in worlds.values())
                            for s in seeds]
                summary.setdefault(task, {})[f"{variant} {kind}"] = {
                    "mean": round(statistics.mean(per_world.values()), 4),
                    "std_over_seeds_of_suite_mean": round(statistics.stdev(per_seed), 4) if len(seeds) > 1 else None,
                    "worst": round(min(per_world.values()), 4),
                    "per_world": {w: round(v, 4) for w, v in per_world.items()}}
    record = {"run": run.name, "method": METHOD, "context_frames": CONTEXT, "worlds": sorted(rep["test_sets"]),
              "summary": summary, "runs": out}
    print(json.dumps(summary, indent=1))
    if args.out:
        args.out.write_text(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
