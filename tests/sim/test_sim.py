"""The simulated Dataset, scenarios and offline generation: determinism, labels, resume, physics."""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
import torch
from torch.utils.data import DataLoader

from radaraug.scene.scene import Scene
from radaraug.sim import offline
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.randomization import TwinRandomization
from radaraug.sim.scenarios import ScenarioSampler
from radaraug.sim.seeding import item_seed
from radaraug.sim.twin import DigitalTwin

FAST = {"tracer_options": {"rays": 48}}  # a coarse room trace keeps the tests quick


@pytest.fixture(scope="module")
def dataset() -> SimulatedRadarDataset:
    return SimulatedRadarDataset("corridor", length=12, seed=7, twin_options=FAST).prepare()


def test_item_seed_mixes_seed_and_index() -> None:
    seeds = {item_seed(s, i) for s in range(4) for i in range(50)}
    assert len(seeds) == 200
    assert item_seed(1, 2) == item_seed(1, 2) and item_seed(1, 2) != item_seed(2, 1)


def test_sampler_labels_and_ranges() -> None:
    sampler = ScenarioSampler()
    g = torch.Generator().manual_seed(0)
    scenarios = [sampler.sample(g) for _ in range(300)]
    counts = np.bincount([s.count for s in scenarios], minlength=3)
    assert counts.min() > 70  # balanced classes (expected 100 each)
    for s in scenarios:
        assert s.occupancy == int(s.count > 0)
        for p in s.params:
            assert 0.6 <= p["speed_m_s"] <= 1.8 and 1.55 <= p["height_m"] <= 1.95
        if s.count == 2:  # the paper's "different speeds"
            assert abs(s.params[0]["speed_m_s"] - s.params[1]["speed_m_s"]) >= 0.2


def test_item_is_pure_function_of_seed_and_index(dataset) -> None:
    x1, y1 = dataset[3]
    x2, y2 = dataset[3]
    assert x1.shape == (3, 64, 256) and x1.dtype == torch.float32
    assert torch.equal(x1, x2) and y1 == y2
    # A fresh dataset object (another process, rank or epoch) gives the same item...
    other = SimulatedRadarDataset("corridor", length=12, seed=7, twin_options=FAST)
    assert torch.equal(other[3][0], x1)
    # ...and another seed or index gives another item.
    assert not torch.equal(dataset[4][0], x1)
    assert not torch.equal(SimulatedRadarDataset("corridor", length=12, seed=8, twin_options=FAST)[3][0], x1)


def test_same_items_in_dataloader_workers(dataset) -> None:
    direct = torch.stack([dataset[i][0] for i in range(4)])
    pickle.dumps(dataset)  # no open handles or generators in the state
    loader = DataLoader(dataset, batch_size=2, num_workers=2, shuffle=False)
    got = torch.cat([x for x, _ in [next(iter(loader)), list(loader)[1]]])
    assert torch.equal(got, direct)


def test_output_units_like_a_real_capture(dataset) -> None:
    x, _ = dataset[0]
    counts = (x + 1) * 4095 / 2
    # SDK floats of 12-bit codes: integers after conversion, inside [0, 4095].
    assert torch.allclose(counts, counts.round(), atol=2e-3)
    assert counts.min() >= 0 and counts.max() <= 4095
    # Per-RX DC offsets of the default BGT60TR13C chain (measured: ~1620 / ~1945 / ~2067 counts).
    dc = counts.mean(dim=(1, 2))
    assert torch.allclose(dc, torch.tensor([1620.0, 1945.0, 2067.5]), atol=25)


