"""calibrate(): empty-room recording -> calibration record in one step; a room with a walker is refused."""

from __future__ import annotations

import json
import re
import warnings

import pytest

from radaraug.capture import VirtualSensor, calibrate
from radaraug.cli import main
from radaraug.errors import CalibrationError
from radaraug.io import open_capture
from radaraug.scene.scene import Scene
from radaraug.transforms import CalibratedDR
from radaraug.transforms.record_file import content_digest, load_record

# 0.1 s frames: in 32 frames (3.2 s) the walker crosses enough range-Doppler cells to be seen.
CFG = Scene.builtin("corridor").config.replace(num_chirps_per_frame=16, num_samples_per_chirp=64,
                                                 frame_repetition_time_s=0.1)


def test_empty_corridor_gives_a_calibration_that_loads(tmp_path) -> None:
    run = calibrate(VirtualSensor("corridor", config=CFG, realtime=False), tmp_path / "cdr.json", seconds=3.2,
                    keep_recording=tmp_path / "empty.h5")
    cdr = CalibratedDR.load(tmp_path / "cdr.json")
    assert cdr.mean_db == run.cdr.mean_db and cdr.std_db == run.cdr.std_db and cdr.motion == 0.0
    assert cdr.num_frames == 32 and cdr.config == CFG
    # One calibration record: the floor and the identity of the capture it was fitted on.
    rec = load_record(tmp_path / "cdr.json")
    assert rec.read_as == "radaraug-calibration 1" and rec.to_dict() == run.record.to_dict()
    assert rec.capture == {"name": str(tmp_path / "empty.h5"), "sha256": content_digest(tmp_path / "empty.h5"),
                           "frames": 32}
    # The same fit as fit-cdr on the same frames, made here from the sensor's stream directly.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        direct = CalibratedDR.fit(VirtualSensor("corridor", config=CFG).frames(0, 32), config=CFG)
    assert cdr.mean_db == pytest.approx(direct.mean_db, abs=1e-4) and cdr.std_db == pytest.approx(direct.std_db, abs=1e-4)
    with open_capture(tmp_path / "empty.h5") as cap:
        assert cap.num_frames == 32
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cdr.json", "empty.h5"]


def test_a_walker_is_refused_with_the_reason(tmp_path, capsys) -> None:
    cfg = tmp_path / "cfg.json"
    CFG.to_json(cfg)
    rc = main(["calibrate", "--board", "virtual", "--scene", "corridor_one_walker", "--radar-config", str(cfg),
               "--seconds", "3.2", "--no-realtime", "--no-progress", "-o", str(tmp_path / "cdr.json")])
    err = capsys.readouterr().err
    assert rc == 3 and err.count("\n") == 1
    assert re.search(r"not empty: \d+\.\d+ % of the range-Doppler cells.*nothing was written", err)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cfg.json"]  # no calibration, no leftover recording


def test_too_short_to_check_is_refused(tmp_path) -> None:
    with pytest.raises(CalibrationError, match="too few to check.*at least 16"):
        calibrate(VirtualSensor("corridor", config=CFG, realtime=False), tmp_path / "cdr.json", seconds=1)


def test_cli_calibrate(tmp_path, capsys) -> None:
    cfg = tmp_path / "cfg.json"
    CFG.to_json(cfg)
    rc = main(["calibrate", "--board", "virtual", "--radar-config", str(cfg), "--seconds", "2", "--no-realtime",
               "--no-progress", "-o", str(tmp_path / "cdr.json"), "--json", "--floor", "empirical"])
    assert rc == 0
    out = json.loads(capsys.readouterr().out)
    assert out["recording"]["frames"] == 20 and out["motion_fraction"] == 0.0 and out["floor"] == "empirical"
    cdr = CalibratedDR.load(tmp_path / "cdr.json")
    assert cdr.num_frames == 20 and cdr.floor == "empirical"
    assert out["chain"][0]["name"] == "InterferenceExcision"  # the recipes' chain by default
    rc = main(["calibrate", "--board", "virtual", "--radar-config", str(cfg), "--seconds", "2", "--no-realtime",
               "--no-progress", "-o", str(tmp_path / "plain.json"), "--json", "--excise-interference-db", "off"])
    assert rc == 0 and json.loads(capsys.readouterr().out)["chain"][0]["name"] == "RangeDoppler"


def test_a_bad_interference_threshold_is_refused_before_recording(tmp_path) -> None:
    with pytest.raises(CalibrationError, match="interference_db must be > 0"):
        calibrate(VirtualSensor("corridor", config=CFG, realtime=False), tmp_path / "cdr.json", interference_db=0.0)
    assert not list(tmp_path.iterdir())
