"""Acceleration structure: a flat two-level bounding-volume hierarchy over triangles.

Built once on CPU by median split; traversal tests every ray against every leaf box, then the triangles of
the candidate (ray, leaf) pairs only: a few large tensor ops on CPU and CUDA instead of a per-ray stack.
Why this shape and its cost: ``docs/raytracer.md``, "Intersection and acceleration".
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import torch

from radaraug.errors import InputTensorError
from radaraug.raytrace.intersect import Hit, barycentrics, intersect, plane_distance, triangle_planes

_BRUTE_FORCE_FACES = 64
"""Up to this many triangles, testing all of them beats any culling."""

_PAIR_BUDGET = 1 << 18
"""Ray-triangle tests held at once on the CPU while testing candidate pairs (chunks only: any budget gives the same hits).

2^18 keeps a chunk's gathered planes (12 x pairs x leaf width floats) near the CPU's cache: 1.47x faster than
2^22 on a randomized room's 16-frame call, 1.02x on its single-frame items, 0.98x on the two-walker
corridor's blocks (``benchmarks/bvh_pair_budget_cpu.json``, ``scripts/pair_budget_bench.py``)."""

_PAIR_BUDGET_GPU = 1 << 22
"""The same on a GPU, where fewer, larger launches win (unchanged from the figures of ``benchmarks/twin_cuda.json``)."""


