"""Every recipe runs (fast_dev_run on CPU) through `radaraug train`, by its installed name; DDP with two gloo processes."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
import yaml

from radaraug import recipes
from radaraug.cli import main

RECIPES = recipes.recipe_names()


def _small_args(tmp: Path, captures, randomization: str = "false") -> list[str]:
    cal, tests = captures
    test = json.dumps([{"path": str(tests[0][0]), "count": 0}, {"path": str(tests[1][0])}])
    return ["--data.calibration", str(cal), "--data.test", test, "--data.twin.train_items", "8",
            "--data.twin.val_items", "4", "--data.twin.randomization", randomization, "--data.twin.tracer_rays", "16",
            "--data.cache_dir", str(tmp / "cache"), "--data.image.size", "[32, 16]", "--data.num_workers", "0",
            "--data.twin.workers", "0", "--data.twin.progress", "false", "--data.batch_size", "4",
            "--trainer.enable_progress_bar", "false", "--trainer.enable_model_summary", "false"]


# the recipes name their logger (Lightning's default one warns that TensorBoard is missing), and
# `radaraug train` does not make LightningCLI warn about args given beside sys.argv
@pytest.mark.filterwarnings("error:Starting from v1.9.0")
@pytest.mark.filterwarnings("error:LightningCLI's args parameter")
@pytest.mark.parametrize("recipe", RECIPES)
def test_recipe_fast_dev_run(recipe, tmp_path, captures, monkeypatch):
    monkeypatch.chdir(tmp_path)
    rc = main(["train", "fit", "--config", recipe, "--trainer.fast_dev_run", "true",
               "--trainer.accelerator", "cpu", *_small_args(tmp_path, captures)])
    assert rc == 0
    assert len(list((tmp_path / "cache").glob("train-*.h5"))) == 1


# testing logs into a new version folder, so the checkpoint callback's state from fit is not restored
@pytest.mark.filterwarnings("ignore:The dirpath has changed")
def test_fit_then_test_from_the_checkpoint_the_docs_name(tmp_path, captures, monkeypatch):
    # docs/training.md: `radaraug train test --config ... --ckpt_path lightning_logs/version_0/checkpoints/last.ckpt`
    monkeypatch.chdir(tmp_path)
    recipe = "occupancy_rt"  # the installed recipe, by its name
    args = [*_small_args(tmp_path, captures), "--trainer.accelerator", "cpu", "--trainer.log_every_n_steps", "1"]
    assert main(["train", "fit", "--config", recipe, "--trainer.max_epochs", "1", *args]) == 0
    run = tmp_path / "lightning_logs" / "version_0"
    assert (run / "checkpoints" / "last.ckpt").is_file() and (run / "metrics.csv").is_file()
    # fit also wrote the classifier file that radaraug predict runs, with the calibration room's gate
    from radaraug.inference import RadarClassifier

    clf = RadarClassifier.load(run / "classifier.pt")
    assert clf.task == "occupancy" and clf.gate is not None and clf.provenance["method"] == "rt"
    assert main(["predict", str(run / "classifier.pt"), str(captures[1][0][0]), "-o", str(tmp_path / "rows.jsonl")]) == 0
    assert len((tmp_path / "rows.jsonl").read_text().splitlines()) == 6
    with pytest.raises(SystemExit):  # radaraug predict, not LightningCLI's: a usage error
        main(["train", "predict", "--config", recipe])
    assert main(["train", "test", "--config", recipe, "--ckpt_path", str(run / "checkpoints" / "last.ckpt"), *args]) == 0
    assert (tmp_path / "lightning_logs" / "version_1" / "test_metrics.json").is_file()


@pytest.mark.parametrize("recipe", ["occupancy_cdr", "occupancy_cdr_profile"])
def test_ddp_two_gloo_processes_each_simulate_their_own_shard(recipe, tmp_path, captures):
    out = tmp_path / "run"
    # by name: every DDP rank relaunches this command line and resolves the name again
    cmd = [sys.executable, "-m", "radaraug.cli", "train", "fit", "--config", recipe,
           "--trainer.max_epochs", "1", "--trainer.strategy", "ddp", "--trainer.devices", "2",
           "--trainer.accelerator", "cpu", "--trainer.logger", "false", "--trainer.enable_checkpointing", "false",
           "--trainer.default_root_dir", str(out), *_small_args(tmp_path, captures), "--data.twin.train_items", "9",
           "--data.batch_size", "3"]
    env = {**os.environ, "PL_DISABLE_FORK": "1", "OMP_NUM_THREADS": "1"}
    res = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=240)
    assert res.returncode == 0, res.stderr[-3000:]
    shards = sorted((tmp_path / "cache").glob("train-*.h5"))
    assert len(shards) == 2
    idx = [set(h5py.File(p, "r")["index"][()].tolist()) for p in shards]
    # no item simulated twice; with 9 items on 2 ranks the 9th is left out (equal steps per rank)
    assert not (idx[0] & idx[1]) and idx[0] | idx[1] == set(range(8)) and len(idx[0]) == len(idx[1])
    report = json.loads((out / "test_metrics.json").read_text())
    # the confusion matrix is summed over both ranks: every test frame counted once
    assert int(np.sum(report["confusion_matrix"])) == 6 + 6
    if recipe.endswith("cdr_profile"):
        # rank 0 fitted the twin profile once and sent it to rank 1
        assert len(list((tmp_path / "cache").glob("profile-*.json"))) == 1
        info = json.loads((out / "clip_range.json").read_text())
        assert info["twin_receiver"] == "profile" and info["twin_profile"]["capture"] == captures[0].name


def test_objects_and_override_files_through_the_cli(tmp_path, captures, monkeypatch):
    # a backbone and a method with a DR of yours as class_path objects, an ablation override as a second --config, test captures
    # spelt PATH:COUNT as on reproduce's command line and as a RadarCaptureDataset object
    monkeypatch.chdir(tmp_path)
    cal, tests = captures
    args = _small_args(tmp_path, captures)
    i = args.index("--data.test")
    given = {"class_path": "radaraug.io.RadarCaptureDataset", "init_args": {"paths": str(tests[1][0]), "label": "count"}}
    args[i + 1] = json.dumps([f"{tests[0][0]}:0", str(tests[1][0]), given])
    backbone = json.dumps({"class_path": "radaraug.training.TorchvisionClassifier", "init_args": {"arch": "resnet18"}})
    dr = json.dumps({"class_path": "radaraug.training.methods.OwnDR", "init_args": {"module": {
        "class_path": "radaraug.transforms.RandomDR", "init_args": {"mean_db": [-90.0, -80.0], "seed": 3}}}})
    rc = main(["train", "fit", "--config", "counting_rt", "--config", "ablation/rt_paper_image",
               "--model.backbone", backbone, "--data.method", dr, "--trainer.max_epochs", "1",
               "--trainer.accelerator", "cpu", "--trainer.enable_checkpointing", "false", *args])
    assert rc == 0
    saved = yaml.safe_load((tmp_path / "lightning_logs" / "version_0" / "config.yaml").read_text())
    assert saved["model"]["backbone"]["init_args"]["arch"] == "resnet18"
    assert saved["data"]["method"]["init_args"]["module"]["class_path"] == "radaraug.transforms.RandomDR"
    assert saved["data"]["image"]["representation"] == "paper"
    assert saved["data"]["test"][2]["class_path"] == "radaraug.io.RadarCaptureDataset"
    info = json.loads((tmp_path / "lightning_logs" / "version_0" / "clip_range.json").read_text())
    assert info["task"] == "counting"
