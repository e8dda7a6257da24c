"""The report builder on a tiny run (explicit captures from the independent generator)."""

import dataclasses
import inspect
import json

import pytest
import torch

import radaraug.training.reproduce as R
from radaraug.cli import main
from radaraug.errors import ConfigError
from radaraug.training.reproduce import ReproduceSettings, parse_test_arg, reproduce
from radaraug.transforms import CalibratedDR

TINY = ReproduceSettings(train_items=9, val_items=3, epochs=1, image_size=(32, 16), batch_size=6, tracer_rays=16,
                         num_workers=0, sim_workers=0, randomization=False, profile_max_frames=10,
                         proxy_frames_per_count=4, ablations=(), calibrate_noise=True,
                         keep_classifiers=False)


def test_parse_test_arg():
    assert parse_test_arg("walk.h5:2") == {"path": "walk.h5", "count": 2}
    assert parse_test_arg("walk.h5") == {"path": "walk.h5"}
    assert parse_test_arg("C:/data/rec") == {"path": "C:/data/rec"}


def test_report_on_a_tiny_run(tmp_path, captures):
    cal, tests = captures
    rep = reproduce(tmp_path / "out", seeds=2, calibration=str(cal), settings=dataclasses.replace(TINY, keep_classifiers=True),
                    progress=False, accelerator="cpu", test=[{"path": str(p), "count": c} for p, c in tests],
                    ablations=["cdr_normal_floor", "rt_paper_image"])
    out = tmp_path / "out"
    data = json.loads((out / "report.json").read_text())
    assert data == json.loads(json.dumps(rep))
    variants = ("rt", "randomdr", "cdr", "cdr_profile", "cdr_normal_floor", "rt_paper_image")
    for task in ("occupancy", "counting"):
        for method in variants:
            bacc = data["results"][task][method]["balanced_accuracy"]
            assert set(bacc) == {"mean", "std", "per_seed"} and len(bacc["per_seed"]) == 2
            assert 0 <= bacc["mean"] <= 1
    assert data["kind"] == "sim-to-capture" and list(data["test_sets"]) == ["captures"]
    # the static-change gate, fitted on the calibration capture, fused beside every row
    gate = data["test_sets"]["captures"]["static_gate"]
    assert gate["threshold_db"] == pytest.approx(gate["calibration_max_db"] + 3.0) and 0 <= gate["test_frames_fired"] <= 1
    assert all(0 <= data["results"][t][m]["static_gate_balanced_accuracy"]["mean"] <= 1
               for t in ("occupancy", "counting") for m in variants)
    assert data["test_sets"]["captures"]["results"] == data["results"]
    assert data["settings"]["cdr_floor"] == "matched" and data["settings"]["representation"] == "floor_relative"
    # the ablation table pairs each ablation with the run it changes
    table = {(r["task"], r["ablation"]): r for r in data["test_sets"]["captures"]["ablation_table"]}
    row = table[("occupancy", "rt_paper_image")]
    assert row["main"] == "rt" and row["changes"] == {"image": {"representation": "paper"}}
    assert row["delta"] == pytest.approx(row["ablation_mean"] - row["main_mean"])
    # two seeds x (4 methods + 2 ablations) x 2 tasks, each with its own metrics files
    assert len(data["runs"]) == 24 and len(list((out / "runs").glob("*/*/test_metrics.json"))) == 24
    for key in ("fig4_noise_floor", "fig5_rd_triplets", "fig6_static_energy", "fig7_feature_maps",
                "fig8_confusion_occupancy", "fig9_confusion_counting", "scores_occupancy", "scores_counting"):
        assert (out / data["figures"][f"captures/{key}"]).read_bytes()[:4] == b"\x89PNG"
    assert set(data["empty_room_median_db"]) == {"simulation", "simulation_cdr", "capture", "simulation_profile",
                                                 "simulation_profile_cdr"}
    # the empty room once floor-referenced: every run of the first task and the capture, beside noise's closed form
    tex = data["test_sets"]["captures"]["empty_room_floor_relative"]
    assert set(tex) == {"noise_alone_texture_std_db", "capture", *variants}
    assert tex["noise_alone_texture_std_db"] == pytest.approx(2.73, abs=0.01)  # three receivers
    assert all(tex[k]["texture_std_db"] > 0 and tex[k]["frames"] > 0 for k in ("capture", *variants))
    assert "Empty room once floor-referenced" in (out / "report.md").read_text()
    # the twin's noise figure was fitted to the calibration capture's floor (independent generator)
    fit = data["twin_noise_fit"]
    assert abs(fit["twin_floor_db"] - fit["target_floor_db"]) < 0.5
    # the profile of the cdr_profile runs: fitted (real diagnose, no scene) on the calibration capture
    prof = data["twin_profile"]
    assert prof["capture"] == cal.name and prof["max_frames"] == TINY.profile_max_frames
    assert prof["path"].startswith("cache/profile-") and (out / prof["path"]).is_file()
    assert prof["error_after_dB"] <= prof["error_before_dB"] and isinstance(prof["effects_added"], list)
    md = (out / "report.md").read_text()
    assert "balanced accuracy" in md and "RT < RandomDR < CDR" in md and "## Twin profile" in md
    assert "| task | rt | randomdr | cdr | cdr_profile | cdr_normal_floor | rt_paper_image |" in md
    assert "| occupancy | rt_paper_image |" in md  # the ablation table
    # rt, randomdr and the ablations share one simulated set; cdr trains on the quiet twin
    # (cdr_twin_noise_offset_db) and cdr_profile on the profile's receiver: a set each
    assert len(list((out / "cache").glob("train-*.h5"))) == 3
    assert len(list((out / "cache").glob("profile-*.json"))) == 1
    # every run kept its classifier; the report names the best method's, which predicts what the run scored
    assert all((out / r["classifier"]).is_file() for r in data["runs"])
    from radaraug.inference import RadarClassifier
    from radaraug.io import open_capture

    for task, chosen in data["classifiers"].items():
        best = max(("rt", "randomdr", "cdr", "cdr_profile"), key=lambda m: data["results"][task][m]["balanced_accuracy"]["mean"])
        assert chosen["method"] == best and chosen["path"].endswith("classifier.pt")
        clf = RadarClassifier.load(out / chosen["path"])
        assert clf.task == task and clf.gate is not None and clf.provenance["seed"] == chosen["seed"]
        frames = []
        for p, _ in tests:
            with open_capture(p) as capture:
                frames.append(capture.read())
        scored = torch.load((out / chosen["path"]).parent / "test_scores.pt", weights_only=True)
        assert torch.allclose(clf.probabilities(torch.cat(frames)), scored["probs"], atol=1e-5)
    assert "Classifiers to use" in md


