"""Stand-ins for radaraug.scene.people and scene-file helpers shared by the scene tests.

The stand-ins have the documented constructor signatures, so the scene-file loader's key mapping
is tested without depending on the real gait models (``stub_people`` in ``conftest.py`` puts them
in the registry the loader uses).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import torch
import yaml

from radaraug.scene.geometry import Ellipsoids, SceneGeometry


class _StubPerson:
    n_seg = 2

    def __init__(self, **kwargs: Any) -> None:
        self.kwargs = kwargs

    def ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        t = torch.as_tensor(t, dtype=torch.float64)
        x0, y0 = self.kwargs.get("start", (0.0, 0.0))
        c = torch.zeros(*t.shape, self.n_seg, 3, dtype=torch.float64)
        c[..., 0] = x0
        c[..., 1] = y0
        rot = torch.eye(3, dtype=torch.float64).expand(*t.shape, self.n_seg, 3, 3)
        return Ellipsoids(c, torch.ones_like(c), rot, torch.zeros_like(c))

    def mesh(self, t: float) -> SceneGeometry:
        x0, y0 = self.kwargs.get("start", (0.0, 0.0))
        v = torch.tensor([[x0, y0, 0.0], [x0, y0 + 0.1, 0.0], [x0, y0, 1.0]])
        return SceneGeometry(v, torch.tensor([[0, 1, 2]]), torch.tensor([0]), ("skin",),
                             torch.zeros(3, 3), torch.tensor([0]))

    def to_dict(self) -> dict[str, Any]:
        return dict(self.kwargs)


class Walker(_StubPerson):
    type_name = "walker"
    def __init__(self, height_m: float = 1.8, speed_m_s: float = 1.4, start: tuple = (0.0, 0.0),
                 heading_rad: float = 0.0, phase: float = 0.0) -> None:
        super().__init__(height_m=height_m, speed_m_s=speed_m_s, start=start, heading_rad=heading_rad,
                         phase=phase)


class BVHPerson(_StubPerson):
    type_name = "bvh"
    n_seg = 3

    def __init__(self, path: Any, *, start: tuple = (0.0, 0.0), heading_rad: float = 0.0,
                 scale: float | None = None, loop: bool = True) -> None:
        super().__init__(path=path, start=start, heading_rad=heading_rad, scale=scale, loop=loop)


class MeshSequencePerson(_StubPerson):
    type_name = "mesh_sequence"

    def __init__(self, files_or_meshes: Any, *, fps: float, start: tuple = (0.0, 0.0),
                 heading_rad: float = 0.0, scale: float = 1.0, max_faces: int | None = None) -> None:
        super().__init__(files_or_meshes=files_or_meshes, fps=fps, start=start, heading_rad=heading_rad,
                         scale=scale, max_faces=max_faces)


STUB_TYPES = (Walker, BVHPerson, MeshSequencePerson)


def base_scene(**extra: Any) -> dict[str, Any]:
    d = {
        "name": "t",
        "radar": {"position": [0.1, 0.0, 1.2], "look_at": [5.0, 0.0, 1.2]},
        "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.5, "max_edge": 1.0},
    }
    d.update(extra)
    return d


def write_scene(path: Path, data: dict[str, Any]) -> Path:
    path.write_text(json.dumps(data) if path.suffix == ".json" else yaml.safe_dump(data))
    return path
