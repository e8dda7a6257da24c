"""People shadowing the static room: per-segment knife-edge diffraction on the static paths' legs.

Each body segment (an ellipsoid) acts on each leg of each static path as a knife edge (ITU-R P.526): its
silhouette seen along the leg gives a signed clearance ``h``, ``nu = h sqrt(2 / lambda (1 / d1 + 1 / d2))``,
and the field factor ``F(nu)``. Per person and leg the most obstructing segment counts; legs and people
multiply. Model, approximations, accuracy and cost: ``docs/shadowing.md``.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import torch

from radaraug.errors import InputTensorError, SceneError
from radaraug.raytrace.vec import dot, matvec
from radaraug.scene.geometry import Ellipsoids
from radaraug.sensor.paths import Paths

_SERIES_MAX = 3.5  # |x| below which the power series is used (its cancellation error is ~1e-8 there)
_SERIES_TERMS = 85  # (pi x^2 / 2)^n / n! * x < 1e-16 at x = 3.5 for n >= 85
_ASYMPTOTIC_TERMS = 9  # smallest asymptotic term at x = 3.5 is ~1e-9 relative
_DENSE_TABLE_MAX = 2**24  # entries of the dominant-edge table; beyond, the keys are sorted instead
_CULL_CHUNK = 2**18  # (segment, leg) pairs per chunk of the bounding-sphere cull
# On a GPU the chunk loop's cost is its launches and its nonzero's host syncs, not cache misses: at
# the CPU's chunk a 1,024-frame corridor batch was ~860 chunks, ~25,000 launches, 0.33 s for 0.06 s
# of GPU work (H200 profile). 2**24 pairs keep each of the cull's dozen temporaries at 64 MiB.
_CULL_CHUNK_GPU = 2**24
SHADOW_TOL = 1e-3
"""Smallest ``|T - 1|`` of a static path that is corrected (-60 dB of the path)."""


def fresnel_integrals(x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Fresnel integrals ``C(x) = int_0^x cos(pi t^2 / 2) dt`` and ``S(x) = int_0^x sin(pi t^2 / 2) dt``.

    Note the order ``(C, S)`` (``scipy.special.fresnel`` returns ``(S, C)``). Computed in float64 (absolute
    error < 1e-8), returned in ``x``'s floating dtype.

    Args:
        x: real tensor, any shape and device.

    Returns:
        ``(C, S)``, each shaped like ``x``.
    """
    q = _q_integral(x.to(torch.float64).abs())
    # int_0^|x| exp(-j pi t^2/2) dt = (1 - j)/2 - Q(|x|) = C - jS; both are odd in x.
    e = (0.5 - 0.5j) - q
    s = torch.sign(x.to(torch.float64))
    dt = x.dtype if x.is_floating_point() else torch.get_default_dtype()
    return (s * e.real).to(dt), (-s * e.imag).to(dt)


