import json
import math
import warnings

import pytest
import torch

from radaraug.errors import CalibrationError
from radaraug.transforms import (
    CalibratedDR,
    CombineRx,
    DopplerFFT,
    MotionWarning,
    RadarCompose,
    RandomDR,
    RangeDoppler,
    RangeFFT,
    RemoveMean,
    ToDecibels,
)

from .conftest import beat_cube


def test_clamp_keeps_cells_above_floor_and_raises_cells_below(dtype):
    x = torch.full((2, 3, 16, 8), -300.0, dtype=dtype)
    x[..., ::2, :] = -40.0
    for t in (RandomDR((-100, -90), (1, 4), seed=1), CalibratedDR(-95, 3, seed=1)):
        y = t(x)
        noise = t.last_params["noise_db"]
        assert torch.equal(y[..., ::2, :], x[..., ::2, :])  # exactly untouched
        assert torch.equal(y[..., 1::2, :], noise.expand_as(x)[..., 1::2, :])  # raised to N
        assert torch.equal(y, torch.maximum(x, noise))


def test_calibrated_noise_statistics():
    t = CalibratedDR(-97.5, 2.5, seed=0)
    t(torch.full((40, 3, 32, 32), -500.0, dtype=torch.float64))
    n = t.last_params["noise_db"]
    assert n.mean().item() == pytest.approx(-97.5, abs=0.02)
    assert n.std().item() == pytest.approx(2.5, abs=0.02)


def test_fit_from_db_tensor_is_exact_mean_and_std():
    power = torch.empty(20, 3, 16, 8, dtype=torch.float64).exponential_()
    maps = 10 * torch.log10(power) - 90  # noise-like dB maps
    cdr = CalibratedDR.fit(maps, input="db")
    assert cdr.mean_db == pytest.approx(maps.mean().item(), abs=1e-12)
    assert cdr.std_db == pytest.approx(maps.std(correction=0).item(), abs=1e-12)
    assert cdr.map_shape == (3, 16, 8) and cdr.num_frames == 20
    assert cdr.chain == [RangeDoppler().chain_spec(), ToDecibels().chain_spec()]


def test_fit_from_raw_tensor_and_dataset_agree():
    g = torch.Generator().manual_seed(2)
    raw = 1e-3 * torch.randn(6, 2, 8, 32, generator=g, dtype=torch.float64)
    db = ToDecibels()(RangeDoppler()(raw))
    a = CalibratedDR.fit(raw, batch_size=4)
    assert a.mean_db == pytest.approx(db.mean().item(), abs=1e-9)
    assert a.std_db == pytest.approx(db.std(correction=0).item(), abs=1e-9)
    dataset = [(raw[i], 0) for i in range(6)]  # a list is a map-style Dataset of (cube, label)
    b = CalibratedDR.fit(dataset, max_frames=6)
    assert (b.mean_db, b.std_db) == pytest.approx((a.mean_db, a.std_db))
    assert b.map_shape == a.map_shape == (2, 16, 8)
    c = CalibratedDR.fit(raw, max_frames=3)
    assert c.num_frames == 3


def test_save_load_round_trip(tmp_path, cfg):
    cdr = CalibratedDR(
        -101.25,
        3.5,
        chain=[RangeDoppler().chain_spec(), ToDecibels().chain_spec()],
        config=cfg,
        map_shape=(3, 64, 32),
        source="empty.h5",
        num_frames=100,
    )
    path = tmp_path / "cdr.json"
    cdr.save(path)
    data = json.loads(path.read_text())  # a calibration record holding the floor
    assert (data["format"], data["version"]) == ("radaraug-calibration", 1)
    assert data["db_convention"].startswith("dB = 20*log10(|X|)")
    assert {"config", "radaraug_version", "cdr"} <= set(data)
    assert {"mean_db", "std_db", "chain", "map_shape", "source", "num_frames"} <= set(data["cdr"])
    back = CalibratedDR.load(path, seed=4)
    assert back.to_dict() == cdr.to_dict()
    assert back.config == cfg
    x = torch.full((2, 3, 64, 32), -200.0)
    assert torch.equal(back(x), CalibratedDR.load(path, seed=4)(x))


