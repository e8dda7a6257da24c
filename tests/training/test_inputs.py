"""The test set and the calibration are checked before anything is simulated (radaraug.testsets.checks, radaraug.training.inputs)."""

import warnings

import numpy as np
import pytest
from data import point_scatterer_frames, small_config

from radaraug.errors import ConfigError
from radaraug.io import write_capture
from radaraug.testsets.checks import TestSetWarning, check_test_set, read_test_counts
from radaraug.training import (
    CDR,
    CalibrationWarning,
    CDRProfile,
    ImageSpec,
    RadarDataModule,
    RandomDR,
    TwinSplits,
)
from radaraug.training.inputs import check_calibration
from radaraug.transforms import CalibratedDR

SMALL = {"twin": TwinSplits(train_items=6, val_items=0, tracer_rays=16, randomization=False, progress=False,
                            calibrate_noise=True), "image": ImageSpec(size=[32, 16]), "batch_size": 3}


def _entries(tests, counts=None):
    return [{"path": str(p), "count": c if counts is None else counts[i]} for i, (p, c) in enumerate(tests)]


def _labelled(path, counts):
    cfg = small_config()
    frames = point_scatterer_frames(cfg, 0, len(counts), 5)
    return write_capture(path, frames, cfg, labels={"count": np.asarray(counts, dtype=np.int64)})


def test_counts_come_from_the_entry_or_the_files_per_frame_labels(captures, tmp_path):
    _, tests = captures
    mixed = _labelled(tmp_path / "mixed.h5", [0, 0, 1, 2, 2, 2])
    got = read_test_counts([{"path": str(tests[1][0]), "count": 1}, {"path": str(tests[2][0])}, {"path": str(mixed)}])
    assert got == [(str(tests[1][0]), {1: 6}), (str(tests[2][0]), {2: 6}), (str(mixed), {0: 2, 1: 1, 2: 3})]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # every class present: no warning
        assert check_test_set([{"path": str(mixed)}], "counting") == {"0": 2, "1": 1, "2": 3}
        assert check_test_set(_entries(tests), "occupancy") == {"empty": 6, "occupied": 12}


def test_a_count_outside_the_tasks_classes_is_refused_naming_the_file(captures, tmp_path):
    _, tests = captures
    with pytest.raises(ConfigError, match=r"walk_2\.h5: people count 3 \(6 frame\(s\)\) is outside the counting"):
        check_test_set(_entries(tests, [0, 1, 3]), "counting")
    three = _labelled(tmp_path / "three.h5", [0, 1, 3])
    with pytest.raises(ConfigError, match=r"three\.h5: people count 3 \(1 frame\(s\)\)"):
        check_test_set([{"path": str(three)}], "counting")
    # occupancy: any count >= 0 is a class ("occupied"), a negative count is not
    assert check_test_set([{"path": str(three)}], "occupancy") == {"empty": 1, "occupied": 2}
    with pytest.raises(ConfigError, match=r"walk_0\.h5: people count -1 .* negative"):
        check_test_set(_entries(tests, [-1, 1, 2]), "occupancy")
    for bad in (1.5, True, "two"):
        with pytest.raises(ConfigError, match="walk_0.h5: the people count must be a whole number"):
            check_test_set(_entries(tests, [bad, 1, 2]), "occupancy")


def test_a_file_without_count_labels_needs_a_count(tmp_path):
    cfg = small_config()
    bare = write_capture(tmp_path / "bare.h5", point_scatterer_frames(cfg, 1, 3, 1), cfg)
    with pytest.raises(ConfigError, match=r"bare\.h5: no people count.*bare\.h5:N"):
        read_test_counts([{"path": str(bare)}])


def test_one_class_only_warns_that_a_constant_net_scores_one(captures):
    _, tests = captures
    occupied = _entries(tests[1:])
    with pytest.warns(TestSetWarning, match=r"only class 'occupied'.*always answers 'occupied' scores 1\.0.*"
                                            r"empty-room capture \(count 0\) must be included"):
        assert check_test_set(occupied, "occupancy") == {"empty": 0, "occupied": 12}
    with pytest.warns(TestSetWarning, match="only class '0'.*captures with people"):
        check_test_set(_entries(tests[:1]), "counting")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_test_set(_entries(tests[:2]), "counting")  # two of three classes: scored over those two
    assert issubclass(TestSetWarning, UserWarning)