def test_generated_test_sets_at_a_non_paper_config_and_shared_training(tmp_path):
    """Two test sets; a run that does not use the calibration trains once and is tested on both."""
    from radaraug.config import RadarConfig
    from radaraug.testsets.independent import make_independent_set

    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, if_gain_dB=38.0)
    a = make_independent_set(tmp_path / "a", config=cfg, frames_per_count=4, calibration_frames=16, seed=1,
                               progress=False)
    b = make_independent_set(tmp_path / "b", config=cfg, frames_per_count=4, calibration_frames=16, seed=2,
                               progress=False)
    import radaraug.training.reproduce as r

    sets = [r.TestSet("a", str(a.calibration), [{"path": str(p), "count": c} for p, c in a.tests]),
            r.TestSet("b", str(b.calibration), [{"path": str(p), "count": c} for p, c in b.tests])]
    orig = r._test_sets
    r._test_sets = lambda *args, **kw: sets
    try:
        # no noise fit and no excision: RT does not use the calibration capture
        settings = dataclasses.replace(TINY, calibrate_noise=False, excise_persistent_db=None)
        rep = reproduce(tmp_path / "out", seeds=1, settings=settings, progress=False, accelerator="cpu",
                        tasks=["occupancy"], methods=["rt", "cdr"], ablation=False)
    finally:
        r._test_sets = orig
    assert list(rep["test_sets"]) == ["a", "b"]
    runs = {(x["test_set"], x["variant"]): x for x in rep["runs"]}
    # RT does not use the calibration here (no noise fit): trained once, tested on both sets;
    # CDR is calibrated on each set's own empty room: trained once per set
    assert not runs[("a", "rt")]["shared_training"] and runs[("b", "rt")]["shared_training"]
    assert runs[("a", "rt")]["fit_seconds"] == runs[("b", "rt")]["fit_seconds"]
    assert not runs[("b", "cdr")]["shared_training"]
    assert rep["settings"]["test_sets"] == ["a", "b"]


