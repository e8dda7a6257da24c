"""Moving targets: analytic ellipsoid body segments (fast) and PO on person meshes.

An ellipsoid segment scatters from its specular point with the geometric-optics RCS of an ellipsoid times
the skin's reflection; first- and second-order multipath via the room's mirror planes by the image method;
a mesh person by monostatic facet PO. Formulas, validity checks and limits: ``docs/raytracer.md``, "People".
"""

from __future__ import annotations

import math

import torch

from radaraug._optional import lazy_import
from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import SceneError
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import Antenna
from radaraug.raytrace.facets import monostatic_facet_rcs
from radaraug.raytrace.po import facet_normals
from radaraug.raytrace.radar import RadarGeometry, radar_amplitude
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.sbr import surface_offset
from radaraug.raytrace.vec import dot, matvec
from radaraug.scene.geometry import Ellipsoids, SceneGeometry
from radaraug.scene.materials import get_material
from radaraug.sensor.paths import Paths


def ellipsoid_rcs(semi_axes: torch.Tensor, local_dir: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """``(sigma, h)`` of ellipsoids ``(..., 3)`` seen along unit local directions ``(..., 3)``."""
    h2 = ((semi_axes * local_dir) ** 2).sum(-1)
    h = h2.sqrt()
    return math.pi * semi_axes.prod(-1) ** 2 / (h2 * h2), h


def ray_hits_ellipsoids(
    origins: torch.Tensor, dirs: torch.Tensor, t_max: torch.Tensor, centers: torch.Tensor,
    semi_axes: torch.Tensor, rotations: torch.Tensor, own: torch.Tensor | None = None,
) -> torch.Tensor:
    """``(N, S_i)`` bool: the ray from segment slot ``i`` meets another ellipsoid of its snapshot.

    Rays ``(N, S_i, 3)``; a hit is on an ellipsoid ``j != own[i]`` of the same snapshot at ``0 < t < t_max``.
    ``own``: each ray's own ellipsoid ``(S_i,)`` (default: ray ``i`` belongs to ellipsoid ``i``).
    """
    # Into each ellipsoid's unit-sphere frame: x' = R^T (x - c) / axes.  Shapes (N, S_i, S_j, 3).
    rot_t = rotations.transpose(-1, -2)[:, None]  # (N, 1, Sj, 3, 3)
    rel = origins[:, :, None] - centers[:, None]
    o_l = matvec(rot_t, rel) / semi_axes[:, None]
    d_l = matvec(rot_t, dirs[:, :, None, :]) / semi_axes[:, None]
    a = dot(d_l, d_l)
    b = dot(o_l, d_l)
    c = dot(o_l, o_l) - 1
    disc = b * b - a * c
    root = disc.clamp_min(0).sqrt()
    t1, t2 = (-b - root) / a, (-b + root) / a
    hit = (disc > 0) & (t2 > 0) & (t1 < t_max[..., None])
    j = torch.arange(centers.shape[1], device=centers.device)
    eye = (j if own is None else own.to(centers.device))[:, None] == j[None, :]
    return (hit & ~eye).any(-1)


class MirrorPlanes:
    """Large planar face groups of a static room, for image-method multipath.

    Attributes:
        normals: ``(K, 3)`` unit plane normals; ``offsets``: ``(K,)`` with ``n . x = offset``.
        face_plane: ``(F,)`` long plane index of each room face, -1 for faces of no mirror plane.
    """

    def __init__(self, room: SceneGeometry, min_area_m2: float, device: torch.device, dtype: torch.dtype) -> None:
        tri = room.triangles.to(device=device, dtype=torch.float64)
        n = facet_normals(tri)
        area = torch.linalg.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0], dim=-1).norm(dim=-1) / 2
        # Canonical sign: the largest component positive, so both windings of a wall agree.
        big = n.abs().argmax(-1, keepdim=True)
        n = n * torch.sign(n.gather(-1, big))
        off = (n * tri[:, 0]).sum(-1)
        key = torch.cat([torch.round(n * 1e3), torch.round(off * 1e3)[:, None]], dim=-1)
        uniq, inv = torch.unique(key, dim=0, return_inverse=True)
        group_area = torch.zeros(uniq.shape[0], dtype=torch.float64, device=device).index_add_(0, inv, area)
        keep = group_area >= min_area_m2
        new_id = torch.full_like(group_area, -1, dtype=torch.long)
        new_id[keep] = torch.arange(int(keep.sum()), device=device)
        self.face_plane = new_id[inv]
        k = int(keep.sum())
        nsum = torch.zeros(uniq.shape[0], 3, dtype=torch.float64, device=device).index_add_(0, inv, n * area[:, None])
        osum = torch.zeros(uniq.shape[0], dtype=torch.float64, device=device).index_add_(0, inv, off * area)
        normals = nsum[keep] / group_area[keep][:, None]
        self.normals = (normals / normals.norm(dim=-1, keepdim=True)).to(dtype)
        self.offsets = (osum[keep] / group_area[keep]).to(dtype)
        self.num_planes = k
        # For the convex-room fast path (see `convex_enclosure`): float64 planes, the vertices,
        # and each plane's material when all its faces share one.
        self._n64 = normals / normals.norm(dim=-1, keepdim=True)
        self._off64 = osum[keep] / group_area[keep]
        self._verts64 = room.vertices.to(device=device, dtype=torch.float64)
        self._closed_convex = _is_closed_convex(tri, area)
        fp = self.face_plane
        self.plane_material: torch.Tensor | None = None
        if k and bool((fp >= 0).all()):
            mat = room.face_material.to(device)
            lo = torch.full((k,), torch.iinfo(torch.long).max, dtype=torch.long, device=device)
            hi = torch.full((k,), -1, dtype=torch.long, device=device)
            lo = lo.scatter_reduce(0, fp, mat, reduce="amin")
            hi = hi.scatter_reduce(0, fp, mat, reduce="amax")
            if bool((lo == hi).all()):
                self.plane_material = lo

    def convex_enclosure(self, point: torch.Tensor, tol: float = 1e-6) -> bool:
        """True when the room is a convex polyhedron of these planes enclosing ``point``.

        Then the room blocks no leg and a bounce point is on its wall iff it is inside every plane: multipath needs
        no ray casting. Requires every face on a mirror plane, one material per plane and no openings.
        """
        if self.plane_material is None or not self._closed_convex:
            return False
        sp = self._n64 @ point.to(torch.float64) - self._off64
        if bool((sp.abs() < tol).any()):
            return False
        sv = self._verts64 @ self._n64.T - self._off64  # (V, K)
        return bool((sv * torch.sign(sp) >= -tol).all())


