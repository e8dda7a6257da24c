"""Physical optics of the room's small faces (furniture, frames, radiators), converged by subdivision.

Faces of no mirror plane are scattered by monostatic facet PO toward the radar, split until every edge is
below the Fresnel limit ``sqrt(lambda R / 4) / sqrt(density)`` so the sum is the spherical-wave PO integral
whatever the mesh's triangulation. See ``docs/raytracer.md``, "The static room".
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import Antenna
from radaraug.raytrace.po import facet_normals, facet_root_rcs
from radaraug.raytrace.radar import RadarGeometry, radar_amplitude
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.sbr import surface_offset
from radaraug.sensor.paths import Paths

MAX_FACETS = 2_000_000
"""Refuse to split a room into more facets than this (a mesh of metres-wide non-planar faces)."""


def fresnel_edge_limit(distance_m: torch.Tensor, wavelength: float, density: float) -> torch.Tensor:
    """Largest facet edge ``sqrt(lambda R / 4 / density)`` at ``distance_m`` from the radar (phase error <= pi/8)."""
    return torch.sqrt(wavelength * distance_m / 4) / math.sqrt(density)


def subdivide(
    triangles: torch.Tensor, face: torch.Tensor, radar_centre: torch.Tensor, wavelength: float, density: float,
) -> tuple[torch.Tensor, torch.Tensor]:
    """Split ``triangles`` ``(F, 3, 3)`` (1 -> 4) until every edge meets :func:`fresnel_edge_limit`.

    Returns the split triangles and, for each, the index of its original face.
    """
    tri, src = triangles, face
    while True:
        dist = (tri - radar_centre).norm(dim=-1).amin(-1).clamp_min(wavelength)
        edges = torch.stack([tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 1], tri[:, 0] - tri[:, 2]], 1)
        big = edges.norm(dim=-1).amax(-1) > fresnel_edge_limit(dist, wavelength, density)
        if not bool(big.any()):
            return tri, src
        if tri.shape[0] + 3 * int(big.sum()) > MAX_FACETS:
            from radaraug.errors import SceneError

            raise SceneError(f"splitting the room's small faces to the Fresnel limit needs more than "
                             f"{MAX_FACETS} facets; model large flat faces as coplanar groups of at least "
                             "mirror_min_area_m2 (image method) or lower the tracer's density")
        t = tri[big]
        a, b, c = t.unbind(1)
        ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
        four = torch.stack([
            torch.stack([a, ab, ca], 1), torch.stack([ab, b, bc], 1),
            torch.stack([ca, bc, c], 1), torch.stack([ab, bc, ca], 1),
        ], 1).reshape(-1, 3, 3)
        tri = torch.cat([tri[~big], four])
        src = torch.cat([src[~big], src[big].repeat_interleave(4)])


def monostatic_facet_rcs(
    triangles: torch.Tensor, material: torch.Tensor, radar: RadarGeometry, reflectivity: FaceReflectivity,
    specular_factor: torch.Tensor | None = None,
) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
    """``(centroid, range, unit vector to the radar, root RCS)`` of the radar-facing facets ``(F, 3, 3)``.

    The root RCS uses the face's Fresnel coefficient times the optional per-material ``specular_factor``.
    """
    cen = triangles.mean(-2)
    to_r = radar.centre - cen
    r = to_r.norm(dim=-1)
    u = to_r / r[:, None]
    n = facet_normals(triangles)
    gamma = reflectivity(material, (n * u).sum(-1).abs(), -u, n, radar.polarization)
    if specular_factor is not None:
        gamma = gamma * specular_factor.to(triangles.device)[material]
    return cen, r, u, facet_root_rcs(triangles, -u, u, radar.wavelength, gamma)


def facet_paths(
    triangles: torch.Tensor,
    face: torch.Tensor,
    face_material: torch.Tensor,
    radar: RadarGeometry,
    antenna: Antenna,
    reflectivity: FaceReflectivity,
    bvh: TriangleBVH,
    *,
    density: float = 1.0,
    specular_factor: torch.Tensor | None = None,
) -> tuple[Paths, torch.Tensor]:
    """Monostatic PO paths of the small faces ``face`` (indices into ``triangles``).

    Args:
        triangles: ``(F, 3, 3)`` all room triangles (the radar's dtype).
        face: ``(Fs,)`` indices of the faces to scatter.
        face_material: ``(F,)`` material index per face.
        radar: TX/RX geometry.
        antenna: TX/RX power pattern.
        reflectivity: Fresnel coefficients of the room's materials.
        bvh: the room's acceleration structure (shadow rays toward the radar).
        density: tightening of the subdivision bound (1 = the documented bound).
        specular_factor: ``(num_materials,)`` coherent-reflection factor per material, or None.

    Returns:
        ``(paths, vertices)``: one path per lit split facet (kind 0) and ``(P, 3, 3)`` vertices
        ``[radar centre, facet centroid, radar centre]``.
    """
    dev, dt = radar.tx.device, radar.tx.dtype
    n_rx = radar.rx.shape[0]
    cdt = torch.complex128 if dt == torch.float64 else torch.complex64
    if face.numel() == 0:
        return Paths.empty(n_rx, dtype=dt, device=dev), torch.zeros(0, 3, 3, dtype=dt, device=dev)
    tri, src = subdivide(triangles[face], face, radar.centre, radar.wavelength, density)
    cen, r, u, root = monostatic_facet_rcs(tri, face_material[src], radar, reflectivity, specular_factor)
    eps = surface_offset(cen)
    lit = root.abs() > 0
    idx = lit.nonzero()[:, 0]
    blocked = bvh.any_hit(cen[idx] + eps[idx, None] * u[idx], u[idx], r[idx] - 2 * eps[idx], t_min=eps[idx])
    keep = idx[~blocked]
    p = cen[keep]
    r_t = (p - radar.tx).norm(dim=-1)
    r_r = (p[:, None] - radar.rx[None]).norm(dim=-1)
    g_t = antenna.gain(radar.to_radar_dirs(p - radar.tx))
    g_r = antenna.gain(radar.to_radar_dirs(p[:, None] - radar.rx[None]))
    amp = radar_amplitude(root[keep, None], r_t[:, None], r_r, g_t[:, None], g_r, radar.wavelength)
    delay = (r_t[:, None] + r_r) / SPEED_OF_LIGHT
    c = radar.centre.expand(keep.numel(), 3)
    vertices = torch.stack([c, p, c], dim=1)
    return Paths(delay, torch.zeros_like(delay), amp.to(cdt), torch.zeros(keep.numel(), dtype=torch.int8,
                                                                         device=dev)), vertices
