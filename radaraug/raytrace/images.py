"""Specular room paths by the image method: exact, no ray density to converge.

The field after reflections on planes ``k1..kn`` is the free-space field of the TX's image times the product
of the Fresnel coefficients, ``a = sqrt(G_t G_r) lambda / (4 pi L) prod Gamma_i`` with ``L = |RX - image|``
(the stationary-phase limit of PO). Existence checks, mirror planes and limits: ``docs/raytracer.md``,
"The static room". Geometry runs in float64, the result in the tracer's dtype.
"""

from __future__ import annotations

import itertools
import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.antenna import Antenna
from radaraug.raytrace.intersect import any_hit
from radaraug.raytrace.radar import RadarGeometry
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.targets import MirrorPlanes
from radaraug.scene.geometry import SceneGeometry
from radaraug.sensor.paths import Paths

_BARY_TOL = 1e-9
"""Barycentric tolerance of the point-on-face test (corner reflection points lie on face edges)."""

_SAME_IMAGE_M = 1e-6
"""Images closer than this are one image (coincident orders of a right-angled corner)."""


def mirror(points: torch.Tensor, normal: torch.Tensor, offset: torch.Tensor) -> torch.Tensor:
    """Mirror ``points`` ``(..., 3)`` in planes ``n . x = offset`` (``normal`` ``(..., 3)`` unit)."""
    return points - 2 * ((points * normal).sum(-1, keepdim=True) - offset[..., None]) * normal


def plane_sequences(num_planes: int, order: int, device: torch.device) -> torch.Tensor:
    """``(N, order)`` long: every sequence of plane indices with no plane twice in a row."""
    seqs = [s for s in itertools.product(range(num_planes), repeat=order)
            if all(a != b for a, b in itertools.pairwise(s))]
    return torch.tensor(seqs, dtype=torch.long, device=device).reshape(-1, order)


