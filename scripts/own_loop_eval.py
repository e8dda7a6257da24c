"""Run docs/training.md's "In your own loop" block as written, at the recorded size, and record its scores.

The block's first assignment (``ITEMS, EPOCHS, SEED, TASK = ...``) and its generated room's size are
replaced; a variant replaces the ``training_chains(...)`` call (the paper's chain as the ablation).
Each run is a fresh interpreter in its own folder, as a reader would run the block.

    python scripts/own_loop_eval.py --items 800 --epochs 4 --seeds 3 -o benchmarks/own_loop_cpu.json
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CALL = 'chains = training_chains(room.calibration, "randomdr", task=TASK, seed=SEED)'
VARIANTS = {
    "randomdr (the measured chain, default)": CALL,
    "the paper's chain (cdr, normal floor, noisy twin, dBFS image clipped to [-110, -40])":
        'from radaraug.training import CDR; '
        'chains = training_chains(room.calibration, CDR(floor="normal", twin_noise_offset_db=None), task=TASK, '
        'seed=SEED, image={"representation": "paper", "clip_range": [-110.0, -40.0], "excise_persistent_db": None, '
        '"excise_interference_db": None})',
}


def block() -> str:
    """The Python block after the ``own-loop`` marker of docs/training.md."""
    text = (ROOT / "docs" / "training.md").read_text(encoding="utf-8")
    start = text.index("<!-- own-loop")
    m = re.search(r"```python\n(.*?)```", text[start:], re.S)
    assert m is not None and CALL in m.group(1), "docs/training.md's own-loop block changed: update this script"
    return m.group(1)


def run(code: str, room: Path) -> float:
    """The balanced accuracy the block prints, run in a fresh interpreter in an empty folder."""
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        r = subprocess.run([sys.executable, "-c", code.replace('"room"', repr(str(room)))], cwd=tmp, env=env,
                           capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-3000:])
    m = re.search(r"balanced accuracy ([0-9.]+)", r.stdout)
    if m is None:
        raise RuntimeError(f"the block printed no score: {r.stdout[-500:]}")
    return float(m.group(1))


def main() -> None:
    """Run every variant, task and seed; write the figures."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--items", type=int, default=800)
    ap.add_argument("--epochs", type=int, default=4)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--frames-per-count", type=int, default=60, help="the generated room's test frames per count")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    code = block()
    head = re.search(r"^ITEMS, EPOCHS, SEED, TASK = .*$", code, re.M)
    assert head is not None
    room = Path(tempfile.mkdtemp()) / "room"
    results: dict[str, dict[str, dict[str, object]]] = {}
    t0 = time.perf_counter()
    for name, call in VARIANTS.items():
        for task in ("occupancy", "counting"):
            scores = []
            for seed in range(args.seeds):
                sized = code.replace(head.group(0), f"ITEMS, EPOCHS, SEED, TASK = {args.items}, {args.epochs}, {seed}, "
                                                    f"{task!r}")
                sized = sized.replace("frames_per_count=10", f"frames_per_count={args.frames_per_count}")
                scores.append(run(sized.replace(CALL, call), room))
                print(f"{name} {task} seed {seed}: {scores[-1]:.3f}", flush=True)
            results.setdefault(name, {})[task] = {
                "mean": statistics.mean(scores), "std": statistics.stdev(scores) if len(scores) > 1 else 0.0,
                "per_seed": scores}
    out = {"benchmark": "own_loop", "what": "docs/training.md's 'In your own loop' block as written (a plain "
           "PyTorch loop on training_chains), balanced accuracy on the independent generator's room, single "
           "frames; validation numbers: this room's generator chose defaults",
           "command": " ".join(["python", "scripts/own_loop_eval.py", *sys.argv[1:]]),
           "items": args.items, "epochs": args.epochs, "seeds": args.seeds, "frames_per_count": args.frames_per_count,
           "results": results, "wall_seconds": round(time.perf_counter() - t0, 1),
           "machine": {"platform": platform.platform(), "cpus": os.cpu_count()}}
    Path(args.output).write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    main()
