"""Physical-optics (PO) scattering of flat facets: closed-form surface integrals.

Scalar Kirchhoff PO, time convention ``exp(+j omega t)``. A facet lit along ``k_i`` and observed toward
``k_s`` has the complex root RCS ``s = sqrt(4 pi) (j / (2 lambda)) Gamma (cos th_i + cos th_s) I(w)``
(``|s|^2 = sigma``), ``I(w)`` the facet integral of ``exp(j w . (r - r_ref))``, ``w = -k (k_i - k_s)``, in
closed form for triangles (Gordon) and parallelograms. Formulas: ``docs/raytracer.md``, "Physical optics".
"""

from __future__ import annotations

import math

import torch

_SMALL_P = 1e-2
"""Below this ``|p| * longest edge`` the triangle integral uses its limit (error ~1e-4)."""


def sinc(x: torch.Tensor) -> torch.Tensor:
    """Unnormalized ``sin(x) / x`` with the limit 1 at 0."""
    small = x.abs() < 1e-4
    safe = torch.where(small, torch.ones_like(x), x)
    return torch.where(small, 1 - x * x / 6, torch.sin(safe) / safe)


def _cexp(phase: torch.Tensor) -> torch.Tensor:
    return torch.polar(torch.ones_like(phase), phase)


def triangle_integral(triangles: torch.Tensor, w: torch.Tensor, ref: torch.Tensor) -> torch.Tensor:
    """``I(w)`` of triangles ``(..., 3, 3)`` for wave vectors ``w`` ``(..., 3)``, phase at ``ref``."""
    r0, r1, r2 = triangles.unbind(-2)
    cr = torch.linalg.cross(r1 - r0, r2 - r0, dim=-1)
    area2 = cr.norm(dim=-1)
    n = cr / area2.clamp_min(1e-30)[..., None]
    p = w - (w * n).sum(-1, keepdim=True) * n
    p2 = (p * p).sum(-1)
    edges = torch.stack([r1 - r0, r2 - r1, r0 - r2], dim=-2)  # (..., 3, 3)
    mids = torch.stack([(r0 + r1) / 2, (r1 + r2) / 2, (r2 + r0) / 2], dim=-2)
    longest = edges.norm(dim=-1).amax(-1)
    out_n = torch.linalg.cross(edges, n[..., None, :].expand_as(edges), dim=-1)  # outward, |a|-long
    wv = w[..., None, :]
    weight = (p[..., None, :] * out_n).sum(-1)
    phase = (wv * (mids - ref[..., None, :])).sum(-1)
    terms = weight * sinc((wv * edges).sum(-1) / 2)
    s = (terms.to(_cdtype(terms)) * _cexp(phase)).sum(-1)
    small = p2.sqrt() * longest < _SMALL_P
    gordon = -1j * s / torch.where(small, torch.ones_like(p2), p2)
    centroid = (r0 + r1 + r2) / 3
    limit = (area2 / 2) * _cexp((w * (centroid - ref)).sum(-1))
    return torch.where(small, limit, gordon)


def parallelogram_integral(e1: torch.Tensor, e2: torch.Tensor, w: torch.Tensor) -> torch.Tensor:
    """``I(w)`` of parallelograms with edges ``e1, e2`` ``(..., 3)``, centred at the phase reference."""
    area = torch.linalg.cross(e1, e2, dim=-1).norm(dim=-1)
    val = area * sinc((w * e1).sum(-1) / 2) * sinc((w * e2).sum(-1) / 2)
    return val.to(_cdtype(val))


def _cdtype(x: torch.Tensor) -> torch.dtype:
    return torch.complex128 if x.dtype == torch.float64 else torch.complex64


def po_prefactor(
    gamma: torch.Tensor, cos_i: torch.Tensor, cos_s: torch.Tensor, wavelength: float,
) -> torch.Tensor:
    """``sqrt(4 pi) j / (2 lambda) * Gamma * (cos_i + cos_s)``, zero where ``cos_s <= 0``."""
    lit = (cos_s > 0) & (cos_i > 0)
    c = torch.where(lit, cos_i + cos_s, torch.zeros_like(cos_i))
    return (1j * math.sqrt(4 * math.pi) / (2 * wavelength)) * gamma * c


def facet_normals(triangles: torch.Tensor) -> torch.Tensor:
    """Unit normals ``(..., 3)`` of triangles ``(..., 3, 3)`` (right-hand rule on vertex order)."""
    r0, r1, r2 = triangles.unbind(-2)
    cr = torch.linalg.cross(r1 - r0, r2 - r0, dim=-1)
    return cr / cr.norm(dim=-1, keepdim=True).clamp_min(1e-30)


def facet_root_rcs(
    triangles: torch.Tensor,
    k_inc: torch.Tensor,
    k_scat: torch.Tensor,
    wavelength: float,
    gamma: torch.Tensor | float = -1.0,
    ref: torch.Tensor | None = None,
    two_sided: bool = True,
) -> torch.Tensor:
    """Complex root RCS ``s`` of each facet, phase referenced at ``ref``.

    Args:
        triangles: ``(..., 3, 3)`` facets.
        k_inc: ``(..., 3)`` unit propagation direction of the incident wave at each facet.
        k_scat: ``(..., 3)`` unit direction from the facet toward the receiver.
        wavelength: metres.
        gamma: reflection coefficient per facet (broadcast), -1 = perfect conductor.
        ref: ``(..., 3)`` phase reference (default: each facet's centroid).
        two_sided: a facet lit from behind scatters too (room walls, meshes of unknown winding).

    Returns:
        Complex ``(...)``; zero for unlit facets and for receivers on the far side.
    """
    n = facet_normals(triangles)
    if ref is None:
        ref = triangles.mean(-2)
    dn = (k_inc * n).sum(-1)
    if two_sided:
        n = torch.where((dn > 0)[..., None], -n, n)  # face the incoming wave
        cos_i = dn.abs()
    else:
        cos_i = -dn
    cos_s = (k_scat * n).sum(-1)
    k = 2 * math.pi / wavelength
    w = -k * (k_inc - k_scat)
    gamma_t = torch.as_tensor(gamma, device=triangles.device)
    return po_prefactor(gamma_t, cos_i, cos_s, wavelength) * triangle_integral(triangles, w, ref)


def plane_wave_rcs(
    triangles: torch.Tensor,
    k_inc: torch.Tensor,
    k_scat: torch.Tensor,
    wavelength: float,
    gamma: torch.Tensor | float = -1.0,
    lit: torch.Tensor | None = None,
    two_sided: bool = False,
) -> torch.Tensor:
    """Far-field PO RCS (m^2) ``|sum_f s_f|^2`` of a facet set for one plane wave (phase reference at the origin).

    ``lit`` (``(F,)`` bool) masks facets shadowed by the rest of the object.
    """
    ref = torch.zeros_like(triangles[..., 0, :])
    s = facet_root_rcs(triangles, k_inc.expand_as(ref), k_scat.expand_as(ref), wavelength, gamma, ref,
                       two_sided=two_sided)
    if lit is not None:
        s = torch.where(lit, s, torch.zeros_like(s))
    return s.sum(-1).abs() ** 2