def test_a_calibration_json_cannot_serve_the_noise_fit_or_cdr_profile(captures, tmp_path):
    cal, _ = captures
    js = tmp_path / "cdr.json"
    CalibratedDR.fit(str(cal), progress=False).save(js)
    with pytest.raises(ConfigError, match=r"'cdr_profile' fits a twin profile.*cdr\.json is a calibration record "
                                          "without one"):
        check_calibration(str(js), CDRProfile())
    with pytest.warns(CalibrationWarning, match=r"cdr\.json is a calibration record without a noise fit: the twin's "
                                                r"noise figure cannot be fitted from it.*default receiver"):
        check_calibration(str(js), CDR(floor=None))
    for args, kw in (((str(js), RandomDR()), {"calibrate_noise": False}),  # no noise fit asked for
                     ((str(js), CDRProfile(floor=None)), {"profile": "fitted/profile.json"})):  # the profile replaces both
        with pytest.warns(CalibrationWarning) as caught:  # only the gate is left out
            check_calibration(*args, **kw)
        assert [str(w.message).split("so ")[1][:30] for w in caught] == ["no static-change gate goes int"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_calibration(str(cal), CDRProfile())  # a capture serves both


def test_a_lever_left_out_for_want_of_the_capture_is_named(captures, tmp_path):
    # the excision and the gate need the empty room's frames; CDR's floor from the JSON is said when it differs
    cal, _ = captures
    js = tmp_path / "cdr.json"
    CalibratedDR.fit(str(cal), progress=False).save(js)  # the paper's normal floor
    with pytest.warns(CalibrationWarning, match=r"cdr\.json is a calibration record \(JSON\): it holds no frames, so the empty "
                                                r"room's persistent lines are not excised from the maps \(-0\.08 occupancy"):
        check_calibration(str(js), RandomDR(), calibrate_noise=False, excise=True)
    with pytest.warns(CalibrationWarning, match="no data.calibration: the empty room's persistent lines are not excised"):
        check_calibration(None, RandomDR(), excise=True)
    with pytest.warns(CalibrationWarning, match=r"fitted with floor 'normal'; this run draws CDR's floor as 'matched'"):
        check_calibration(str(js), CDR(floor="matched"), calibrate_noise=False)
    # Without excision the lost gate (and, with no calibration at all, the noise fit) is still named.
    with pytest.warns(CalibrationWarning, match="no data.calibration: no static-change gate goes into the classifier "
                                                "file, and the twin's noise is not fitted"):
        check_calibration(None, RandomDR(), excise=False)
    with pytest.warns(CalibrationWarning, match=r"cdr\.json is a calibration record \(JSON\): it holds no frames, so no "
                                                "static-change gate") as caught:
        check_calibration(str(js), CDR(floor="normal"), calibrate_noise=False)
    assert not any("fitted with floor" in str(w.message) for w in caught)  # the floor asked for is the JSON's own
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_calibration(str(cal), RandomDR(), excise=True)  # the capture serves everything


def test_the_data_module_checks_before_simulating(captures, tmp_path):
    cal, tests = captures
    js = tmp_path / "cdr.json"
    CalibratedDR.fit(str(cal), progress=False).save(js)
    cache = tmp_path / "cache"
    dm = RadarDataModule(task="counting", method=CDR(floor=None), calibration=str(js), test=_entries(tests, [0, 1, 4]),
                         cache_dir=str(cache), **SMALL)
    with pytest.warns(CalibrationWarning, match="noise figure cannot be fitted"), \
            pytest.raises(ConfigError, match=r"walk_2\.h5: people count 4"):
        dm.setup("fit")
    dm = RadarDataModule(task="occupancy", method=CDRProfile(), calibration=str(js), test=_entries(tests),
                         cache_dir=str(cache), **SMALL)
    with pytest.raises(ConfigError, match="cdr_profile.*calibration record without one"):
        dm.setup("fit")
    assert not cache.exists()  # nothing was simulated
