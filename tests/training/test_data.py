"""RadarDataModule on captures the twin did not make: Infineon folders, per-file labels, errors."""

import json
from dataclasses import replace

import pytest
import torch
from data import point_scatterer_frames, small_config

from radaraug.errors import ConfigError
from radaraug.io import open_capture, write_capture, write_infineon_recording
from radaraug.training import CDR, RT, ImageSpec, OwnDR, RadarDataModule, RandomDR, TwinSplits, rd_db_chain

TWIN = TwinSplits(train_items=6, val_items=0, tracer_rays=16, randomization=False, progress=False)
SMALL = {"twin": TWIN, "image": ImageSpec(size=[32, 16]), "batch_size": 3}


def test_infineon_folders_with_a_count_per_file(tmp_path):
    cfg = small_config()
    cal = write_infineon_recording(tmp_path / "empty", point_scatterer_frames(cfg, 0, 8, 1), cfg)
    walk = write_infineon_recording(tmp_path / "walk2", point_scatterer_frames(cfg, 2, 5, 2), cfg)
    dm = RadarDataModule(task="counting", method=CDR(floor=None, twin_noise_offset_db=None), calibration=str(cal),
                         cache_dir=str(tmp_path / "c"), test=[{"path": str(walk), "count": 2}], **SMALL)
    dm.setup("fit")
    x, y = next(iter(dm.test_dataloader()))
    assert x.shape == (3, cfg.num_rx, cfg.num_range_bins, cfg.num_chirps_per_frame)  # per-RX dB maps
    assert y.tolist() == [2, 2, 2]
    img, _ = dm.on_after_batch_transfer((x, y), 0)
    assert img.shape == (3, 3, 32, 16) and 0 <= float(img.min()) and float(img.max()) <= 1
    # occupancy labels the same file "occupied"
    dm2 = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), cache_dir=str(tmp_path / "c"),
                          test=[{"path": str(walk), "count": 2}], **SMALL)
    dm2.setup("fit")
    assert {int(v) for _, v in dm2._test} == {1}
    dm.write_run_files(tmp_path / "run")
    info = json.loads((tmp_path / "run" / "clip_range.json").read_text())
    assert info["method"] == "cdr" and info["clip_range_db"] == list(dm.clip)


def test_config_mismatch_and_bad_entries_are_clear_errors(tmp_path):
    cfg = small_config()
    cal = write_capture(tmp_path / "empty.h5", point_scatterer_frames(cfg, 0, 6, 1), cfg)
    other = cfg.replace(if_gain_dB=48)
    walk = write_capture(tmp_path / "walk.h5", point_scatterer_frames(other, 1, 3, 2), other)
    dm = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), test=[{"path": str(walk), "count": 1}],
                         cache_dir=str(tmp_path / "c"), **SMALL)
    with pytest.raises(ConfigError, match="walk.h5.*another radar config"):
        dm.setup("fit")
    with pytest.raises(ConfigError, match="test\\[0\\] must be PATH, PATH:COUNT or a mapping"):
        RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), test=[{"count": 1}],
                        cache_dir=str(tmp_path / "c"), **SMALL)
    # the command line's spelling is the recipes' too: PATH:COUNT, PATH (per-frame labels)
    spelt = RadarDataModule(test=[f"{walk}:1", str(walk)], cache_dir=str(tmp_path / "c"))
    assert spelt.hparams["test"] == [{"path": str(walk), "count": 1}, {"path": str(walk)}]
    with pytest.raises(ConfigError, match="task"):
        RadarDataModule(task="segmentation")
    with pytest.raises(ConfigError, match="needs data.calibration"):
        RadarDataModule(task="occupancy", method=CDR(), test=[{"path": str(cal), "count": 0}],
                        cache_dir=str(tmp_path / "c"), **SMALL).setup("fit")