@pytest.mark.parametrize(
    "text, match",
    [
        ("{not json", "not valid JSON"),
        ('{"format": "something else"}', "is not a calibration record: format 'something else'"),
        ('{"format": "radaraug.CalibratedDR", "std_db": 1}', "lacks the key 'mean_db'"),
        ('{"format": "radaraug.CalibratedDR", "mean_db": "x", "std_db": 1}', "malformed"),
        (
            '{"format": "radaraug.CalibratedDR", "mean_db": -90, "std_db": 1, "config": {"bogus": 1}}',
            "config",
        ),
        (
            '{"format": "radaraug.CalibratedDR", "mean_db": -90, "std_db": 1, "map_shape": [1, 2]}',
            "map_shape",
        ),
        # before: a bare AttributeError
        ('{"format": "radaraug.CalibratedDR", "mean_db": -90, "std_db": 1, "config": [1]}', "config"),
        # before: accepted silently
        ('{"format": "radaraug.CalibratedDR", "format_version": 3, "mean_db": -90, "std_db": 1}', "format_version"),
        (
            '{"format": "radaraug.CalibratedDR", "db_convention": "dB = 10*log10(|X|)", "mean_db": -90, "std_db": 1}',
            "another dB convention",
        ),
        # before: KeyError 'name' when the chain was compared
        ('{"format": "radaraug.CalibratedDR", "mean_db": -90, "std_db": 1, "chain": [{"x": 1}]}', "string 'name'"),
        # before: OverflowError
        ('{"format": "radaraug.CalibratedDR", "mean_db": ' + "1" * 401 + ', "std_db": 1}', "401 digits"),
        # before: RecursionError
        ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
        ('{"format": "radaraug.CalibratedDR", "mean_db": -90, "std_db": 1, "map_shape": [3, true, 4]}', "map_shape"),
    ],
)
def test_load_malformed_names_the_file(tmp_path, text, match):
    path = tmp_path / "bad_cal.json"
    path.write_text(text)
    with pytest.raises(CalibrationError, match=match) as err:
        CalibratedDR.load(path)
    assert "bad_cal.json" in str(err.value)
    with pytest.raises(CalibrationError, match="does not exist"):
        CalibratedDR.load(tmp_path / "missing.json")


def test_shape_and_config_mismatch(cfg):
    cdr = CalibratedDR(-100, 2, map_shape=(3, 64, 32), config=cfg)
    cdr(torch.zeros(5, 3, 64, 32))
    with pytest.raises(CalibrationError, match=r"\(3, 64, 32\)"):
        cdr(torch.zeros(5, 3, 64, 16))
    cdr.check_config(cfg)
    with pytest.raises(CalibrationError, match="if_gain_dB"):
        cdr.check_config(cfg.replace(if_gain_dB=40))
    with pytest.warns(UserWarning, match="no recorded radar config"):
        CalibratedDR(-100, 2).check_config(cfg)


