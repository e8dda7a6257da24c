"""The scene data model (radaraug.scene.scene.Scene): people's segments and meshes, merged geometry.

Reading and writing scene files is tested in ``test_scene_file.py``.
"""

from __future__ import annotations

import types
from pathlib import Path

import pytest
import torch
from scene_stubs import base_scene, write_scene

from radaraug.scene.scene import Scene


def test_builtin_walkers_with_real_people_module() -> None:
    people = pytest.importorskip("radaraug.scene.people")
    if not hasattr(people, "Walker"):
        pytest.skip("radaraug.scene.people.Walker not available yet")
    s = Scene.builtin("corridor_two_walkers")
    e = s.people_ellipsoids(torch.tensor([0.0, 0.5]))
    assert e.centers.shape[:1] == (2,) and e.centers.shape[-1] == 3
    assert e.num_segments == sum(p.ellipsoids(torch.tensor([0.0])).num_segments for p in s.people)


def test_people_ellipsoids_and_meshes(stub_people: types.SimpleNamespace, tmp_path: Path) -> None:
    frames = tmp_path / "frames"
    frames.mkdir()
    for i in range(3):
        (frames / f"f{i:02d}.obj").write_text("")
    data = base_scene(people=[
        {"type": "walker", "start": [3.0, 0.2]},
        {"type": "mesh_sequence", "files": "frames/*.obj", "fps": 30, "start": [2.0, 0.0]},
    ])
    s = Scene.from_file(write_scene(tmp_path / "s.yaml", data))
    assert [p.name for p in s.people[1].kwargs["files_or_meshes"]] == ["f00.obj", "f01.obj", "f02.obj"]
    e = s.people_ellipsoids(torch.linspace(0, 1, 5))
    assert e.centers.shape == (5, 4, 3) and e.rotations.shape == (5, 4, 3, 3)
    assert e.centers[0, 0, 0].item() == 3.0 and e.centers[0, 2, 0].item() == 2.0
    meshes = s.people_meshes(0.3)
    assert len(meshes) == 2
    g = s.geometry(0.3)
    assert g.num_faces == s.room.num_faces + 2
    assert g.object_id[-2:].tolist() == [1, 2] and set(g.object_id[: s.room.num_faces].tolist()) == {0}
    assert "skin" in g.materials
    empty = Scene.from_file(write_scene(tmp_path / "e.yaml", base_scene()))
    assert empty.people_ellipsoids(torch.zeros(4)).centers.shape == (4, 0, 3)
