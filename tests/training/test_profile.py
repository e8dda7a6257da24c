"""The fourth method, CDRProfile, and data.twin.profile: the twin's receiver from a fitted twin profile."""

import json
import shutil
from dataclasses import replace
from types import SimpleNamespace

import pytest
import torch
from data import point_scatterer_frames, small_config

import radaraug.diagnosis as calibration_mod
from radaraug.errors import ConfigError
from radaraug.io import write_capture
from radaraug.sensor.profile import TwinProfile
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.randomization import TwinRandomization
from radaraug.training import CDR, RT, CDRProfile, ImageSpec, RadarDataModule, TwinSplits
from radaraug.training.cache import cache_key, cache_spec, content_digest
from radaraug.training.methods import METHODS
from radaraug.training.preparation import profile_cache_path
from radaraug.transforms import CalibratedDR

SMALL_TWIN = TwinSplits(train_items=6, val_items=0, tracer_rays=16, randomization=False, progress=False,
                        calibrate_noise=True)
TWIN = {"tracer_options": {"rays": 16}}


def _profile(noise_figure_dB: float = 21.5, capture: str = "x") -> TwinProfile:
    """A valid profile that differs from the default receiver (another noise figure)."""
    rx = FMCWReceiver(small_config()).to_dict()
    for e in rx["effects"]:
        if e["name"] == "thermal_noise":
            e["params"]["noise_figure_dB"] = noise_figure_dB
    return TwinProfile(rx, {"capture": capture, "mode": "estimated", "effects_added": ["adc_noise"],
                            "error_before_dB": 4.5, "error_after_dB": 0.5})


@pytest.fixture
def fake_diagnose(monkeypatch):
    """radaraug.diagnosis.diagnose replaced by a recorder that returns _profile()."""
    calls = []

    def diagnose(capture, scene=None, max_frames=100, progress=False, **kw):
        calls.append({"capture": capture, "scene": scene, "max_frames": max_frames})
        return SimpleNamespace(profile=_profile(capture=str(capture)))

    monkeypatch.setattr(calibration_mod, "diagnose", diagnose)
    return calls


def _dm(tmp_path, captures, method, twin=None, **kw):
    """A small data module; ``twin``: TwinSplits fields changed from SMALL_TWIN."""
    cal, tests = captures
    args = {"task": "occupancy", "calibration": str(cal), "test": [{"path": str(tests[0][0]), "count": 0}],
            "cache_dir": str(tmp_path / "c"), "method": method, "twin": replace(SMALL_TWIN, **(twin or {})),
            "image": ImageSpec(size=[32, 16]), "batch_size": 3} | kw
    return RadarDataModule(**args)


def _run_info(dm, folder):
    dm.write_run_files(folder)
    return json.loads((folder / "clip_range.json").read_text())


def test_cdr_profile_is_the_fourth_method_with_cdrs_dr(captures):
    cal, _ = captures
    assert list(METHODS) == ["rt", "randomdr", "cdr", "cdr_profile"]
    fitted = CalibratedDR.fit(cal, progress=False)
    a, b = CDR(floor=None).dr(fitted, seed=3), CDRProfile(floor=None).dr(fitted, seed=3)
    assert type(a) is type(b) is CalibratedDR
    assert (a.mean_db, a.std_db) == (b.mean_db, b.std_db)
    x = torch.full((2, 3, 32, 16), -150.0)
    assert torch.equal(a.train()(x), b.train()(x))  # same draws for the same seed
    with pytest.raises(ConfigError, match="'cdr_profile' needs a calibration"):
        CDRProfile().dr(None, seed=0)


