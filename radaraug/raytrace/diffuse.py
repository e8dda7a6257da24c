"""Diffuse static clutter of a room: independent random scatterers on every surface.

A stochastic model (effective roughness, :mod:`radaraug.scene.scattering`), not a discretization that must
converge: every face is tiled into cells of area ``<= cell_m^2``, each one scatterer at a random point with
RCS ``sigma0(theta) A_cell``, a unit-power complex Gaussian factor and the radar equation, kept when it sees
the radar. Seeded, so the clutter is a pure function of the scene. See ``docs/diffuse_clutter.md``.
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import SceneError
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import Antenna
from radaraug.raytrace.merge import coherent_sum, weighted_mean
from radaraug.raytrace.po import facet_normals
from radaraug.raytrace.radar import RadarGeometry, radar_amplitude
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.sbr import surface_offset
from radaraug.scene.geometry import SceneGeometry
from radaraug.scene.scattering import ScatteringOverrides, get_scattering
from radaraug.sensor.paths import Paths

DEFAULT_CELL_M = 0.1
"""Default cell size (m): cells have area at most ``cell_m^2`` (see the module docstring)."""

MAX_CELLS = 5_000_000
"""Guard against a tiny ``cell_m`` on a big room eating all memory."""


def surface_cells(
    room: SceneGeometry, cell_m: float, generator: torch.Generator,
) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Tile every face into cells and draw one point per cell (CPU, float64).

    Args:
        room: the geometry.
        cell_m: cell size; cells have area ``<= cell_m^2``.
        generator: CPU generator; two uniforms are drawn per cell, in face order.

    Returns:
        ``(points (C, 3), face (C,) long, area (C,))``: scatterer positions, their face and cell area (m^2).
    """
    if not (math.isfinite(cell_m) and cell_m > 0):
        raise SceneError(f"diffuse_paths: cell_m must be a positive number, got {cell_m!r}")
    tri = room.triangles.detach().to("cpu", torch.float64)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    area = 0.5 * torch.linalg.cross(e1, e2, dim=-1).norm(dim=-1)
    n = torch.ceil(area.sqrt() / cell_m - 1e-9).clamp_min(1).long()
    n = torch.where(area > 0, n, torch.zeros_like(n))  # degenerate faces scatter nothing
    total = int((n * n).sum())
    if total > MAX_CELLS:
        raise SceneError(f"diffuse_paths: cell_m={cell_m} gives {total} cells (more than {MAX_CELLS})")
    face = torch.repeat_interleave(torch.arange(len(n)), n * n)
    level = n[face]
    # Local index k of the cell inside its face: 0 .. n^2 - 1.
    start = torch.cumsum(n * n, 0) - n * n
    k = torch.arange(total) - start[face]
    corners = torch.empty(total, 3, 2, dtype=torch.float64)  # barycentric (u, v) grid corners
    for lv in torch.unique(level).tolist():
        sel = (level == lv).nonzero()[:, 0]
        corners[sel] = _sub_triangles(lv)[k[sel]]
    u = torch.rand(total, 2, generator=generator, dtype=torch.float64)
    # Uniform point in the sub-triangle (a, b, c): sqrt trick on two uniforms.
    r1 = u[:, 0].sqrt()
    w = torch.stack([1 - r1, r1 * (1 - u[:, 1]), r1 * u[:, 1]], dim=1)  # (C, 3)
    uv = (w[:, :, None] * corners).sum(1)  # (C, 2) barycentric (along e1, along e2)
    points = tri[face, 0] + uv[:, :1] * e1[face] + uv[:, 1:] * e2[face]
    cell_area = area[face] / (level * level).to(torch.float64)
    return points, face, cell_area


_UP_CORNERS = torch.tensor([[0, 0], [1, 0], [0, 1]])
"""Grid offsets of the corners of the upward sub-triangle at grid point ``(i, j)``."""

_DOWN_CORNERS = torch.tensor([[1, 0], [1, 1], [0, 1]])
"""Grid offsets of the corners of the downward sub-triangle at grid point ``(i, j)``."""


def _sub_triangles(n: int) -> torch.Tensor:
    """``(n^2, 3, 2)`` barycentric corners of the ``n^2`` congruent sub-triangles of a triangle."""
    ij = torch.stack(torch.meshgrid(torch.arange(n), torch.arange(n), indexing="ij"), -1).reshape(-1, 2)
    up = ij[ij.sum(-1) <= n - 1]
    down = ij[ij.sum(-1) <= n - 2]
    corners = torch.cat([up[:, None] + _UP_CORNERS, down[:, None] + _DOWN_CORNERS])
    return corners.to(torch.float64) / n