def _is_closed_convex(tri: torch.Tensor, area: torch.Tensor) -> bool:
    """True when the triangles tile the surface of their convex hull (a closed convex room)."""
    import warnings

    trimesh = lazy_import("trimesh", feature="meshes")
    # trimesh's convex hull is scipy's Qhull: without scipy the fast path would silently turn off
    QhullError = lazy_import("scipy.spatial", feature="the convex-room fast path").QhullError

    pts = tri.reshape(-1, 3).cpu().numpy()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # flat scenes: trimesh divides by a zero hull volume
        try:
            hull = trimesh.convex.convex_hull(pts)
            volume, hull_area = float(hull.volume), float(hull.area)
        except (QhullError, ValueError, IndexError):  # too few or degenerate points: not a closed room
            return False
    total = float(area.sum())
    return bool(volume > 1e-9 and abs(hull_area - total) <= 1e-6 * max(total, 1.0))


def ellipsoid_paths(
    ell: Ellipsoids,
    radar: RadarGeometry,
    antenna: Antenna,
    *,
    room_bvh: TriangleBVH | None = None,
    room_face_material: torch.Tensor | None = None,
    room_reflectivity: FaceReflectivity | None = None,
    mirrors: MirrorPlanes | None = None,
    frequency_Hz: float,
    convex_room: bool = False,
    targets: torch.Tensor | None = None,
) -> Paths:
    """Paths of ellipsoid segments ``(..., S)`` -> :class:`Paths` ``(..., P, RX)`` with a mask.

    ``P = S`` direct paths, plus ``3 S K`` multipath slots with ``mirrors`` (K planes): radar -> wall ->
    segment -> radar, the reverse, and radar -> wall -> segment -> same wall -> radar, each block
    segment-major. ``convex_room`` (:meth:`MirrorPlanes.convex_enclosure`) skips the ray casts. ``targets``
    (ascending segment indices): only those segments' slots, in the same order; every segment still occludes.

    Raises:
        SceneError: semi-axes not finite and positive; multipath without ``room_reflectivity``; ``convex_room``
            with mirror planes that have no material each.
    """
    dev, dt = radar.tx.device, radar.tx.dtype
    lead = ell.centers.shape[:-2]
    s_count = ell.centers.shape[-2]
    n_rx = radar.rx.shape[0]
    if s_count == 0:  # no segments (a scene without people): no paths, but the leading dims stay
        return Paths.empty(n_rx, dtype=dt, device=dev, lead=tuple(lead), mask=True)
    c = ell.centers.to(device=dev, dtype=dt).reshape(-1, s_count, 3)
    ax = ell.semi_axes.to(device=dev, dtype=dt).reshape(-1, s_count, 3)
    rot = ell.rotations.to(device=dev, dtype=dt).reshape(-1, s_count, 3, 3)
    vel = ell.velocities.to(device=dev, dtype=dt).reshape(-1, s_count, 3)
    omega = None if ell.angular_velocities is None else \
        ell.angular_velocities.to(device=dev, dtype=dt).reshape(-1, s_count, 3)

    def point_velocity(bis: torch.Tensor, rot_: torch.Tensor, ax_: torch.Tensor,
                       distance: torch.Tensor | None = None) -> torch.Tensor:
        """Material velocity ``(N, S, ..., 3)`` at each segment's true specular point for bisector ``bis``.

        ``v + omega x o``, ``o`` the offset of the surface point whose normal is the bisector (envelope theorem).
        With ``distance`` (monostatic) the aspect's turn as the centre crosses the line of sight is added, so the
        rate is the time derivative of the delay ``|c - r| - h`` (``docs/raytracer.md``, "People").
        """
        extra = bis.ndim - 3
        v = vel.reshape(*vel.shape[:2], *([1] * extra), 3).expand_as(bis)
        if omega is None:
            return v
        local = (rot_.transpose(-1, -2) @ bis[..., None])[..., 0]
        a2l = ax_.square() * local
        h = (a2l * local).sum(-1, keepdim=True).sqrt().clamp_min(1e-12)
        offset = -(rot_ @ (a2l / h)[..., None])[..., 0]
        w = omega.reshape(*omega.shape[:2], *([1] * extra), 3).expand_as(bis)
        out = v + torch.linalg.cross(w, offset, dim=-1)
        if distance is not None:
            across = v - (v * bis).sum(-1, keepdim=True) * bis
            out = out + ((offset * across).sum(-1, keepdim=True) / distance[..., None]) * bis
        return out
    if (ax <= 0).any() or not torch.isfinite(ax).all():
        raise SceneError("ellipsoid semi_axes must be finite and positive")
    occluders = (c, ax, rot)
    if targets is not None:  # point_velocity reads vel and omega: they are the targets' from here on
        targets = targets.to(dev)
        c, ax, rot, vel = (t.index_select(1, targets) for t in (c, ax, rot, vel))
        omega = None if omega is None else omega.index_select(1, targets)
    eps_skin = get_material(ell.material).permittivity(frequency_Hz)
    gamma_skin = (1 - complex(eps_skin) ** 0.5) / (1 + complex(eps_skin) ** 0.5)  # Gamma_TE at normal

    # --- direct (monostatic) paths
    to_t = c - radar.centre
    u = to_t / to_t.norm(dim=-1, keepdim=True)
    p, sigma = _specular(c, ax, rot, _bisector(u, -u))
    root = gamma_skin * sigma.sqrt()
    los = p - radar.centre
    r_los = los.norm(dim=-1)
    u_los = los / r_los[..., None]
    eps = surface_offset(p)
    blocked = ray_hits_ellipsoids(radar.centre.expand_as(p), u_los, r_los - eps, *occluders, own=targets)
    if room_bvh is not None and not convex_room:
        blocked = blocked | room_bvh.any_hit(radar.centre.expand_as(p).reshape(-1, 3), u_los.reshape(-1, 3),
                                              (r_los - eps).reshape(-1)).reshape(blocked.shape)
    # the echo's range moves at the material velocity of its specular point (envelope theorem)
    direct = _bistatic(p, root, radar.tx, radar.rx, p, point_velocity(u, rot, ax, to_t.norm(dim=-1)), radar,
                       antenna, ~blocked)
    parts = [direct + (torch.zeros_like(blocked, dtype=torch.int8),)]

    # --- first-order multipath via mirror planes
    if mirrors is not None and mirrors.num_planes and room_bvh is not None:
        if room_reflectivity is None:
            raise SceneError("ellipsoid_paths: multipath (mirrors and room_bvh) needs room_reflectivity")
        nrm, off = mirrors.normals.to(dev, dt), mirrors.offsets.to(dev, dt)
        k = nrm.shape[0]
        img = radar.centre - 2 * ((nrm @ radar.centre) - off)[:, None] * nrm  # (K, 3)
        cc = c[:, :, None]  # (N, S, 1, 3)
        to_img = img - cc
        u_seg_in = -to_img / to_img.norm(dim=-1, keepdim=True)  # wall -> segment (from the centre)
        c_k = c[:, :, None].expand(-1, -1, k, -1)
        rot_k = rot[:, :, None].expand(-1, -1, k, -1, -1)
        ax_k = ax[:, :, None].expand(-1, -1, k, -1)
        bis = _bisector(u_seg_in, _unit(radar.centre - cc))
        pk, sigma = _specular(c_k, ax_k, rot_k, bis)
        q, ok, g_wall = _wall_bounce(pk, img, nrm, off, mirrors, radar, convex_room, room_bvh,
                                     room_face_material, room_reflectivity)
        root_k = gamma_skin * sigma.sqrt() * g_wall
        # Path A: TX -> wall -> segment -> RX ; path B: TX -> segment -> wall -> RX.
        vel_k = point_velocity(bis, rot_k, ax_k)
        a = _bistatic(pk, root_k, radar.tx, radar.rx, q, vel_k, radar, antenna, ok, first_leg_via=True)
        b = _bistatic(pk, root_k, radar.tx, radar.rx, q, vel_k, radar, antenna, ok, first_leg_via=False)
        # Path C (second order, same wall twice): TX -> wall -> segment -> wall -> RX, the segment
        # seen monostatically from the radar's image in the plane.
        c2 = _second_order(c, ax, rot, point_velocity, radar, antenna, nrm, off, img, gamma_skin, mirrors, room_bvh,
                           room_face_material, room_reflectivity, convex_room)
        for part in (a, b, c2):
            parts.append(tuple(x.reshape(x.shape[0], -1, *x.shape[3:]) for x in part)
                         + (torch.ones(ok.shape[0], ok.shape[1] * k, dtype=torch.int8, device=dev),))
    delay, rate, amp, mask, kind = (torch.cat(list(x), dim=1) for x in zip(*parts))
    return Paths(delay.reshape(*lead, -1, n_rx), rate.reshape(*lead, -1, n_rx), amp.reshape(*lead, -1, n_rx),
                 kind.reshape(*lead, -1), mask.reshape(*lead, -1))


