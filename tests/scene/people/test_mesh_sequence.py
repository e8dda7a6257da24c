"""Animated mesh sequences: loading, interpolation, exact vertex velocities, decimation."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import torch
import trimesh

from radaraug.errors import SceneError
from radaraug.scene.people import MeshSequencePerson, person_from_dict


def frames(n: int = 8, step: float = 0.05, subdivisions: int = 3) -> list[trimesh.Trimesh]:
    """A body-sized ellipsoid moving along +Z of a Y-up file by ``step`` per frame."""
    out = []
    for k in range(n):
        m = trimesh.creation.icosphere(subdivisions=subdivisions)
        m.vertices = m.vertices * [0.2, 0.8, 0.15] + [0.3, 0.85, step * k]
        out.append(m)
    return out


def test_rigid_translation_gives_exact_velocities() -> None:
    fps, step = 25.0, 0.04  # 1 m/s along the file's +Z = forward
    p = MeshSequencePerson(frames(step=step), fps=fps, start=(1.0, 2.0), heading_rad=math.pi / 2)
    g = p.mesh(0.1, dtype=torch.float64)
    expect = torch.tensor([0.0, 1.0, 0.0], dtype=torch.float64)  # heading +y
    assert torch.allclose(g.vertex_velocity, expect.expand_as(g.vertex_velocity), atol=1e-9)
    pos0, _ = p.vertices(torch.zeros(1, dtype=torch.float64))
    assert torch.allclose(pos0[0, :, :2].mean(0), torch.tensor([1.0, 2.0], dtype=torch.float64), atol=1e-9)
    assert pos0[0, :, 2].min().item() == pytest.approx(0.85 - 0.8, abs=1e-9)  # file floor kept (Y up -> z)
    e = p.ellipsoids(torch.tensor([0.1], dtype=torch.float64))
    assert e.centers.shape == (1, 16, 3)
    assert torch.allclose(e.velocities[0], expect.expand(16, 3), atol=1e-9)


def test_root_motion_speed() -> None:
    still = [frames(1)[0]] * 4
    p = MeshSequencePerson(still, fps=30, speed_m_s=1.2, heading_rad=0.0)
    pos, vel = p.vertices(torch.tensor([0.0, 0.5], dtype=torch.float64))
    assert torch.allclose(pos[1] - pos[0], torch.tensor([0.6, 0.0, 0.0], dtype=torch.float64).expand_as(pos[0]))
    assert torch.allclose(vel, torch.tensor([1.2, 0.0, 0.0], dtype=torch.float64).expand_as(vel))


def test_files_keep_vertex_order(tmp_path: Path) -> None:
    fr = frames(3, subdivisions=2)
    files = []
    for k, m in enumerate(fr):
        f = tmp_path / f"frame_{k:03d}.obj"
        m.export(f)
        files.append(f)
    p = MeshSequencePerson(files, fps=10, up_axis="z")
    pos, _ = p.vertices(torch.tensor([0.1], dtype=torch.float64))
    shift = torch.tensor([*(-fr[0].vertices.mean(0)[:2]), 0.0], dtype=torch.float64)
    assert torch.allclose(pos[0], torch.as_tensor(fr[1].vertices) + shift, atol=1e-5)
    p2 = person_from_dict(p.to_dict())
    assert torch.allclose(p2.vertices(torch.tensor([0.1], dtype=torch.float64))[0], pos)


def test_decimation_keeps_motion() -> None:
    p = MeshSequencePerson(frames(step=0.04), fps=25.0, max_faces=200)
    assert p.faces.shape[0] <= 200
    g = p.mesh(0.07, dtype=torch.float64)
    assert torch.allclose(g.vertex_velocity, torch.tensor([1.0, 0.0, 0.0], dtype=torch.float64).expand_as(g.vertex_velocity), atol=1e-9)


def test_bad_sequences_raise(tmp_path: Path) -> None:
    fr = frames(2)
    fr.append(trimesh.creation.icosphere(subdivisions=1))
    with pytest.raises(SceneError, match="frame 2 has 42 vertices"):
        MeshSequencePerson(fr, fps=10)
    with pytest.raises(SceneError, match="not found"):
        MeshSequencePerson([tmp_path / "missing.obj"], fps=10)
    with pytest.raises(SceneError, match="fps"):
        MeshSequencePerson(frames(2), fps=0)
