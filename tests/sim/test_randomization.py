"""Twin randomization: reproducible per (seed, index), every drawn quantity varies, RCS and gain
are applied exactly (closed forms), YAML round trip, and ``off()`` is the plain twin."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest
import torch
import yaml

from radaraug.errors import ConfigError
from radaraug.scene.people import Walker
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import ThermalNoise
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.randomization import (
    DEFAULT_MATERIALS,
    ItemDraw,
    TwinRandomization,
)
from radaraug.sim.twin import DigitalTwin

# The image-method room without diffuse clutter keeps the tests quick; no shadowing, so that
# "frame - room signal" is the people's own signal (what the RCS scaling acts on).
FAST = {"tracer_options": {"diffuse": False}, "shadowing": False}
SMALL = {"room": {"variants": 2}}


@pytest.fixture(scope="module")
def dataset() -> SimulatedRadarDataset:
    return SimulatedRadarDataset("corridor", length=60, seed=5, twin_options=FAST,
                                 randomization=TwinRandomization(**SMALL)).prepare()


def _linear_chain(config, *, noise: bool) -> list:
    """The default chain up to the analogue output: no phase noise, DC offset, ADC-side noise or
    ADC (so the output is linear in the paths and in the gain), thermal noise on or at 0 K."""
    effects = []
    for e in default_effects(config):
        if e.kind == "nonlinear" or e.name in ("dc_offset", "phase_noise", "adc_noise"):
            continue
        if e.name == "thermal_noise" and not noise:
            e = ThermalNoise(noise_figure_dB=12.0, temperature_K=0.0)
        effects.append(e)
    return effects


# ------------------------------------------------------------------------------ configuration
def test_dict_round_trip_yaml_and_errors() -> None:
    r = TwinRandomization(people={"rcs_scale_dB": [-12, 3]}, room={"variants": 3, "materials": {"floor": ["concrete"]}})
    assert r.people.rcs_scale_dB == (-12.0, 3.0)  # lists accepted, stored as pairs
    assert r.room.materials["floor"] == ("concrete",) and r.room.materials["ceiling"] == DEFAULT_MATERIALS["ceiling"]
    assert r.replace(people={"speed_m_s": [1, 2]}).people == dataclasses.replace(r.people, speed_m_s=(1.0, 2.0))
    text = yaml.safe_dump(r.to_dict())
    assert TwinRandomization.from_dict(yaml.safe_load(text)) == r
    assert TwinRandomization.from_dict({}) == TwinRandomization()
    with pytest.raises(ConfigError, match="rcs_scale_db"):
        TwinRandomization.from_dict({"people": {"rcs_scale_db": [0, 1]}})
    with pytest.raises(ConfigError, match="sections"):  # a field outside its section
        TwinRandomization.from_dict({"rcs_scale_dB": [0, 1]})
    for bad, name in (({"room": {"width_m": [3, 2]}}, "room.width_m"), ({"room": {"variants": 0}}, "room.variants"),
                      ({"enabled": "yes"}, "enabled"), ({"gain": 1}, "gain"),
                      ({"room": {"materials": {"floor": ["unobtainium"]}}}, "room.materials.floor"),
                      ({"room": {"materials": {"roof": ["wood"]}}}, "roof"),
                      ({"levels": {"noise_figure_offset_dB": [0, math.inf]}}, "levels.noise_figure_offset_dB"),
                      ({"room": {"length_m": 5.0}}, "room.length_m"), ({"people": []}, "people")):
        with pytest.raises(ConfigError, match=name):
            TwinRandomization.from_dict(bad)
    defaults = TwinRandomization()
    lo, hi = defaults.people.rcs_scale_dB
    assert lo <= -10 and hi >= 10  # covers +-10 dB around the twin's own walker


def test_scene_and_receiver_are_checked() -> None:
    from radaraug.scene.geometry import RadarPose
    from radaraug.scene.room import corridor

    python_room = Scene(room=corridor(10.0), radar=RadarPose.look_at((0.1, 0, 1.2), (5, 0, 1.2)))
    with pytest.raises(ConfigError, match="corridor"):
        SimulatedRadarDataset(python_room, length=2, twin_options=FAST, randomization=TwinRandomization(**SMALL))
    cfg = Scene.builtin("corridor").config
    no_gain = FMCWReceiver(cfg, effects=[e for e in default_effects(cfg) if e.name != "system_gain"])
    with pytest.raises(ConfigError, match="system_gain"):
        SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_gain},
                              randomization=TwinRandomization(**SMALL))
    # The effect catalog's wide levels offset the gain too.
    with pytest.raises(ConfigError, match="wide_levels.system_gain_offset_dB"):
        SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_gain},
                              randomization=TwinRandomization(levels={"system_gain_offset_dB": (0, 0)}, **SMALL))
    # Without gain offsets such a receiver is fine.
    SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_gain},
                          randomization=TwinRandomization(levels={"system_gain_offset_dB": (0, 0)},
                                                          catalog={"wide_levels": {"probability": 0}}, **SMALL))
    no_pn = FMCWReceiver(cfg, effects=[e for e in default_effects(cfg) if e.name != "phase_noise"])
    with pytest.raises(ConfigError, match="phase_noise"):
        SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_pn},
                              randomization=TwinRandomization(**SMALL))


# ------------------------------------------------------------------------------ draws
def test_every_drawn_quantity_varies() -> None:
    r = TwinRandomization()
    draws = [r.item(0, i, 2) for i in range(200)]
    rcs = np.array([d.rcs_scale_dB for d in draws])
    assert rcs.max() - rcs.min() >= 20 and rcs.min() >= -20 and rcs.max() <= 10
    assert np.ptp([d.system_gain_offset_dB for d in draws]) > 8
    assert np.ptp([d.noise_figure_offset_dB for d in draws]) > 5  # of the 6 dB range
    assert set(d.variant for d in draws) == set(range(r.room.variants))
    # The room pool: a pure function of (seed, k), different across seeds and variants.
    rooms = [r.room_draw(s, k) for s in range(40) for k in range(r.room.variants)]
    assert r.room_draw(3, 1) == r.room_draw(3, 1) and r.room_draw(3, 1) != r.room_draw(4, 1)
    p = r.room
    for name, (lo, hi) in (("length_m", p.length_m), ("width_m", p.width_m), ("height_m", p.height_m),
                           ("radar_pitch_deg", p.radar_pitch_deg), ("radar_yaw_deg", p.radar_yaw_deg)):
        v = np.array([getattr(room, name) for room in rooms])
        assert v.min() >= lo and v.max() <= hi and np.ptp(v) > 0.6 * (hi - lo), name
    heights = np.array([room.radar_height_m for room in rooms])
    assert np.ptp(heights) > 0.8 and all(room.radar_height_m <= room.height_m - 0.15 for room in rooms)
    for surface, choices in r.room.materials.items():
        assert {room.materials[surface] for room in rooms} == set(choices), surface


def test_item_params_people_inside_the_drawn_room(dataset) -> None:
    # Building a walker costs ~0.1 s (its gait's ground offset): 40 items keep this quick.
    params = [dataset.item_params(i) for i in range(40)]
    counts = np.bincount([p["count"] for p in params], minlength=3)
    assert counts.min() >= 8  # 0/1/2 stay balanced (expected ~13 each)
    people = [(p, q) for p in params for q in p["people"]]
    r = dataset.randomization.people
    for p, q in people:
        room = p["room"]
        assert abs(q["lateral_m"]) <= room["width_m"] / 2 - r.wall_margin_m + 1e-9
        assert q["range_m"] <= room["length_m"] - 0.1 - r.wall_margin_m + 1e-9
        assert r.rcs_scale_dB[0] <= q["rcs_scale_dB"] <= r.rcs_scale_dB[1]
    heights = [q["height_m"] for _, q in people]
    speeds = [q["speed_m_s"] for _, q in people]
    assert min(heights) < 1.55 and max(heights) > 1.95  # wider than the paper-like sampler
    assert min(speeds) < 0.6 and max(speeds) > 1.8
    # Heading jitter beyond the plain sampler's +-5 deg.
    off_axis = [math.degrees(abs(math.remainder(q["heading_rad"], math.pi))) for _, q in people]
    assert max(off_axis) > 15
    gains = [p["system_gain_dB"] for p in params]
    nfs = [p["noise_figure_dB"] for p in params]
    assert min(gains) < -4 and max(gains) > 4 and min(nfs) < 10 and max(nfs) > 14
    assert {p["variant"] for p in params} == {0, 1}
    # JSON-able, and a pure function of (seed, index).
    import json

    json.dumps(params[:5])
    other = SimulatedRadarDataset("corridor", length=60, seed=5, twin_options=FAST,
                                  randomization=TwinRandomization(**SMALL))
    assert other.item_params(17) == params[17]
    assert SimulatedRadarDataset("corridor", length=200, seed=6, twin_options=FAST,
                                 randomization=TwinRandomization(**SMALL)).item_params(17) != params[17]


# ------------------------------------------------------------------------------ reproducibility
def test_items_reproducible_in_any_order_and_process(dataset) -> None:
    idx = [0, 1, 2, 3]
    first = [dataset[i] for i in idx]
    assert all(x.shape == (3, 64, 256) for x, _ in first)
    fresh = SimulatedRadarDataset("corridor", length=60, seed=5, twin_options=FAST,
                                  randomization=TwinRandomization(**SMALL))
    backwards = {i: fresh[i] for i in reversed(idx)}
    for i, (x, y) in zip(idx, first):
        assert torch.equal(backwards[i][0], x) and backwards[i][1] == y
        assert torch.equal(dataset[i][0], x)
    assert not torch.equal(first[0][0], first[1][0])
    # A DataLoader worker gets the traced rooms with the pickled dataset and traces nothing.
    copy = pickle.loads(pickle.dumps(dataset))
    assert sorted(copy._variant_static) == [0, 1] and not copy._variant_twins
    assert torch.equal(copy[2][0], first[2][0])
    # Windows of frames and ADC codes work the same way.
    win = SimulatedRadarDataset("corridor", length=60, seed=5, twin_options=FAST, frames_per_item=2,
                                as_counts=True, randomization=TwinRandomization(**SMALL))
    win._variant_static = copy._variant_static
    x, y = win[2]
    assert x.shape == (2, 3, 64, 256) and x.dtype == torch.uint16 and y == first[2][1]


def test_off_is_the_plain_twin() -> None:
    plain = SimulatedRadarDataset("corridor", length=4, seed=2, twin_options=FAST)
    items = {i: plain[i] for i in (0, 3)}
    for r in (TwinRandomization.off(), {"enabled": False}):
        off = SimulatedRadarDataset("corridor", length=4, seed=2, twin_options=FAST, randomization=r)
        assert not off.randomized
        off._twin, off._static_signal = None, plain.twin.static_signal()  # skip a second room trace
        for i, (x, y) in items.items():
            assert torch.equal(off[i][0], x) and off[i][1] == y
        assert off.item_params(1) == plain.item_params(1)
    assert "variant" not in plain.item_params(1)


# ------------------------------------------------------------------------------ physics
@pytest.fixture(scope="module")
def ideal_twin() -> DigitalTwin:
    scene = Scene.builtin("corridor")
    return DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), **FAST)


def test_rcs_scale_gives_the_same_db_on_the_person_rd_peak(ideal_twin) -> None:
    """+6 dB RCS -> +6 dB on the walker's RD peak (ideal receiver: linear, no noise)."""
    from radaraug.transforms import RangeDoppler, ToDecibels

    walker = Walker(height_m=1.8, speed_m_s=1.2, start=(6.1, 0.0), heading_rad=0.0)
    times = ideal_twin.frame_times([0])
    static = ideal_twin.static_signal()

    def peak(db: float) -> float:
        x = ideal_twin.simulate([walker], times, draw=ItemDraw(0, 0.0, 0.0, (db,))) - static
        return float(ToDecibels()(RangeDoppler()(x)).amax())

    assert peak(6.0) - peak(0.0) == pytest.approx(6.0, abs=1e-3)
    assert peak(-14.0) - peak(0.0) == pytest.approx(-14.0, abs=1e-3)