def image_paths(
    room: SceneGeometry,
    mirrors: MirrorPlanes,
    radar: RadarGeometry,
    antenna: Antenna,
    reflectivity: FaceReflectivity,
    *,
    max_order: int,
    specular_factor: torch.Tensor | None = None,
) -> tuple[Paths, torch.Tensor]:
    """Specular paths of orders ``1..max_order`` and their vertices.

    Args:
        room: the static room (its faces and materials).
        mirrors: the room's mirror planes.
        radar: TX/RX geometry.
        antenna: TX/RX power pattern with ``gain(dirs_radar_frame)``.
        reflectivity: Fresnel coefficients of the room's materials.
        max_order: most reflections per path.
        specular_factor: ``(num_materials,)`` amplitude factor of the specular reflection (the rough-surface
            reduction ``sqrt(1 - S^2)``), None for 1.

    Returns:
        ``(paths, vertices)``: :class:`Paths` ``(P, RX)`` (kind 0 for one reflection, 1 for more) and
        ``(P, max_order + 2, 3)`` vertices ``[radar centre, q_1, ..., q_n, radar centre]``, padded with the centre.
    """
    dev, dt = radar.tx.device, radar.tx.dtype
    f64 = torch.float64
    n_rx = radar.rx.shape[0]
    k_planes = mirrors.num_planes
    v_count = max_order + 2
    if k_planes == 0 or room.num_faces == 0:
        return _empty(n_rx, v_count, dev, dt)
    tri = room.triangles.to(device=dev, dtype=f64)
    nrm = mirrors.normals.to(device=dev, dtype=f64)
    off = mirrors.offsets.to(device=dev, dtype=f64)
    face_material = room.face_material.to(dev)
    centre = radar.centre.to(f64)
    tx = radar.tx.to(f64)
    rx = radar.rx.to(f64)
    plane_faces = _plane_faces(mirrors.face_plane.to(dev), k_planes)
    scale = float(tri.abs().max()) + 1.0

    found: list[tuple[torch.Tensor, ...]] = []  # (delay, amplitude, kind, vertices, image) per order
    for order in range(1, max_order + 1):
        seq = plane_sequences(k_planes, order, dev)  # (N, n), empty for one plane and n > 1
        # Images of the radar centre (for the geometry) and of the TX (for the exact delays).
        img_c = [centre.expand(seq.shape[0], 3)]
        img_t = [tx.expand(seq.shape[0], 3)]
        for i in range(order):
            img_c.append(mirror(img_c[-1], nrm[seq[:, i]], off[seq[:, i]]))
            img_t.append(mirror(img_t[-1], nrm[seq[:, i]], off[seq[:, i]]))
        # Trace back from the radar: q_n on the segment radar -> I_n, q_{i} on q_{i+1} -> I_i.
        ok = torch.ones(seq.shape[0], dtype=torch.bool, device=dev)
        q: list[torch.Tensor] = []  # filled from the last reflection point to the first
        start = centre.expand(seq.shape[0], 3)
        for i in range(order - 1, -1, -1):
            n_i, o_i = nrm[seq[:, i]], off[seq[:, i]]
            seg = img_c[i + 1] - start
            den = (seg * n_i).sum(-1)
            t = (o_i - (start * n_i).sum(-1)) / torch.where(den.abs() < 1e-12, torch.ones_like(den), den)
            ok &= (den.abs() >= 1e-12) & (t > -1e-9) & (t < 1 + 1e-9)
            start = start + t[:, None] * seg
            q.insert(0, start)
        face = torch.stack([_face_at(q[i], seq[:, i], plane_faces, tri) for i in range(order)], dim=1)
        ok &= (face >= 0).all(-1)
        pts = torch.stack([centre.expand(seq.shape[0], 3), *q, centre.expand(seq.shape[0], 3)], dim=1)
        ok &= ~_legs_blocked(pts, ok, tri, scale)
        idx = ok.nonzero()[:, 0]
        if idx.numel() == 0:
            continue
        pts, seq_ok, face = pts[idx], seq[idx], face[idx]
        image_t = img_t[-1][idx]
        # Amplitude: free-space field of the TX image times the Fresnel coefficient per bounce.
        # Propagation direction before each reflection: the launch direction mirrored by the
        # planes already met (exact for a specular chain, and defined at corners where legs
        # between coincident reflection points have zero length).
        d = pts[:, 1] - pts[:, 0]
        d = d / d.norm(dim=-1, keepdim=True)
        u_launch = d
        gamma = torch.ones(idx.numel(), dtype=torch.complex128, device=dev)
        for i in range(order):
            n_i = nrm[seq_ok[:, i]]
            cos_i = (d * n_i).sum(-1).abs()
            mat = face_material[face[:, i]]
            g = reflectivity(mat, cos_i.to(dt), d.to(dt), n_i.to(dt), radar.polarization).to(torch.complex128)
            if specular_factor is not None:
                g = g * specular_factor.to(dev)[mat].to(torch.complex128)
            gamma = gamma * g
            d = d - 2 * (d * n_i).sum(-1, keepdim=True) * n_i
        g_t = antenna.gain(radar.to_radar_dirs(u_launch.to(dt))).to(f64)
        g_r = antenna.gain(radar.to_radar_dirs((-d).to(dt))).to(f64)
        length = (rx[None] - image_t[:, None]).norm(dim=-1)  # (P, RX)
        amp = (torch.sqrt(g_t * g_r)[:, None] * radar.wavelength / (4 * math.pi * length)) * gamma[:, None]
        kind = torch.full((idx.numel(),), min(order - 1, 1), dtype=torch.int8, device=dev)
        pad = centre.expand(idx.numel(), v_count - pts.shape[1], 3)
        found.append((length / SPEED_OF_LIGHT, amp, kind, torch.cat([pts, pad], dim=1), img_c[-1][idx]))
    if not found:
        return _empty(n_rx, v_count, dev, dt)
    delay, amp, kind, vert, key = (torch.cat(x) for x in zip(*found))
    keep = _first_of_each_image(key)
    cdt = torch.complex128 if dt == torch.float64 else torch.complex64
    paths = Paths(delay[keep].to(dt), torch.zeros_like(delay[keep]).to(dt), amp[keep].to(cdt), kind[keep])
    return paths, vert[keep].to(dt)


