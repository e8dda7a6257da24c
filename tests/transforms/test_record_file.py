"""The calibration record: one versioned file, one reader; older files read as partial records."""

from __future__ import annotations

import json

import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.record import fit_record
from radaraug.errors import CalibrationError
from radaraug.io import write_capture
from radaraug.sensor import FMCWReceiver
from radaraug.sensor.profile import TwinProfile
from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels
from radaraug.transforms.record_file import CalibrationRecord, content_digest, load_record
from radaraug.units import DB_CONVENTION, float_to_counts

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16)


@pytest.fixture(scope="module")
def capture(tmp_path_factory):
    """20 frames of receiver noise as a radaraug capture."""
    path = tmp_path_factory.mktemp("cal") / "empty.h5"
    g = torch.Generator().manual_seed(3)
    counts = float_to_counts(1e-3 * torch.randn(20, 3, 16, 64, generator=g, dtype=torch.float64))
    write_capture(path, counts.numpy().astype("uint16"), CFG)
    return path


def _old_cdr_json(cdr: CalibratedDR, version: int | None) -> dict:
    """The file ``CalibratedDR.save`` wrote before the calibration record (format_version 1 or 2, or none)."""
    record = cdr.to_dict()
    data = {"format": "radaraug.CalibratedDR", **record["cdr"], "config": record["config"],
            "db_convention": DB_CONVENTION, "radaraug_version": "0.9"}
    if version is not None:
        data["format_version"] = version
    return data


def test_round_trip_of_every_section(capture, tmp_path):
    rec = fit_record(capture, floor="empirical", persistent_db=3.0)
    assert rec.capture == {"name": "empty.h5", "sha256": content_digest(capture), "frames": 20}
    assert rec.config == CFG and rec.cdr is not None and rec.cdr["num_frames"] == 20
    rec.profile = TwinProfile(FMCWReceiver(CFG).to_dict(), {"capture": "empty.h5"})
    rec.noise_fit = {"noise_figure_dB": 14.2, "adc_noise_rms_counts": 1.9, "target_floor_db": -97.0}
    path = rec.save(tmp_path / "cal.json")
    data = json.loads(path.read_text())
    assert (data["format"], data["version"], data["db_convention"]) == ("radaraug-calibration", 1, DB_CONVENTION)
    back = load_record(path)
    assert back.to_dict() == rec.to_dict() and back.file == str(path) and back.read_as == "radaraug-calibration 1"
    assert back.config == CFG and back.capture == rec.capture and back.noise_fit == rec.noise_fit
    assert torch.equal(back.persistent_mask(), rec.persistent_mask())
    assert back.profile is not None and back.profile.to_dict() == rec.profile.to_dict()
    assert not list(tmp_path.glob(".*"))  # written atomically: no temporary left


def test_the_record_gives_the_clamp_of_the_old_path_bit_for_bit(capture, tmp_path):
    x = RadarCompose([RangeDoppler(), ToDecibels()])(torch.zeros(4, 3, 16, 64)) - 60.0
    for floor in ("normal", "empirical"):
        old = CalibratedDR.fit(capture, floor=floor, seed=7)  # the old path, in memory
        new = CalibratedDR.from_record(fit_record(capture, floor=floor), seed=7)
        assert torch.equal(old(x), new(x))
        # On disk: an old CalibratedDR JSON and the record carry the same (rounded) floor.
        legacy = tmp_path / f"old_{floor}.json"
        legacy.write_text(json.dumps(_old_cdr_json(old, 2 if floor == "empirical" else 1)))
        fit_record(capture, floor=floor).save(tmp_path / f"new_{floor}.json")
        a, b = CalibratedDR.load(legacy, seed=7), CalibratedDR.load(tmp_path / f"new_{floor}.json", seed=7)
        assert torch.equal(a(x), b(x)) and a.to_dict() == b.to_dict()
        assert b.provenance["from"] == "file" and b.file == str(tmp_path / f"new_{floor}.json")