def slot_segments(s_count: int, num_slots: int, device: torch.device | None = None) -> torch.Tensor:
    """The segment ``(num_slots,)`` of each slot of :func:`ellipsoid_paths` (``num_slots = S (1 + 3 K)``)."""
    k = (num_slots // s_count - 1) // 3
    seg = torch.arange(s_count, device=device)
    return torch.cat([seg, *(seg.repeat_interleave(k),) * 3])


def _bisector(u_in: torch.Tensor, u_out: torch.Tensor) -> torch.Tensor:
    """Unit bisector ``u_in - u_out`` of an incidence and a scattering direction (unit)."""
    bis = u_in - u_out
    return bis / bis.norm(dim=-1, keepdim=True).clamp_min(1e-12)


def _specular(c: torch.Tensor, ax: torch.Tensor, rot: torch.Tensor,
              bis: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Specular point ``c - h bis`` and RCS of ellipsoids whose outward normal there is ``-bis`` (unit)."""
    sigma, h = ellipsoid_rcs(ax, (rot.transpose(-1, -2) @ bis[..., None])[..., 0])
    return c - h[..., None] * bis, sigma


def _second_order(c, ax, rot, point_velocity, radar: RadarGeometry, antenna, nrm, off, img, gamma_skin, mirrors: MirrorPlanes,
                  room_bvh: TriangleBVH, room_face_material, room_reflectivity, convex_room: bool):
    """Wall -> segment -> same wall paths ``(N, S, K, RX)``: delay, rate, amplitude, valid.

    The segment scatters monostatically towards the radar's image in plane ``k``; both legs cross the plane
    at the same bounce point and angle, so the amplitude carries ``Gamma(theta)^2``. Validity as
    :func:`_wall_bounce`.
    """
    dt = c.dtype
    k = nrm.shape[0]

    def mirror(x: torch.Tensor) -> torch.Tensor:  # (..., 3) -> (..., K, 3)
        return x[..., None, :] - 2 * ((x[..., None, :] * nrm).sum(-1) - off)[..., None] * nrm

    cc = c[:, :, None]  # (N, S, 1, 3)
    u = _unit(cc - img)  # image radar -> centre, (N, S, K, 3)
    ax_k = ax[:, :, None].expand(-1, -1, k, -1)
    rot_k = rot[:, :, None].expand(-1, -1, k, -1, -1)
    p, sigma = _specular(cc, ax_k, rot_k, u)  # specular point facing the image radar
    q, ok, g_wall = _wall_bounce(p, img, nrm, off, mirrors, radar, convex_room, room_bvh, room_face_material,
                                 room_reflectivity)
    root = gamma_skin * sigma.sqrt() * g_wall * g_wall
    tx_img = mirror(radar.tx)  # (K, 3)
    rx_img = mirror(radar.rx).transpose(0, 1)  # (K, RX, 3)
    r_t = (p - tx_img).norm(dim=-1)  # (N, S, K)
    u_rp = p[..., None, :] - rx_img  # (N, S, K, RX, 3): image RX -> p
    r_r = u_rp.norm(dim=-1)
    # Antenna gains towards the bounce point (the direction the radar sees the ghost in).
    g_t = antenna.gain(radar.to_radar_dirs(_unit(q - radar.tx)))
    g_r = antenna.gain(radar.to_radar_dirs(_unit(q[..., None, :] - radar.rx)))
    amp = radar_amplitude(root[..., None], r_t[..., None], r_r, g_t[..., None], g_r, radar.wavelength)
    amp = torch.where(ok[..., None], amp, torch.zeros_like(amp))
    delay = (r_t[..., None] + r_r) / SPEED_OF_LIGHT
    # Both legs leave the segment towards the images: d|p - img|/dt = v . (p - img) / |p - img|.
    # (N, S, K, 3): the true specular point's material velocity, seen monostatically from the image radar
    vel = point_velocity(u, rot_k, ax_k, (cc - img).norm(dim=-1))
    rate_t = (vel * _unit(p - tx_img)).sum(-1)
    rate_r = (vel[..., None, :] * (u_rp / r_r[..., None])).sum(-1)
    rate = (rate_t[..., None] + rate_r) / SPEED_OF_LIGHT
    return delay.to(dt), rate.to(dt), amp, ok


def _unit(v: torch.Tensor) -> torch.Tensor:
    return v / v.norm(dim=-1, keepdim=True)


def _wall_bounce(p, img, nrm, off, mirrors: MirrorPlanes, radar: RadarGeometry, convex_room: bool,
                 room_bvh: TriangleBVH, room_face_material, room_reflectivity: FaceReflectivity):
    """``(q, ok, gamma)``: bounce points ``(N, S, K, 3)`` of scatterers ``p`` on the mirror planes.

    ``q`` is where the line from ``p`` to the radar's image in plane ``k`` crosses it; ``gamma`` is the wall's
    reflection coefficient for the radar -> ``q`` leg. Valid when ``p`` is on the radar's side, ``q`` on that
    plane's faces and the ``q`` -> radar leg clear (in a convex room: ``q`` inside every other plane).
    """
    u_img = _unit(img - p)
    denom = (u_img * nrm).sum(-1)
    t_q = (off - (p * nrm).sum(-1)) / torch.where(denom.abs() < 1e-12, torch.ones_like(denom), denom)
    q = p + t_q[..., None] * u_img
    u_wall_in = _unit(q - radar.centre)  # radar -> wall
    radar_side = (nrm @ radar.centre) - off  # (K,)
    same_side = ((p * nrm).sum(-1) - off) * radar_side > 0
    k = nrm.shape[0]
    dev = q.device
    if convex_room:
        if mirrors.plane_material is None:
            raise SceneError("convex_room needs mirror planes of one material each (see MirrorPlanes.convex_enclosure)")
        side = ((q[..., None, :] * nrm).sum(-1) - off) * torch.sign(radar_side)  # (N, S, K, K)
        tol = 1e-5 * (1 + off.abs().max())
        ok = same_side & (side >= -tol).all(-1)
        material = mirrors.plane_material.to(dev).expand(q.shape[:-1])
    else:
        hit = room_bvh.intersect(p.reshape(-1, 3), u_img.reshape(-1, 3), t_min=0.0)
        plane_id = torch.arange(k, device=dev).expand(q.shape[:-1]).reshape(-1)
        face = hit.face
        on_plane = (face >= 0) & (mirrors.face_plane.to(dev)[face.clamp_min(0)] == plane_id)
        r_wr = (radar.centre - q).norm(dim=-1).reshape(-1)
        eps_q = surface_offset(q).reshape(-1)
        clear = ~room_bvh.any_hit(q.reshape(-1, 3), -u_wall_in.reshape(-1, 3), r_wr - eps_q, t_min=eps_q)
        ok = (on_plane & same_side.reshape(-1) & clear).reshape(q.shape[:-1])
        material = room_face_material[face.clamp_min(0)].reshape(q.shape[:-1])
    cos_w = (u_wall_in * nrm).sum(-1).abs()
    return q, ok, room_reflectivity(material, cos_w, u_wall_in, nrm.expand_as(u_wall_in), radar.polarization)


def _bistatic(p, root, tx, rx, q, vel, radar: RadarGeometry, antenna, valid, first_leg_via: bool | None = None):
    """Delay, rate, amplitude ``(..., RX)`` and mask of scatterer ``p`` (optionally via wall point ``q``).

    ``first_leg_via``: None = direct; True = TX -> q -> p -> RX; False = TX -> p -> q -> RX.
    """
    def unit(v):
        n = v.norm(dim=-1, keepdim=True)
        return v / n, n[..., 0]

    lam = radar.wavelength
    rxs = rx.reshape(*([1] * (p.ndim - 1)), -1, 3)
    if first_leg_via is None or first_leg_via is False:
        u_t, r_t = unit(p - tx)
        g_t = antenna.gain(radar.to_radar_dirs(u_t))
        rate_t = (vel * u_t).sum(-1)
    else:
        u_tq, r_tq = unit(q - tx)
        u_qp, r_qp = unit(p - q)
        r_t, g_t, rate_t = r_tq + r_qp, antenna.gain(radar.to_radar_dirs(u_tq)), (vel * u_qp).sum(-1)
    if first_leg_via is None or first_leg_via is True:
        u_r, r_r = unit(p[..., None, :] - rxs)
        g_r = antenna.gain(radar.to_radar_dirs(u_r))
        rate_r = (vel[..., None, :] * u_r).sum(-1)
    else:
        u_pq, r_pq = unit(q - p)
        u_rq, r_rq = unit(q[..., None, :] - rxs)
        r_r = r_pq[..., None] + r_rq
        g_r = antenna.gain(radar.to_radar_dirs(u_rq))
        rate_r = (-(vel * u_pq).sum(-1))[..., None].expand_as(r_r)
    amp = radar_amplitude(root[..., None], r_t[..., None], r_r, g_t[..., None], g_r, lam)
    amp = torch.where(valid[..., None], amp, torch.zeros_like(amp))
    delay = (r_t[..., None] + r_r) / SPEED_OF_LIGHT
    rate = (rate_t[..., None] + rate_r) / SPEED_OF_LIGHT
    return delay, rate, amp, valid


def mesh_po_paths(
    mesh: SceneGeometry,
    radar: RadarGeometry,
    antenna: Antenna,
    reflectivity: FaceReflectivity,
    *,
    room_bvh: TriangleBVH | None = None,
) -> Paths:
    """Monostatic facet-PO paths ``(F_lit, RX)`` of a (moving) mesh at one instant."""
    dev, dt = radar.tx.device, radar.tx.dtype
    tri = mesh.triangles.to(device=dev, dtype=dt)
    if tri.ndim != 3 or tri.shape[0] == 0:
        raise SceneError(f"mesh must have (F, 3) faces, got triangles of shape {tuple(tri.shape)}")
    cen, r, u, root = monostatic_facet_rcs(tri, mesh.face_material.to(dev), radar, reflectivity)
    eps = surface_offset(cen)
    start = cen + eps[:, None] * u
    lit = root.abs() > 0
    blocked = TriangleBVH(tri).any_hit(start, u, r - eps, t_min=eps)
    if room_bvh is not None:
        blocked |= room_bvh.any_hit(start, u, r - eps, t_min=eps)
    keep = (lit & ~blocked).nonzero()[:, 0]
    if mesh.vertex_velocity is not None:
        vel = mesh.vertex_velocity.to(device=dev, dtype=dt)[mesh.faces.to(dev)].mean(-2)
    else:
        vel = torch.zeros_like(cen)
    d, rate, amp, _ = _bistatic(cen[keep], root[keep], radar.tx, radar.rx, cen[keep], vel[keep], radar, antenna,
                                torch.ones(keep.numel(), dtype=torch.bool, device=dev))
    return Paths(d, rate, amp, torch.zeros(keep.numel(), dtype=torch.int8, device=dev))
