"""The report builder on a tiny run (explicit captures from the independent generator)."""

import inspect
import json

import pytest

from radaraug.cli import main
from radaraug.errors import ConfigError
from radaraug.training.reproduce import ReproduceSettings, parse_test_arg, reproduce

TINY = ReproduceSettings(train_items=9, val_items=3, epochs=1, image_size=(32, 16), batch_size=6, tracer_rays=16,
                         num_workers=0, sim_workers=0, randomization=False, profile_max_frames=10)


def test_parse_test_arg():
    assert parse_test_arg("walk.h5:2") == {"path": "walk.h5", "count": 2}
    assert parse_test_arg("walk.h5") == {"path": "walk.h5"}
    assert parse_test_arg("C:/data/rec") == {"path": "C:/data/rec"}


def test_report_on_a_tiny_run(tmp_path, captures):
    cal, tests = captures
    rep = reproduce(tmp_path / "out", seeds=2, calibration=str(cal), settings=TINY, progress=False,
                    accelerator="cpu", test=[{"path": str(p), "count": c} for p, c in tests])
    out = tmp_path / "out"
    data = json.loads((out / "report.json").read_text())
    assert data == json.loads(json.dumps(rep))
    for task in ("occupancy", "counting"):
        for method in ("rt", "randomdr", "cdr", "cdr_profile", "cdr_no_twin_randomization"):
            bacc = data["results"][task][method]["balanced_accuracy"]
            assert set(bacc) == {"mean", "std", "per_seed"} and len(bacc["per_seed"]) == 2
            assert 0 <= bacc["mean"] <= 1
    assert data["kind"] == "sim-to-capture"
    assert data["settings"]["cdr_floor"] == "normal"  # the paper's CDR unless asked otherwise
    # two seeds x (4 methods + ablation) x 2 tasks, each with its own metrics files
    assert len(data["runs"]) == 20 and len(list((out / "runs").glob("*/test_metrics.json"))) == 20
    for key in ("fig4_noise_floor", "fig5_rd_triplets", "fig6_static_energy", "fig7_feature_maps",
                "fig8_confusion_occupancy", "fig9_confusion_counting"):
        assert (out / data["figures"][key]).read_bytes()[:4] == b"\x89PNG"
    assert set(data["empty_room_median_db"]) == {"simulation", "simulation_cdr", "capture", "simulation_profile",
                                                 "simulation_profile_cdr"}
    # the twin's noise figure was fitted to the calibration capture's floor (independent generator)
    fit = data["twin_noise_fit"]
    assert abs(fit["twin_floor_db"] - fit["target_floor_db"]) < 0.5
    # the profile of the cdr_profile runs: fitted (real diagnose, no scene) on the calibration capture
    prof = data["twin_profile"]
    assert prof["capture"] == cal.name and prof["max_frames"] == TINY.profile_max_frames
    assert prof["path"].startswith("cache/profile-") and (out / prof["path"]).is_file()
    assert prof["error_after_dB"] <= prof["error_before_dB"] and isinstance(prof["effects_added"], list)
    md = (out / "report.md").read_text()
    assert "Balanced accuracy" in md and "RT < RandomDR < CDR" in md and "## Twin profile" in md
    assert "| task | rt | randomdr | cdr | cdr_profile | cdr_no_twin_randomization |" in md
    # the main runs of a task share one simulated set (one train cache file per randomization setting),
    # but cdr_profile simulates with the profile's receiver: a set of its own
    assert len(list((out / "cache").glob("train-*.h5"))) == 2
    assert len(list((out / "cache").glob("profile-*.json"))) == 1


def test_cli_reproduce_and_bad_arguments(tmp_path, captures, capsys, monkeypatch):
    cal, tests = captures
    with pytest.raises(ConfigError, match="seeds"):
        reproduce(tmp_path, seeds=0)
    with pytest.raises(ConfigError, match="unknown task"):
        reproduce(tmp_path, tasks=["segmentation"])
    import radaraug.training.reproduce as r

    assert r.ReproduceSettings.quick().profile_max_frames == 40
    assert "cdr_profile" in inspect.signature(reproduce).parameters["methods"].default
    with pytest.raises(ConfigError, match="cdr_profile.*CalibratedDR JSON"):
        reproduce(tmp_path, calibration="cdr.json", test=[{"path": str(tests[0][0]), "count": 0}])
    monkeypatch.setattr(r.ReproduceSettings, "quick", classmethod(lambda cls: TINY))
    import radaraug.calibration as calibration_mod

    real_diagnose, frames = calibration_mod.diagnose, []

    def diagnose(*a, **kw):  # the real one, recording the frames it was asked to read
        frames.append(kw.get("max_frames"))
        return real_diagnose(*a, **kw)

    monkeypatch.setattr(calibration_mod, "diagnose", diagnose)
    rc = main(["reproduce", "--quick", "--seeds", "1", "--no-ablation", "--accelerator", "cpu", "--calibration",
               str(cal), *[a for p, c in tests for a in ("--test", f"{p}:{c}")], "-o", str(tmp_path / "o")])
    assert rc == 0
    assert "report.md" in capsys.readouterr().out
    data = json.loads((tmp_path / "o" / "report.json").read_text())
    assert set(data["results"]["counting"]) == {"rt", "randomdr", "cdr", "cdr_profile"}
    assert frames == [TINY.profile_max_frames]  # quick settings reach the diagnose; one fit for both tasks
