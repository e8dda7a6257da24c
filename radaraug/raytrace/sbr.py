"""Shooting and bouncing rays (SBR) with ray-tube physical optics toward the radar (Ling, Chou and Lee, 1989).

Tubes leave the TX on a gnomonic grid; at each hit the tube's parallelogram footprint radiates its PO field
back to the radar (one path per hit, return leg checked for occlusion), then the ray and tube reflect
specularly, diverging from the TX image. Delays are per RX; static paths have ``delay_rate = 0``.
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import Antenna
from radaraug.raytrace.po import facet_normals, parallelogram_integral, po_prefactor
from radaraug.raytrace.radar import RadarGeometry, radar_amplitude
from radaraug.raytrace.rays import RayTubes
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.sensor.paths import Paths


def surface_offset(p: torch.Tensor) -> torch.Tensor:
    """Distance to step off a surface before tracing again (float rounding of ``p``)."""
    eps = 256 * torch.finfo(p.dtype).eps
    return eps * (1 + p.abs().amax(-1))


def shoot_and_bounce(
    bvh: TriangleBVH,
    face_material: torch.Tensor,
    reflectivity: FaceReflectivity,
    radar: RadarGeometry,
    tubes: RayTubes,
    antenna: Antenna,
    *,
    max_bounces: int = 2,
) -> Paths:
    """Trace ``tubes`` through the scene of ``bvh`` and return one path per (ray, hit).

    Args:
        bvh: acceleration structure of the scene's triangles.
        face_material: ``(F,)`` material index per face.
        reflectivity: reflection coefficients of the scene's materials.
        radar: TX/RX positions, polarization and wavelength.
        tubes: launched ray tubes.
        antenna: object with ``gain(directions_radar_frame) -> power gain`` (TX and RX).
        max_bounces: most surface interactions per ray (1 = single scattering only).

    Returns:
        Unmerged :class:`Paths` ``(P, RX)`` with ``kind`` 0 for first hits, 1 for later ones.
    """
    normals_all = facet_normals(bvh.triangles)
    lam = radar.wavelength
    k = 2 * math.pi / lam
    o, d, g1, g2 = tubes.origins, tubes.directions, tubes.g1, tubes.g2
    gain_t = antenna.gain(tubes.launch_dirs)
    s = torch.zeros(o.shape[0], dtype=o.dtype, device=o.device)
    cdt = torch.complex128 if o.dtype == torch.float64 else torch.complex64
    coef = torch.ones(o.shape[0], dtype=cdt, device=o.device)
    t_min = torch.zeros_like(s)
    out: list[Paths] = []
    for bounce in range(max_bounces):
        hit = bvh.intersect(o, d, t_min=t_min)
        keep = hit.valid.nonzero()[:, 0]
        if keep.numel() == 0:
            break
        o, d, g1, g2, s, coef, gain_t = (x[keep] for x in (o, d, g1, g2, s, coef, gain_t))
        face, t = hit.face[keep], hit.t[keep]
        p = o + t[:, None] * d
        s = s + t
        n = normals_all[face]
        dn = (d * n).sum(-1)
        n_f = torch.where((dn > 0)[:, None], -n, n)  # normal on the lit side
        cos_i = dn.abs()
        gamma = reflectivity(face_material[face], cos_i, d, n, radar.polarization)

        # --- PO of the tube footprint toward the radar
        to_c = radar.centre - p
        r_c = to_c.norm(dim=-1)
        k_s = to_c / r_c[:, None]
        cos_s = (k_s * n_f).sum(-1)
        foot = [_project_on_plane(s[:, None] * g, d, n_f, cos_i) for g in (g1, g2)]
        integral = parallelogram_integral(foot[0], foot[1], -k * (d - k_s))
        root_rcs = po_prefactor(gamma, cos_i, cos_s, lam) * integral * coef
        eps = surface_offset(p)
        start = p + eps[:, None] * n_f
        faces_radar = cos_s > 0
        blocked = torch.zeros_like(faces_radar)
        if faces_radar.any():
            idx = faces_radar.nonzero()[:, 0]
            blocked[idx] = bvh.any_hit(start[idx], k_s[idx], t_max=r_c[idx] - eps[idx], t_min=eps[idx])
        ok = (faces_radar & ~blocked).nonzero()[:, 0]
        if ok.numel():
            r_rx = (p[ok, None, :] - radar.rx[None]).norm(dim=-1)  # (P, RX)
            gain_r = antenna.gain(radar.to_radar_dirs(-k_s[ok]))
            amp = radar_amplitude(root_rcs[ok, None], s[ok, None], r_rx, gain_t[ok, None],
                                  gain_r[:, None], lam)
            delay = (s[ok, None] + r_rx) / SPEED_OF_LIGHT
            kind = torch.full((ok.numel(),), min(bounce, 1), dtype=torch.int8, device=o.device)
            out.append(Paths(delay, torch.zeros_like(delay), amp, kind))

        # --- specular reflection of the ray and its tube
        coef = coef * gamma
        d = d - 2 * dn[:, None] * n
        g1, g2 = (g - 2 * (g * n).sum(-1, keepdim=True) * n for g in (g1, g2))
        o = start
        t_min = eps
    if not out:
        return Paths.empty(radar.rx.shape[0], dtype=o.dtype, device=o.device)
    return Paths.cat(out)


def _project_on_plane(e: torch.Tensor, d: torch.Tensor, n_f: torch.Tensor, cos_i: torch.Tensor) -> torch.Tensor:
    """Project tube edge ``e`` along the ray direction ``d`` onto the plane with normal ``n_f``."""
    return e + ((e * n_f).sum(-1) / cos_i.clamp_min(1e-6))[:, None] * d
