"""Scene files (radaraug.scene.scene_file): YAML/JSON, radar poses, people keys, round trips, errors."""

from __future__ import annotations

import math
import re
import types
from pathlib import Path
from typing import Any

import pytest
import torch
from scene_stubs import Walker, base_scene, write_scene

from radaraug.config import RadarConfig
from radaraug.errors import SceneError
from radaraug.scene.geometry import RadarPose
from radaraug.scene.materials import MATERIALS
from radaraug.scene.room import corridor
from radaraug.scene.scene import Scene
from radaraug.scene.scene_file import builtin_scene


# -------------------------------------------------------------------------------- built-in scenes
def test_builtin_corridor_is_the_paper_setup() -> None:
    s = Scene.from_file(builtin_scene("corridor"))
    assert s.config == RadarConfig.bgt60tr13c()
    assert s.people == []
    v = s.room.vertices.double()
    assert v.max(0).values.tolist() == pytest.approx([20.0, 1.0, 2.7])
    # Radar at one end, boresight down the corridor (+x), sensor y up.
    torch.testing.assert_close(s.radar.rotation[:, 2], torch.tensor([1.0, 0, 0], dtype=torch.float64))
    torch.testing.assert_close(s.radar.rotation[:, 1], torch.tensor([0, 0, 1.0], dtype=torch.float64))
    assert s.radar.position.tolist() == pytest.approx([0.1, 0.0, 1.2])
    with pytest.raises(SceneError, match="corridor"):
        builtin_scene("nope")


def test_builtin_walker_scenes(stub_people: types.SimpleNamespace) -> None:
    one = Scene.builtin("corridor_one_walker")
    assert len(one.people) == 1 and isinstance(one.people[0], Walker)
    kw = one.people[0].kwargs
    assert kw["heading_rad"] == pytest.approx(math.pi) and kw["height_m"] == 1.75 and kw["speed_m_s"] == 1.2
    two = Scene.builtin("corridor_two_walkers")
    speeds = sorted(p.kwargs["speed_m_s"] for p in two.people)
    assert len(two.people) == 2 and speeds[0] != speeds[1]
    # One walks toward the radar (-x), one away (+x).
    dirs = sorted(math.cos(p.kwargs["heading_rad"]) for p in two.people)
    assert dirs == pytest.approx([-1.0, 1.0])


# ----------------------------------------------------------------------------------- round trips
@pytest.mark.parametrize("suffix", [".yaml", ".json"])
def test_round_trip(tmp_path: Path, suffix: str, stub_people: types.SimpleNamespace) -> None:
    (tmp_path / "motion").mkdir()
    bvh = tmp_path / "motion" / "walk.bvh"
    bvh.write_text("HIERARCHY\n")
    data = base_scene(people=[
        {"type": "walker", "height": 1.7, "speed": 1.0, "start": [3.0, 0.2], "heading_deg": 180, "phase": 0.1},
        {"type": "bvh", "file": "motion/walk.bvh", "start": [2.0, -0.3], "heading_deg": 0, "loop": False},
    ])
    data["room"]["materials"] = {"floor": "wood"}
    data["room"]["thickness"] = {"ceiling": 0.1}
    src = write_scene(tmp_path / f"scene{suffix}", data)
    s = Scene.from_file(src)
    assert s.source == src and s.name == "t"
    assert s.people[1].kwargs["path"] == bvh
    out = tmp_path / "elsewhere" / f"copy{suffix}"
    out.parent.mkdir()
    s.save(out)
    s2 = Scene.from_file(out)
    assert s2.to_dict() == s.to_dict()
    assert s2.people[1].kwargs["path"].resolve() == bvh.resolve()
    for a in ("vertices", "faces", "face_material"):
        assert torch.equal(getattr(s2.room, a), getattr(s.room, a))
    assert s2.room.materials == s.room.materials and "ceiling_board@0.1" in s.room.materials
    assert torch.equal(s2.radar.rotation, s.radar.rotation)
    assert torch.equal(s2.radar.position, s.radar.position)
    # Saved paths are relative to the new file's folder.
    saved = out.read_text()
    assert "../motion/walk.bvh" in saved


def test_python_built_scene_saves_inline(tmp_path: Path) -> None:
    room = corridor(3.0, 1.0, 1.0, max_edge_m=1.5)
    cfg = RadarConfig.bgt60tr13c(num_chirps_per_frame=32)
    s = Scene(room=room, radar=RadarPose.look_at((0.1, 0, 0.5), (3, 0, 0.5)), config=cfg, name="py")
    s2 = Scene.from_file(s.save(tmp_path / "py.yaml"))
    assert s2.config == cfg
    assert torch.equal(s2.room.faces, room.faces) and s2.room.materials == room.materials
    torch.testing.assert_close(s2.room.vertices, room.vertices)


