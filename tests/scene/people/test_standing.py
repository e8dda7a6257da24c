"""StandingPerson: rest pose, breathing and sway against their closed forms."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.errors import SceneError
from radaraug.scene.people import StandingPerson, person_from_dict
from radaraug.scene.people.skeleton import (
    ANKLE_HEIGHT_FRACTION,
    JOINT_INDEX,
    SEGMENT_LENGTH_FRACTIONS,
    SEGMENT_NAMES,
)


def _person(**kw: float) -> StandingPerson:
    base = dict(height_m=1.8, position=(3.0, -0.5), facing_rad=math.pi, breathing_m=0.008, breathing_Hz=0.3,
                sway_rad=0.01, sway_Hz=0.25, sway_phase=0.1)
    base.update(kw)
    return StandingPerson(**base)  # type: ignore[arg-type]


def test_rest_pose_stands_on_the_floor_at_its_height() -> None:
    p = _person(breathing_m=0.0, sway_rad=0.0)
    pos, vel = p.joints(torch.tensor([0.0, 1.3]))
    assert torch.all(vel == 0)
    assert pos[0, JOINT_INDEX["left_toe"], 2].item() == pytest.approx(0.0)
    f = SEGMENT_LENGTH_FRACTIONS
    top = (ANKLE_HEIGHT_FRACTION + f["lower_leg"] + f["upper_leg"] + f["torso"] + f["head"]) * 1.8
    assert pos[0, JOINT_INDEX["head_top"], 2].item() == pytest.approx(top)
    assert pos[0, JOINT_INDEX["pelvis"], :2].tolist() == pytest.approx([3.0, -0.5])
    # Facing -x: the toes point toward -x from the ankles.
    assert (pos[0, JOINT_INDEX["left_toe"], 0] - pos[0, JOINT_INDEX["left_ankle"], 0]).item() < 0


def test_velocities_are_the_derivative_of_positions() -> None:
    p = _person(sway_direction_rad=0.7)
    t = torch.linspace(0.0, 4.0, 41, dtype=torch.float64)
    h = 1e-5
    pp, _ = p.joints(t + h)
    pm, _ = p.joints(t - h)
    _, vel = p.joints(t)
    assert torch.allclose((pp - pm) / (2 * h), vel, atol=1e-8)


def test_torso_centre_moves_by_the_chest_displacement() -> None:
    p = _person(sway_rad=0.0, breathing_phase=0.0)
    period = 1 / 0.3
    t = torch.tensor([0.25 * period, 0.75 * period], dtype=torch.float64)  # breathing peak and trough
    e = p.ellipsoids(t)
    torso = SEGMENT_NAMES.index("torso")
    # Facing -x: breathing moves the chest toward -x; peak to trough is twice breathing_m.
    swing = (e.centers[0, torso, 0] - e.centers[1, torso, 0]).item()
    assert swing == pytest.approx(-2 * 0.008, rel=1e-9)


def test_sway_pivots_about_the_ankles() -> None:
    p = _person(breathing_m=0.0, sway_phase=0.0)
    t = torch.tensor([0.0, 1.0], dtype=torch.float64)  # sway peak at a quarter period (1 s at 0.25 Hz)
    pos, _ = p.joints(t)
    moved = pos[1] - pos[0]
    assert moved[JOINT_INDEX["left_ankle"]].abs().max().item() == pytest.approx(0.0, abs=1e-12)
    lever = pos[0, JOINT_INDEX["pelvis"], 2].item() - ANKLE_HEIGHT_FRACTION * 1.8
    assert moved[JOINT_INDEX["pelvis"]].norm().item() == pytest.approx(0.01 * lever, rel=1e-9)


def test_a_standing_person_sits_inside_one_doppler_bin_of_the_paper_config() -> None:
    # The physics the docs state: at 60 GHz a standing person's fastest joint is slower than one
    # Doppler bin, so a one-frame RD map shows them at zero Doppler only. Quiet standing: a 1 cm
    # breath at 20/min, 1 cm of sway at 0.3 Hz.
    cfg = RadarConfig.bgt60tr13c()
    p = StandingPerson(breathing_m=0.01, breathing_Hz=1 / 3, sway_rad=0.01, sway_Hz=0.3)
    _, vel = p.joints(torch.linspace(0, 5, 500, dtype=torch.float64))
    vmax = vel.norm(dim=-1).max().item()
    assert vmax <= p.peak_speed_m_s + 1e-12
    bin_m_s = cfg.wavelength_m / (2 * cfg.num_chirps_per_frame * cfg.chirp_repetition_time_s)
    assert vmax < bin_m_s


def test_round_trip_and_bad_input() -> None:
    p = _person(sway_direction_rad=1.0)
    d = p.to_dict()
    assert d["type"] == "standing"
    assert person_from_dict(d).to_dict() == d
    q = person_from_dict(d)
    t = torch.tensor([0.7], dtype=torch.float64)
    assert torch.equal(q.joints(t)[0], p.joints(t)[0])
    with pytest.raises(SceneError, match="breathing_m"):
        StandingPerson(breathing_m=0.5)
    with pytest.raises(SceneError, match="sway_phase"):
        StandingPerson(sway_phase=1.0)
    with pytest.raises(SceneError, match="unknown parameters"):
        person_from_dict({**d, "speed_m_s": 1.0})


def test_mesh_has_the_velocities_of_its_joints() -> None:
    p = _person()
    m = p.mesh(0.4, faces_per_segment=80, dtype=torch.float64)
    assert m.vertex_velocity is not None
    assert m.vertex_velocity.norm(dim=-1).max().item() < 0.2
    assert m.vertices[:, 2].min().item() > -0.05


def test_scene_file_with_a_standing_person(tmp_path) -> None:
    import yaml

    from radaraug.scene import Scene

    scene = {
        "name": "t",
        "radar": {"position": [0.1, 0.0, 1.2], "look_at": [5.0, 0.0, 1.2]},
        "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.5, "max_edge": 1.0},
        "people": [{"type": "standing", "height": 1.6, "position": [3.0, 0.2], "breathing_m": 0.005}],
    }
    path = tmp_path / "s.yaml"
    path.write_text(yaml.safe_dump(scene))
    s = Scene.from_file(path)
    assert isinstance(s.people[0], StandingPerson) and s.people[0].position == (3.0, 0.2)
    assert s.to_dict()["people"][0]["type"] == "standing"
    path.write_text(yaml.safe_dump({**scene, "people": [{"type": "standing", "speed": 1.0}]}))
    with pytest.raises(SceneError, match="speed"):
        Scene.from_file(path)
