"""make gpu-check's driver: its steps fit the time asked for, and the recorded projection is its formula's."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _driver():
    spec = importlib.util.spec_from_file_location("gpu_check", ROOT / "scripts" / "gpu_check.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_step_limits_end_inside_ten_minutes():
    assert sum(limit for _, limit in _driver().STEPS) < 600


def test_recorded_reproduce_projection_is_the_drivers_formula():
    rec = json.loads((ROOT / "benchmarks" / "reproduce_cuda.json").read_text())
    rate = json.loads((ROOT / "benchmarks" / "training_cuda.json").read_text())["pipeline_images_per_s"]
    size = rec["size"]
    driver = _driver()
    got = driver.projection(rec["fit_seconds_per_run"], rec["wall_seconds"], size["train_items"],
                            size["val_items"], size["epochs"], driver.proxy_frames(size["train_items"]), rate)
    assert got["full_mode_projected_seconds_linear_upper_bound"] == pytest.approx(
        rec["full_mode_projected_seconds_linear_upper_bound"], rel=2e-3)
    assert got["full_mode_projected_seconds_lower_bound"] == pytest.approx(
        rec["full_mode_projected_seconds_lower_bound"], rel=2e-3)
    assert got["medium_projection"]["projected_seconds"] == pytest.approx(
        rec["medium_projection"]["projected_seconds"], rel=2e-3)
    assert got["full_mode_runs"] == 66