def test_cli_reproduce_and_bad_arguments(tmp_path, captures, capsys, monkeypatch):
    cal, tests = captures
    with pytest.raises(ConfigError, match="seeds"):
        reproduce(tmp_path, seeds=0)
    with pytest.raises(ConfigError, match="unknown task"):
        reproduce(tmp_path, tasks=["segmentation"])
    import radaraug.training.reproduce as r

    assert r.ReproduceSettings.quick().profile_max_frames == 40
    assert "cdr_profile" in r.ReproduceSettings.full().methods and inspect.signature(reproduce).parameters["methods"].default is None
    js = tmp_path / "cdr.json"
    CalibratedDR.fit(str(cal), progress=False).save(js)  # a record of the floor only: no profile
    with pytest.raises(ConfigError, match="cdr_profile.*calibration record without one"):
        reproduce(tmp_path / "r", calibration=str(js), test=[{"path": str(tests[0][0]), "count": 0}])
    # test captures without their empty room: refused, not calibrated on a generated room
    with pytest.raises(ConfigError, match="--test needs --calibration"):
        reproduce(tmp_path, test=[{"path": str(tests[0][0]), "count": 0}], settings=TINY)
    with pytest.raises(ConfigError, match="--calibration without --test"):
        reproduce(tmp_path, calibration=str(cal), settings=TINY)
    with pytest.raises(ConfigError, match="unknown ablation"):
        reproduce(tmp_path, calibration=str(cal), test=[{"path": str(tests[0][0]), "count": 0}], settings=TINY,
                  ablations=["rt_with_magic"])
    with pytest.raises(ConfigError, match="unknown test set"):
        reproduce(tmp_path, settings=TINY, test_sets=["mars"])
    # a count the task has no class for is refused before anything is simulated
    with pytest.raises(ConfigError, match="count"):
        reproduce(tmp_path / "bad", calibration=str(cal), test=[{"path": str(tests[0][0]), "count": 3}],
                  settings=TINY, tasks=["counting"])
    assert not (tmp_path / "bad" / "cache").exists()
    monkeypatch.setattr(r.ReproduceSettings, "quick", classmethod(lambda cls: TINY))
    import radaraug.diagnosis as calibration_mod

    real_diagnose, frames = calibration_mod.diagnose, []

    def diagnose(*a, **kw):  # the real one, recording the frames it was asked to read
        frames.append(kw.get("max_frames"))
        return real_diagnose(*a, **kw)

    monkeypatch.setattr(calibration_mod, "diagnose", diagnose)
    rc = main(["reproduce", "--quick", "--seeds", "1", "--no-ablation", "--accelerator", "cpu", "--calibration",
               str(cal), *[a for p, c in tests for a in ("--test", f"{p}:{c}")], "-o", str(tmp_path / "o")])
    assert rc == 0
    printed = capsys.readouterr().out
    assert "report.md" in printed and "(+ static gate " in printed
    data = json.loads((tmp_path / "o" / "report.json").read_text())
    assert set(data["results"]["counting"]) == {"rt", "randomdr", "cdr", "cdr_profile"}
    assert frames == [TINY.profile_max_frames]  # quick settings reach the diagnose; one fit for both tasks