def test_walker_lands_in_the_right_range_and_doppler_bins() -> None:
    """A walker straight ahead: its torso at range R bin, at Doppler of its speed (closed forms)."""
    from radaraug.scene.people import Walker
    from radaraug.transforms import RangeDoppler, ToDecibels

    scene = Scene.builtin("corridor")
    twin = DigitalTwin(scene, **FAST)
    cfg = twin.config
    walker = Walker(height_m=1.8, speed_m_s=1.2, start=(6.1, 0.0), heading_rad=0.0)  # 6 m, walking away
    x = twin.simulate([walker], twin.frame_times([0]), generators=torch.Generator().manual_seed(0))
    rd = ToDecibels()(RangeDoppler(static_clutter=True)(x))[0].mean(0)  # (range, doppler)
    r, d = np.unravel_index(int(rd.argmax()), tuple(rd.shape))
    radar_z = float(scene.radar.position[2])
    slant = float(np.hypot(6.0, radar_z - 1.0))
    assert abs(r * cfg.range_resolution_m - slant) < 0.5
    v = (d - cfg.num_chirps_per_frame // 2) * cfg.velocity_resolution_m_s
    assert 0.5 < v < 2.0  # torso near the walking speed, receding = positive


def test_empty_room_has_no_motion_and_people_do(dataset) -> None:
    from radaraug.transforms import RangeDoppler, ToDecibels

    labels = [dataset.scenario(i).count for i in range(len(dataset))]
    empty = labels.index(0)
    busy = labels.index(2) if 2 in labels else labels.index(1)

    def moving_energy(i: int) -> float:
        db = ToDecibels()(RangeDoppler(static_clutter=True)(dataset[i][0]))
        return float(db.amax())
    assert moving_energy(busy) > moving_energy(empty) + 10


def test_offline_shards_equal_one_run_and_resume(tmp_path, monkeypatch) -> None:
    scene = Scene.builtin("corridor_one_walker")
    whole = offline.simulate_capture(scene, tmp_path / "all.h5", frames=40, seed=3, progress=False,
                                     twin_options=FAST)
    from radaraug.io import open_capture

    with open_capture(whole["path"]) as c:
        ref = c.read(as_float=False)
        assert c.labels["count"].tolist() == [1] * 40
    parts = [offline.simulate_capture(scene, tmp_path / "p.h5", frames=40, seed=3, shard=(i, 2), progress=False,
                                      twin_options=FAST) for i in range(2)]
    got = []
    for p in parts:
        with open_capture(p["path"]) as c:
            got.append(c.read(as_float=False))
    assert torch.equal(torch.cat(got), ref)

    # A crash after the first block: the re-run resumes and the file equals the clean run.
    calls = {"n": 0}
    real = offline.people_inside

    def crash(*a, **k):
        calls["n"] += 1
        if calls["n"] == 2:
            raise KeyboardInterrupt
        return real(*a, **k)

    monkeypatch.setattr(offline, "people_inside", crash)
    with pytest.raises(KeyboardInterrupt):
        offline.simulate_capture(scene, tmp_path / "r.h5", frames=40, seed=3, progress=False, twin_options=FAST)
    monkeypatch.setattr(offline, "people_inside", real)
    again = offline.simulate_capture(scene, tmp_path / "r.h5", frames=40, seed=3, progress=False, twin_options=FAST)
    assert again["resumed_from"] == 16 and again["simulated"] == 24
    with open_capture(again["path"]) as c:
        assert torch.equal(c.read(as_float=False), ref)
    # A finished job is not redone; another job's file is refused.
    assert offline.simulate_capture(scene, tmp_path / "r.h5", frames=40, seed=3, progress=False,
                                    twin_options=FAST)["simulated"] == 0
    from radaraug.errors import CaptureError

    with pytest.raises(CaptureError, match="not made by this job"):
        offline.simulate_capture(scene, tmp_path / "r.h5", frames=40, seed=4, progress=False, twin_options=FAST)


def test_parse_shard_errors() -> None:
    from radaraug.errors import ConfigError

    assert offline.parse_shard("1/4") == (1, 4)
    for bad in ("4/4", "x", "1/0", "-1/2"):
        with pytest.raises(ConfigError):
            offline.parse_shard(bad)


def test_dataset_with_a_real_recordings_config(real_data) -> None:
    from radaraug.config import RadarConfig

    cfgs = sorted(real_data.rglob("recording_2022_05_25_18_53_49/RadarIfxAvian_00/config.json"))
    if not cfgs:
        pytest.skip("recording not present")
    cfg = RadarConfig.from_infineon(cfgs[0])
    ds = SimulatedRadarDataset("corridor", length=2, seed=0, config=cfg, twin_options=FAST)
    x, _ = ds[0]
    assert x.shape == (3, 64, 128)


def test_dataset_with_another_config_read_from_infineon_json() -> None:
    """The ifxdaq people-counting config (1 GHz, 128 samples @ 2 MHz, 64 chirps @ 400 us, 3 RX)."""
    from radaraug.config import RadarConfig

    cfg = RadarConfig.from_infineon({"device_config": {"fmcw_single_shape": {
        "rx_antennas": [1, 2, 3], "tx_antennas": [1], "tx_power_level": 31, "if_gain_dB": 38,
        "start_frequency_Hz": 60.5e9, "end_frequency_Hz": 61.5e9, "num_chirps_per_frame": 64,
        "num_samples_per_chirp": 128, "chirp_repetition_time_s": 400e-6, "frame_repetition_time_s": 0.05,
        "sample_rate_Hz": 2e6, "mimo_mode": "off"}}})
    ds = SimulatedRadarDataset("corridor", length=3, seed=0, config=cfg, twin_options=FAST, frames_per_item=2)
    x, y = ds[1]
    assert x.shape == (2, 3, 64, 128) and y == ds.scenario(1).count
    assert torch.isfinite(x).all() and x.abs().max() <= 1


def test_sampler_standing_people() -> None:
    from radaraug.errors import ConfigError
    from radaraug.scene.people import StandingPerson, Walker

    walkers = [ScenarioSampler().sample(torch.Generator().manual_seed(s)) for s in range(20)]
    zero = [ScenarioSampler(standing_probability=0.0).sample(torch.Generator().manual_seed(s)) for s in range(20)]
    # Off: nothing extra is drawn, so the scenarios are the walkers-only ones.
    assert [w.params for w in walkers] == [z.params for z in zero]
    sampler = ScenarioSampler(standing_probability=1.0, counts=(1, 2))
    for s in range(30):
        sc = sampler.sample(torch.Generator().manual_seed(s))
        assert sc.count in (1, 2) and all(isinstance(p, StandingPerson) for p in sc.people)
        for p, par in zip(sc.people, sc.params):
            assert 0.003 <= p.breathing_m <= 0.012 and 0.1 <= p.sway_Hz <= 0.5 and par["standing"] == 1.0
            assert 1.0 <= par["range_m"] <= 12.0
    again = sampler.sample(torch.Generator().manual_seed(3))
    assert again.params == sampler.sample(torch.Generator().manual_seed(3)).params
    mixed = ScenarioSampler(standing_probability=0.5, counts=(2,))
    kinds = {type(p) for s in range(20) for p in mixed.sample(torch.Generator().manual_seed(s)).people}
    assert kinds == {StandingPerson, Walker}
    with pytest.raises(ConfigError, match="standing_probability"):
        ScenarioSampler(standing_probability=1.5)


def test_sampler_crossing_walkers() -> None:
    from radaraug.errors import ConfigError

    walkers = [ScenarioSampler().sample(torch.Generator().manual_seed(s)) for s in range(20)]
    zero = [ScenarioSampler(crossing_probability=0.0).sample(torch.Generator().manual_seed(s)) for s in range(20)]
    # Off: nothing extra is drawn, so the scenarios are those of before.
    assert [w.params for w in walkers] == [z.params for z in zero]
    jitter = math.radians(5.0)
    sides = set()
    for s in range(30):
        sc = ScenarioSampler(crossing_probability=1.0, counts=(1, 2)).sample(
            torch.Generator().manual_seed(s), axis_deg=30.0)
        for par in sc.params:
            off = par["heading_rad"] - math.radians(30.0)
            # across the axis: within the jitter of +-90 deg
            assert abs(math.cos(off)) <= math.sin(jitter) + 1e-12 and par["crossing"] == 1.0
            sides.add(math.copysign(1.0, math.sin(off)))
    assert sides == {1.0, -1.0}
    mixed = ScenarioSampler(crossing_probability=0.5, counts=(2,))
    kinds = {"crossing" in par for s in range(20) for par in mixed.sample(torch.Generator().manual_seed(s)).params}
    assert kinds == {True, False}
    twin_sampler = TwinRandomization(people={"crossing_probability": 0.4}).sampler(
        ScenarioSampler(), TwinRandomization().room_draw(0, 0), radar_x_m=0.1)
    assert twin_sampler.crossing_probability == 0.4
    with pytest.raises(ConfigError, match="crossing_probability"):
        ScenarioSampler(crossing_probability=-0.1)


def test_crossing_walker_sits_near_zero_doppler_and_a_radial_one_at_its_speed() -> None:
    """Closed form: a walker's body returns at Doppler bin v_r / velocity resolution. The torso's
    speed swings over a stride, so over four gait phases: walking straight at the radar at 1.2 m/s,
    the strongest bin of its field is at that bin on average; crossing the boresight at the same
    speed (v_r = 0 for the torso), its field's Doppler centroid is within a bin of zero."""
    from radaraug.scene.people import Walker
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.transforms import RangeDoppler

    scene = Scene.builtin("corridor")
    twin = DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), **FAST)  # linear, no noise
    cfg = twin.config
    t = twin.frame_times([0])
    x_empty = twin.simulate([], t, generators=torch.Generator().manual_seed(0))
    rd = RangeDoppler()
    bins = torch.arange(cfg.num_chirps_per_frame) - cfg.num_chirps_per_frame // 2
    peak, centroid = {}, {}
    for name, heading in (("toward", math.pi), ("crossing", math.pi / 2)):
        p, c = [], []
        for phase in (0.0, 0.25, 0.5, 0.75):
            walker = Walker(height_m=1.8, speed_m_s=1.2, start=(4.1, 0.0), heading_rad=heading, phase=phase)
            x = twin.simulate([walker], t, generators=torch.Generator().manual_seed(0))
            field = (rd(x) - rd(x_empty)).abs().square().mean(1)[0].sum(0)  # the walker's Doppler profile
            p.append(float(bins[field.argmax()]))
            c.append(float((field * bins).sum() / field.sum()))
        peak[name], centroid[name] = sum(p) / len(p), sum(c) / len(c)
    expected = 1.2 / cfg.velocity_resolution_m_s  # toward the radar: negative bins
    assert abs(-peak["toward"] - expected) <= 1.5
    assert abs(centroid["crossing"]) <= 1.0