def test_mesh_room_relative_path(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "r.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\ng floor\nf 1 2 3\n")
    data = base_scene(room={"type": "mesh", "file": "meshes/r.obj", "materials": {"floor": "wood"}, "scale": 2.0})
    s = Scene.from_file(write_scene(tmp_path / "s.yaml", data))
    assert s.room.materials == ("wood",)
    assert s.room.vertices.max().item() == pytest.approx(2.0)
    (tmp_path / "sub").mkdir()
    s2 = Scene.from_file(s.save(tmp_path / "sub" / "s2.yaml"))
    assert "../meshes/r.obj" in (tmp_path / "sub" / "s2.yaml").read_text()
    assert torch.equal(s2.room.vertices, s.room.vertices)


# ------------------------------------------------------------------------------------ radar pose
def _pose(tmp_path: Path, radar: dict[str, Any]) -> RadarPose:
    return Scene.from_file(write_scene(tmp_path / "p.yaml", base_scene(radar=radar))).radar


def test_pose_forms_agree(tmp_path: Path) -> None:
    p = [0.1, 0.0, 1.2]
    ref = RadarPose.look_at(tuple(p), (5.0, 0.0, 1.2))
    ypr = _pose(tmp_path, {"position": p, "yaw_pitch_roll_deg": [0, 0, 0]})
    rot = _pose(tmp_path, {"position": p, "rotation": ref.rotation.tolist()})
    default = _pose(tmp_path, {"position": p})
    for pose in (ypr, rot, default):
        torch.testing.assert_close(pose.rotation, ref.rotation)
    # Yaw 90 looks along +y; pitch 90 looks up; roll 90 turns the sensor's right side down.
    torch.testing.assert_close(_pose(tmp_path, {"position": p, "yaw_pitch_roll_deg": [90, 0, 0]}).rotation[:, 2],
                               torch.tensor([0, 1.0, 0], dtype=torch.float64), atol=1e-12, rtol=0)
    torch.testing.assert_close(_pose(tmp_path, {"position": p, "yaw_pitch_roll_deg": [0, 90, 0]}).rotation[:, 2],
                               torch.tensor([0, 0, 1.0], dtype=torch.float64), atol=1e-12, rtol=0)
    torch.testing.assert_close(_pose(tmp_path, {"position": p, "yaw_pitch_roll_deg": [0, 0, 90]}).rotation[:, 0],
                               torch.tensor([0, 0, -1.0], dtype=torch.float64), atol=1e-12, rtol=0)
    # Yaw/pitch match look_at at an arbitrary direction.
    y, pt = math.radians(30), math.radians(-10)
    d = (math.cos(pt) * math.cos(y), math.cos(pt) * math.sin(y), math.sin(pt))
    look = RadarPose.look_at((0, 0, 0), d)
    torch.testing.assert_close(_pose(tmp_path, {"position": [0, 0, 0], "yaw_pitch_roll_deg": [30, -10, 0]}).rotation,
                               look.rotation)


def test_portrait_mounting(tmp_path: Path) -> None:
    pose = _pose(tmp_path, {"position": [0, 0, 1], "look_at": [1, 0, 1], "mounting": "portrait"})
    torch.testing.assert_close(pose.rotation[:, 2], torch.tensor([1.0, 0, 0], dtype=torch.float64))
    torch.testing.assert_close(pose.rotation[:, 0], torch.tensor([0, 0, 1.0], dtype=torch.float64))


def test_config_forms(tmp_path: Path) -> None:
    cfg = RadarConfig.bgt60tr13c(num_chirps_per_frame=128)
    cfg.to_json(tmp_path / "radar.json")
    for form in ({"preset": "bgt60tr13c", "num_chirps_per_frame": 128}, cfg.to_dict(), "radar.json"):
        radar = {"position": [0, 0, 1], "config": form}
        assert Scene.from_file(write_scene(tmp_path / "c.yaml", base_scene(radar=radar))).config == cfg