def test_dr_only_on_simulated_splits(tmp_path, captures):
    cal, tests = captures
    dm = RadarDataModule(task="occupancy", method=RandomDR(), calibration=str(cal),
                         test=[{"path": str(tests[0][0]), "count": 0}], cache_dir=str(tmp_path / "c"), **SMALL)
    dm.setup("fit")
    x = torch.full((2, 3, 32, 16), -200.0)  # far below any floor: DR would lift it

    class T:  # the trainer states the hook reads
        def __init__(self, **kw):
            self.training = self.validating = self.sanity_checking = False
            self.__dict__.update(kw)

    dm.trainer = T(testing=True)
    test_img, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    dm.trainer = T(training=True)
    train_img, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    assert torch.equal(test_img, dm.image(x)) and not torch.equal(train_img, test_img)
    # test_dr: the test captures go through the run's DR too (opt-in, not the paper's protocol)
    dm.method = RandomDR(test_dr=True)
    dm.trainer, dm.image = T(testing=True), torch.nn.Identity()  # the maps before clipping
    lifted, _ = dm.on_after_batch_transfer((x, torch.zeros(2)), 0)
    assert bool((lifted > -150).all())
    assert RadarDataModule().method.test_dr is False
    # a DR of yours: OwnDR, on the plain twin
    from radaraug.transforms import RandomDR as RandomDRTransform

    mine = RandomDRTransform(mean_db=(-90.0, -80.0), seed=5)
    dm2 = RadarDataModule(task="occupancy", method=OwnDR(mine), calibration=str(cal),
                          test=[f"{tests[0][0]}:0"], cache_dir=str(tmp_path / "c"), **SMALL)
    dm2.setup("fit")
    assert dm2.dr is mine and dm2.hparams["method"]["init_args"]["module"] == repr(mine)



def test_test_recording_starts_and_zero_doppler_blanking(tmp_path, captures):
    cal, tests = captures
    entries = [{"path": str(p), "count": c} for p, c in tests]
    dm = RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=entries,
                         cache_dir=str(tmp_path / "c"), **(SMALL | {"image": ImageSpec(size=[32, 16], blank_zero_doppler=3)}))
    dm.setup("fit")
    from radaraug.io import open_capture

    frames = []
    for p, _ in tests:
        with open_capture(p) as cap:
            frames.append(cap.num_frames)
    starts = dm.test_recording_starts
    assert starts.shape == (sum(frames),) and starts.sum() == len(tests)
    assert starts[0] and starts[frames[0]] and not starts[1]
    # the blanked bins reach the network input: 3 bins on each side of zero Doppler set to the row's floor
    floor = [m for m in dm.image.modules() if type(m).__name__ == "FloorRelative"]
    assert len(floor) == 1 and floor[0].blank_zero_doppler == 3


def test_caches_default_to_the_user_cache_folder_not_the_working_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("RADARAUG_CACHE_DIR", str(tmp_path / "user_cache"))
    dm = RadarDataModule()
    assert dm.hparams["cache_dir"] == str(tmp_path / "user_cache")
    assert RadarDataModule(cache_dir="c").hparams["cache_dir"] == "c"


def test_floor_relative_excises_the_calibrations_lines_and_cdr_gets_a_quiet_twin(tmp_path, captures):
    import numpy as np

    from radaraug.io import open_capture

    cal, tests = captures
    # the calibration capture with a spur tone added: a persistent line the twin does not have
    with open_capture(cal) as c:
        cfg = c.config
        frames = c.read(0, c.num_frames).numpy()
    n = np.arange(cfg.num_samples_per_chirp) / cfg.sample_rate_Hz
    spur = 40 / 2047.5 * np.cos(2 * np.pi * 0.31 * cfg.sample_rate_Hz * n)
    spurred = np.clip(np.round((frames + spur + 1) * 4095 / 2), 0, 4095).astype(np.uint16)
    cal2 = write_capture(tmp_path / "empty_spur.h5", spurred, cfg)
    kw = SMALL | {"cache_dir": str(tmp_path / "c"), "test": [{"path": str(p), "count": c} for p, c in tests]}
    dm = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal2), **kw)
    dm.setup("fit")
    assert dm.excise is not None and int(dm.excise.sum()) >= 1
    # the spur's line is excised at its range bin (0.31 fs is 0.62 of the range axis), with whatever else
    # stands in every frame of this generator's empty room (leakage and wall sidelobes); a small part of the map
    rows = set(dm.excise.nonzero()[:, 0].tolist())
    assert round(0.62 * cfg.num_range_bins) in rows and dm.excise.float().mean() < 0.05
    # the mask is part of the model: a checkpoint restores it
    state = dm.state_dict()
    dm2 = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal2), **kw)
    dm2.load_state_dict(state)
    assert torch.equal(dm2.excise, dm.excise) and dm2.clip == dm.clip
    # no excision: no mask
    dm3 = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal2),
                          **(kw | {"image": ImageSpec(size=[32, 16], excise_persistent_db=None)}))
    dm3.setup("fit")
    assert dm3.excise is None
    # CDR's twin: both noise sources lowered by the offset, a simulated set of its own
    cdr = RadarDataModule(task="occupancy", method=CDR(floor=None, twin_noise_offset_db=-15.0), calibration=str(cal),
                          **kw)
    cdr.setup("fit")
    rx = cdr.simulated_dataset().twin_options["receiver"]
    from radaraug.sensor.defaults import DEFAULT_NOISE_FIGURE_DB

    nf = next(e.noise_figure_dB for e in rx.effects if e.name == "thermal_noise")
    assert nf == pytest.approx(DEFAULT_NOISE_FIGURE_DB - 15.0)
    assert "-15 dB" in cdr.receiver_kind()
    rt = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), **kw)
    rt.setup("fit")
    assert "receiver" not in rt.simulated_dataset().twin_options and rt.receiver_kind() == "default"