def test_rcs_scale_is_per_person_including_wall_multipath(ideal_twin) -> None:
    """Two people traced together, scaled per person, equal each traced alone and scaled (they do
    not shadow each other here): the scaling hits every path of the right person."""
    a = Walker(height_m=1.7, speed_m_s=1.0, start=(3.1, -0.6), heading_rad=0.0)
    b = Walker(height_m=1.9, speed_m_s=1.5, start=(8.1, 0.6), heading_rad=math.pi)
    times = ideal_twin.frame_times([0, 1])
    paths = ideal_twin.paths([a, b], times)
    assert bool((paths.kind == 1).any())  # wall multipath is present
    static = ideal_twin.static_signal()

    def sim(people, rcs):
        return ideal_twin.simulate(people, times, draw=ItemDraw(0, 0.0, 0.0, rcs)) - static

    both = sim([a, b], (6.0, -10.0))
    alone = 10 ** (6 / 20) * sim([a], (0.0,)) + 10 ** (-10 / 20) * sim([b], (0.0,))
    # Fast synthesis keeps Taylor terms down to 1e-5 of the call's strongest path: calls with
    # different people truncate differently, at that level.
    assert torch.allclose(both, alone, rtol=1e-4, atol=1e-4 * float(alone.abs().max()))
    # 0 dB is exactly the unrandomized twin.
    plain = ideal_twin.simulate([a, b], times)
    assert torch.equal(sim([a, b], (0.0, 0.0)) + static, plain)
    assert isinstance(paths, Paths)


