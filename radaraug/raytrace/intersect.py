"""Batched ray-triangle intersection (brute force), eager or ``torch.compile``-d.

Every ray is tested against every triangle, chunked over rays, with per-triangle plane and dual vectors
(:func:`triangle_planes`); Möller–Trumbore gives the winners' barycentrics. ``RADARAUG_COMPILE=0`` keeps the
eager kernel, and a compiler failure falls back to it. Directions need not be unit vectors: ``t`` is in
units of ``|direction|``. See ``docs/raytracer.md``, "Intersection and acceleration".
"""

from __future__ import annotations

import os
import warnings
from typing import NamedTuple

import torch

from radaraug.errors import InputTensorError

DEFAULT_CHUNK_TESTS = 1 << 22
"""Ray-triangle tests held in memory at once by the eager kernel (~16 M floats per temporary)."""

_COMPILE_MIN_TESTS = 1 << 24
"""Below this many tests per call, compile warm-up can never pay off: stay eager."""


class Hit(NamedTuple):
    """Nearest hit per ray.

    Attributes:
        t: ``(R,)`` distance along the ray (units of ``|direction|``), ``inf`` on a miss.
        face: ``(R,)`` long index of the hit triangle, ``-1`` on a miss.
        u: ``(R,)`` barycentric weight of vertex 1 (0 on a miss).
        v: ``(R,)`` barycentric weight of vertex 2 (0 on a miss); the point is ``(1-u-v) p0 + u p1 + v p2``.
    """

    t: torch.Tensor
    face: torch.Tensor
    u: torch.Tensor
    v: torch.Tensor

    @property
    def valid(self) -> torch.Tensor:
        """``(R,)`` bool, True where the ray hit something."""
        return self.face >= 0


def compile_enabled(compiled: bool | None = None) -> bool:
    """Whether to use the compiled kernel: the explicit flag, else ``RADARAUG_COMPILE`` (``0``/``off``...: no)."""
    if compiled is not None:
        return bool(compiled)
    return os.environ.get("RADARAUG_COMPILE", "1").strip().lower() not in ("0", "false", "no", "off")