def diffuse_paths(
    room: SceneGeometry,
    radar: RadarGeometry,
    antenna: Antenna,
    bvh: TriangleBVH | None,
    *,
    frequency_Hz: float,
    seed: int,
    scattering: ScatteringOverrides | None = None,
    gain_dB: float = 0.0,
    cell_m: float = DEFAULT_CELL_M,
    occlusion: bool = True,
    merge_bin_m: float | None = 0.05,
    merge_voxel_m: float = 1.0,
) -> tuple[Paths, torch.Tensor]:
    """Diffuse scattering paths of a static room (``docs/diffuse_clutter.md``).

    Args:
        room: static geometry (walls, floor, ceiling, objects); materials by key.
        radar: TX/RX positions, polarization and wavelength (its device and dtype are used).
        antenna: object with ``gain(directions_radar_frame) -> power gain`` (TX and RX).
        bvh: acceleration structure of ``room``'s triangles for the shadow rays; None skips them.
        frequency_Hz: carrier (Fresnel coefficients).
        seed: seed of the cells' points and complex Gaussian factors.
        scattering: per-material overrides (key or base name -> :class:`DiffuseScattering`,
            ``{S, pattern, alpha_R}`` or a number ``S``) over :data:`~radaraug.scene.scattering.DIFFUSE_DEFAULTS`.
        gain_dB: one power gain on every diffuse path (the calibration's knob).
        cell_m: cell size (m), cells have area ``<= cell_m^2``.
        occlusion: cast shadow rays (needs ``bvh``).
        merge_bin_m: path-length bin of the coherent merge; None returns one path per visible cell.
        merge_voxel_m: voxel edge of the merge (cells merge only within one voxel).

    Returns:
        ``(paths, vertices)``: static :class:`Paths` ``(P, RX)`` (``kind`` 0, ``delay_rate`` 0) and
        ``vertices`` ``(P, 3, 3)`` = ``[radar.centre, scatter point, radar.centre]``.
    """
    device, dtype = radar.tx.device, radar.tx.dtype
    gen = torch.Generator().manual_seed(int(seed))
    points, face, area = surface_cells(room, cell_m, gen)
    # Complex Gaussian factor of unit mean power, drawn for every cell (visible or not) so that a
    # cell's draw does not depend on what else is in the scene.
    z = torch.randn(points.shape[0], 2, generator=gen, dtype=torch.float64)
    z = torch.complex(z[:, 0], z[:, 1]) / math.sqrt(2)

    mats = room.face_material.detach().to("cpu")[face]
    params = [get_scattering(m, scattering) for m in room.materials]
    s_mat = torch.tensor([p.S for p in params], dtype=torch.float64)
    live = (s_mat[mats] > 0).nonzero()[:, 0]
    points, face, area, z, mats = (x[live].to(device) for x in (points, face, area, z, mats))

    p = points.to(dtype)
    tri = room.triangles.detach().to(device=device, dtype=dtype)
    n = facet_normals(tri)[face]
    to_c = radar.centre - p
    r_c = to_c.norm(dim=-1).clamp_min(1e-9)
    k_s = to_c / r_c[:, None]
    cos_s = (k_s * n).sum(-1)
    n_f = torch.where((cos_s < 0)[:, None], -n, n)  # normal on the radar's side
    cos_t = cos_s.abs()
    ok = cos_t > 1e-6
    if occlusion and bool(ok.any()):
        occ = occluder_faces(tri, radar.centre)
        # Only faces that can block a leg between the radar and the room's surface need
        # tracing against: a BVH of those alone (a corridor has none; a furnished room its
        # objects), or the caller's full BVH when the reduction was not attempted.
        shadow = bvh if occ is None else None
        if occ is not None and bool(occ.any()):
            shadow = TriangleBVH(tri[occ]) if int(occ.sum()) < tri.shape[0] or bvh is None else bvh
        if shadow is not None:
            idx = ok.nonzero()[:, 0]
            eps = surface_offset(p[idx])
            start = p[idx] + eps[:, None] * n_f[idx]
            blocked = shadow.any_hit(start, k_s[idx], t_max=r_c[idx] - eps, t_min=eps)
            ok[idx[blocked]] = False
    keep = ok.nonzero()[:, 0]
    p, k_s, n, cos_t, r_c, mats, area, z = (x[keep] for x in (p, k_s, n, cos_t, r_c, mats, area, z))

    refl = FaceReflectivity(room.materials, frequency_Hz, device, dtype)
    gamma = refl(mats, cos_t, -k_s, n, radar.polarization)
    gamma2 = gamma.abs() ** 2
    sigma0 = torch.zeros_like(cos_t)
    for m, prm in enumerate(params):
        sel = mats == m
        if prm.S > 0 and bool(sel.any()):
            sigma0[sel] = prm.sigma0(gamma2[sel], cos_t[sel])
    rcs = sigma0 * area.to(dtype) * 10 ** (gain_dB / 10)
    cdt = torch.complex128 if dtype == torch.float64 else torch.complex64
    root = rcs.sqrt().to(cdt) * z.to(cdt)

    r_t = (p - radar.tx).norm(dim=-1)
    r_r = (p[:, None, :] - radar.rx[None]).norm(dim=-1)  # (P, RX)
    gain_t = antenna.gain(radar.to_radar_dirs(p - radar.tx))
    gain_r = antenna.gain(radar.to_radar_dirs(-k_s))
    amp = radar_amplitude(root[:, None], r_t[:, None], r_r, gain_t[:, None], gain_r[:, None], radar.wavelength)
    delay = (r_t[:, None] + r_r) / SPEED_OF_LIGHT
    paths = Paths(delay, torch.zeros_like(delay), amp, torch.zeros(delay.shape[0], dtype=torch.int8, device=device))
    if merge_bin_m:
        paths, p = merge_cells(paths, p, frequency_Hz, bin_m=merge_bin_m, voxel_m=merge_voxel_m)
    centre = radar.centre.expand(p.shape[0], 3)
    return paths, torch.stack([centre, p, centre], dim=1)