def test_gain_offset_scales_room_people_and_noise_alike() -> None:
    """An item at +g dB equals the item at 0 dB times 10**(g/20) (same noise draws), and equals an
    independent reference that traces the room with the people through a receiver set to +g."""
    scene = Scene.builtin("corridor")
    g = 4.5
    base = dict(length=8, seed=1, twin_options={**FAST, "receiver": FMCWReceiver(
        scene.config, effects=_linear_chain(scene.config, noise=True))})
    # The effect catalog off: its stages (spur, drift...) do not scale with the gain.
    r0 = TwinRandomization(levels={"system_gain_offset_dB": (0, 0), "phase_noise_rms_Hz": (0, 0)},
                           room={"variants": 1}, catalog={"scale": 0})
    rg = TwinRandomization(levels={"system_gain_offset_dB": (g, g), "phase_noise_rms_Hz": (0, 0)},
                           room={"variants": 1}, catalog={"scale": 0})
    ds0 = SimulatedRadarDataset(scene, randomization=r0, **base)
    dsg = SimulatedRadarDataset(scene, randomization=rg, **base)
    dsg._variant_static = {0: ds0.prepare().variant_twin(0).static_signal()}  # one room trace
    i = next(i for i in range(8) if ds0.item_params(i)["count"] > 0)
    assert ds0.item_params(i)["people"] == dsg.item_params(i)["people"]
    x0, xg = ds0[i][0], dsg[i][0]
    assert torch.allclose(xg, 10 ** (g / 20) * x0, rtol=1e-5, atol=1e-6 * float(xg.abs().max()))
    # The shared receiver and the cached room are untouched by the item's gain.
    rx = dsg.variant_twin(0).receiver
    assert float(rx.effect("system_gain").gain_dB) == 0.0
    assert torch.equal(dsg.variant_twin(0).static_signal(), ds0.variant_twin(0).static_signal())

    # Independent reference, noise off: room and people traced together, receiver at +g dB.
    quiet = {**FAST, "receiver": FMCWReceiver(scene.config, effects=_linear_chain(scene.config, noise=False))}
    dsq = SimulatedRadarDataset(scene, length=8, seed=1, twin_options=quiet, randomization=rg)
    twin = dsq.variant_twin(0)
    params = dsq.item_params(i)
    got = dsq[i][0]
    effects = _linear_chain(scene.config, noise=False)
    effects = [e if e.name != "system_gain" else type(e)(gain_dB=g) for e in effects]
    ref_rx = FMCWReceiver(scene.config, effects=effects)
    draw = dsq.randomization.item(dsq.seed, i, params["count"])
    from radaraug.sim.item_signal import scale_people_paths, static_scatterer_paths

    times = twin.frame_times([0])
    walkers = dsq.scenario(i).people
    segments = [int(p.ellipsoids(times[:1]).centers.shape[-2]) for p in walkers]
    people = scale_people_paths(twin.paths(walkers, times), segments, draw.rcs_scale_dB)
    room = twin.tracer.static_paths().map(lambda t: t.expand(1, *t.shape))
    extra = [static_scatterer_paths(scene.config, draw.scatterers, people)] if draw.scatterers else []
    ref = ref_rx(Paths.cat([room, people, *extra]), frame_start_s=times)[0]
    assert torch.allclose(got, ref, rtol=1e-4, atol=1e-5 * float(ref.abs().max()))


