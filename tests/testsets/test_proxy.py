"""The held-out proxy set: files, labels, determinism, reuse, and what differs from the training twin."""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import torch

from radaraug import RadarConfig
from radaraug.errors import ConfigError, SceneError
from radaraug.io import RadarCaptureDataset, open_capture
from radaraug.scene.people import BVHPerson, Walker, read_bvh
from radaraug.scene.people.sine_gait import SineGait, write_sine_gait_bvh
from radaraug.scene.people.skeleton import JOINT_INDEX
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import default_effects
from radaraug.testsets import proxy
from radaraug.transforms import CalibratedDR, RangeDoppler, ToDecibels
from radaraug.transforms.summary import summarize_capture

SMALL = {"frames_per_count": 8, "calibration_frames": 16, "seed": 3, "progress": False,
         "tracer_options": {"rays": 48}}  # a coarse room trace keeps the tests quick


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> proxy.ProxySet:
    return proxy.make_proxy(tmp_path_factory.mktemp("proxy"), **SMALL)


def _read(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    with open_capture(path) as cap:
        return cap.read(as_float=False).numpy(), dict(cap.labels)


def test_files_open_with_the_training_config(made: proxy.ProxySet) -> None:
    assert made.config == RadarConfig.bgt60tr13c()
    assert [c for _, c in made.tests] == [0, 1, 2]
    for path, n in [(made.calibration, 16), *((p, 8) for p, _ in made.tests)]:
        with open_capture(path) as cap:
            assert cap.config == RadarConfig.bgt60tr13c()
            assert cap.shape == (n, 3, 64, 256)
            assert cap.timestamps is not None and np.all(np.diff(cap.timestamps) > 0)
            assert "not sim-to-real" in cap.attrs["note"]
    assert made.test_specs() == [f"{p}:{c}" for p, c in made.tests]
    d = made.to_dict()
    assert json.loads(json.dumps(d))["tests"][2][1] == 2


def test_labels_per_frame_and_per_file(made: proxy.ProxySet) -> None:
    _, cal = _read(made.calibration)
    assert np.all(cal["count"] == 0) and np.all(cal["occupancy"] == 0)
    for path, count in made.tests:
        _, labels = _read(path)
        assert np.all(labels["count"] == count)
        assert np.all(labels["occupancy"] == int(count > 0))
    # Usable per frame (label name) and per file (PATH:COUNT dict) alike.
    per_frame = RadarCaptureDataset([p for p, _ in made.tests], label="count")
    per_file = RadarCaptureDataset([p for p, _ in made.tests], label={p: c for p, c in made.tests})
    assert [per_frame[i][1] for i in range(len(per_frame))] == [per_file[i][1] for i in range(len(per_file))]


def test_manifest_describes_the_set(made: proxy.ProxySet) -> None:
    m = json.loads(made.manifest.read_text())
    assert m["format"] == "radaraug-heldout-proxy"
    assert m["settings"]["frames_per_count"] == 8 and m["settings"]["seed"] == 3
    assert m["settings"]["tracer_options"] == {"rays": 48}
    assert "not sim-to-real" in m["statement"]
    assert {t["count"] for t in m["files"]["tests"]} == {0, 1, 2}
    for name in m["files"]["motion"]:  # the generated clips are there and are valid BVH
        read_bvh(made.manifest.parent / "motion" / name)
    assert m["files"]["motion"]  # counts 1 and 2 have people
    diffs = m["differences"]
    assert {d["effect"] for d in diffs["receiver_effects"]} >= {
        "spur_tone", "phase_noise", "thermal_noise", "system_gain", "rx_gain_phase_mismatch", "tx_rx_leakage"}
    assert diffs["room"]["proxy"]["size_m"] == [14.0, 2.6, 3.0]
    # The empty room is saved as a scene file with the radar pose (for the diagnosis loop).
    scene = Scene.from_file(made.manifest.parent / "room.json")
    assert scene.room.num_faces == proxy.proxy_room().num_faces
    assert proxy.load_proxy(made.manifest.parent).tests == made.tests


def test_rerun_reuses_files(made: proxy.ProxySet) -> None:
    out = made.manifest.parent
    stamps = {p: p.stat().st_mtime_ns for p in out.glob("*.h5")}
    again = proxy.make_proxy(out, **SMALL)
    assert again.reused and again.tests == made.tests
    assert {p: p.stat().st_mtime_ns for p in out.glob("*.h5")} == stamps
    # Other settings or an incomplete set are not reused.
    settings = json.loads(made.manifest.read_text())["settings"]
    assert proxy._reusable(out, {**settings, "seed": 4}) is None
    assert proxy._reusable(out, settings) is not None
    assert proxy._reusable(out / "nowhere", settings) is None


def test_deterministic_per_count(made: proxy.ProxySet, tmp_path: Path) -> None:
    other = proxy.make_proxy(tmp_path, **{**SMALL, "counts": (1,)})
    assert [c for _, c in other.tests] == [1]
    a, la = _read(made.tests[1][0])
    b, lb = _read(other.tests[0][0])
    assert np.array_equal(a, b) and np.array_equal(la["count"], lb["count"])
    assert np.array_equal(_read(made.calibration)[0], _read(other.calibration)[0])
    assert not np.array_equal(_read(made.tests[0][0])[0], a)


def _off_zero_energy(path: Path) -> float:
    """Median over frames of each frame's strongest off-zero-Doppler cell (linear power): a person
    is a few cells, so the peak shows them where the map's mean hardly moves."""
    with open_capture(path) as cap:
        db = ToDecibels()(RangeDoppler()(cap.read()))
    d = db.shape[-1]
    keep = (torch.arange(d) - d // 2).abs() > 2
    return float((10 ** (db[..., keep].flatten(1).amax(dim=1) / 10)).median())


def test_calibration_is_empty_and_people_add_motion(made: proxy.ProxySet) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the motion warning of CalibratedDR.fit would fail the test
        cdr = CalibratedDR.fit(made.calibration)
    assert cdr.num_frames == 16 and math.isfinite(cdr.mean_db)
    with open_capture(made.calibration) as cap:
        assert summarize_capture(cap)["motion"]["motion"] is False
    empty = _off_zero_energy(made.tests[0][0])
    one = _off_zero_energy(made.tests[1][0])
    # The empty room's strongest off-zero cell is the proxy's spur line; since the front-end gain was
    # refitted on real noise floors (20.5 dB lower), a walker's per-frame peak is only a few dB
    # above it (2.5 dB measured on this small set), so the margin asked is small.
    assert 10 * math.log10(one / empty) > 1.5


def test_proxy_differs_from_the_training_twin() -> None:
    config = RadarConfig.bgt60tr13c()
    train = {e.name: e for e in default_effects(config)}
    rx = proxy.proxy_receiver(config)
    names = [e.name for e in rx.effects]
    assert "spur_tone" in names and "spur_tone" not in train
    assert "rx_gain_phase_mismatch" in names and "rx_gain_phase_mismatch" not in train
    pn = rx.effect("phase_noise")
    assert float(pn.freq_noise_rms_Hz) > float(train["phase_noise"].freq_noise_rms_Hz)
    assert float(rx.effect("thermal_noise").noise_figure_dB) == 9.0 != float(train["thermal_noise"].noise_figure_dB)
    assert float(rx.effect("system_gain").gain_dB) == -4.0
    # Hardware order: leakage first, ADC last, the spur after the IF filters and before the ADC.
    assert names[0] == "tx_rx_leakage" and names[-2:] == ["adc_quantization", "adc_clipping"]
    assert names.index("anti_alias_lowpass") < names.index("spur_tone") < names.index("dc_offset")
    # Room: other size, materials and clutter; radar elsewhere and tilted down.
    corridor = Scene.builtin("corridor")
    room = proxy.proxy_room()
    ext = (room.vertices.max(0).values - room.vertices.min(0).values).tolist()
    ext_train = (corridor.room.vertices.max(0).values - corridor.room.vertices.min(0).values).tolist()
    assert ext == pytest.approx([14.0, 2.6, 3.0]) and ext != pytest.approx(ext_train)
    assert {"metal", "glass", "wood"} <= {m.split("@")[0] for m in room.materials}
    assert "metal" not in corridor.room.materials and int(room.object_id.max()) == 3
    pose = proxy.proxy_pose()
    assert not torch.allclose(pose.position.double(), corridor.radar.position.double())
    assert float(pose.rotation[2, 2]) < -0.05  # boresight points down
    assert proxy.BODY_MATERIAL.name != "skin"


def test_people_in_view_counts_only_people_in_front_inside() -> None:
    twin = SimpleNamespace(scene=proxy.proxy_scene())  # people_in_view needs the room and the pose only
    t = torch.arange(3, dtype=torch.float64) * 0.1

    class Standing:  # a body centre at a fixed place (what the count looks at)
        def __init__(self, x: float, y: float) -> None:
            self.c = torch.tensor([x, y, 1.0], dtype=torch.float64)

        def ellipsoids(self, times: torch.Tensor) -> SimpleNamespace:
            return SimpleNamespace(centers=self.c.expand(len(times), 2, 3))

    people = [Standing(5.0, 0.0),    # in front, inside
              Standing(0.25, 0.0),   # inside the room, beside/behind the radar
              Standing(1.0, 0.5),    # inside, but closer than MIN_RANGE_M in front
              Standing(20.0, 0.0)]   # outside the room
    assert proxy.people_in_view(twin, people, t).tolist() == [1, 1, 1]
    assert proxy.people_in_view(twin, people[:1] * 2, t).tolist() == [2, 2, 2]


def test_bad_arguments() -> None:
    for kwargs in ({"frames_per_count": 0}, {"counts": (3,)}, {"counts": (1, 1)}, {"seed": -1},
                   {"device": "nope"}, {"calibration_frames": 1.5}):
        with pytest.raises(ConfigError):
            proxy.make_proxy("unused", **kwargs)


# ------------------------------------------------------------------------------------ SineGait
def test_sine_gait_bvh_round_trip_and_playback(tmp_path: Path) -> None:
    gait = SineGait(height_m=1.8, speed_m_s=1.3, phase=0.25)
    path = write_sine_gait_bvh(gait, tmp_path / "g.bvh")
    sk = read_bvh(path)
    fk = sk.forward_kinematics() * 0.01
    mine = gait.forward_kinematics(gait.clip_times())
    lift = torch.tensor([0.0, gait.pelvis_height_m(), 0.0], dtype=torch.float64)
    for name in ("Hips", "LeftFoot", "RightHand_end", "Head_end"):
        assert torch.allclose(fk[:, sk.names.index(name)], mine[name] + lift, atol=1e-6)
    person = BVHPerson(path, start=(2.0, 0.0), heading_rad=0.0)
    assert person.estimated_height_m == pytest.approx(1.8, rel=1e-3)
    assert person.duration_s == pytest.approx(gait.cycle_duration_s, rel=1e-6)
    t = torch.linspace(0.0, 2 * gait.cycle_duration_s, 201, dtype=torch.float64)
    e = person.ellipsoids(t)
    pelvis_travel = float(e.centers[-1, -1, 0] - e.centers[0, -1, 0])  # torso centre, two cycles
    assert pelvis_travel == pytest.approx(2 * gait.stride_length_m, rel=1e-3)
    lowest = float((e.centers[..., 2] - e.semi_axes.amax(-1)).min())
    assert -0.1 < lowest < 0.05  # feet reach the floor, nothing deep below it
    assert float(e.velocities.norm(dim=-1)[:, :2].max()) > 2.5 * 1.3  # swinging feet outrun the body


def test_sine_gait_is_not_the_boulic_walker() -> None:
    walker = Walker(height_m=1.75, speed_m_s=0.6)
    # Another cadence law: linear in speed and independent of height (Boulic: 1.346 / sqrt(V / 0.491 H)).
    assert walker.cycle_duration_s - SineGait(1.75, 0.6).cycle_duration_s > 0.2
    assert SineGait(1.5, 1.0).cycle_duration_s == SineGait(1.95, 1.0).cycle_duration_s
    # A larger arm swing: the wrist's fore-aft excursion relative to the pelvis is longer.
    t = torch.linspace(0.0, 2.0, 201, dtype=torch.float64)
    joints, _ = walker.joints(t)
    w = joints[:, JOINT_INDEX["right_wrist"], 0] - joints[:, JOINT_INDEX["pelvis"], 0]
    pos = SineGait(1.75, 0.6).forward_kinematics(t)
    g = pos["RightHand"][:, 2] - pos["Hips"][:, 2]  # BVH axes: z is forward
    assert float(g.max() - g.min()) > 1.2 * float(w.max() - w.min())
    assert SineGait(speed_m_s=0.5).cycle_duration_s == pytest.approx(1 / (0.575 + 0.275 * 0.5))
    with pytest.raises(SceneError):
        SineGait(speed_m_s=3.0)


def test_proxy_is_data(tmp_path: Path) -> None:
    """The proxy's settings come from the shipped data file; a broken one is refused, naming the file."""
    assert proxy.SPEC_PATH.is_file() and proxy.GENERATOR_VERSION == proxy.SPEC["generator_version"]
    assert [e.name for e in proxy.proxy_effects(RadarConfig.bgt60tr13c())] == [
        e["name"] for e in proxy.SPEC["receiver"]["effects"]]
    assert proxy.proxy_draw().static_phase_noise_paths == 8
    bad = tmp_path / "proxy.yaml"
    bad.write_text("generator_version: 4\nscene: {}\n")
    with pytest.raises(ConfigError, match="proxy.yaml: the proxy description lacks"):
        proxy._load_spec(bad)
    bad.write_text("scene: [unclosed\n")
    with pytest.raises(ConfigError, match="proxy.yaml: cannot read"):
        proxy._load_spec(bad)