def test_a_simulated_dataset_given_as_an_object_is_used_as_given(tmp_path, captures):
    from radaraug.sim.dataset import SimulatedRadarDataset

    cal, tests = captures
    with open_capture(str(cal)) as cap:
        config = cap.config
    mine = SimulatedRadarDataset("corridor", length=8, seed=11, config=config, target="count",
                                 twin_options={"tracer_options": {"method": "sbr", "rays": 16}})
    def kw(dataset, **more):
        return SMALL | {"twin": replace(TWIN, train_items=5, val_items=2, dataset=dataset, **more)}

    dm = RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[f"{tests[0][0]}:0"],
                         cache_dir=str(tmp_path / "c"), **kw(mine))
    dm.setup("fit")
    assert dm.simulated_dataset() is mine and "dataset" not in dm.hparams["twin"]
    # the maps are mine (seed 11), item for item
    x0 = dm._train.base.maps([0])[0].float()
    raw, count = mine[0]
    assert torch.allclose(x0, rd_db_chain()(raw[None])[0].clamp(-300, 300).half().float())
    # fitted-receiver options are not applied to a given dataset: said, not silent
    with pytest.warns(UserWarning, match="calibrate_noise not applied"):
        RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[f"{tests[0][0]}:0"],
                        cache_dir=str(tmp_path / "c"), **kw(mine, calibrate_noise=True)).setup("fit")
    other = SimulatedRadarDataset("corridor", length=8, seed=11, config=config.replace(if_gain_dB=48), target="count")
    with pytest.raises(ConfigError, match="data.twin.dataset has another radar config"):
        RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[f"{tests[0][0]}:0"],
                        cache_dir=str(tmp_path / "c"), **kw(other)).setup("fit")
    short = SimulatedRadarDataset("corridor", length=3, seed=11, config=config, target="count")
    with pytest.raises(ConfigError, match="at least"):
        RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[f"{tests[0][0]}:0"],
                        cache_dir=str(tmp_path / "c"), **kw(short)).setup("fit")


def test_test_captures_as_dataset_objects(tmp_path):
    """A RadarCaptureDataset labelled with people counts is a test set as it is (the module gives it its RD
    chain); its files are checked like path entries; one that cannot be scored is refused up front."""
    from radaraug.io import RadarCaptureDataset

    cfg = small_config()
    cal = write_capture(tmp_path / "empty.h5", point_scatterer_frames(cfg, 0, 6, 1), cfg)
    one = write_capture(tmp_path / "one.h5", point_scatterer_frames(cfg, 1, 4, 2), cfg)
    two = write_capture(tmp_path / "two.h5", point_scatterer_frames(cfg, 2, 5, 3), cfg)
    given = RadarCaptureDataset([one, two], label={str(one): 1, str(two): 2})
    dm = RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[f"{cal}:0", given],
                         cache_dir=str(tmp_path / "c"), **SMALL)
    assert dm.hparams["test"] == [{"path": str(cal), "count": 0}, {"path": str(one), "count": 1, "dataset": 0},
                                  {"path": str(two), "count": 2, "dataset": 0}]
    dm.setup("fit")
    assert given.transform is None  # the module applies its RD chain to a copy, not to the user's object
    assert sorted(int(y) for _, y in dm._test) == [0] * 6 + [1] * 4 + [2] * 5
    x, _ = dm._test[6]
    assert x.shape == (cfg.num_rx, cfg.num_range_bins, cfg.num_chirps_per_frame)  # dB maps, as from a path entry
    with pytest.raises(ConfigError, match="test\\[0\\]: a test RadarCaptureDataset gives one frame per item"):
        RadarDataModule(test=[RadarCaptureDataset(one, label=1, frames_per_item=2)])
    with pytest.raises(ConfigError, match="label must be the people count"):
        RadarDataModule(test=[RadarCaptureDataset(one, label=1.5)])
    with pytest.raises(ConfigError, match="outside the counting task"):
        RadarDataModule(task="counting", method=RT(), calibration=str(cal), test=[RadarCaptureDataset(two, label=3)],
                        cache_dir=str(tmp_path / "c"), **SMALL).setup("fit")


