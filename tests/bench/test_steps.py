"""``radaraug bench steps`` at a small size: its figures are consistent (the timings are the benchmark's)."""

from __future__ import annotations

import json

from radaraug.bench.steps import run_steps_benchmark


def test_steps_benchmark_runs_and_writes(tmp_path) -> None:
    out = tmp_path / "steps.json"
    r = run_steps_benchmark(frames=8, out=out)
    assert json.loads(out.read_text()) == r
    assert r["calibrate_frames"] == 8 and r["calibrate_fit_s"] > 0 and r["read_frames_s"] > 0
    assert r["calibrate_fit_vs_read"] > 0 and r["export_torchscript_vs_classifier_batch"] > 0
    done = [f for f in ("torchscript", "onnx", "torch_export") if f not in r["export_formats_skipped"]]
    assert "torchscript" in done and all(r[f"export_{f}_s"] > 0 for f in done)