def _empty(n_rx: int, v_count: int, dev: torch.device, dt: torch.dtype) -> tuple[Paths, torch.Tensor]:
    return Paths.empty(n_rx, dtype=dt, device=dev), torch.zeros(0, v_count, 3, dtype=dt, device=dev)


def _plane_faces(face_plane: torch.Tensor, k_planes: int) -> torch.Tensor:
    """``(K, Fmax)`` face indices of each plane, padded with -1."""
    counts = torch.bincount(face_plane[face_plane >= 0], minlength=k_planes)
    out = torch.full((k_planes, int(counts.max())), -1, dtype=torch.long, device=face_plane.device)
    for k in range(k_planes):
        f = (face_plane == k).nonzero()[:, 0]
        out[k, : f.numel()] = f
    return out


def _face_at(points: torch.Tensor, plane: torch.Tensor, plane_faces: torch.Tensor, tri: torch.Tensor,
             chunk: int = 1 << 22) -> torch.Tensor:
    """Index of a face of ``plane`` that contains each point (on the plane), -1 where none does."""
    out = torch.full(points.shape[:1], -1, dtype=torch.long, device=points.device)
    width = plane_faces.shape[1]
    step = max(1, chunk // max(width, 1))
    for s in range(0, points.shape[0], step):
        cand = plane_faces[plane[s: s + step]]  # (n, W)
        t = tri[cand.clamp_min(0)]  # (n, W, 3, 3)
        p = points[s: s + step, None]
        a, b, c = t.unbind(-2)
        v0, v1, v2 = b - a, c - a, p - a
        d00, d01, d11 = (v0 * v0).sum(-1), (v0 * v1).sum(-1), (v1 * v1).sum(-1)
        d20, d21 = (v2 * v0).sum(-1), (v2 * v1).sum(-1)
        den = (d00 * d11 - d01 * d01).clamp_min(1e-300)
        v = (d11 * d20 - d01 * d21) / den
        w = (d00 * d21 - d01 * d20) / den
        inside = (v >= -_BARY_TOL) & (w >= -_BARY_TOL) & (v + w <= 1 + _BARY_TOL) & (cand >= 0)
        first = torch.where(inside, torch.arange(width, device=points.device), width).amin(-1)
        hit = first < width
        out[s: s + step] = torch.where(hit, cand.gather(1, first.clamp_max(width - 1)[:, None])[:, 0], -1)
    return out


def _legs_blocked(pts: torch.Tensor, ok: torch.Tensor, tri: torch.Tensor, scale: float) -> torch.Tensor:
    """``(N,)`` bool: some leg of a candidate path crosses the room between its end points."""
    blocked = torch.zeros(pts.shape[0], dtype=torch.bool, device=pts.device)
    idx = ok.nonzero()[:, 0]
    a, b = pts[idx, :-1], pts[idx, 1:]
    seg = (b - a).reshape(-1, 3)
    length = seg.norm(dim=-1)
    # Legs of zero length (coincident reflection points at a corner) cannot be blocked.
    eps = 1e-9 * scale
    live = length > 10 * eps
    d = seg / length.clamp_min(1e-300)[:, None]
    hit = torch.zeros_like(live)
    li = live.nonzero()[:, 0]
    if li.numel():
        o = a.reshape(-1, 3)[li]
        hit[li] = any_hit(o, d[li], tri, (length[li] - eps), t_min=eps, compiled=False)
    blocked[idx] = hit.reshape(idx.numel(), pts.shape[1] - 1).any(-1)
    return blocked


def _first_of_each_image(images: torch.Tensor) -> torch.Tensor:
    """Indices of the first path of each distinct image point (within ``_SAME_IMAGE_M``), in order."""
    near = torch.cdist(images, images) < _SAME_IMAGE_M  # valid paths only: a few hundred
    first = torch.where(near, torch.arange(images.shape[0], device=images.device), images.shape[0]).amin(-1)
    return (first == torch.arange(images.shape[0], device=images.device)).nonzero()[:, 0]