def test_old_files_read_as_partial_records(capture, tmp_path):
    cdr = CalibratedDR.fit(capture, floor="empirical")
    for version, read_as in ((None, "radaraug.CalibratedDR 1"), (1, "radaraug.CalibratedDR 1"),
                             (2, "radaraug.CalibratedDR 2")):
        path = tmp_path / f"cdr_{version}.json"
        path.write_text(json.dumps(_old_cdr_json(cdr, version)))
        rec = load_record(path)
        assert rec.read_as == read_as and rec.config == CFG and rec.profile is None and rec.noise_fit is None
        assert rec.cdr is not None and rec.cdr["mean_db"] == cdr.mean_db and rec.cdr["floor"] == "empirical"
    profile = TwinProfile(FMCWReceiver(CFG).to_dict(), {"capture": "empty.h5", "config": CFG.to_dict()})
    profile.save(tmp_path / "profile.json")
    rec = load_record(tmp_path / "profile.json")
    assert rec.cdr is None and rec.profile is not None and rec.config == CFG
    assert rec.read_as == "radaraug-twin-profile 2"
    with pytest.raises(CalibrationError, match=r"profile\.json.*holds no CalibratedDR floor"):
        CalibratedDR.from_record(rec)
    fit = {"noise_figure_dB": 14.0, "adc_noise_rms_counts": 1.9}
    for name, data, read_as in (("nf2.json", {**fit, "format": "radaraug-noise-fit", "version": 2},
                                 "radaraug-noise-fit 2"),
                                ("nf_untagged.json", {"noise_figure_dB": 12.5}, "radaraug-noise-fit 1 (untagged)")):
        (tmp_path / name).write_text(json.dumps(data))
        rec = load_record(tmp_path / name)
        assert rec.read_as == read_as and rec.noise_fit is not None and rec.cdr is None


@pytest.mark.parametrize("data, match", [
    ({"format": "radaraug-calibration", "version": 2}, r"radaraug-calibration version 2; this radaraug reads 1"),
    ({"format": "radaraug-calibration"}, r"radaraug-calibration version None"),
    ({"format": "radaraug.CalibratedDR", "format_version": 3, "mean_db": -90, "std_db": 1},
     r"radaraug.CalibratedDR format_version 3; this radaraug reads 1, 2"),
    ({"format": "radaraug-twin-profile", "version": 9, "receiver": {}}, r"twin profile version 9"),
    ({"format": "radaraug-noise-fit", "version": 7, "noise_figure_dB": 3.0}, r"radaraug-noise-fit version 7"),
    ({"format": "radaraug.SomethingElse", "version": 1}, r"not a calibration record: format 'radaraug.SomethingElse'"),
    ({"version": 1}, r"not a calibration record: format None"),
])
def test_unknown_format_or_version_is_refused_naming_the_file(tmp_path, data, match):
    path = tmp_path / "future_cal.json"
    path.write_text(json.dumps(data))
    with pytest.raises(CalibrationError, match=match) as err:
        load_record(path)
    assert "future_cal.json" in str(err.value)


@pytest.mark.parametrize("text, match", [
    ('{"format": "radaraug-calibration", "version": 1, "cdr": {"mean_db": -90', "not valid JSON"),
    ("\x00\x01binary", "not valid JSON"),
    ('{"format": "radaraug-calibration", "version": 1, "cdr": [1, 2]}', "'cdr' must be an object"),
    ('{"format": "radaraug-calibration", "version": 1, "cdr": {"std_db": 1}}', "lacks the key 'mean_db'"),
    ('{"format": "radaraug-calibration", "version": 1, "config": {"bogus": 1}}', "bad radar config"),
    ('{"format": "radaraug-calibration", "version": 1, "noise_fit": {"noise_figure_dB": "x"}}', "noise_figure_dB"),
    ('{"format": "radaraug-calibration", "version": 1, "capture": {"frames": -1}}', "malformed 'capture'"),
    ('{"format": "radaraug-calibration", "version": 1, "persistent_cells": '
     '{"threshold_db": 3, "shape": [4, 4], "cells": [[9, 0]]}}', "malformed 'persistent_cells'"),
    ('{"format": "radaraug-calibration", "version": 1, "persistent_cells": '
     '{"threshold_db": 3, "shape": ["4", 4], "cells": []}}', "malformed 'persistent_cells'"),
    ('{"format": "radaraug-calibration", "version": 1, "db_convention": "dB = 10*log10(|X|)"}',
     "another dB convention"),
])
def test_a_corrupted_record_is_refused_naming_the_file(tmp_path, text, match):
    path = tmp_path / "broken_cal.json"
    path.write_text(text)
    with pytest.raises(CalibrationError, match=match) as err:
        load_record(path)
    assert "broken_cal.json" in str(err.value)


def test_from_record_names_the_file_of_a_bad_floor(tmp_path):
    path = tmp_path / "bad_floor.json"
    CalibrationRecord(cdr={"mean_db": -90.0, "std_db": 1.0, "map_shape": [1, 2]}).save(path)
    with pytest.raises(CalibrationError, match=r"bad_floor\.json.*map_shape"):
        CalibratedDR.load(path)
