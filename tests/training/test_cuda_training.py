"""The training path on CUDA: a tiny reproduce run and the recipe's step (skipped without a GPU)."""

from __future__ import annotations

import json

import pytest
import torch

from radaraug.training.reproduce import ReproduceSettings, reproduce

pytestmark = [pytest.mark.cuda, pytest.mark.skipif(not torch.cuda.is_available(), reason="no CUDA device")]

TINY = ReproduceSettings(train_items=9, val_items=3, epochs=1, image_size=(32, 16), batch_size=6, tracer_rays=16,
                         num_workers=0, sim_workers=0, randomization=False, profile_max_frames=10,
                         proxy_frames_per_count=4, ablations=(), calibrate_noise=True)


def test_tiny_reproduce_on_cuda(tmp_path, captures):
    cal, tests = captures
    rep = reproduce(tmp_path / "out", seeds=1, calibration=str(cal), settings=TINY, progress=False,
                    accelerator="cuda", methods=("rt", "cdr"), tasks=("occupancy",),
                    test=[{"path": str(p), "count": c} for p, c in tests])
    data = json.loads((tmp_path / "out" / "report.json").read_text())
    assert data["machine"]["device"] == "cuda" and data == json.loads(json.dumps(rep))
    for method in ("rt", "cdr"):
        assert 0 <= data["results"]["occupancy"][method]["balanced_accuracy"]["mean"] <= 1


def test_cuda_recipe_step_with_amp_and_channels_last():
    from radaraug.bench.training import run_training_benchmark

    res = run_training_benchmark(batch=8, steps=2, image_size=(64, 32), device="cuda")
    assert res["device"].startswith("cuda") and res["pipeline_images_per_s"] > 0
    assert res["amp_channels_last"]["pipeline_images_per_s"] > 0