def test_a_calibration_record_serves_what_it_holds(tmp_path, captures):
    """A record JSON with persistent cells, a profile and a noise fit serves the excision, CDRProfile's twin
    and the noise fit without the capture's frames; only the static-change gate is left out (and said)."""
    from radaraug.diagnosis.record import PERSISTENT_THRESHOLD_DB, fit_record, recipes_map_chain
    from radaraug.sensor.profile import TwinProfile
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.training import CalibrationWarning, CDRProfile

    cal, tests = captures
    kw = SMALL | {"cache_dir": str(tmp_path / "c"), "test": [{"path": str(p), "count": c} for p, c in tests]}
    from_capture = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), **kw)
    from_capture.setup("fit")
    rec = fit_record(cal, persistent_db=PERSISTENT_THRESHOLD_DB, pipeline=recipes_map_chain())  # as fit-cdr
    rec.profile = TwinProfile(FMCWReceiver(rec.config).to_dict(), {"capture": cal.name, "mode": "estimated"})
    rec.noise_fit = {"noise_figure_dB": 13.0, "adc_noise_rms_counts": 2.0}
    path = rec.save(tmp_path / "record.json")
    with pytest.warns(CalibrationWarning) as caught:
        dm = RadarDataModule(task="occupancy", method=CDRProfile(), calibration=str(path),
                             **(kw | {"twin": replace(TWIN, calibrate_noise=True)}))
        dm.setup("fit")
    said = " ".join(str(w.message) for w in caught)
    assert "static-change gate" in said and "not excised" not in said and "noise figure" not in said
    assert "fitted on maps made by" not in said  # fitted on the recipes' chain
    assert torch.equal(dm.excise, from_capture.excise)
    assert dm.prepared.twin_profile.to_dict() == rec.profile.to_dict()
    assert dm.prepared.profile_info["source"] == f"the calibration record {path}"
    # the record's noise fit: taken where the twin is not a profile's
    rt = RadarDataModule(task="occupancy", method=RT(), calibration=str(path),
                         **(kw | {"twin": replace(TWIN, calibrate_noise=True)}))
    with pytest.warns(CalibrationWarning):
        rt.setup("fit")
    assert rt.prepared.noise_fit == rec.noise_fit and rt.receiver_kind() == "noise_fit"
    # a record fitted on other maps (here without the interference excision): used, with a warning naming both
    plain = fit_record(cal, persistent_db=PERSISTENT_THRESHOLD_DB).save(tmp_path / "plain.json")
    with pytest.warns(CalibrationWarning, match="plain.json was fitted on maps made by RemoveMean"):
        RadarDataModule(task="occupancy", method=RT(), calibration=str(plain), **kw).setup("fit")
    # a record of another config's maps: refused, naming the file
    rec.persistent_cells = dict(rec.persistent_cells, shape=[7, 5], cells=[[1, 2]])
    other = rec.save(tmp_path / "other.json")
    with pytest.warns(CalibrationWarning), pytest.raises(ConfigError, match="other.json: its persistent cells"):
        RadarDataModule(task="occupancy", method=RT(), calibration=str(other), **kw).setup("fit")