def _series_coefficients() -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Real and imaginary parts of ``c_n = (-j pi / 2)^n / (n! (2n + 1))``, highest ``n`` first (Horner)."""
    re, im = [], []
    for n in range(_SERIES_TERMS):
        mag = (math.pi / 2) ** n / (math.factorial(n) * (2 * n + 1))
        # (-j)^n cycles 1, -j, -1, j.
        re.append((mag, 0.0, -mag, 0.0)[n % 4])
        im.append((0.0, -mag, 0.0, mag)[n % 4])
    return tuple(reversed(re)), tuple(reversed(im))


_COEF_RE, _COEF_IM = _series_coefficients()


def _q_integral(nu: torch.Tensor) -> torch.Tensor:
    """``Q(nu) = int_nu^inf exp(-j pi t^2 / 2) dt`` (complex128) for real float64 ``nu`` of any sign."""
    a = nu.abs()
    q_pos = torch.empty(a.shape, dtype=torch.complex128, device=a.device)
    small = a <= _SERIES_MAX
    xs = a[small]
    if xs.numel():
        # int_0^x exp(-j pi t^2/2) dt = x sum_n c_n (x^2)^n, Horner in the real x^2 (float64:
        # the largest term at x = 3.5 is ~2e7, so the cancellation error is ~1e-8).
        y = xs * xs
        re = torch.full_like(xs, _COEF_RE[0])
        im = torch.full_like(xs, _COEF_IM[0])
        for cr, ci in zip(_COEF_RE[1:], _COEF_IM[1:]):
            re = re * y + cr
            im = im * y + ci
        q_pos[small] = (0.5 - 0.5j) - torch.complex(re * xs, im * xs)
    xa = a[~small]
    if xa.numel():
        # Asymptotic expansion: Q(a) = (g - j f) exp(-j pi a^2 / 2), with
        # f ~ 1/(pi a) sum_k (-1)^k (4k-1)!! / (pi a^2)^(2k), g ~ 1/(pi^2 a^3) sum_k (-1)^k (4k+1)!! / (pi a^2)^(2k).
        w = 1.0 / (math.pi * xa * xa) ** 2
        f_sum = torch.ones_like(xa)
        g_sum = torch.ones_like(xa)
        tf = torch.ones_like(xa)
        tg = torch.ones_like(xa)
        for k in range(1, _ASYMPTOTIC_TERMS):
            tf = -tf * w * ((4 * k - 1) * (4 * k - 3))
            tg = -tg * w * ((4 * k + 1) * (4 * k - 1))
            f_sum = f_sum + tf
            g_sum = g_sum + tg
        f = f_sum / (math.pi * xa)
        g = g_sum / (math.pi**2 * xa**3)
        phase = torch.polar(torch.ones_like(xa), -0.5 * math.pi * xa * xa)
        q_pos[~small] = torch.complex(g, -f) * phase
    # Q(-a) = int_{-inf}^{inf} - Q(a) = (1 - j) - Q(a).
    return torch.where(nu >= 0, q_pos, (1.0 - 1.0j) - q_pos)


def knife_edge(nu: torch.Tensor) -> torch.Tensor:
    """Complex field factor of a half-plane (knife-edge) obstacle, ITU-R P.526 convention.

    ``F(nu) = (1 + j) / 2 * int_nu^inf exp(-j pi t^2 / 2) dt``: 1 far in the lit region, 1/2 at grazing
    (``nu = 0``), ``~ 1 / (pi sqrt(2) nu)`` deep in the shadow. It multiplies the free-space field (fields vary
    as ``exp(-j k r)``); the loss is ``-20 log10 |F|`` dB.

    Args:
        nu: real tensor, the Fresnel-Kirchhoff diffraction parameter.

    Returns:
        Complex tensor shaped like ``nu`` (complex64 for float32 input, else complex128), error < 1e-8.
    """
    f = (0.5 + 0.5j) * _q_integral(nu.to(torch.float64))
    return f.to(torch.complex64 if nu.dtype in (torch.float32, torch.float16, torch.bfloat16) else torch.complex128)


_TABLE_LO, _TABLE_HI, _TABLE_STEP = -8.0, 3.5, 1.0 / 256  # the fast knife edge's table range and spacing
_TABLES: dict[torch.device, tuple[torch.Tensor, torch.Tensor]] = {}


def _knife_edge_fast(nu: torch.Tensor) -> torch.Tensor:
    """:func:`knife_edge` (complex128) of float64 ``nu`` by cubic Hermite interpolation of a table.

    ``F`` and its exact derivative every 1/256 on [-8, 3.5] (within 1e-8 of scipy); the exact function outside.
    """
    dev = nu.device
    if dev not in _TABLES:
        grid = torch.arange(_TABLE_LO, _TABLE_HI + _TABLE_STEP / 2, _TABLE_STEP, dtype=torch.float64, device=dev)
        value = knife_edge(grid)
        slope = -(0.5 + 0.5j) * torch.polar(torch.ones_like(grid), -0.5 * math.pi * grid * grid)
        _TABLES[dev] = (value, slope * _TABLE_STEP)  # derivative per table step
    value, slope = _TABLES[dev]
    t = (nu - _TABLE_LO) / _TABLE_STEP
    inside = (t >= 0) & (t < value.shape[0] - 1)
    i = t.clamp(0, value.shape[0] - 2).floor()
    s = (t.clamp(0, value.shape[0] - 1) - i)
    i = i.long()
    s2, s3 = s * s, s * s * s
    h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, 3 * s2 - 2 * s3, s3 - s2
    f = (h00 * value.index_select(0, i) + h10 * slope.index_select(0, i)
         + h01 * value.index_select(0, i + 1) + h11 * slope.index_select(0, i + 1))
    if not bool(inside.all()):
        out = ~inside
        f[out] = knife_edge(nu[out])
    return f


def _check_inputs(vertices: torch.Tensor, ellipsoids: Ellipsoids, wavelength: float) -> None:
    if vertices.dim() != 3 or vertices.shape[-1] != 3 or vertices.shape[1] < 2:
        raise InputTensorError(f"shadow: vertices must be (P, V >= 2, 3), got {tuple(vertices.shape)}")
    c = ellipsoids.centers
    if c.dim() < 2 or c.shape[-1] != 3:
        raise SceneError(f"shadow: ellipsoid centers must be (..., S, 3), got {tuple(c.shape)}")
    if ellipsoids.semi_axes.shape != c.shape or ellipsoids.rotations.shape != (*c.shape, 3):
        raise SceneError(
            f"shadow: ellipsoid semi_axes {tuple(ellipsoids.semi_axes.shape)} / rotations "
            f"{tuple(ellipsoids.rotations.shape)} do not match centers {tuple(c.shape)}"
        )
    if not (wavelength > 0):
        raise InputTensorError(f"shadow: wavelength must be > 0, got {wavelength}")


def leg_basis(u: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Orthonormal basis ``(e1, e2)`` of the plane normal to unit vectors ``u`` ``(N, 3)``."""
    ref = torch.zeros_like(u)
    use_z = u[:, 2].abs() < 0.9
    ref[:, 2] = use_z.to(u.dtype)
    ref[:, 0] = (~use_z).to(u.dtype)
    e1 = torch.linalg.cross(ref, u)
    e1 = e1 / e1.norm(dim=-1, keepdim=True).clamp(min=1e-30)
    return e1, torch.linalg.cross(u, e1)


