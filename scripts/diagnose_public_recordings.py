"""Run ``diagnose`` on the five public BGT60TR13C recordings and write one record (benchmarks/diagnose_public_recordings_cpu.json).

Each recording (third-party, read from the real-data folder, never copied into the project) is
diagnosed in estimated mode (no scene: none comes with one), 100 frames or as many as it has; the
record keeps, per recording, its IF gain, the frames used, the held-out overall error of the
default twin, after the base refit and at the end, the cut (1 - final / default), the effects
named with their fitted parameters, and the seconds the diagnosis took. docs/diagnosis.md's
table "Since the signatures" quotes it.

    python scripts/diagnose_public_recordings.py REAL_DIR -o benchmarks/diagnose_public_recordings_cpu.json
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path
from typing import Any

import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from radaraug.diagnosis import diagnose  # noqa: E402

MAX_FRAMES = 100

RECORDINGS: dict[str, str] = {
    "ssalehi_2_reflectors": "ssalehi152431__Beamforming-with-Infineon-BGT60TR13C/Beamforming/beamforming_data/"
                            "2_reflectors20251027-150925",
    "zharfanw_breathing": "zharfanw__bgt60tr13c_processing/.dataset/BGT60TR13C_record_napaszhar_220260106-151615",
    "jjustin_18_53_49": "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_53_49",
    "jjustin_18_48_07": "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_48_07",
    "jjustin_18_52_43": "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_52_43",
}
"""Short name -> the recording's folder relative to the real-data folder (the docs' table order)."""


def _rounded(value: Any) -> Any:
    """``value`` with its floats rounded to 4 decimals (lists and dicts too); other values as they are."""
    if isinstance(value, bool) or value is None or isinstance(value, (int, str)):
        return value
    if isinstance(value, float):
        return round(value, 4)
    if isinstance(value, torch.Tensor):
        return _rounded(value.tolist())
    if isinstance(value, (list, tuple)):
        return [_rounded(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _rounded(v) for k, v in value.items()}
    return str(value)


def row(real_dir: Path, rel: str) -> dict[str, Any]:
    """Diagnose the recording at ``real_dir / rel`` and return its entry of the record.

    Args:
        real_dir: the real-data folder.
        rel: the recording's folder relative to it.

    Returns:
        The record's entry: path, IF gain, frames, errors (dB), cut, effects named (``added`` by
        the search, then declared stages ``refitted_declared`` at other parameters), their fitted
        parameters and the seconds the diagnosis took.
    """
    t = time.perf_counter()
    diag = diagnose(real_dir / rel, max_frames=MAX_FRAMES)
    seconds = time.perf_counter() - t
    r = diag.result
    default, base, final = r.before.overall, r.base.overall, r.after.overall
    params = {s["effect"]: _rounded(s["params"]) for s in r.steps}
    params |= {d["effect"]: _rounded(d["params_after"]) for d in diag.refitted_declared}
    return {"path": rel, "if_gain_dB": float(diag.config.if_gain_dB), "frames_used": diag.frames["read"],
            "error_default_dB": round(default, 4), "error_base_refit_dB": round(base, 4),
            "error_final_dB": round(final, 4), "cut": round(1.0 - final / default, 4),
            "named": diag.named_effects, "added": [s["effect"] for s in r.steps],
            "refitted_declared": [d["effect"] for d in diag.refitted_declared], "params": params,
            "seconds": round(seconds, 1)}


def main() -> None:
    """Parse the arguments, diagnose every recording and write the JSON record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("real_dir", type=Path, help="the real-data folder (e.g. ../shared/real)")
    ap.add_argument("-o", "--output", type=Path, required=True, help="JSON record (overwritten)")
    args = ap.parse_args()
    missing = [rel for rel in RECORDINGS.values() if not (args.real_dir / rel).is_dir()]
    if missing:
        ap.error(f"not under {args.real_dir}: {missing}")
    out = args.output.name if args.output.is_absolute() else args.output.as_posix()  # no machine path in the record
    rows: dict[str, Any] = {}
    for i, (name, rel) in enumerate(RECORDINGS.items()):
        rows[name] = r = row(args.real_dir, rel)
        print(f"[{i + 1}/{len(RECORDINGS)}] {name}: {r['error_default_dB']} -> {r['error_base_refit_dB']} -> "
              f"{r['error_final_dB']} dB (cut {r['cut']:.0%}), named {r['named']}, {r['seconds']} s", flush=True)
    record = {"benchmark": "diagnose-public-recordings",
              "command": f"python scripts/diagnose_public_recordings.py REAL_DIR -o {out}",
              "what": f"radaraug.diagnosis.diagnose(recording, max_frames={MAX_FRAMES}) in estimated mode on "
                      "each public recording; errors are the held-out overall error (dB) of the default twin, "
                      "after the base refit and at the end; cut = 1 - final / default",
              "machine": f"{os.cpu_count()}-core {platform.machine()} CPU, {torch.get_num_threads()} threads, "
                         f"torch {torch.__version__}",
              "recordings": rows}
    args.output.write_text(json.dumps(record, indent=1) + "\n")
    print("wrote", args.output)


if __name__ == "__main__":
    main()
