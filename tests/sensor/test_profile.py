"""Twin profiles: the room section (fitted room parameters) next to the receiver chain."""

from __future__ import annotations

import json

import pytest

from radaraug import RadarConfig
from radaraug.errors import CalibrationError, CaptureError
from radaraug.sensor import FMCWReceiver
from radaraug.sensor.profile import PROFILE_VERSION, TwinProfile
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.twin import DigitalTwin

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=32, num_chirps_per_frame=8)


def _profile(room=None) -> TwinProfile:
    return TwinProfile(FMCWReceiver(CFG).to_dict(), {"capture": "test"}, room=room)


def test_room_section_round_trips_and_version_1_files_still_load(tmp_path):
    p = _profile({"diffuse_gain_dB": 4.2}).save(tmp_path / "p.json")
    data = json.loads(p.read_text())
    assert data["version"] == PROFILE_VERSION == 2 and data["room"] == {"diffuse_gain_dB": 4.2}
    assert TwinProfile.load(p).tracer_options() == {"diffuse_gain_dB": 4.2}
    old = {k: v for k, v in data.items() if k != "room"} | {"version": 1}
    (tmp_path / "old.json").write_text(json.dumps(old))
    prof = TwinProfile.load(tmp_path / "old.json")
    assert prof.room == {} and prof.effect_names == _profile().effect_names


@pytest.mark.parametrize("room, match", [
    ({"diffuse_gain": 1.0}, "unknown room parameter 'diffuse_gain'"),
    ({"diffuse_gain_dB": float("nan")}, "finite number"),
    ({"diffuse_gain_dB": "3"}, "finite number"),
    ([1.0], "must be a mapping"),
])
def test_bad_room_sections_name_the_file(tmp_path, room, match):
    data = _profile().to_dict() | {"room": room}
    (tmp_path / "bad.json").write_text(json.dumps(data))
    with pytest.raises(CalibrationError, match=match) as err:
        TwinProfile.load(tmp_path / "bad.json")
    assert "bad.json" in str(err.value)
    data["version"] = 3
    (tmp_path / "v3.json").write_text(json.dumps(data))
    with pytest.raises(CalibrationError, match="version 3, this radaraug reads 1, 2"):
        TwinProfile.load(tmp_path / "v3.json")


def test_twin_and_dataset_trace_with_the_profiles_room():
    prof = _profile({"diffuse_gain_dB": 4.2})
    # The twin passes the room to its tracer unless its tracer_options say otherwise.
    assert DigitalTwin(_scene(), config=CFG, profile=prof).tracer.diffuse_gain_dB == 4.2
    assert DigitalTwin(_scene(), config=CFG, profile=prof,
                       tracer_options={"diffuse_gain_dB": 1.0}).tracer.diffuse_gain_dB == 1.0
    assert DigitalTwin(_scene(), config=CFG, profile=_profile()).tracer.diffuse_gain_dB == 0.0
    ds = SimulatedRadarDataset(_scene(), length=1, config=CFG, profile=prof,
                               twin_options={"tracer_options": {"cache": False}})
    assert ds.twin_options["tracer_options"] == {"diffuse_gain_dB": 4.2, "cache": False}
    assert ds.twin.tracer.diffuse_gain_dB == 4.2


def test_simulate_job_identity_includes_the_room(tmp_path):
    """A resume never mixes frames of two profiles that differ only in their room section."""
    from radaraug.sim.offline import simulate_capture

    out = tmp_path / "s.h5"
    simulate_capture(_scene(), out, frames=1, seed=0, progress=False, profile=_profile({"diffuse_gain_dB": 4.2}))
    with pytest.raises(CaptureError, match="not made by this job"):
        simulate_capture(_scene(), out, frames=1, seed=0, progress=False, profile=_profile({"diffuse_gain_dB": 2.0}))


def _scene():
    from radaraug.scene.scene import Scene

    return Scene.from_dict({
        "name": "tiny-corridor",
        "radar": {"config": CFG.to_dict(), "position": [0.1, 0.0, 1.2], "look_at": [3.0, 0.0, 1.2]},
        "room": {"type": "corridor", "length": 3.0, "width": 2.0, "height": 2.5, "max_edge": 1.0},
        "people": [],
    })