def silhouette_clearance(
    rel: torch.Tensor, t: torch.Tensor, u: torch.Tensor, e1: torch.Tensor, e2: torch.Tensor,
    shape: torch.Tensor,
) -> torch.Tensor:
    """Signed clearance of a leg from an ellipsoid's silhouette (``docs/shadowing.md``, "Model").

    Args:
        rel: ``(N, 3)`` ellipsoid centre minus the leg's start.
        t: ``(N,)`` ``rel . u``: distance along the leg to the point of closest approach.
        u: ``(N, 3)`` unit direction of the leg.
        e1: ``(N, 3)`` with ``e2``, an orthonormal basis of the plane normal to ``u`` (:func:`leg_basis`).
        e2: see ``e1``.
        shape: ``(N, 3, 3)`` shape matrix ``M = R diag(s^2) R^T`` (the ellipsoid is ``(x - c)^T M^-1 (x - c) <= 1``).

    Returns:
        ``(N,)`` clearance in metres, positive when the leg passes inside the silhouette (obstructed).
    """
    w = t[:, None] * u - rel  # from the centre to the leg, normal to the leg
    me1, me2 = matvec(shape, e1), matvec(shape, e2)
    n11, n12, n22 = dot(e1, me1), dot(e1, me2), dot(e2, me2)
    # Principal axes of the silhouette ellipse (2x2 symmetric eigenproblem, closed form).
    mean = 0.5 * (n11 + n22)
    dev = torch.sqrt((0.5 * (n11 - n22)) ** 2 + n12**2)
    tiny = torch.finfo(u.dtype).tiny ** 0.5
    a2 = (mean + dev).clamp(min=tiny)
    b2 = (mean - dev).clamp(min=tiny)
    phi = 0.5 * torch.atan2(2 * n12, n11 - n22)
    w1, w2 = dot(w, e1), dot(w, e2)
    cp, sp = torch.cos(phi), torch.sin(phi)
    x = w1 * cp + w2 * sp
    y = -w1 * sp + w2 * cp
    r2 = x * x / a2 + y * y / b2  # (normalized radius)^2: 1 on the silhouette
    rho = torch.sqrt(x * x + y * y)
    # Boundary radius along the direction from the centre to the leg; at the centre itself (no
    # direction) the semi-minor axis, the nearest edge.
    centred = rho <= tiny
    ex = torch.where(centred, torch.zeros_like(x), x / rho.clamp(min=tiny))
    ey = torch.where(centred, torch.ones_like(y), y / rho.clamp(min=tiny))
    rho_b = torch.rsqrt(ex * ex / a2 + ey * ey / b2)
    outside = rho_b - rho  # radial distance to the boundary: negative outside, positive inside
    grad = 2 * torch.sqrt(x * x / (a2 * a2) + y * y / (b2 * b2))
    sampson = (1 - r2) / grad.clamp(min=tiny)
    chord_y = torch.sqrt(b2) * torch.sqrt((1 - x * x / a2).clamp(min=0)) - y.abs()
    chord_x = torch.sqrt(a2) * torch.sqrt((1 - y * y / b2).clamp(min=0)) - x.abs()
    # Every candidate over-estimates the distance from inside; the radial one is exact for circles.
    inside = torch.minimum(torch.minimum(sampson, outside), torch.minimum(chord_x, chord_y))
    return torch.where(r2 >= 1, outside, inside)


