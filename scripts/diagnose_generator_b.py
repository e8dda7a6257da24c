"""Run ``diagnose`` on generator B's cases and write one row per case (benchmarks/diagnose_generator_b_cpu.json).

Each case (``tests/diagnosis/generator_b.py`` ``CASES``) is simulated at a seed, written as a
capture and diagnosed in estimated mode (40 frames); a row says what was named (the search's
steps, plus declared stages refitted at other parameters), whether that is exactly the case's
effects, the verdicts, the held-out error before and after, and the fitted parameters.

    python scripts/diagnose_generator_b.py --seed 3 [--cases NAME ...] -o rows.jsonl
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from radaraug.diagnosis import diagnose  # noqa: E402
from radaraug.io import write_capture  # noqa: E402
from radaraug.units import float_to_counts  # noqa: E402
from tests.diagnosis.generator_b import CASES, Case  # noqa: E402


def row(case: Case, seed: int) -> dict:
    """Diagnose one case at ``seed``."""
    t = time.perf_counter()
    x = torch.as_tensor(case.capture(seed))
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "capture.h5"
        write_capture(path, float_to_counts(x), case.config)
        diag = diagnose(path, max_frames=40)
    steps = diag.result.steps
    named = diag.named_effects
    return {"case": case.name, "expected": sorted(case.expected), "named": named,
            "ok": sorted(named) == sorted(case.expected), "verdicts": [s["verdict"] for s in steps],
            "error_before_dB": round(diag.result.before.overall, 3), "error_after_dB": round(diag.result.after.overall, 3),
            "params": {s["effect"]: {k: _rounded(v) for k, v in s["params"].items() if _rounded(v) is not None}
                       for s in steps},
            "refitted_declared": [{"effect": r["effect"], "params_after": r["params_after"]} for r in diag.refitted_declared],
            "seconds": round(time.perf_counter() - t, 1)}


def _rounded(v: object) -> float | list[float] | None:
    """A number (or a list of numbers, one per RX) to 5 significant digits; None for anything else."""
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return float(f"{float(v):.5g}")
    if isinstance(v, (list, tuple)) and v and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
        return [float(f"{float(x):.5g}") for x in v]
    return None


def main() -> None:
    """Parse the arguments and append a JSON line per case to the output."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--cases", nargs="*", default=None, help="case names (default: every case)")
    ap.add_argument("-o", "--output", type=Path, required=True, help="JSON-lines file (appended)")
    args = ap.parse_args()
    by = {c.name: c for c in CASES}
    names = args.cases or list(by)
    unknown = sorted(set(names) - set(by))
    if unknown:
        ap.error(f"unknown cases {unknown}")
    with args.output.open("a") as out:
        for i, name in enumerate(names):
            r = row(by[name], args.seed)
            out.write(json.dumps(r) + "\n")
            out.flush()
            print(f"[{i + 1}/{len(names)}] {name}: named {r['named']} "
                  f"({'ok' if r['ok'] else 'MISS'}), {r['error_before_dB']} -> {r['error_after_dB']} dB", flush=True)


if __name__ == "__main__":
    main()
