"""training_chains: the recipes' measured chain as transforms, and the twin that goes with them."""

from __future__ import annotations

import pytest
import torch

from radaraug.diagnosis.record import PERSISTENT_THRESHOLD_DB, fit_record
from radaraug.io import RadarCaptureDataset
from radaraug.training import CDR, CalibrationWarning, ImageSpec, RadarDataModule, TwinSplits, training_chains
from radaraug.transforms import CalibratedDR, FloorRelative, RandomDR

SMALL = {"estimate_items": 8, "twin": {"tracer_rays": 16, "randomization": False}, "image_size": (32, 16)}


def test_the_chains_are_the_recipes_chains(captures, tmp_path) -> None:
    cal, tests = captures
    ch = training_chains(cal, "randomdr", cache_dir=tmp_path, **SMALL)
    assert isinstance(ch.dr, RandomDR) and ch.excise is not None and ch.config.num_chirps_per_frame > 0
    assert any(isinstance(m, FloorRelative) for m in ch.test.modules())
    real = RadarCaptureDataset(tests[1][0], label="count", transform=ch.test)
    image, label = real[0]
    assert image.shape == (3, 32, 16) and 0 <= float(image.min()) and float(image.max()) <= 1 and label == 1
    # the same clip range and excision as the data module of the recipe (its estimate on the same items)
    dm = RadarDataModule(calibration=str(cal), test=[{"path": str(cal), "count": 0}], cache_dir=str(tmp_path),
                         twin=TwinSplits(train_items=8, val_items=0, tracer_rays=16, randomization=False,
                                         progress=False, workers=2),
                         image=ImageSpec(size=[32, 16], blank_zero_doppler=1))
    with pytest.warns(UserWarning):
        dm.setup("fit")
    assert dm.clip == ch.clip_range_db and torch.equal(dm.excise, ch.excise)
    sim = ch.simulated(4, seed=3)
    x, count = sim[2]
    assert len(sim) == 4 and x.shape == (3, 32, 16) and count in (0, 1, 2)
    assert torch.equal(ch.simulated(4, seed=3)[2][0], x)  # a pure function of (seed, index)
    assert len(ch.simulated(5, seed=3)) == 5 and len(sim) == 4


def test_cdr_gets_the_matched_floor(captures, tmp_path) -> None:
    cal, _ = captures
    ch = training_chains(cal, "cdr", cache_dir=tmp_path, **SMALL)
    assert isinstance(ch.dr, CalibratedDR) and ch.dr.floor == "empirical"  # matched: quantiles against the twin
    paper = training_chains(cal, CDR(floor="normal"), cache_dir=tmp_path,
                            image={"representation": "paper", "clip_range": [-110.0, -40.0],
                                   "excise_persistent_db": None}, **SMALL)
    assert paper.clip_range_db == (-110.0, -40.0) and paper.excise is None and paper.dr.floor == "normal"


def test_a_calibration_record_serves_what_it_holds(captures, tmp_path) -> None:
    cal, _ = captures
    ch = training_chains(cal, "cdr", cache_dir=tmp_path, **SMALL)
    record = tmp_path / "cdr.json"  # what radaraug calibrate / fit-cdr write: the floor and the persistent cells
    fit_record(cal, persistent_db=PERSISTENT_THRESHOLD_DB).save(record)
    with pytest.warns(CalibrationWarning, match="static-change gate"):
        from_record = training_chains(record, "cdr", cache_dir=tmp_path, **SMALL)
    assert from_record.config == ch.config and torch.equal(from_record.excise, ch.excise)
    assert from_record.clip_range_db == ch.clip_range_db  # the same twin items, the same clip estimate
    assert isinstance(from_record.dr, CalibratedDR) and from_record.dr.floor == "empirical"
    # matched against the same twin floor (the record keeps its quantiles to JSON precision)
    assert torch.allclose(from_record.dr.quantiles_db, ch.dr.quantiles_db, atol=1e-3, rtol=0)
    floor_only = tmp_path / "floor.json"  # a record without persistent cells: nothing to excise, said so
    CalibratedDR.fit(str(cal), progress=False).save(floor_only)
    with pytest.warns(CalibrationWarning, match="not excised"):
        bare = training_chains(floor_only, "randomdr", cache_dir=tmp_path, **SMALL)
    assert bare.excise is None and bare.config == ch.config


def test_a_randomization_override_keeps_the_recipes_other_keys(captures, tmp_path) -> None:
    cal, _ = captures
    ch = training_chains(cal, "rt", cache_dir=tmp_path, estimate_items=4, image_size=(32, 16),
                         twin={"tracer_rays": 16, "randomization": {"room": {"variants": 1}}})
    rz = ch._datamodule.simulated_dataset().randomization
    assert rz.room.variants == 1  # the override
    assert rz.catalog["spur_tone"].probability == 0 == rz.catalog["vibrating_clutter"].probability  # the recipe's


def test_prepare_takes_the_config_from_the_calibration_and_reproduce_refuses_no_test(captures, tmp_path) -> None:
    from radaraug.errors import ConfigError
    from radaraug.io import open_capture
    from radaraug.training import RT, prepare
    from radaraug.training.reproduce import reproduce

    cal, _ = captures
    with open_capture(cal) as cap:
        config = cap.config
    twin, image = TwinSplits(train_items=2, val_items=0, randomization=False), ImageSpec(size=[32, 16])
    # no test capture to read the config from: the calibration capture's (or record's) serves
    assert prepare(RT(), str(cal), None, twin, image, tmp_path, dr_seed=0, simulate=False).config == config
    record = tmp_path / "cdr.json"
    CalibratedDR.fit(str(cal), progress=False).save(record)
    assert prepare(RT(), str(record), None, twin, image, tmp_path, dr_seed=0, simulate=False).config == config
    with pytest.raises(ConfigError, match="no radar config"):
        prepare(RT(), None, None, twin, image, tmp_path, dr_seed=0, simulate=False)
    with pytest.raises(ConfigError, match="the test set is empty"):
        reproduce(tmp_path / "out", quick=True, calibration=str(cal), test=[], progress=False)
