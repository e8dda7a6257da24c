"""Static objects (`objects:`) and per-material diffuse parameters in scene files."""

from __future__ import annotations

import pytest
import torch

from radaraug.errors import SceneError
from radaraug.scene import Scene
from radaraug.scene.scattering import DiffuseScattering, get_scattering

BASE = {
    "radar": {"position": [0.1, 0.0, 1.2], "look_at": [10.0, 0.0, 1.2]},
    "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.5, "max_edge": 1.0},
}


def _scene(**extra):
    return Scene.from_dict({**BASE, **extra})


def test_objects_parse_and_merge_into_room():
    plain = _scene()
    sc = _scene(objects=[
        {"type": "box", "size": [0.8, 0.4, 1.2], "position": [3.0, 0.7, 0.0], "yaw_deg": 90, "material": "metal"},
        {"type": "cylinder", "radius": 0.1, "height": 2.0, "position": [2.0, -0.8, 0.0], "material": "wood"},
    ])
    assert sc.room.num_faces > plain.room.num_faces
    assert "metal" in sc.room.materials and "wood" in sc.room.materials
    assert int(sc.room.object_id.abs().sum()) == 0  # objects belong to the static room
    extra = sc.room.vertices[plain.room.vertices.shape[0]:]
    # The box stands on the floor; yaw 90 swaps its x / y extents.
    box = extra[extra[:, 0] > 2.5]
    assert abs(float(box[:, 2].min())) < 1e-6 and abs(float(box[:, 2].max()) - 1.2) < 1e-6
    assert abs(float(box[:, 0].max() - box[:, 0].min()) - 0.4) < 1e-6
    cyl = extra[extra[:, 0] < 2.5]
    r = (cyl[:, :2] - torch.tensor([2.0, -0.8], dtype=cyl.dtype)).norm(dim=-1)
    assert float(r.max()) <= 0.1 + 1e-6


def test_objects_round_trip(tmp_path):
    import trimesh

    mesh_file = tmp_path / "chair.stl"
    trimesh.creation.box(extents=(0.5, 0.5, 0.9)).export(mesh_file)
    data = {**BASE, "objects": [
        {"type": "box", "name": "cabinet", "size": [0.8, 0.4, 1.2], "position": [3.0, 0.7, 0.0], "material": "metal"},
        {"type": "mesh", "file": "chair.stl", "position": [4.0, 0.0, 0.45], "yaw_deg": 30.0, "material": "wood"},
    ], "materials": {"plasterboard": {"diffuse": {"S": 0.3, "pattern": "directive", "alpha_R": 3}}}}
    src = tmp_path / "room.yaml"
    import yaml

    src.write_text(yaml.safe_dump(data))
    sc = Scene.from_file(src)
    out = sc.save(tmp_path / "copy.yaml")
    again = Scene.from_file(out)
    assert again.room.num_faces == sc.room.num_faces
    torch.testing.assert_close(again.room.vertices, sc.room.vertices)
    assert again.to_dict() == sc.to_dict()
    assert again.to_dict(relative_to=tmp_path)["objects"][1]["file"] == "chair.stl"
    assert again.scattering["plasterboard"] == DiffuseScattering(0.3, "directive", 3)
    js = sc.save(tmp_path / "copy.json")
    assert Scene.from_file(js).room.num_faces == sc.room.num_faces


@pytest.mark.parametrize("obj, key", [
    ({"type": "sofa", "position": [1, 0, 0], "material": "wood"}, "objects[0].type"),
    ({"type": "box", "position": [1, 0, 0], "material": "wood"}, "objects[0].size"),
    ({"type": "box", "size": [1, 0, 1], "position": [1, 0, 0], "material": "wood"}, "objects[0].size[1]"),
    ({"type": "box", "size": [1, 1, 1], "position": [1, 0], "material": "wood"}, "objects[0].position"),
    ({"type": "box", "size": [1, 1, 1], "position": [1, 0, 0], "material": "unobtainium"}, "objects[0].material"),
    ({"type": "box", "size": [1, 1, 1], "position": [1, 0, 0], "material": "wood", "colour": "red"}, "objects[0]"),
    ({"type": "cylinder", "radius": -1, "height": 1, "position": [1, 0, 0], "material": "wood"},
     "objects[0].radius"),
    ({"type": "cylinder", "radius": 1, "height": 1, "position": [1, 0, 0], "material": "wood", "sections": 2},
     "objects[0].sections"),
    ({"type": "mesh", "file": "missing.obj", "position": [1, 0, 0], "material": "wood"}, "objects[0].file"),
])
def test_bad_objects_name_file_and_key(tmp_path, obj, key):
    import yaml

    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump({**BASE, "objects": [obj]}))
    with pytest.raises(SceneError) as err:
        Scene.from_file(path)
    assert str(path) in str(err.value) and f"key '{key}'" in str(err.value)


def test_objects_must_be_a_list():
    with pytest.raises(SceneError, match="key 'objects'"):
        _scene(objects={"type": "box"})


@pytest.mark.parametrize("spec, key", [
    ({"plasterboard": {"diffuse": {"S": 1.5}}}, "materials.plasterboard.diffuse"),
    ({"plasterboard": {"diffuse": {"S": 0.5, "lobe": 2}}}, "materials.plasterboard.diffuse"),
    ({"plasterboard": {"diffuse": {"pattern": "gaussian"}}}, "materials.plasterboard.diffuse"),
    ({"nosuch": {"diffuse": {"S": 0.5}}}, "materials.nosuch"),
])
def test_bad_diffuse_specs(spec, key):
    with pytest.raises(SceneError, match=f"key '{key}'"):
        _scene(materials=spec)


def test_diffuse_overrides_and_defaults():
    sc = _scene(materials={"concrete": {"diffuse": 0.2}, "foam2": {"a": 1.1, "diffuse": {"S": 0.05}}})
    assert get_scattering("concrete", sc.scattering).S == 0.2
    assert get_scattering("concrete@0.1", sc.scattering).S == 0.2
    assert get_scattering("foam2", sc.scattering).S == 0.05
    assert get_scattering("plasterboard", sc.scattering) == get_scattering("plasterboard")
    assert sc.to_dict()["materials"]["foam2"]["diffuse"] == {"S": 0.05}


def test_builtin_furnished_corridor():
    sc = Scene.builtin("corridor_furnished")
    plain = Scene.builtin("corridor")
    assert sc.room.num_faces > plain.room.num_faces
    assert len(sc.objects_spec) >= 5 and {"metal", "wood"} <= set(sc.room.materials)
    assert Scene.from_dict(sc.to_dict()).room.num_faces == sc.room.num_faces