def test_default_ablations_name_recipes():
    # Full mode once named an ablation recipe that had been renamed, and failed only when run.
    from radaraug import recipes
    from radaraug.training.reproduce import ReproduceSettings

    for mode in (ReproduceSettings.full(), ReproduceSettings.quick()):
        assert set(mode.ablations) <= set(recipes.ablations()), set(mode.ablations) - set(recipes.ablations())


def test_the_runs_take_their_hyperparameters_from_the_recipes():
    # the values the experiment's reports were measured with, now written once, in the recipes
    eff = R.effective_settings(R.ReproduceSettings.quick())
    assert {k: eff[k] for k in R.RECIPE_KEYS} == {
        "randomization": {"catalog": {"spur_tone": {"probability": 0.0}, "vibrating_clutter": {"probability": 0.0}}},
        "representation": "floor_relative", "excise_persistent_db": 3.0, "excise_interference_db": 6.0,
        "calibrate_noise": False, "cdr_twin_noise_offset_db": -15.0, "cdr_floor": "matched", "lr": 0.001,
        "context_frames": 8, "blank_zero_doppler": 1, "resample": "bilinear", "count_labels": "drawn"}
    # an explicit setting overrides every run's recipe; an ablation's one change wins over it
    s = R.ReproduceSettings(representation="paper")
    assert R.run_recipe("counting", "rt", s)["data"]["image"]["representation"] == "paper"
    assert R.run_recipe("counting", "cdr", s, "cdr_normal_floor")["data"]["method"]["init_args"]["floor"] == "normal"
    assert R.ABLATIONS["rt_no_excision"] == ("rt", {"image": {"excise_persistent_db": None}})
    assert R.ABLATIONS["randomdr_no_interference_excision"] == ("randomdr", {"image": {"excise_interference_db": None}})
    # a method's argument is set only on the methods that take it
    floor = R.ReproduceSettings(cdr_floor="empirical")
    assert R.run_recipe("counting", "cdr", floor)["data"]["method"]["init_args"]["floor"] == "empirical"
    assert "init_args" not in R.run_recipe("counting", "rt", floor)["data"]["method"]