def test_compose_checks_the_chain_before_calibrated_dr():
    cdr = CalibratedDR(-100, 2, chain=[RangeDoppler().chain_spec(), ToDecibels().chain_spec()])
    RadarCompose([RangeDoppler(), ToDecibels(), cdr])
    RadarCompose([RemoveMean(), RangeFFT(), DopplerFFT(), ToDecibels(), cdr])  # same chain, spelt out
    RadarCompose([cdr, CombineRx(db=True)])  # maps made elsewhere: only the shape is checked
    RadarCompose([RangeDoppler(), ToDecibels(), RandomDR(), cdr])  # random steps are not DSP
    with pytest.raises(CalibrationError, match="blackman"):
        RadarCompose([RangeDoppler(range_window="blackman"), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="StaticClutterRemoval"):
        RadarCompose([RangeDoppler(static_clutter=True), ToDecibels(), cdr])
    with pytest.raises(CalibrationError, match="ToDecibels"):
        RadarCompose([RangeDoppler(), CalibratedDR(-100, 2)])
    with pytest.raises(CalibrationError, match="ToDecibels"):
        RadarCompose([RangeDoppler(), RandomDR()])


def _noise_and_clutter(cfg, frames, g):
    static = beat_cube(cfg, 2.0, 0.0, amplitude=0.05, n_rx=2)
    return static + 1e-3 * torch.randn(
        frames, 2, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp, generator=g, dtype=torch.float64
    )


def test_fit_warns_on_motion_not_on_noise_and_static_clutter(cfg):
    g = torch.Generator().manual_seed(0)
    empty = _noise_and_clutter(cfg, 24, g)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = CalibratedDR.fit(empty)
    assert quiet.motion == 0.0
    # A person walking away from 1 m to 4 m, one position per frame.
    walker = torch.stack([beat_cube(cfg, 1.0 + 0.125 * f, 1.2, amplitude=2e-3, n_rx=2) for f in range(24)])
    with pytest.warns(MotionWarning, match="shows motion"):
        busy = CalibratedDR.fit(empty + walker)
    assert busy.motion > 1e-3


def test_fit_from_capture_path(tmp_path, cfg):
    io = pytest.importorskip("radaraug.io")
    from radaraug.units import counts_to_float, float_to_counts

    g = torch.Generator().manual_seed(3)
    x = _noise_and_clutter(cfg, 20, g) + 0.01 * torch.randn(20, 2, 32, 128, generator=g, dtype=torch.float64)
    counts = float_to_counts(x)
    path = io.write_capture(
        tmp_path / "empty_room.h5", counts.numpy().astype("uint16"), cfg.replace(rx_antennas=(1, 2))
    )
    cdr = CalibratedDR.fit(path)
    ref = CalibratedDR.fit(counts_to_float(counts))
    assert cdr.mean_db == pytest.approx(ref.mean_db, abs=1e-4)
    assert cdr.std_db == pytest.approx(ref.std_db, abs=1e-4)
    assert cdr.source == "empty_room.h5" and cdr.num_frames == 20
    assert cdr.config == cfg.replace(rx_antennas=(1, 2))
    with pytest.raises(CalibrationError, match="differs"):
        CalibratedDR.fit(path, config=cfg)


@pytest.mark.real
def test_real_recordings_motion_check(real_data):
    pytest.importorskip("radaraug.io")
    static = real_data / "ssalehi152431__Beamforming-with-Infineon-BGT60TR13C/Beamforming/beamforming_data"
    static = next(static.glob("2_reflectors*"))
    moving = real_data / "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_48_07"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cdr = CalibratedDR.fit(static)
    # radaraug dBFS, default chain, 23 dB IF gain, 64 samples at 2 MHz, 64 chirps (see docs)
    assert -102 < cdr.mean_db < -95 and math.isfinite(cdr.std_db)
    with pytest.warns(UserWarning, match="shows motion"):
        CalibratedDR.fit(moving)


def test_fit_refuses_bad_frame_counts_and_empty_sources():
    frames = 0.01 * torch.randn(4, 3, 8, 16)
    # before: max_frames=-1 silently fitted on frames[:-1]; 0 and empty tensors gave "got nan, nan";
    # batch_size=0 a bare RuntimeError from torch.split
    for kwargs, match in (
        ({"max_frames": -1}, "max_frames must be a positive integer"),
        ({"max_frames": 0}, "max_frames must be a positive integer"),
        ({"batch_size": 0}, "batch_size must be a positive integer"),
    ):
        with pytest.raises(CalibrationError, match=match):
            CalibratedDR.fit(frames, **kwargs)
    with pytest.raises(CalibrationError, match="has no frames"):
        CalibratedDR.fit(frames[:0])
    assert CalibratedDR.fit(frames, max_frames=3).num_frames == 3


def test_save_to_an_unwritable_place_names_the_file(tmp_path):
    # before: a bare FileNotFoundError
    with pytest.raises(CalibrationError, match="cdr.json"):
        CalibratedDR(-100, 2).save(tmp_path / "missing_dir" / "cdr.json")