def test_standing_person_returns_only_at_zero_doppler() -> None:
    """A standing person (breathing, sway) is slower than a Doppler bin: the frame shows them at
    zero Doppler (their range bin rises over the empty room) and nowhere else (closed form: the
    fastest joint is under one velocity bin)."""
    from radaraug.scene.people import StandingPerson
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.transforms import RangeDoppler

    scene = Scene.builtin("corridor")
    twin = DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), **FAST)  # linear, no noise
    cfg = twin.config
    person = StandingPerson(height_m=1.8, position=(4.1, 0.0), facing_rad=3.14159, breathing_m=0.01, sway_rad=0.01)
    assert person.peak_speed_m_s < cfg.velocity_resolution_m_s
    t = twin.frame_times([0])
    g = torch.Generator().manual_seed(0)
    x_person = twin.simulate([person], t, generators=g)
    x_empty = twin.simulate([], t, generators=torch.Generator().manual_seed(0))
    rd = RangeDoppler()
    diff = (rd(x_person) - rd(x_empty)).abs().square().mean(1)[0]  # (range, doppler): the person's field
    mid = cfg.num_chirps_per_frame // 2
    # Inside the Doppler window's main lobe around zero (Hann: +-2 bins for a tone off a bin centre).
    share = diff[:, mid - 2:mid + 3].sum() / diff.sum()
    assert share > 0.99
    r = int(diff[:, mid].argmax())
    assert abs(r * cfg.range_resolution_m - 4.0) < 0.6