def test_a_suite_of_worlds_reports_mean_and_worst_world(tmp_path, capsys, monkeypatch):
    """``--test-sets design``: one test set per world, trained in its config, summarized over worlds."""
    settings = dataclasses.replace(TINY, calibrate_noise=False, excise_persistent_db=None, proxy_frames_per_count=3,
                                   context_frames=3)
    rep = reproduce(tmp_path / "out", seeds=2, settings=settings, progress=False, accelerator="cpu",
                    tasks=["occupancy"], methods=["rt"], ablation=False, test_sets=["design"], worlds=2)
    assert list(rep["test_sets"]) == ["design-w00", "design-w01"]
    summ = rep["suites"]["design"]
    assert summ["worlds"] == ["design-w00", "design-w01"] and "validation" in summ["role"]
    row = summ["results"]["occupancy"]["rt"]
    per_world = {w: rep["test_sets"][w]["results"]["occupancy"]["rt"]["balanced_accuracy"]["mean"]
                 for w in summ["worlds"]}
    assert row["per_world"] == per_world
    assert row["mean"] == pytest.approx(sum(per_world.values()) / 2) and row["worst"] == min(per_world.values())
    assert row["worst_world"] in per_world and row["val_mean"] is not None
    # the headline uses 3 frames of context, the single frame beside it, and the two seeds' ensemble
    res = rep["test_sets"]["design-w00"]["results"]["occupancy"]["rt"]
    assert set(res["single_frame_balanced_accuracy"]) == {"mean", "std", "per_seed"}
    assert res["ensemble"]["seeds"] == 2 and 0 <= res["ensemble"]["balanced_accuracy"] <= 1
    assert "single_frame_mean" in row and "ensemble_mean" in row and "ensemble_worst" in row
    run = json.loads((tmp_path / "out" / "runs" / "design-w00" / "occupancy_rt_seed0" / "run.json").read_text())
    assert run["protocol"] == "context of 3 frames" and run["context"]["balanced_accuracy"] == run["balanced_accuracy"]
    scores = torch.load(tmp_path / "out" / "runs" / "design-w00" / "occupancy_rt_seed0" / "test_scores.pt")
    assert scores["probs"].shape == (9, 2) and scores["recording_starts"].sum() == 3  # 3 files of 3 frames
    # the same network on the world's empty-room capture (its operating point there: metrics.empty_room_threshold)
    from radaraug.io import open_capture

    cal_frames = len(open_capture(rep["test_sets"]["design-w00"]["calibration"]))
    assert scores["calibration_probs"].shape == (cal_frames, 2)
    assert torch.allclose(scores["calibration_probs"].sum(dim=1), torch.ones(cal_frames))
    # the worlds have other radar configs: RT does not use the calibration, yet trains once per config
    runs = {x["test_set"]: x for x in rep["runs"] if x["seed"] == 0}
    assert not runs["design-w01"]["shared_training"]
    md = (tmp_path / "out" / "report.md").read_text()
    assert "## Suite `design`: mean over 2 worlds" in md and "validation" in md and "World `design-w00`" in md
    assert "sim val" in md
    monkeypatch.setattr(R.ReproduceSettings, "quick", classmethod(lambda cls: settings))
    capsys.readouterr()
    rc = main(["reproduce", "--quick", "--seeds", "1", "--no-ablation", "--accelerator", "cpu", "--test-sets",
               "design", "--worlds", "1", "--methods", "rt", "-o", str(tmp_path / "cli")])
    out = capsys.readouterr().out
    assert rc == 0 and "design-w00" in out and "design-w01" not in out


def test_early_stopping_tests_the_best_epoch(tmp_path, captures, monkeypatch):
    """With a patience, a run stops once validation stops rising and is tested with its best epoch's weights."""
    cal, tests = captures
    settings = dataclasses.replace(TINY, epochs=4, early_stopping_patience=1)
    fitted = []
    real_fit = R._fit

    def spy(*args, **kwargs):
        out = real_fit(*args, **kwargs)
        fitted.append(out)
        return out

    monkeypatch.setattr(R, "_fit", spy)
    rep = reproduce(tmp_path / "out", seeds=1, calibration=str(cal), settings=settings, progress=False,
                    accelerator="cpu", test=[{"path": str(p), "count": c} for p, c in tests], methods=["rt"],
                    tasks=["occupancy"], ablation=False)
    model, _, trainer, _, val = fitted[0]
    best = trainer.checkpoint_callback
    assert best.best_model_path and val == pytest.approx(float(best.best_model_score))
    weights = torch.load(best.best_model_path, map_location="cpu", weights_only=False)["state_dict"]
    assert all(torch.equal(v, model.state_dict()[k]) for k, v in weights.items())
    assert trainer.current_epoch <= 4 and rep["settings"]["early_stopping_patience"] == 1
    assert rep["runs"][0]["val_balanced_accuracy"] == pytest.approx(val)


def test_a_json_calibration_says_the_report_has_no_gate(tmp_path, captures, monkeypatch):
    """With a CalibratedDR JSON, reproduce says once per test set that no gated accuracies come (before training)."""
    import radaraug.training.reproduce as r
    from radaraug.training.inputs import CalibrationWarning

    _, tests = captures

    class Stop(Exception):
        pass

    def stop(*a, **kw):
        raise Stop

    monkeypatch.setattr(r, "run_recipe", stop)
    with pytest.warns(CalibrationWarning, match="no static-change gate.*no\\s+gated accuracies"), pytest.raises(Stop):
        reproduce(tmp_path, calibration="cdr.json", test=[{"path": str(p), "count": c} for p, c in tests],
                  settings=TINY, methods=["rt"], progress=False)
