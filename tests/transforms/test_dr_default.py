"""``CalibratedDR()`` with no arguments: the calibration named by RADARAUG_CDR, nothing shipped."""

import pytest
import torch

from radaraug.errors import CalibrationError
from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels
from radaraug.transforms.dr import ENV_VAR

from .conftest import beat_cube


@pytest.fixture
def empty_room(cfg):
    g = torch.Generator().manual_seed(5)
    static = beat_cube(cfg, 2.0, 0.0, amplitude=0.05, n_rx=2)
    return static + 1e-3 * torch.randn(12, 2, 32, 128, generator=g, dtype=torch.float64)


def test_unset_environment_is_a_clear_error(monkeypatch):
    monkeypatch.delenv(ENV_VAR, raising=False)
    with pytest.raises(CalibrationError, match=rf"{ENV_VAR}.*not set.*radaraug fit-cdr"):
        CalibratedDR()
    with pytest.raises(CalibrationError, match="both mean_db and std_db"):
        CalibratedDR(-100.0)
    monkeypatch.setenv(ENV_VAR, "/nonexistent/room.h5")
    with pytest.raises(CalibrationError, match="nonexistent"):
        CalibratedDR()


def test_no_arguments_loads_the_json_named_by_the_environment(tmp_path, monkeypatch, cfg, empty_room):
    fitted = CalibratedDR.fit(empty_room, config=cfg)
    fitted.save(tmp_path / "cdr.json")
    monkeypatch.setenv(ENV_VAR, str(tmp_path / "cdr.json"))
    cdr = CalibratedDR(seed=1)
    assert (cdr.mean_db, cdr.std_db, cdr.map_shape) == (fitted.mean_db, fitted.std_db, fitted.map_shape)
    assert cdr.provenance == {"from": ENV_VAR, "path": str(tmp_path / "cdr.json"), "source": None,
                              "num_frames": 12}
    assert cdr.file == str(tmp_path / "cdr.json")
    # The recorded chain, map shape and config are enforced as for a loaded calibration.
    RadarCompose([RangeDoppler(), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="blackman"):
        RadarCompose([RangeDoppler(range_window="blackman"), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="cdr.json"):
        cdr(torch.zeros(2, 3, 64, 32))
    with pytest.raises(CalibrationError, match="if_gain_dB"):
        cdr.check_config(cfg.replace(if_gain_dB=40))


def test_no_arguments_fits_a_capture_named_by_the_environment(tmp_path, monkeypatch, cfg, empty_room):
    io = pytest.importorskip("radaraug.io")
    from radaraug.units import float_to_counts

    counts = float_to_counts(empty_room)
    path = io.write_capture(tmp_path / "room.h5", counts.numpy().astype("uint16"), cfg.replace(rx_antennas=(1, 2)))
    monkeypatch.setenv(ENV_VAR, str(path))
    cdr = CalibratedDR()
    ref = CalibratedDR.fit(path)
    assert (cdr.mean_db, cdr.std_db) == (ref.mean_db, ref.std_db)
    assert cdr.provenance["fitted"] is True and cdr.provenance["source"] == "room.h5"
    assert cdr.config == cfg.replace(rx_antennas=(1, 2)) and cdr.file is None
    assert CalibratedDR(-100, 2).provenance == {"from": "arguments", "source": None, "num_frames": None}
