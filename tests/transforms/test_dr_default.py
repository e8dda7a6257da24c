"""``CalibratedDR(...)`` is explicit: it takes fitted numbers, never reads the environment or fits.

radaraug ships no default floor; ``CalibratedDR()`` without ``mean_db``/``std_db`` is one clear
``ConfigError`` naming ``CalibratedDR.fit`` / ``CalibratedDR.load``, the ways to get one.
"""

import pytest
import torch

from radaraug.errors import CalibrationError, ConfigError
from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels, floor_fit
from radaraug.transforms import dr as dr_module

from .conftest import beat_cube


@pytest.fixture
def empty_room(cfg):
    g = torch.Generator().manual_seed(5)
    static = beat_cube(cfg, 2.0, 0.0, amplitude=0.05, n_rx=2)
    return static + 1e-3 * torch.randn(12, 2, 32, 128, generator=g, dtype=torch.float64)


@pytest.mark.parametrize("kwargs", [{}, {"seed": 1}, {"p": 0.5, "floor": "normal"}])
def test_no_floor_is_one_clear_config_error(kwargs):
    with pytest.raises(ConfigError, match=r"mean_db and std_db.*CalibratedDR\.fit.*CalibratedDR\.load") as e:
        CalibratedDR(**kwargs)
    assert not isinstance(e.value, CalibrationError)


def test_half_a_floor_names_what_is_missing():
    with pytest.raises(ConfigError, match=r"no std_db\b.*CalibratedDR\.fit"):
        CalibratedDR(-100.0)
    with pytest.raises(ConfigError, match=r"no mean_db\b.*CalibratedDR\.load"):
        CalibratedDR(std_db=2.0)


def test_the_environment_is_never_read(tmp_path, monkeypatch, cfg, empty_room):
    """RADARAUG_CDR (read by radaraug <= this change) naming a valid calibration changes nothing."""
    CalibratedDR.fit(empty_room, config=cfg).save(tmp_path / "cdr.json")
    monkeypatch.setenv("RADARAUG_CDR", str(tmp_path / "cdr.json"))
    with pytest.raises(ConfigError, match="CalibratedDR.load"):
        CalibratedDR()
    assert not hasattr(dr_module, "ENV_VAR")


def test_the_constructor_never_fits(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("CalibratedDR(...) fitted a capture")

    monkeypatch.setattr(floor_fit, "floor_statistics", refuse)  # the fit CalibratedDR.fit delegates to
    cdr = CalibratedDR(-100, 2, seed=0)
    assert (cdr.mean_db, cdr.std_db) == (-100.0, 2.0)
    assert cdr.provenance == {"from": "arguments", "source": None, "num_frames": None}
    with pytest.raises(AssertionError, match="fitted"):
        CalibratedDR.fit(torch.zeros(2, 1, 8, 16))  # fitting goes through fit(), only


def test_load_is_the_explicit_path_to_a_saved_calibration(tmp_path, cfg, empty_room):
    fitted = CalibratedDR.fit(empty_room, config=cfg)
    fitted.save(tmp_path / "cdr.json")
    cdr = CalibratedDR.load(tmp_path / "cdr.json", seed=1)
    assert (cdr.mean_db, cdr.std_db, cdr.map_shape) == (fitted.mean_db, fitted.std_db, fitted.map_shape)
    assert cdr.provenance == {"from": "file", "path": str(tmp_path / "cdr.json"), "source": None,
                              "num_frames": 12}
    assert cdr.file == str(tmp_path / "cdr.json")
    # The recorded chain, map shape and config are enforced.
    RadarCompose([RangeDoppler(), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="blackman"):
        RadarCompose([RangeDoppler(range_window="blackman"), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="cdr.json"):
        cdr(torch.zeros(2, 3, 64, 32))
    with pytest.raises(CalibrationError, match="if_gain_dB"):
        cdr.check_config(cfg.replace(if_gain_dB=40))
    # replace(): the same calibration with another floor or seed, its numbers, provenance and file kept
    other = cdr.replace(floor="empirical", seed=5)
    assert (other.mean_db, other.std_db, other.map_shape, other.chain, other.config) == (
        cdr.mean_db, cdr.std_db, cdr.map_shape, cdr.chain, cdr.config)
    assert other.floor == "empirical" and torch.equal(other.quantiles_db, cdr.quantiles_db)
    assert other.provenance == cdr.provenance and other.file == cdr.file and cdr.floor == "normal"
    with pytest.raises(CalibrationError, match="floor must be one of"):
        cdr.replace(floor="flat")


def test_fit_is_the_explicit_path_from_a_capture(tmp_path, cfg, empty_room):
    io = pytest.importorskip("radaraug.io")
    from radaraug.units import float_to_counts

    counts = float_to_counts(empty_room)
    path = io.write_capture(tmp_path / "room.h5", counts.numpy().astype("uint16"), cfg.replace(rx_antennas=(1, 2)))
    cdr = CalibratedDR.fit(path)
    assert cdr.provenance["from"] == "arguments" and cdr.provenance["source"] == "room.h5"
    assert cdr.config == cfg.replace(rx_antennas=(1, 2)) and cdr.file is None
    again = CalibratedDR(cdr.mean_db, cdr.std_db, chain=cdr.chain, config=cdr.config, map_shape=cdr.map_shape)
    assert (again.mean_db, again.std_db, again.map_shape) == (cdr.mean_db, cdr.std_db, cdr.map_shape)