def test_data_profile_json_sets_the_twin_receiver(tmp_path, captures):
    prof = _profile()
    path = prof.save(tmp_path / "profile.json")
    dm = _dm(tmp_path, captures, RT(), twin={"profile": str(path)})
    dm.setup("fit")
    sim = dm.simulated_dataset()
    assert sim.twin_options["receiver"].to_dict() == prof.receiver(dm.config).to_dict()
    assert dm.prepared.noise_fit is None and dm.receiver_kind() == "profile"  # the profile replaces the noise fit
    info = _run_info(dm, tmp_path / "run")
    assert info["twin_receiver"] == "profile" and info["twin_noise_fit"].startswith("skipped")
    assert info["twin_profile"]["path"] == str(path) and info["twin_profile"]["effects_added"] == ["adc_noise"]
    assert info["twin_profile"]["error_after_dB"] == 0.5
    # the same set without the profile: the default chain with a fitted noise figure, another cache file
    plain = _dm(tmp_path, captures, RT())
    plain.setup("fit")
    assert plain.receiver_kind() == "noise_fit" and plain.prepared.twin_profile is None
    assert len(list((tmp_path / "c").glob("train-*.h5"))) == 2


def test_cdr_profile_fits_once_on_the_calibration_capture(tmp_path, captures, fake_diagnose):
    cal, _ = captures
    dm = _dm(tmp_path, captures, CDRProfile(max_frames=40))
    dm.setup("fit")
    assert fake_diagnose == [{"capture": str(cal), "scene": None, "max_frames": 40}]
    cached = list((tmp_path / "c").glob("profile-*.json"))
    assert len(cached) == 1 and dm.prepared.profile_info["path"] == str(cached[0])
    assert TwinProfile.load(cached[0]).to_dict() == _profile(capture=str(cal)).to_dict()
    assert dm.simulated_dataset().twin_options["receiver"].to_dict() == _profile().receiver(dm.config).to_dict()
    assert dm.prepared.noise_fit is None and dm.prepared.profile_info["calibrate_noise"].startswith("skipped")
    # another run (another task, same capture): the cached profile, no second diagnose
    again = _dm(tmp_path, captures, CDRProfile(max_frames=40), task="counting")
    again.setup("fit")
    assert len(fake_diagnose) == 1 and again.prepared.profile_info["path"] == str(cached[0])
    # a given data.twin.profile wins: nothing is fitted
    given = _profile(noise_figure_dB=30.0).save(tmp_path / "given.json")
    dm3 = _dm(tmp_path, captures, CDRProfile(), twin={"profile": str(given)})
    dm3.setup("fit")
    assert len(fake_diagnose) == 1 and dm3.prepared.profile_info["source"] == "data.twin.profile"


def test_profile_cache_key_follows_the_capture_content(tmp_path, captures):
    cal, _ = captures
    renamed = tmp_path / "renamed.h5"
    shutil.copy(cal, renamed)
    assert content_digest(renamed) == content_digest(cal)

    def path(capture, max_frames=100):
        return profile_cache_path(str(capture), tmp_path / "c", max_frames)

    assert path(renamed) == path(cal)
    cfg = small_config()
    other = write_capture(tmp_path / "other.h5", point_scatterer_frames(cfg, 0, 12, 7), cfg)
    assert path(other) != path(cal)
    assert path(cal, 40) != path(cal)
    assert path(cal).name.startswith("profile-")


def test_cdr_profile_with_a_calibrated_dr_json_is_a_clear_error(tmp_path, captures, fake_diagnose):
    cal, tests = captures
    js = tmp_path / "cdr.json"
    CalibratedDR.fit(cal, progress=False).save(js)
    dm = _dm(tmp_path, captures, CDRProfile(), calibration=str(js))
    with pytest.raises(ConfigError, match="calibration record without one.*data.twin.profile"):
        dm.setup("fit")
    assert fake_diagnose == []
    # cdr takes the same JSON; cdr_profile does with a given profile
    _dm(tmp_path, captures, CDR(floor=None), calibration=str(js)).setup("fit")
    prof = _profile().save(tmp_path / "p.json")
    _dm(tmp_path, captures, CDRProfile(floor=None), calibration=str(js), twin={"profile": str(prof)}).setup("fit")
    with pytest.raises(ConfigError, match="'cdr_profile' needs data.calibration"):
        _dm(tmp_path, captures, CDRProfile(), calibration=None).setup("fit")