def _taper(nu: torch.Tensor, nu_full: float, nu_cut: float) -> torch.Tensor:
    """Weight of ``F - 1``: 1 for ``nu >= -nu_full``, 0 for ``nu <= -nu_cut``, raised cosine between."""
    s = ((-nu - nu_full) / (nu_cut - nu_full)).clamp(0, 1)
    return 0.5 * (1 + torch.cos(math.pi * s))


def shadow_transmission(
    vertices: torch.Tensor,
    ellipsoids: Ellipsoids,
    wavelength: float,
    *,
    segments_per_person: int = 16,
    nu_full: float = 3.0,
    nu_cut: float = 5.0,
    combine: str = "dominant",
) -> torch.Tensor:
    """Field transmission of each static path through the people's body segments.

    Legs far from every person and segment are culled first (``docs/shadowing.md``, "Cost"); one knife-edge
    factor is then evaluated per (snapshot, path, leg, person).

    Args:
        vertices: ``(P, V, 3)`` path vertices (radar centre, interaction points, radar centre; padded by
            repeating the last vertex), world frame, metres.
        ellipsoids: body segments ``(..., S)`` at the snapshot times.
        wavelength: carrier wavelength, metres.
        segments_per_person: segments per person, for the cull's bounding spheres.
        nu_full: ``F - 1`` is applied in full for ``nu >= -nu_full``.
        nu_cut: and not at all for ``nu <= -nu_cut`` (raised-cosine taper between); also the cull's margin.
        combine: ``"dominant"`` (per person and leg, the segment with the largest ``nu``) or ``"product"``
            (the product of every segment's factor).

    Returns:
        ``(..., P)`` complex transmission (complex64 for float32 ellipsoids), 1 where no segment is near.

    Raises:
        InputTensorError: ``vertices`` is not ``(P, V, 3)`` or the wavelength is not positive.
        SceneError: the ellipsoid tensors do not have matching shapes.
    """
    _check_inputs(vertices, ellipsoids, wavelength)
    if combine not in ("dominant", "product"):
        raise InputTensorError(f"shadow: combine must be 'dominant' or 'product', got {combine!r}")
    if not (0 <= nu_full < nu_cut):
        raise InputTensorError(f"shadow: need 0 <= nu_full < nu_cut, got {nu_full}, {nu_cut}")

    def leg(v: torch.Tensor) -> torch.Tensor:
        return _leg_transmission(v, ellipsoids, wavelength, segments_per_person=segments_per_person,
                                 nu_full=nu_full, nu_cut=nu_cut, combine=combine)

    # Most static paths go radar -> point -> radar (diffuse cells, small-face PO, first-order
    # images): out and back along one line, whose factor is the same both ways. Their transmission
    # is the square of the one-way leg's, traced once (and their padded zero-length legs not at all).
    if vertices.shape[1] < 3:
        return leg(vertices)
    single = (vertices[:, 2:] - vertices[:, :1]).abs().amax(dim=(-1, -2)) == 0
    if not bool(single.any()):
        return leg(vertices)
    cplx = torch.complex64 if ellipsoids.centers.dtype == torch.float32 else torch.complex128
    t = torch.ones(*ellipsoids.centers.shape[:-2], vertices.shape[0], dtype=cplx, device=ellipsoids.centers.device)
    idx = single.nonzero()[:, 0]
    one_way = leg(vertices[idx, :2])
    t[..., idx.to(t.device)] = one_way * one_way
    rest = (~single).nonzero()[:, 0]
    if rest.numel():
        t[..., rest.to(t.device)] = leg(vertices[rest])
    return t


