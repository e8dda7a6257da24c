"""The two-level BVH returns exactly what brute force returns."""

from __future__ import annotations

import pytest
import torch

from radaraug.errors import InputTensorError
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.intersect import intersect


def _scene(dtype, device, n_tri=400, n_rays=600, seed=0):
    g = torch.Generator().manual_seed(seed)
    centres = torch.rand(n_tri, 1, 3, generator=g, dtype=dtype) * 6 - 3
    tri = centres + 0.3 * torch.randn(n_tri, 3, 3, generator=g, dtype=dtype)
    o = torch.randn(n_rays, 3, generator=g, dtype=dtype) * 4
    d = torch.randn(n_rays, 3, generator=g, dtype=dtype)
    d = d / d.norm(dim=1, keepdim=True)
    return tri.to(device), o.to(device), d.to(device)


@pytest.mark.parametrize("leaf_size", [None, 3, 50])
def test_bvh_matches_brute_force(device, dtype, leaf_size):
    tri, o, d = _scene(dtype, device)
    ref = intersect(o, d, tri, compiled=False)
    bvh = TriangleBVH(tri, leaf_size=leaf_size)
    hit = bvh.intersect(o, d)
    assert (ref.face >= 0).sum() > 50
    assert torch.equal(hit.face, ref.face)
    torch.testing.assert_close(hit.t, ref.t)
    t_max = torch.where(torch.isfinite(ref.t), ref.t * 0.999, torch.full_like(ref.t, 100.0))
    shadow = bvh.any_hit(o, d, t_max)
    assert torch.equal(shadow, intersect(o, d, tri, t_max=t_max, compiled=False).valid)
    # any_hit's own loop (no nearest-hit bookkeeping) answers as the nearest hit does, t_min too
    assert torch.equal(bvh.any_hit(o, d, t_max, t_min=0.5), bvh.intersect(o, d, t_min=0.5, t_max=t_max).face >= 0)


def test_axis_aligned_rays_and_flat_boxes(device):
    """Rays with zero direction components against an axis-aligned wall (flat leaf boxes)."""
    y, z = torch.meshgrid(torch.linspace(-1, 1, 21), torch.linspace(-1, 1, 21), indexing="ij")
    pts = torch.stack([torch.full_like(y, 5.0), y, z], -1).reshape(-1, 3).double()
    tri = torch.stack([pts[:-22], pts[1:-21], pts[22:]], 1)[:200].to(device)
    o = torch.zeros(5, 3, dtype=torch.float64, device=device)
    o[:, 1] = torch.linspace(-0.9, 0.9, 5)
    o[:, 2] = 0.05
    d = torch.tensor([[1.0, 0.0, 0.0]], dtype=torch.float64, device=device).expand(5, 3)
    hit = TriangleBVH(tri, leaf_size=8).intersect(o, d)
    ref = intersect(o, d, tri, compiled=False)
    assert torch.equal(hit.face, ref.face)
    assert hit.valid.any()
    torch.testing.assert_close(hit.t[hit.valid], torch.full_like(hit.t[hit.valid], 5.0))


def test_bad_triangles():
    with pytest.raises(InputTensorError):
        TriangleBVH(torch.zeros(4, 3))


@pytest.mark.parametrize("budget", [1 << 8, 1 << 12])
def test_pair_budget_changes_only_the_chunks(budget, monkeypatch):
    """Any number of tests at once gives the same hits (the budget is a speed setting: docs/simulation.md)."""
    import radaraug.raytrace.accel as accel

    tri, o, d = _scene(torch.float32, "cpu")
    bvh = TriangleBVH(tri, leaf_size=8)
    ref = bvh.intersect(o, d)
    t_max = torch.full_like(ref.t, 2.0)
    ref_shadow = bvh.any_hit(o, d, t_max)
    monkeypatch.setattr(accel, "_PAIR_BUDGET", budget)
    hit = bvh.intersect(o, d)
    assert torch.equal(hit.face, ref.face) and torch.equal(hit.t, ref.t)
    assert torch.equal(bvh.any_hit(o, d, t_max), ref_shadow)