def test_cache_keys_differ_between_plain_and_profile_receivers():
    cfg = small_config()

    def key(**kw):
        return cache_key(cache_spec(SimulatedRadarDataset("corridor", length=4, seed=0, config=cfg,
                                                          twin_options=dict(TWIN), **kw), range(4)))

    plain = key()
    default_profile = key(profile=TwinProfile(FMCWReceiver(cfg).to_dict()))
    fitted = key(profile=_profile())
    assert len({plain, default_profile, fitted}) == 3
    assert key(profile=_profile()) == fitted  # an unchanged profile reuses its set


def test_twin_randomization_draws_around_a_profile_receiver():
    cfg = small_config()
    prof = _profile(noise_figure_dB=25.0)
    ds = SimulatedRadarDataset("corridor", length=2, seed=0, config=cfg, twin_options=dict(TWIN), profile=prof,
                               randomization=TwinRandomization(room={"variants": 1}))
    lo, hi = TwinRandomization().levels.noise_figure_offset_dB
    nf = ds.item_params(0)["noise_figure_dB"]
    assert 25.0 + lo <= nf <= 25.0 + hi
    x, _ = ds[0]
    assert torch.isfinite(x).all()


@pytest.mark.skipif(not hasattr(calibration_mod, "diagnose"), reason="radaraug.diagnosis.diagnose is missing")
def test_cdr_profile_end_to_end_with_the_real_diagnose(tmp_path, captures):
    cal, _ = captures
    # twin randomization on: its gain / noise-figure / phase-noise draws act on the fitted chain's stages
    dm = _dm(tmp_path, captures, CDRProfile(floor=None), twin={"randomization": {"room": {"variants": 1}}})
    dm.setup("fit")
    cached = list((tmp_path / "c").glob("profile-*.json"))
    assert len(cached) == 1
    prof = TwinProfile.load(cached[0])
    assert prof.fitted_on["capture"] == cal.name and prof.fitted_on["scene"] is None
    assert dm.simulated_dataset().twin_options["receiver"].to_dict() == prof.receiver(dm.config).to_dict()
    info = _run_info(dm, tmp_path / "run")
    assert info["method"] == "cdr_profile" and info["twin_profile"]["effects"] == prof.effect_names
    assert info["twin_profile"]["error_after_dB"] <= info["twin_profile"]["error_before_dB"]
    x, _ = next(iter(dm.train_dataloader()))
    assert torch.isfinite(x).all()


def test_catalog_priors_from_the_calibrations_diagnosis(tmp_path, captures, monkeypatch):
    """catalog_priors="calibration": the (cached) diagnosis of the calibration capture moves the
    randomization's catalog to the effects it added; the receiver stays the method's own."""
    from radaraug.sensor.effects import SpurTone

    calls = []

    def diagnose(capture, scene=None, max_frames=100, progress=False, **kw):
        calls.append(capture)
        rx = FMCWReceiver(small_config(), effects=[SpurTone(freq_Hz=150e3, amplitude_counts=3.0)])
        return SimpleNamespace(profile=TwinProfile(rx.to_dict(), {"capture": str(capture), "effects_added": ["spur_tone"]}))

    monkeypatch.setattr(calibration_mod, "diagnose", diagnose)
    kw = {"randomization": {"room": {"variants": 1}}, "calibrate_noise": False, "train_items": 3}
    dm = _dm(tmp_path, captures, RT(), twin=kw | {"catalog_priors": "calibration"})
    dm.setup("fit")
    assert len(calls) == 1 and dm.prepared.twin_profile is None and dm.receiver_kind() == "default"
    rz = dm.simulated_dataset().randomization
    frac = 150e3 / (small_config().sample_rate_Hz / 2)
    spur = rz.catalog["spur_tone"]
    assert spur.freq_nyquist[0] < frac < spur.freq_nyquist[1] and spur.probability == 0.7
    info = _run_info(dm, tmp_path / "run")["catalog_priors"]
    assert info["found"] == ["spur_tone"] and "spur_tone" in info["changes"]
    plain = _dm(tmp_path, captures, RT(), twin=kw)
    plain.setup("fit")
    assert plain.simulated_dataset().randomization.catalog["spur_tone"].freq_nyquist == (0.01, 0.99)
    assert len(calls) == 1 and plain.prepared.catalog_prior_info is None
