"""simplify_mesh: pymeshlab repair + quadric decimation."""

from __future__ import annotations

import numpy as np
import pytest
import torch
import trimesh

from radaraug.errors import SceneError
from radaraug.scene.people import simplify_mesh


@pytest.mark.parametrize("target", [1000, 300])
def test_icosphere_decimation(target: int) -> None:
    s = trimesh.creation.icosphere(subdivisions=4)  # 5120 faces
    v, f = simplify_mesh(torch.as_tensor(s.vertices), torch.as_tensor(s.faces), target)
    assert isinstance(v, torch.Tensor) and v.dtype == torch.float64 and f.dtype == torch.long
    assert 0 < f.shape[0] <= target
    m = trimesh.Trimesh(v.numpy(), f.numpy(), process=False)
    assert m.is_watertight and m.is_winding_consistent
    assert m.volume == pytest.approx(s.volume, rel=0.03)  # sphere volume kept
    assert m.volume == pytest.approx(4 / 3 * np.pi, rel=0.05)


def test_repair_and_numpy_io() -> None:
    s = trimesh.creation.box()
    # Duplicate every vertex (an unwelded mesh) and add an unreferenced vertex.
    v = np.concatenate([s.vertices[s.faces].reshape(-1, 3), [[9.0, 9.0, 9.0]]])
    f = np.arange(len(s.faces) * 3).reshape(-1, 3)
    v2, f2 = simplify_mesh(v, f, 100)
    assert isinstance(v2, np.ndarray)
    assert len(v2) == 8 and len(f2) == 12


def test_bad_input() -> None:
    with pytest.raises(SceneError):
        simplify_mesh(np.zeros((3, 2)), np.zeros((1, 3), dtype=int), 10)
    with pytest.raises(SceneError, match="out of range"):
        simplify_mesh(np.zeros((3, 3)), np.array([[0, 1, 5]]), 10)
    with pytest.raises(SceneError):
        simplify_mesh(np.eye(3), np.array([[0, 1, 2]]), 2)