class TriangleBVH:
    """Two-level BVH over a static triangle soup.

    Args:
        triangles: ``(F, 3, 3)`` vertices; the device and dtype of the traversal.
        leaf_size: most triangles per leaf (default ``max(8, round(sqrt(F) / 2))``).

    Attributes:
        triangles: ``(F, 3, 3)`` the input triangles.
        boxes_lo, boxes_hi: ``(L, 3)`` leaf bounds.
        leaf_faces: ``(L, S)`` long face indices, padded with ``F`` (a degenerate triangle).
    """

    def __init__(self, triangles: torch.Tensor, leaf_size: int | None = None) -> None:
        if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
            raise InputTensorError(f"TriangleBVH: triangles must be (F, 3, 3), got {tuple(triangles.shape)}")
        self.triangles = triangles
        n = triangles.shape[0]
        self.num_faces = n
        # sqrt(F) / 2: measured on the randomized rooms' ~5,500 faces (people's wall-bounce shadow rays),
        # 10-20 % faster per simulated item than sqrt(F) in paired runs (the hits are the same for any size).
        size = leaf_size or max(8, int(round(math.sqrt(max(n, 1)) / 2)))
        leaves = _median_split(triangles.detach().to("cpu", torch.float64).numpy(), size)
        width = max([len(x) for x in leaves] + [1])
        table = np.full((len(leaves), width), n, dtype=np.int64)
        for i, idx in enumerate(leaves):
            table[i, : len(idx)] = idx
        dev, dt = triangles.device, triangles.dtype
        self.leaf_faces = torch.as_tensor(table, device=dev)
        padded = torch.cat([triangles, torch.zeros(1, 3, 3, dtype=dt, device=dev)])
        with torch.no_grad():
            self._planes = triangle_planes(padded)  # the padding row is NaN: never hit
            self._planes_t = self._planes.t().contiguous()  # (12, F + 1): per-pair gathers stay contiguous
        leaf_tris = padded[self.leaf_faces]  # (L, S, 3, 3); padding rows are zeros: mask them out
        real = (self.leaf_faces < n)[..., None, None]
        big = torch.finfo(dt).max
        lo = torch.where(real, leaf_tris, torch.full_like(leaf_tris, big)).amin(dim=(1, 2))
        hi = torch.where(real, leaf_tris, torch.full_like(leaf_tris, -big)).amax(dim=(1, 2))
        # Pad the boxes a little so that flat (zero-thickness) boxes and rounding never drop a hit.
        pad = 1e-6 * (1 + torch.maximum(lo.abs(), hi.abs()))
        self.boxes_lo, self.boxes_hi = lo - pad, hi + pad

    @property
    def num_leaves(self) -> int:
        """Number of leaves ``L``."""
        return int(self.leaf_faces.shape[0])

    def _candidates(self, o: torch.Tensor, d: torch.Tensor, lo: torch.Tensor, hi: torch.Tensor) -> torch.Tensor:
        """``(P, 2)`` (ray, leaf) pairs whose box the ray segment ``[lo, hi]`` crosses."""
        inv = 1.0 / d  # inf for zero components: the slab test below stays correct
        # One axis at a time on (R, L) planes: contiguous passes instead of reductions over a
        # trailing axis of 3 (the same values: min and max round nothing).
        t_near = t_far = None
        for k in range(3):
            t0 = (self.boxes_lo[:, k][None] - o[:, k, None]) * inv[:, k, None]
            t1 = (self.boxes_hi[:, k][None] - o[:, k, None]) * inv[:, k, None]
            # 0 * inf = nan when a ray lies exactly in a slab plane: treat as inside that slab.
            near = torch.minimum(t0, t1).nan_to_num_(nan=-float("inf"))
            far = torch.maximum(t0, t1).nan_to_num_(nan=float("inf"))
            t_near = near if t_near is None else torch.maximum(t_near, near)
            t_far = far if t_far is None else torch.minimum(t_far, far)
        assert t_near is not None and t_far is not None
        ok = (t_near <= t_far) & (t_far >= lo[:, None]) & (t_near <= hi[:, None])
        return ok.nonzero()

    def _pair_t(self, o, d, lo, hi, pairs) -> tuple[torch.Tensor, torch.Tensor]:
        """Nearest ``t`` and face per candidate pair."""
        ray, leaf = pairs[:, 0], pairs[:, 1]
        f = self.leaf_faces[leaf]  # (P, S)
        planes = self._planes_t.index_select(1, f.reshape(-1)).view(12, *f.shape)
        t = plane_distance(o[ray][:, None], d[ray][:, None], planes, lo[ray][:, None], hi[ray][:, None], coef_dim=0)
        tmin, k = t.min(dim=1)
        return tmin, f.gather(1, k[:, None])[:, 0]

    def _pair_hits(
        self, o: torch.Tensor, d: torch.Tensor, lo: torch.Tensor, hi: torch.Tensor,
    ) -> Iterator[tuple[torch.Tensor, torch.Tensor, torch.Tensor]]:
        """``(ray, t, face)`` per candidate pair, in chunks of at most :data:`_PAIR_BUDGET` tests."""
        n = o.shape[0]
        budget = _PAIR_BUDGET if o.device.type == "cpu" else _PAIR_BUDGET_GPU
        ray_step = max(1, budget // max(self.num_leaves, 1))
        pair_step = max(1, budget // self.leaf_faces.shape[1])
        for s in range(0, n, ray_step):
            sl = slice(s, min(n, s + ray_step))
            pairs = self._candidates(o[sl], d[sl], lo[sl], hi[sl])
            pairs[:, 0] += s
            for p in range(0, pairs.shape[0], pair_step):
                pp = pairs[p: p + pair_step]
                t, f = self._pair_t(o, d, lo, hi, pp)
                yield pp[:, 0], t, f

    def intersect(
        self,
        origins: torch.Tensor,
        directions: torch.Tensor,
        *,
        t_min: torch.Tensor | float | None = None,
        t_max: torch.Tensor | float | None = None,
    ) -> Hit:
        """Nearest hit per ray (same contract as :func:`radaraug.raytrace.intersect.intersect`)."""
        o, d = origins, directions
        if o.ndim != 2 or o.shape[-1] != 3 or d.shape != o.shape:
            raise InputTensorError(f"rays must be (R, 3) origins and directions, got {tuple(o.shape)}, "
                                   f"{tuple(d.shape)}")
        n = o.shape[0]
        lo, hi = _ray_bounds(o, t_min, t_max)
        best = torch.full((n,), float("inf"), dtype=o.dtype, device=o.device)
        face = torch.full((n,), -1, dtype=torch.long, device=o.device)
        if n == 0 or self.num_faces == 0:
            return Hit(best, face, torch.zeros_like(best), torch.zeros_like(best))
        if self.num_faces <= _BRUTE_FORCE_FACES:
            return intersect(o, d, self.triangles, t_min=lo, t_max=hi, compiled=False)
        for ray, t, f in self._pair_hits(o, d, lo, hi):
            best.scatter_reduce_(0, ray, t, reduce="amin")
            # The winning face: among pairs reaching the ray's minimum, the smallest index
            # (deterministic on ties, e.g. a ray through a shared edge).
            win = torch.isfinite(t) & (t == best[ray])
            cand = torch.where(win, f, torch.full_like(f, self.num_faces))
            face_fill = torch.full_like(face, self.num_faces)
            face_fill.scatter_reduce_(0, ray, cand, reduce="amin")
            # A later chunk may lower best: keep the face only where it matches the new min.
            improved = face_fill < self.num_faces
            face = torch.where(improved, face_fill, face)
        face = torch.where(torch.isfinite(best), face, torch.full_like(face, -1))
        u, v = barycentrics(o, d, self.triangles, face)
        return Hit(best, face, u, v)

    def any_hit(
        self,
        origins: torch.Tensor,
        directions: torch.Tensor,
        t_max: torch.Tensor | float,
        *,
        t_min: torch.Tensor | float | None = None,
    ) -> torch.Tensor:
        """``(R,)`` bool: something lies on the ray between ``t_min`` and ``t_max`` (shadow ray).

        ``intersect(...).face >= 0`` without the nearest-hit bookkeeping.
        """
        o, d = origins, directions
        if o.ndim != 2 or o.shape[-1] != 3 or d.shape != o.shape or self.num_faces <= _BRUTE_FORCE_FACES:
            return self.intersect(origins, directions, t_min=t_min, t_max=t_max).face >= 0
        lo, hi = _ray_bounds(o, t_min, t_max)
        blocked = torch.zeros(o.shape[0], dtype=torch.bool, device=o.device)
        for ray, t, _ in self._pair_hits(o, d, lo, hi):
            blocked[ray[torch.isfinite(t)]] = True
        return blocked


def _ray_bounds(
    o: torch.Tensor, t_min: torch.Tensor | float | None, t_max: torch.Tensor | float | None,
) -> tuple[torch.Tensor, torch.Tensor]:
    """``(R,)`` each ray's ``t`` range (defaults 0 and inf) on the rays' device and dtype."""
    n = o.shape[0]
    lo = torch.as_tensor(0.0 if t_min is None else t_min, dtype=o.dtype, device=o.device).expand(n)
    hi = torch.as_tensor(float("inf") if t_max is None else t_max, dtype=o.dtype, device=o.device).expand(n)
    return lo, hi


def _median_split(tri: np.ndarray, leaf_size: int) -> list[np.ndarray]:
    """Leaves (arrays of face indices) of a median-split tree on the centroids (iterative)."""
    cent = tri.mean(axis=1)
    stack = [np.arange(tri.shape[0])]
    leaves = []
    while stack:
        idx = stack.pop()
        if len(idx) <= leaf_size:
            if len(idx):
                leaves.append(idx)
            continue
        c = cent[idx]
        axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
        order = np.argsort(c[:, axis], kind="stable")
        half = len(idx) // 2
        stack.append(idx[order[half:]])
        stack.append(idx[order[:half]])
    return leaves
