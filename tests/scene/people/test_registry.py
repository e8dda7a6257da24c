"""One registry of person types: scene files and person_from_dict both read it."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

from radaraug.errors import SceneError
from radaraug.scene import Scene
from radaraug.scene.people import BVHPerson, MeshSequencePerson, StandingPerson, Walker, person_from_dict
from radaraug.scene.people.person import PERSON_TYPES, person_type, register_person


def test_builtin_types_registered_under_their_scene_names() -> None:
    assert PERSON_TYPES == {"walker": Walker, "bvh": BVHPerson, "mesh_sequence": MeshSequencePerson,
                            "standing": StandingPerson}
    assert person_type("walker") is Walker
    with pytest.raises(SceneError, match="expected one of"):
        person_type("robot")


def test_to_dict_type_is_the_registered_name() -> None:
    w = Walker(height_m=1.7, speed_m_s=1.1, heading_rad=0.5)
    d = w.to_dict()
    assert d["type"] == Walker.type_name == "walker"
    assert person_from_dict(d).to_dict() == d


def test_register_refuses_a_taken_or_empty_name() -> None:
    with pytest.raises(ValueError, match="taken"):
        register_person(type("Other", (Walker,), {"type_name": "walker"}))
    with pytest.raises(ValueError, match="empty"):
        register_person(type("Nameless", (Walker,), {"type_name": ""}))


def test_a_registered_type_is_readable_from_a_scene_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    class Strider(Walker):
        type_name = "strider"

    monkeypatch.setitem(PERSON_TYPES, "strider", Strider)
    scene = {
        "name": "t",
        "radar": {"position": [0.1, 0.0, 1.2], "look_at": [5.0, 0.0, 1.2]},
        "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.5, "max_edge": 1.0},
        "people": [{"type": "strider", "height": 1.6, "speed": 0.9, "heading_deg": 90}],
    }
    path = tmp_path / "s.yaml"
    path.write_text(yaml.safe_dump(scene))
    s = Scene.from_file(path)
    assert type(s.people[0]) is Strider and s.people[0].heading_rad == pytest.approx(math.pi / 2)
    assert s.to_dict()["people"][0]["type"] == "strider"
    with pytest.raises(SceneError, match="strider"):  # the error lists the registered types
        path.write_text(yaml.safe_dump({**scene, "people": [{"type": "nope"}]}))
        Scene.from_file(path)


def test_builtin_scene_people_unchanged_by_the_registry() -> None:
    # Recorded before the registry replaced the scene reader's own table: same file, same people,
    # same ellipsoids to the last bit (so the same simulated frames).
    import torch

    s = Scene.builtin("corridor_two_walkers")
    assert s.to_dict()["people"] == [
        {"type": "walker", "height": 1.8, "speed": 1.4, "start": [12.0, 0.45], "heading_deg": 180.0, "phase": 0.0},
        {"type": "walker", "height": 1.65, "speed": 0.9, "start": [3.0, -0.45], "heading_deg": 0.0, "phase": 0.3},
    ]
    e = s.people_ellipsoids(torch.tensor([0.0, 0.37, 1.5], dtype=torch.float64))
    fresh = [Walker(height_m=1.8, speed_m_s=1.4, start=(12.0, 0.45), heading_rad=math.pi),
             Walker(height_m=1.65, speed_m_s=0.9, start=(3.0, -0.45), heading_rad=0.0, phase=0.3)]
    ref = torch.cat([p.ellipsoids(torch.tensor([0.0, 0.37, 1.5], dtype=torch.float64)).centers for p in fresh], dim=1)
    assert torch.equal(e.centers, ref)