def mt_distance(
    o: torch.Tensor, d: torch.Tensor, v0: torch.Tensor, e1: torch.Tensor, e2: torch.Tensor,
    t_min: torch.Tensor | float, t_max: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Möller–Trumbore on broadcast shapes; returns ``(t, u, v)`` with ``t = inf`` where missed.

    Rays ``o, d`` and triangles ``v0, e1, e2`` (vertex 0 and two edges) are ``(..., 3)``, broadcast; no
    ``(..., 3)`` temporary of the broadcast shape is made. Degenerate triangles (padding) never hit.
    """
    ox, oy, oz = o.unbind(-1)
    dx, dy, dz = d.unbind(-1)
    ax, ay, az = v0.unbind(-1)
    e1x, e1y, e1z = e1.unbind(-1)
    e2x, e2y, e2z = e2.unbind(-1)
    px = dy * e2z - dz * e2y
    py = dz * e2x - dx * e2z
    pz = dx * e2y - dy * e2x
    det = e1x * px + e1y * py + e1z * pz
    inv = 1.0 / det
    sx, sy, sz = ox - ax, oy - ay, oz - az
    u = (sx * px + sy * py + sz * pz) * inv
    qx = sy * e1z - sz * e1y
    qy = sz * e1x - sx * e1z
    qz = sx * e1y - sy * e1x
    v = (dx * qx + dy * qy + dz * qz) * inv
    t = (e2x * qx + e2y * qy + e2z * qz) * inv
    ok = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > t_min) & (t < t_max)
    return torch.where(ok, t, torch.full_like(t, float("inf"))), u, v


def triangle_planes(triangles: torch.Tensor) -> torch.Tensor:
    """Per-triangle precomputation ``(F, 12)`` for :func:`_nearest_kernel` (Baldwin-Weber style).

    Columns: normal ``n = e1 x e2`` and ``n . v0``; dual vectors ``U = (e2 x n)/|n|^2``, ``V = (n x e1)/|n|^2`` and
    their offsets, so a point ``P`` of the plane has ``u = U . P + u0``, ``v = V . P + v0``. Degenerate
    triangles get NaN rows and never hit.
    """
    v0 = triangles[:, 0]
    e1 = triangles[:, 1] - v0
    e2 = triangles[:, 2] - v0
    n = torch.linalg.cross(e1, e2, dim=-1)
    nn = (n * n).sum(-1, keepdim=True)
    big_u = torch.linalg.cross(e2, n, dim=-1) / nn
    big_v = torch.linalg.cross(n, e1, dim=-1) / nn
    return torch.cat([
        n, (n * v0).sum(-1, keepdim=True), big_u, -(big_u * v0).sum(-1, keepdim=True),
        big_v, -(big_v * v0).sum(-1, keepdim=True),
    ], dim=-1).contiguous()


def plane_distance(
    o: torch.Tensor, d: torch.Tensor, planes: torch.Tensor, t_min: torch.Tensor | float,
    t_max: torch.Tensor | float, *, coef_dim: int = -1,
) -> torch.Tensor:
    """Hit distance (``inf`` on a miss) of rays ``o, d`` ``(..., 3)`` on :func:`triangle_planes` rows ``(..., 12)``.

    All broadcast; ``coef_dim=0`` takes the 12 coefficients first, ``(12, ...)`` (contiguous blocks, same result).
    """
    ox, oy, oz = o.unbind(-1)
    dx, dy, dz = d.unbind(-1)
    nx, ny, nz, nd, ux, uy, uz, u0, vx, vy, vz, v0 = planes.unbind(coef_dim)
    t = (nd - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz)
    px, py, pz = ox + t * dx, oy + t * dy, oz + t * dz
    u = ux * px + uy * py + uz * pz + u0
    v = vx * px + vy * py + vz * pz + v0
    ok = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > t_min) & (t < t_max)
    return torch.where(ok, t, torch.full_like(t, float("inf")))


def _nearest_kernel(
    o: torch.Tensor, d: torch.Tensor, planes: torch.Tensor, t_min: torch.Tensor, t_max: torch.Tensor,
) -> tuple[torch.Tensor, torch.Tensor]:
    """``(R,)`` nearest ``t`` and face of rays ``(R, 3)`` against ``planes`` ``(12, F)`` (rows contiguous)."""
    t = plane_distance(o[:, None], d[:, None], planes, t_min[:, None], t_max[:, None], coef_dim=0)
    return t.min(dim=1)


_compiled_kernel = None
_compile_failed = False


def _kernel(use_compile: bool):
    """The nearest-hit kernel, compiled once per process when asked and possible."""
    global _compiled_kernel
    if use_compile and not _compile_failed:
        if _compiled_kernel is None:
            _compiled_kernel = torch.compile(_nearest_kernel, dynamic=True)
        return _compiled_kernel
    return _nearest_kernel


def compile_failed() -> bool:
    """Whether ``torch.compile`` of the kernel failed in this process (it then runs eagerly)."""
    return _compile_failed


def _check_rays(origins: torch.Tensor, directions: torch.Tensor) -> None:
    if origins.ndim != 2 or origins.shape[-1] != 3 or directions.shape != origins.shape:
        raise InputTensorError(
            f"rays must be (R, 3) origins and directions of equal shape, got {tuple(origins.shape)} "
            f"and {tuple(directions.shape)}"
        )


def _check_triangles(triangles: torch.Tensor) -> None:
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
        raise InputTensorError(f"triangles must be (F, 3, 3), got {tuple(triangles.shape)}")


def _as_bounds(x: torch.Tensor | float | None, n: int, like: torch.Tensor, default: float) -> torch.Tensor:
    if x is None:
        x = default
    return torch.as_tensor(x, dtype=like.dtype, device=like.device).expand(n).contiguous()


def barycentrics(
    origins: torch.Tensor, directions: torch.Tensor, triangles: torch.Tensor, face: torch.Tensor,
) -> tuple[torch.Tensor, torch.Tensor]:
    """``(u, v)`` of each ray on its face (``face = -1``: zeros). Cheap: one test per ray."""
    f = face.clamp(min=0)
    tri = triangles[f]
    v0 = tri[:, 0]
    _, u, v = mt_distance(origins, directions, v0, tri[:, 1] - v0, tri[:, 2] - v0, -float("inf"), float("inf"))
    miss = face < 0
    return u.masked_fill(miss, 0.0), v.masked_fill(miss, 0.0)


def intersect(
    origins: torch.Tensor,
    directions: torch.Tensor,
    triangles: torch.Tensor,
    *,
    t_min: torch.Tensor | float | None = None,
    t_max: torch.Tensor | float | None = None,
    compiled: bool | None = None,
    chunk_tests: int = DEFAULT_CHUNK_TESTS,
) -> Hit:
    """Nearest hit of every ray against every triangle (brute force).

    Args:
        origins: ``(R, 3)`` ray origins.
        directions: ``(R, 3)`` ray directions (``t`` is in units of their length).
        triangles: ``(F, 3, 3)`` vertex coordinates, same device and dtype as the rays.
        t_min: scalar or ``(R,)`` lower bound of accepted ``t`` (exclusive), default 0.
        t_max: scalar or ``(R,)`` upper bound (exclusive), default ``inf``.
        compiled: use the compiled kernel (None: ``RADARAUG_COMPILE``, only for calls large enough).
        chunk_tests: ray-triangle tests per chunk (memory bound of the eager kernel).

    Returns:
        :class:`Hit` with ``t``, ``face``, ``u``, ``v``.
    """
    _check_rays(origins, directions)
    _check_triangles(triangles)
    n_rays, n_faces = origins.shape[0], triangles.shape[0]
    lo = _as_bounds(t_min, n_rays, origins, 0.0)
    hi = _as_bounds(t_max, n_rays, origins, float("inf"))
    t_out = torch.full((n_rays,), float("inf"), dtype=origins.dtype, device=origins.device)
    face = torch.full((n_rays,), -1, dtype=torch.long, device=origins.device)
    if n_rays == 0 or n_faces == 0:
        return Hit(t_out, face, torch.zeros_like(t_out), torch.zeros_like(t_out))
    planes = triangle_planes(triangles).T.contiguous()
    use_compile = compile_enabled(compiled) and (compiled or n_rays * n_faces >= _COMPILE_MIN_TESTS)
    step = max(1, chunk_tests // n_faces) if not use_compile else max(1, (1 << 26) // n_faces)
    for s in range(0, n_rays, step):
        sl = slice(s, min(n_rays, s + step))
        t, f = _run_kernel(use_compile, origins[sl], directions[sl], planes, lo[sl], hi[sl])
        t_out[sl] = t
        face[sl] = torch.where(torch.isfinite(t), f, torch.full_like(f, -1))
    u, v = barycentrics(origins, directions, triangles, face)
    return Hit(t_out, face, u, v)


def _run_kernel(use_compile: bool, *args: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Run the kernel; a compiler failure switches this process to eager (with one warning)."""
    global _compile_failed
    if use_compile and not _compile_failed:
        try:
            return _kernel(True)(*args)
        except Exception as e:  # noqa: BLE001 - any backend failure (no compiler, inductor bug) -> eager
            _compile_failed = True
            warnings.warn(f"torch.compile of the ray-triangle kernel failed ({type(e).__name__}: {e}); "
                          "using the eager kernel", RuntimeWarning, stacklevel=3)
    return _nearest_kernel(*args)


def any_hit(
    origins: torch.Tensor,
    directions: torch.Tensor,
    triangles: torch.Tensor,
    t_max: torch.Tensor | float,
    *,
    t_min: torch.Tensor | float | None = None,
    compiled: bool | None = None,
    chunk_tests: int = DEFAULT_CHUNK_TESTS,
) -> torch.Tensor:
    """``(R,)`` bool: a triangle lies on the ray strictly between ``t_min`` and ``t_max`` (shadow rays).

    Same arguments as :func:`intersect`.
    """
    hit = intersect(origins, directions, triangles, t_min=t_min, t_max=t_max, compiled=compiled,
                    chunk_tests=chunk_tests)
    return hit.face >= 0