def _leg_transmission(
    vertices: torch.Tensor, ellipsoids: Ellipsoids, wavelength: float, *, segments_per_person: int,
    nu_full: float, nu_cut: float, combine: str,
) -> torch.Tensor:
    """:func:`shadow_transmission` of every leg of every path (the product over its legs)."""
    centres = ellipsoids.centers
    dtype, device = centres.dtype, centres.device
    cplx = torch.complex64 if dtype == torch.float32 else torch.complex128
    batch = centres.shape[:-2]
    s_count = centres.shape[-2]
    num_p = vertices.shape[0]
    nb = math.prod(batch)
    out_log = torch.zeros(nb * num_p, dtype=cplx, device=device)
    if s_count == 0 or num_p == 0 or nb == 0:
        return out_log.exp().reshape(*batch, num_p)
    c = centres.reshape(nb, s_count, 3)
    semi = ellipsoids.semi_axes.reshape(nb, s_count, 3).to(dtype)
    rot = ellipsoids.rotations.reshape(nb, s_count, 3, 3).to(dtype)

    v = vertices.to(device=device, dtype=dtype)
    a_pts = v[:, :-1]  # (P, Lg, 3)
    seg = v[:, 1:] - a_pts
    length = seg.norm(dim=-1)  # (P, Lg)
    u = seg / length.clamp(min=1e-12)[..., None]
    num_legs = a_pts.shape[1]
    # Largest clearance at which |nu| reaches nu_cut on a leg (at its middle): nu_cut sqrt(lambda L / 8).
    margin = nu_cut * torch.sqrt(wavelength * length / 8)
    e1, e2 = leg_basis(u.reshape(-1, 3))
    e1, e2 = e1.reshape(u.shape), e2.reshape(u.shape)
    shape_all = rot @ torch.diag_embed(semi * semi) @ rot.transpose(-1, -2)  # (nb, S, 3, 3)
    seg_r = semi.amax(-1)  # (nb, S) bounding-sphere radius of each segment

    g = segments_per_person if segments_per_person > 0 and s_count % segments_per_person == 0 else s_count
    ng = s_count // g
    # Work relative to the first vertex: float32 keeps millimetres for rooms of tens of metres.
    origin = v[0, 0]
    c0 = c - origin
    a0 = (a_pts - origin).reshape(-1, 3)
    uf, lf, mf = u.reshape(-1, 3), length.reshape(-1), margin.reshape(-1)

    # Cull 1: each person's sphere over the whole batch (its segments at every snapshot) against
    # every leg segment; keeps the legs that any person can reach.
    cb = c0.reshape(nb, ng, g, 3).transpose(0, 1).reshape(ng, nb * g, 3)
    pc = cb.mean(1)  # (ng, 3)
    pr = ((cb - pc[:, None]).norm(dim=-1) + seg_r.reshape(nb, ng, g).transpose(0, 1).reshape(ng, -1)).amax(-1)
    rel = pc[:, None] - a0  # (ng, P*Lg, 3)
    t = torch.minimum(dot(rel, uf).clamp(min=0), lf)
    reach = pr[:, None] + mf
    off = rel - t[..., None] * uf
    legs = torch.nonzero((dot(off, off) < reach * reach).any(0) & (lf > 0))[:, 0]
    if legs.shape[0] == 0:
        return out_log.exp().reshape(*batch, num_p)
    a_k, u_k, l_k = a0[legs], uf[legs], lf[legs]

    # Cull 2: every segment at every snapshot against those legs, as matrix products:
    # d1 = (c - a) . u along the leg, perpendicular distance^2 = |c - a|^2 - d1^2.
    cs = c0.reshape(-1, 3)  # (nb*S, 3)
    r_s = seg_r.reshape(-1)
    au = dot(a_k, u_k)
    a2 = dot(a_k, a_k)
    c2 = dot(cs, cs)
    half_lam, inv_l = 0.5 * wavelength, 1 / l_k.clamp(min=1e-12)
    hits = []
    # Chunks of ~2**18 (segment, leg) pairs: the dozen full-size passes below stay in the cache.
    chunk = _CULL_CHUNK if device.type == "cpu" else _CULL_CHUNK_GPU
    rows = max(1, int(chunk // max(1, legs.shape[0])))
    for r0 in range(0, cs.shape[0], rows):
        cc = cs[r0:r0 + rows]
        d1 = cc @ u_k.T - au
        perp2 = c2[r0:r0 + rows, None] - 2 * (cc @ a_k.T) + a2 - d1 * d1
        # Reach: the segment's radius plus the clearance where |nu| = nu_cut at this d1
        # (nu_cut sqrt(lambda d1 d2 / (2 L))); 1e-6 m^2 slack for the rounding of the expanded square.
        reach = r_s[r0:r0 + rows, None] + nu_cut * torch.sqrt((half_lam * d1 * (l_k - d1) * inv_l).clamp(min=0))
        idx = torch.nonzero((d1 > 0) & (d1 < l_k) & (perp2 < reach * reach + 1e-6))
        idx[:, 0] += r0
        hits.append(idx)
    idx = torch.cat(hits)
    if idx.shape[0] == 0:
        return out_log.exp().reshape(*batch, num_p)
    # The candidates are carried as index tensors and gathered once per stage (boolean masks over
    # nine tensors per stage cost more than the geometry itself: ~0.5 M candidates per 16 frames
    # in the two-walker corridor). Flat index_select gathers: advanced indexing with (bi, si)
    # pairs costs several times more. Integer division of half a million int64 indices costs
    # more than the geometry too, so every index the later stages need is a lookup in a small
    # per-row (snapshot, segment) or per-leg table instead.
    seg_row = idx[:, 0]  # snapshot * S + segment
    leg_k = idx[:, 1]  # index into the surviving legs
    row_ids = torch.arange(nb * s_count, device=device)
    row_b = row_ids // s_count
    # The (snapshot, path, leg, person) table key of a candidate is row_key[seg_row] + leg_key[leg_k].
    row_key = row_b * (num_p * num_legs * ng) + (row_ids % s_count) // g
    leg_key = legs * ng
    # Vectors are gathered component-major ((3, n), used through ``.T`` views whose components
    # are contiguous): gathering three rows of n is ~3x cheaper than n rows of three.
    a_t, u_t, c_t = a_k.T.contiguous(), u_k.T.contiguous(), cs.T.contiguous()
    direction = u_t.index_select(1, leg_k).T
    leg_len = l_k.index_select(0, leg_k)
    rel = (c_t.index_select(1, seg_row) - a_t.index_select(1, leg_k)).T
    d1 = dot(rel, direction)
    # The exact d1 (not the expanded form of the cull) decides; a candidate outside the leg is
    # dropped with the dominance prune below (or on its own without it).
    inside = (d1 > 0) & (d1 < leg_len)
    table = nb * num_p * num_legs * ng
    if combine == "dominant" and table <= _DENSE_TABLE_MAX:
        # Prune segments that cannot be their person's dominant edge on this leg: the clearance
        # lies between (smallest semi-axis - distance) and (largest semi-axis - distance) (the
        # silhouette contains the disk of the smallest semi-axis and lies in the sphere of the largest).
        k_nu = torch.sqrt(2.0 / wavelength * (1 / d1.clamp(min=1e-9) + 1 / (leg_len - d1).clamp(min=1e-9)))
        perp = torch.sqrt((dot(rel, rel) - d1 * d1).clamp(min=0))
        key = row_key.index_select(0, seg_row) + leg_key.index_select(0, leg_k)
        lower = torch.where(inside, k_nu * (semi.amin(-1).reshape(-1).index_select(0, seg_row) - perp), -math.inf)
        best_lower = torch.full((table,), -math.inf, dtype=dtype, device=device)
        best_lower.scatter_reduce_(0, key, lower, reduce="amax")
        # 1e-4 of slack in nu for rounding; ties keep both.
        inside &= k_nu * (r_s.index_select(0, seg_row) - perp) >= best_lower.index_select(0, key) - 1e-4
    sel = inside.nonzero()[:, 0]
    seg_row, leg_k, d1, leg_len = (x.index_select(0, sel) for x in (seg_row, leg_k, d1, leg_len))
    rel, direction = (x.T.index_select(1, sel).T for x in (rel, direction))
    flat_leg = legs.index_select(0, leg_k)
    e1f, e2f = (e.reshape(-1, 3).T.index_select(1, flat_leg).T for e in (e1, e2))
    h = silhouette_clearance(rel, d1, direction, e1f, e2f, shape_all.reshape(-1, 9).index_select(0, seg_row).reshape(-1, 3, 3))
    d2 = leg_len - d1
    nu = h * torch.sqrt(2.0 / wavelength * (1 / d1.clamp(min=1e-9) + 1 / d2.clamp(min=1e-9)))
    keep = torch.nonzero(nu > -nu_cut)[:, 0]
    if keep.shape[0] == 0:
        return out_log.exp().reshape(*batch, num_p)
    nu, seg_row, leg_k = nu.index_select(0, keep), seg_row.index_select(0, keep), leg_k.index_select(0, keep)
    key = row_key.index_select(0, seg_row) + leg_key.index_select(0, leg_k)
    if combine == "dominant":
        # One knife edge per (snapshot, path, leg, person): the segment with the largest nu.
        if table <= _DENSE_TABLE_MAX:  # a dense table is cheaper than sorting the keys
            dense = torch.full((table,), -math.inf, dtype=nu.dtype, device=device)
            dense.scatter_reduce_(0, key, nu, reduce="amax")
            key = torch.nonzero(dense > -math.inf)[:, 0]
            nu = dense.index_select(0, key)
        else:
            key, inv = torch.unique(key, return_inverse=True)
            nu = torch.full(key.shape, -math.inf, dtype=nu.dtype, device=device).scatter_reduce_(
                0, inv, nu, reduce="amax")
    nu64 = nu.to(torch.float64)
    f = 1 + _taper(nu64, nu_full, nu_cut) * (_knife_edge_fast(nu64) - 1)
    if combine == "dominant" and table <= _DENSE_TABLE_MAX:
        # One factor per key: a dense (snapshot * path, leg * person) table of factors (1 where no
        # edge) and a product along its rows; cheaper than complex logs, a sum and an exp.
        factors = torch.ones(table, dtype=torch.complex128, device=device)
        factors[key] = f
        return factors.reshape(nb * num_p, num_legs * ng).prod(dim=-1).to(cplx).reshape(*batch, num_p)
    row = key // (num_legs * ng)  # snapshot * P + path
    # Product over legs (and segments or people) as a sum of complex logs (|F| > 0 for finite nu).
    out_log = out_log.to(torch.complex128).index_add_(0, row, torch.log(f))
    return out_log.exp().to(cplx).reshape(*batch, num_p)


def shadow_correction_paths(
    static: Paths,
    vertices: torch.Tensor,
    ellipsoids: Ellipsoids,
    wavelength: float,
    *,
    tol: float = SHADOW_TOL,
    **options: Any,
) -> Paths:
    """Paths to add to the people's so that static + correction = the shadowed static paths.

    An affected static path ``p`` gets a path with its delay, amplitude ``(T - 1) a`` and ``delay_rate = 0`` (``T``
    held within the frame); only paths with ``|T - 1| > tol`` somewhere in the batch are returned.

    Args:
        static: the static paths ``(P, RX)`` (no batch dims), aligned with ``vertices``.
        vertices: ``(P, V, 3)`` their geometry (:func:`shadow_transmission`).
        ellipsoids: body segments ``(..., S)`` at the snapshot times.
        wavelength: carrier wavelength, metres.
        tol: smallest ``|T - 1|`` kept (1e-3: -60 dB relative to the path).
        **options: ``segments_per_person``, ``nu_full``, ``nu_cut``, ``combine`` of :func:`shadow_transmission`.

    Returns:
        :class:`Paths` ``(..., P', RX)`` with ``kind = 0`` and ``mask = True``.

    Raises:
        InputTensorError: ``static`` is not ``(P, RX)`` or does not match ``vertices``.
    """
    if static.delay_s.dim() != 2 or static.amplitude.shape != static.delay_s.shape:
        raise InputTensorError(f"shadow: static paths must be (P, RX), got {tuple(static.delay_s.shape)}")
    if vertices.shape[0] != static.delay_s.shape[0]:
        raise InputTensorError(
            f"shadow: {vertices.shape[0]} path geometries for {static.delay_s.shape[0]} static paths"
        )
    return correction_paths(static, shadow_transmission(vertices, ellipsoids, wavelength, **options), tol=tol)


def correction_paths(static: Paths, t: torch.Tensor, *, tol: float = SHADOW_TOL) -> Paths:
    """The correction paths of :func:`shadow_correction_paths` for transmissions ``t`` ``(..., P)`` of ``static``."""
    batch = t.shape[:-1]
    dev = (t - 1).abs().reshape(-1, t.shape[-1])
    sel = torch.nonzero((dev > tol).any(0))[:, 0] if dev.shape[0] else torch.zeros(0, dtype=torch.long)
    sel = sel.to(static.delay_s.device)
    amp = static.amplitude[sel]
    corr = (t[..., sel].to(amp.device) - 1).to(amp.dtype)[..., None] * amp
    delay = static.delay_s[sel].expand(*batch, -1, -1).clone()
    n = int(sel.shape[0])
    return Paths(
        delay_s=delay,
        delay_rate=torch.zeros_like(delay),
        amplitude=corr,
        kind=torch.zeros(*batch, n, dtype=torch.int8, device=delay.device),
        mask=torch.ones(*batch, n, dtype=torch.bool, device=delay.device),
    )


@functools.lru_cache(maxsize=4)
def _gauss_legendre(nodes: int) -> tuple[torch.Tensor, torch.Tensor]:
    """Gauss-Legendre nodes and weights on [-1, 1] (float64), cached: numpy solves an eigenproblem."""
    import numpy as np  # reference computation, outside the simulation's hot path

    x, w = np.polynomial.legendre.leggauss(nodes)
    return torch.from_numpy(x), torch.from_numpy(w)


def ellipse_obstacle_transmission(
    offset: torch.Tensor, semi_axes: tuple[float, float], d1: float, d2: float, wavelength: float,
    *, nodes: int = 400,
) -> torch.Tensor:
    """Physical-optics (Fresnel-Kirchhoff) transmission past one elliptic opaque screen.

    By Babinet, ``T = 1 - (j / 2) iint_ellipse exp(-j pi |nu|^2 / 2) d^2 nu`` in Fresnel-zone units; the
    reference of the docs' walker figure (a centred disk gives ``|T| = 1``, the Poisson spot).

    Args:
        offset: ``(N, 2)`` ellipse centre relative to the leg, along the ellipse's axes, metres.
        semi_axes: the ellipse's semi-axes along those axes, metres.
        d1: distance from the leg's start to the screen, metres.
        d2: distance from the screen to the leg's end, metres.
        wavelength: metres.
        nodes: Gauss-Legendre nodes (the outer integral, in ``y = b sin(theta)``).

    Returns:
        ``(N,)`` complex128 transmission.
    """
    scale = math.sqrt(2.0 / wavelength * (1 / d1 + 1 / d2))
    a, b = semi_axes[0] * scale, semi_axes[1] * scale
    off = offset.to(torch.float64) * scale
    xg, wg = _gauss_legendre(nodes)
    theta = xg * (math.pi / 2)
    wt = wg * (math.pi / 2)
    yy = b * torch.sin(theta)  # (K,)
    jac = b * torch.cos(theta)
    half = a * torch.cos(theta)
    x0 = off[:, 0:1]
    y = off[:, 1:2] + yy  # (N, K)
    c1, s1 = fresnel_integrals(x0 + half)
    c0, s0 = fresnel_integrals(x0 - half)
    inner = torch.complex(c1 - c0, -(s1 - s0))  # int exp(-j pi x^2/2) dx across the chord
    integrand = inner * torch.polar(torch.ones_like(y), -0.5 * math.pi * y * y) * jac * wt
    return 1 - 0.5j * integrand.sum(-1)
