"""Walker mesh: tessellated ellipsoids with rigid-motion vertex velocities."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from scipy.special import ellipeinc, ellipkinc

from radaraug.scene.people import Walker
from radaraug.scene.people.person import tessellate


def ellipsoid_area(a: float, b: float, c: float) -> float:
    """Exact surface area (Legendre's incomplete elliptic integrals)."""
    a, b, c = sorted((a, b, c), reverse=True)
    if a - c < 1e-9 * a:
        return 4 * np.pi * a * a
    phi = np.arccos(c / a)
    m = (a * a * (b * b - c * c)) / (b * b * (a * a - c * c)) if b > c else 0.0
    s = np.sin(phi)
    return 2 * np.pi * c * c + 2 * np.pi * a * b / s * (ellipeinc(phi, m) * s * s + ellipkinc(phi, m) * np.cos(phi) ** 2)


def test_mesh_area_normals_and_velocities() -> None:
    w = Walker(height_m=1.8, speed_m_s=1.4, heading_rad=0.4)
    t = 0.61
    g = w.mesh(t, faces_per_segment=1280, dtype=torch.float64)
    e = w.ellipsoids(torch.tensor([t], dtype=torch.float64))
    assert g.faces.shape[0] == 16 * 1280
    assert g.materials == ("skin",) and int(g.face_material.max()) == 0
    tri = g.triangles
    cross = torch.linalg.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0], dim=-1)
    area = 0.5 * cross.norm(dim=-1).sum().item()
    exact = sum(ellipsoid_area(*map(float, ax)) for ax in e.semi_axes[0])
    assert area == pytest.approx(exact, rel=0.01)  # inscribed polyhedron: slightly less
    assert area < exact
    # Outward normals: each face normal points away from its ellipsoid's centre.
    seg = torch.arange(16).repeat_interleave(1280)
    centroid = tri.mean(1)
    assert ((cross * (centroid - e.centers[0, seg])).sum(-1) > 0).all()
    # Rigid motion: the vertex velocities of a segment average to its centre velocity
    # (the icosphere's vertices average to its centre) and differ by omega x r.
    nv = g.vertices.shape[0] // 16
    mean_v = g.vertex_velocity.view(16, nv, 3).mean(1)
    assert torch.allclose(mean_v, e.velocities[0], atol=1e-5)
    r = g.vertices.view(16, nv, 3) - e.centers[0, :, None]
    dv = g.vertex_velocity.view(16, nv, 3) - e.velocities[0, :, None]
    assert (r * dv).sum(-1).abs().max().item() < 1e-5  # rigid: relative velocity is perpendicular to r


def test_tessellate_levels() -> None:
    e = Walker().ellipsoids(torch.zeros(1))
    for budget, faces in ((20, 20), (79, 20), (80, 80), (320, 320), (1000, 320)):
        v, f = tessellate(e, budget)
        assert f.shape[0] == 16 * faces
        assert int(f.max()) == v.shape[-2] - 1