def test_variant_pose_keeps_the_mounting_and_applies_tilt() -> None:
    r = TwinRandomization(room={"radar_pitch_deg": (7, 7), "radar_yaw_deg": (-3, -3), "variants": 1})
    for mounting in ("landscape", "portrait"):
        data = Scene.builtin("corridor").to_dict()
        data["radar"] = {"position": [0.1, 0.0, 1.2], "look_at": [10.0, 0.0, 1.2], "mounting": mounting}
        base = Scene.from_dict(data)
        room = r.room_draw(0, 0)
        rot = room.scene(base).radar.rotation
        b = rot[:, 2]
        assert math.degrees(math.asin(float(b[2]))) == pytest.approx(7.0, abs=1e-6)
        assert math.degrees(math.atan2(float(b[1]), float(b[0]))) == pytest.approx(-3.0, abs=1e-6)
        # The sensor's own x axis stays horizontal (landscape) or in the vertical plane (portrait).
        x_axis_z = float(rot[2, 0])
        assert (abs(x_axis_z) < 1e-9) if mounting == "landscape" else (abs(x_axis_z) > 0.99)
        level = TwinRandomization(room={"radar_pitch_deg": (0, 0), "radar_yaw_deg": (0, 0), "variants": 1}).room_draw(0, 0)
        assert torch.allclose(level.scene(base).radar.rotation, base.radar.rotation, atol=1e-12)
        assert float(room.scene(base).radar.position[2]) == pytest.approx(room.radar_height_m)