def occluder_faces(tri: torch.Tensor, centre: torch.Tensor, *, budget: int = 400_000_000) -> torch.Tensor | None:
    """``(F,)`` bool: faces that may block a segment from ``centre`` to a point of the room.

    A face whose plane supports the whole vertex set, ``centre`` included, cannot. None when ``F x V`` exceeds
    ``budget`` (then every face counts).
    """
    f = tri.shape[0]
    if f == 0:
        return torch.zeros(0, dtype=torch.bool, device=tri.device)
    verts = torch.unique(tri.reshape(-1, 3), dim=0)
    if f * verts.shape[0] > budget:
        return None
    nrm = facet_normals(tri)
    off = (nrm * tri[:, 0]).sum(-1)
    scale = float(verts.abs().max()) + 1.0
    tol = 1e-5 * scale if tri.dtype == torch.float32 else 1e-9 * scale
    side_c = (nrm * centre).sum(-1) - off  # (F,)
    supporting = torch.zeros(f, dtype=torch.bool, device=tri.device)
    step = max(1, 4_000_000 // verts.shape[0])  # (V, step) distances held at once
    for s in range(0, f, step):
        sl = slice(s, s + step)
        d = verts @ nrm[sl].T - off[sl]  # (V, f_chunk)
        sign = torch.sign(side_c[sl])
        supporting[sl] = ((d * sign) >= -tol).all(0) & (side_c[sl].abs() > tol)
    return ~supporting


def merge_cells(
    paths: Paths, points: torch.Tensor, frequency_Hz: float, *, bin_m: float = 0.01, voxel_m: float = 0.5,
) -> tuple[Paths, torch.Tensor]:
    """Coherent merge of cells sharing a path-length bin and a voxel (``docs/diffuse_clutter.md``, "Merge").

    Returns:
        ``(paths, points)``: merged paths ``(G, RX)`` and their power-weighted centroids ``(G, 3)``.
    """
    if paths.num_paths == 0:
        return paths, points
    if not (bin_m > 0 and voxel_m > 0):
        raise SceneError(f"merge_cells: bin_m and voxel_m must be positive, got {bin_m!r}, {voxel_m!r}")
    length_bin = torch.round(paths.delay_s.mean(-1) * SPEED_OF_LIGHT / bin_m).long()
    vox = torch.floor(points / voxel_m).long()
    _, inv = torch.unique(torch.cat([length_bin[:, None], vox], dim=1), dim=0, return_inverse=True)
    tau_bar, merged, kinds, weight = coherent_sum(paths, inv, frequency_Hz)
    centroid = weighted_mean(points, inv, weight, tau_bar.shape[0])
    return Paths(tau_bar, torch.zeros_like(tau_bar), merged, kinds), centroid


__all__ = ["DEFAULT_CELL_M", "diffuse_paths", "merge_cells", "occluder_faces", "surface_cells"]
