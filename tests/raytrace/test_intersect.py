"""Ray-triangle intersection (brute force) against closed-form geometry."""

from __future__ import annotations

import pytest
import torch

from radaraug.errors import InputTensorError
from radaraug.raytrace.intersect import any_hit, compile_enabled, intersect


def _unit_triangle(dtype, device, z=2.0):
    return torch.tensor([[[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]]], dtype=dtype, device=device)


def test_hit_distance_and_barycentrics_closed_form(device, dtype):
    """Rays along +z from (x, y, 0) hit the plane z = 2 at t = 2 / d_z; u = x, v = y on the unit triangle."""
    tri = _unit_triangle(dtype, device)
    o = torch.tensor([[0.2, 0.3, 0.0], [0.6, 0.6, 0.0], [-0.1, 0.5, 0.0], [0.1, 0.1, 0.0]], dtype=dtype, device=device)
    d = torch.tensor([[0, 0, 1.0], [0, 0, 1.0], [0, 0, 1.0], [0, 0, 2.0]], dtype=dtype, device=device)
    hit = intersect(o, d, tri, compiled=False)
    assert hit.face.tolist() == [0, -1, -1, 0]
    torch.testing.assert_close(hit.t[[0, 3]], torch.tensor([2.0, 1.0], dtype=dtype, device=device))
    assert torch.isinf(hit.t[1]) and torch.isinf(hit.t[2])
    torch.testing.assert_close(hit.u[0], torch.tensor(0.2, dtype=dtype, device=device))
    torch.testing.assert_close(hit.v[0], torch.tensor(0.3, dtype=dtype, device=device))


def test_nearest_of_stacked_triangles_and_bounds(device):
    """Three parallel triangles at z = 1, 2, 3: nearest wins; t_min / t_max select the others."""
    tris = torch.cat([_unit_triangle(torch.float64, device, z) for z in (3.0, 1.0, 2.0)])
    o = torch.tensor([[0.1, 0.1, 0.0]] * 3, dtype=torch.float64, device=device)
    d = torch.tensor([[0, 0, 1.0]] * 3, dtype=torch.float64, device=device)
    hit = intersect(o, d, tris, t_min=torch.tensor([0.0, 1.5, 2.5], dtype=torch.float64, device=device),
                    compiled=False)
    assert hit.face.tolist() == [1, 2, 0]
    assert any_hit(o, d, tris, t_max=torch.tensor([0.5, 1.5, 3.5], dtype=torch.float64, device=device),
                   compiled=False).tolist() == [False, True, True]


def test_chunking_does_not_change_result():
    g = torch.Generator().manual_seed(1)
    tri = torch.rand(50, 3, 3, generator=g, dtype=torch.float64) * 4 - 2
    o = torch.randn(300, 3, generator=g, dtype=torch.float64) * 3
    d = torch.randn(300, 3, generator=g, dtype=torch.float64)
    a = intersect(o, d, tri, compiled=False)
    b = intersect(o, d, tri, compiled=False, chunk_tests=50 * 7)
    assert torch.equal(a.face, b.face) and torch.equal(a.t, b.t)
    assert (a.face >= 0).sum() > 10


def test_hit_points_lie_on_sphere(dtype):
    """A tessellated unit sphere: every hit point is within the chord sag of radius 1."""
    trimesh = pytest.importorskip("trimesh")
    m = trimesh.creation.icosphere(3, 1.0)
    tri = torch.tensor(m.vertices[m.faces], dtype=dtype)
    g = torch.Generator().manual_seed(0)
    o = torch.randn(500, 3, generator=g, dtype=dtype) * 3
    target = torch.randn(500, 3, generator=g, dtype=dtype)
    target = 0.8 * target / target.norm(dim=1, keepdim=True)  # points inside the inscribed sphere
    d = target - o
    hit = intersect(o, d, tri, compiled=False)
    assert hit.valid.all()  # every ray aims inside the sphere
    p = o + hit.t[:, None] * d
    r = p.norm(dim=1)
    assert (r <= 1 + 1e-5).all() and (r > 0.99).all()
    tri_hit = tri[hit.face]
    p_bary = (1 - hit.u - hit.v)[:, None] * tri_hit[:, 0] + hit.u[:, None] * tri_hit[:, 1] + hit.v[:, None] * tri_hit[:, 2]
    torch.testing.assert_close(p_bary, p, atol=1e-5, rtol=0)


def test_bad_shapes_raise():
    with pytest.raises(InputTensorError, match="rays"):
        intersect(torch.zeros(3, 2), torch.zeros(3, 2), torch.zeros(1, 3, 3))
    with pytest.raises(InputTensorError, match="triangles"):
        intersect(torch.zeros(3, 3), torch.ones(3, 3), torch.zeros(4, 3))


def test_compile_flag(monkeypatch):
    monkeypatch.setenv("RADARAUG_COMPILE", "0")
    assert not compile_enabled()
    assert compile_enabled(True)
    monkeypatch.setenv("RADARAUG_COMPILE", "1")
    assert compile_enabled() and not compile_enabled(False)