def test_the_hyperparameters_are_plain_and_rebuild_the_module():
    """A checkpoint keeps plain values (no objects); they build the same module again."""
    dm = RadarDataModule(task="counting", method=CDR(floor="normal"), twin=replace(TWIN, train_items=7),
                         image=ImageSpec(size=[32, 16], blank_zero_doppler=2), seed=4)
    assert dm.hparams["method"] == {"class_path": "radaraug.training.methods.CDR",
                                    "init_args": {"floor": "normal", "twin_noise_offset_db": -15.0, "test_dr": False}}
    assert json.loads(json.dumps(dict(dm.hparams))) == dict(dm.hparams)
    again = RadarDataModule(**dm.hparams)
    assert again.method == dm.method and again.twin == dm.twin and again.image_spec == dm.image_spec
    assert again.hparams == dm.hparams
    with pytest.raises(ConfigError, match="data: .*unexpected keyword"):
        RadarDataModule.from_recipe({"train_items": 5})


def test_interference_excision_reaches_twin_captures_and_the_classifier_file(tmp_path, captures):
    from radaraug.inference import RadarClassifier
    from radaraug.training import RDClassifier
    from radaraug.training.classifier_file import classifier_record

    cal, tests = captures
    kw = SMALL | {"cache_dir": str(tmp_path / "c"), "test": [{"path": str(p), "count": c} for p, c in tests]}
    plain = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal),
                            **(kw | {"image": ImageSpec(size=[32, 16], excise_interference_db=None)}))
    plain.setup("fit")
    dm = RadarDataModule(task="occupancy", method=RT(), calibration=str(cal), **kw)  # the default: 6 dB
    dm.setup("fit")
    # the twin's maps are made through the excision: a cache of their own, not the plain chain's
    assert len(list((tmp_path / "c").glob("train-*.h5"))) == 2
    assert [s["name"] for s in dm.rd_chain().chain_spec()] == ["InterferenceExcision", "RangeDoppler", "ToDecibels"]
    assert dm._test is not None
    capture_chain = dm._test.base.dataset.datasets[0].transform
    assert capture_chain.chain_spec() == dm.rd_chain().chain_spec()  # captures as the twin
    # the classifier file keeps it, and its chain runs it
    clf = RadarClassifier.from_record(classifier_record(RDClassifier(task="occupancy"), dm), source="x")
    assert clf.chain.interference_db == 6.0
    assert classifier_record(RDClassifier(task="occupancy"), plain)["chain"]["interference_db"] is None
    # the resample reaches the file too
    plain.image_spec.resample = "max"
    assert RadarClassifier.from_record(classifier_record(RDClassifier(task="occupancy"), plain),
                                       source="x").chain.resample == "max"
    # CDR's floor is fitted on the calibration's maps as the run makes them
    cdr = RadarDataModule(task="occupancy", method=CDR(), calibration=str(cal), **kw)
    cdr.setup("fit")
    assert cdr.dr.chain[0]["name"] == "InterferenceExcision"
    with pytest.raises(ConfigError, match="excise_interference_db"):
        ImageSpec(excise_interference_db=0)


def test_observable_count_labels_lower_only_counting_training_labels(tmp_path, captures):
    cal, tests = captures
    twin = replace(TWIN, train_items=24, count_labels="observable")
    kw = {"calibration": str(cal), "test": [{"path": str(tests[0][0]), "count": 0}], "cache_dir": str(tmp_path / "c"),
          "twin": twin, "image": ImageSpec(size=[32, 16]), "batch_size": 3}
    dm = RadarDataModule(task="counting", method=RT(), **kw)
    dm.setup("fit")
    drawn = dm._train.base.indices.clone()  # the items; their drawn counts come from the dataset
    counts = torch.tensor([dm.prepared.simulated.scenario(int(i)).count for i in drawn])
    labels = torch.tensor([int(y) for _, y in dm._train])
    assert bool((labels <= counts).all()) and torch.equal(labels == 0, counts == 0)
    assert dm.train_class_counts.tolist() == torch.bincount(labels, minlength=3).tolist()
    assert dm.observable_relabelled["items"] == int((labels != counts).sum()) > 0  # small maps: most pairs share a blob
    occ = RadarDataModule(task="occupancy", method=RT(), **kw)
    occ.setup("fit")
    assert [int(y) for _, y in occ._train] == (counts > 0).long().tolist()  # occupancy keeps the drawn labels