# ---------------------------------------------------------------------------------------- people
def test_people_key_errors(stub_people: types.SimpleNamespace, tmp_path: Path) -> None:
    bad = base_scene(people=[{"type": "walker"}, {"type": "walker", "speed": 1.0, "wings": 2}])
    with pytest.raises(SceneError, match=r"bad\.yaml.*people\[1\]\.wings"):
        Scene.from_file(write_scene(tmp_path / "bad.yaml", bad))
    with pytest.raises(SceneError, match=r"people\[0\]\.type"):
        Scene.from_file(write_scene(tmp_path / "bad.yaml", base_scene(people=[{"type": "robot"}])))
    with pytest.raises(SceneError, match="matches no file"):
        Scene.from_file(write_scene(tmp_path / "bad.yaml",
                               base_scene(people=[{"type": "mesh_sequence", "files": "none/*.obj", "fps": 30}])))


# ---------------------------------------------------------------------------------------- errors
_INLINE_TRIANGLE = {"type": "inline", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]],
                    "materials": ["concrete"], "face_material": [0]}


def test_inline_triangle_is_valid(tmp_path: Path) -> None:
    """The base of the inline-room error cases loads (so each case fails for its own reason)."""
    s = Scene.from_file(write_scene(tmp_path / "ok.yaml", base_scene(room=_INLINE_TRIANGLE)))
    assert s.room.faces.tolist() == [[0, 1, 2]]


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ({"radar": None}, "radar"),
        ({"radar": {"look_at": [1, 0, 0]}}, "radar.position"),
        ({"radar": {"position": [0, 0]}}, "radar.position"),
        ({"radar": {"position": [0, 0, 1], "mounting": "sideways"}}, "radar.mounting"),
        ({"radar": {"position": [0, 0, 1], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}}, "radar.rotation"),
        ({"radar": {"position": [0, 0, 1], "config": {"start_frequency_Hz": 1}}}, "radar.config"),
        ({"radar": {"position": [0, 0, 1], "look_at": [1, 0, 1], "yaw_pitch_roll_deg": [0, 0, 0]}}, "radar"),
        ({"room": {"type": "castle"}}, "room.type"),
        ({"room": {"type": "corridor", "length": -3}}, "room.length"),
        ({"room": {"type": "corridor", "materials": {"floor": "lava"}}}, "room"),
        ({"room": {"type": "corridor", "colour": "red"}}, "room"),
        ({"room": {"type": "mesh", "file": "nowhere.obj"}}, "room"),
        ({"extra": 1}, "(top level)"),
        ({"materials": {"x@1": {"a": 1.0}}}, "materials.x@1"),
        ({"room": _INLINE_TRIANGLE | {"vertices": [[0, 0, float("nan")], [1, 0, 0], [0, 1, 0]]}}, "room.vertices"),
        ({"room": _INLINE_TRIANGLE | {"faces": [[0, 1.5, 2]]}}, "room.faces"),
        ({"room": _INLINE_TRIANGLE | {"face_material": [0.7]}}, "room.face_material"),
    ],
)
def test_bad_content_names_file_and_key(tmp_path: Path, change: dict[str, Any], key: str) -> None:
    data = base_scene()
    data.update(change)
    data = {k: v for k, v in data.items() if v is not None}
    with pytest.raises(SceneError, match=rf"bad\.yaml: key '{re.escape(key)}"):
        Scene.from_file(write_scene(tmp_path / "bad.yaml", data))


def test_bad_files(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="nope.yaml"):
        Scene.from_file(tmp_path / "nope.yaml")
    (tmp_path / "s.txt").write_text("")
    with pytest.raises(SceneError, match="suffix"):
        Scene.from_file(tmp_path / "s.txt")
    (tmp_path / "broken.yaml").write_text("radar: [unclosed\n")
    with pytest.raises(SceneError, match="broken.yaml"):
        Scene.from_file(tmp_path / "broken.yaml")
    (tmp_path / "broken.json").write_text("{")
    with pytest.raises(SceneError, match="broken.json"):
        Scene.from_file(tmp_path / "broken.json")


def test_scene_materials_section(tmp_path: Path) -> None:
    data = base_scene(materials={"test_scene_foam": {"a": 1.2, "c": 0.001, "d": 1.0}})
    data["room"]["materials"] = {"ceiling": "test_scene_foam"}
    try:
        s = Scene.from_file(write_scene(tmp_path / "m.yaml", data))
        assert "test_scene_foam" in s.room.materials
        assert MATERIALS["test_scene_foam"].permittivity(60e9).real == pytest.approx(1.2)
        assert s.to_dict()["materials"] == {"test_scene_foam": {"a": 1.2, "c": 0.001, "d": 1.0}}
        data["materials"] = {"test_scene_foam": {"a": 9.0}}
        with pytest.raises(SceneError, match="materials.test_scene_foam"):
            Scene.from_file(write_scene(tmp_path / "m.yaml", data))
    finally:
        MATERIALS.pop("test_scene_foam", None)