def test_static_scatterer_lands_in_its_range_bin_at_zero_doppler() -> None:
    """One 0 dBsm scatterer at 6 m on boresight: peak at the 6 m range bin, zero Doppler; the
    same scatterer at +10 dBsm reads +10 dB (RCS enters the power linearly)."""
    from radaraug.transforms import RangeDoppler, ToDecibels

    scene = Scene.builtin("corridor")
    cfg = scene.config
    twin = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=[]), **{"tracer_options": FAST["tracer_options"]})
    times = twin.frame_times([0])
    levels = []
    for rcs in (0.0, 10.0):
        draw = ItemDraw(0, 0.0, 0.0, (), ((6.0, 0.0, 0.0, rcs),))
        x = twin.simulate([], times, draw=draw)
        x = x - twin.static_signal()  # the room's part (same in every frame) out
        db = ToDecibels()(RangeDoppler()(x))[0].amax(0)  # (range, doppler), strongest RX
        r, d = divmod(int(db.argmax()), db.shape[-1])
        assert d == cfg.num_chirps_per_frame // 2
        assert abs(cfg.range_axis_m()[r] - 6.0) <= cfg.range_resolution_m
        levels.append(float(db.max()))
    assert levels[1] - levels[0] == pytest.approx(10.0, abs=0.05)


def test_scatterers_and_clutter_vary_and_are_reproducible(dataset) -> None:
    r = dataset.randomization
    counts = {len(r.item(5, i, 0).scatterers) for i in range(40)}
    assert min(counts) == 0 and max(counts) >= 6
    a, b = r.item(5, 3, 2).scatterers, r.item(5, 3, 0).scatterers
    assert a == b  # independent of the number of people
    params = dataset.item_params(3)
    assert len(params["static_scatterers"]) == len(a)
    rooms = [r.room_draw(5, k) for k in range(r.room.variants)]
    big = TwinRandomization(room={"variants": 12})
    n_obj = [len(big.room_draw(0, k).clutter) for k in range(12)]
    assert min(n_obj) < max(n_obj) <= 6
    with_clutter = next(room for room in [big.room_draw(0, k) for k in range(12)] if room.clutter)
    plain = Scene.builtin("corridor")
    scene = with_clutter.scene(plain)
    c = with_clutter.clutter[0]
    assert c["material"] in scene.room.materials or any(m.startswith(c["material"]) for m in scene.room.materials)
    assert int(scene.room.object_id.max()) == len(with_clutter.clutter)  # walls 0, one id per object
    assert with_clutter.to_dict()["clutter"][0]["max"][2] <= with_clutter.height_m
    assert rooms == [r.room_draw(5, k) for k in range(r.room.variants)]
    with pytest.raises(ConfigError, match="room.scatterers"):
        TwinRandomization(room={"scatterers": (3, 1)})
    with pytest.raises(ConfigError, match="clutter_materials"):
        TwinRandomization(room={"clutter_materials": ["unobtainium"]})


def test_drawn_phase_noise_skirts_a_strong_static_scatterer() -> None:
    """A +40 dBsm scatterer at 8 m: with 400 kHz RMS frequency noise its range bin fills across
    Doppler (a skirt); with 30 kHz it stays at zero Doppler."""
    from radaraug.transforms import RangeDoppler, ToDecibels

    scene = Scene.builtin("corridor")
    cfg = scene.config
    twin = DigitalTwin(scene, tracer_options=FAST["tracer_options"])
    times = twin.frame_times([0])
    off = []
    for pn in (30e3, 400e3):
        draw = ItemDraw(0, 0.0, 0.0, (), ((8.0, 0.0, 0.0, 40.0),), pn)
        x = twin.simulate([], times, generators=torch.Generator().manual_seed(0), draw=draw)
        db = ToDecibels()(RangeDoppler()(x))[0].amax(0)
        r = min(range(db.shape[0]), key=lambda k: abs(cfg.range_axis_m()[k] - 8.0))
        m = cfg.num_chirps_per_frame
        off.append(float(torch.cat([db[r, : m // 2 - 3], db[r, m // 2 + 4:]]).median()))
    assert off[1] - off[0] > 6.0
    draws = [TwinRandomization().item(0, i, 0).phase_noise_rms_Hz for i in range(100)]
    assert min(draws) < 80e3 and max(draws) > 350e3


