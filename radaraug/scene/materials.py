"""Building materials (ITU-R P.2040-3, Table 3) and their Fresnel reflection, in torch.

``eps = a f^b - j 17.98 c f^(d-1)`` (f in GHz), time convention ``exp(+j omega t)``. A name
``"plasterboard@0.0125"`` is a 12.5 mm slab in air. Conventions and signs: ``docs/scenes.md``, "Materials".
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, replace

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import SceneError

_COS_MIN = 1e-6  # keeps grazing incidence finite for eps = 1 (absorber) without changing physics


@dataclass(frozen=True)
class Material:
    """An ITU-R P.2040 material: ``eps' = a f^b``, ``sigma = c f^d`` with ``f`` in GHz.

    Args:
        name: material name (a key of :data:`MATERIALS` for the built-in ones).
        a, b: real relative permittivity ``eps' = a * f_GHz**b``.
        c, d: conductivity ``sigma = c * f_GHz**d`` in S/m.
        thickness_m: slab thickness in metres; None for a half-space (a wall whose back face does not matter).
        eps_complex_override: a measured ``eps' - j eps''`` used at every frequency (e.g. skin at 60 GHz).
        valid_GHz: frequency range of the ITU-R fit; outside it :meth:`permittivity` warns and extrapolates.
    """

    name: str
    a: float
    b: float
    c: float
    d: float
    thickness_m: float | None = None
    eps_complex_override: complex | None = None
    valid_GHz: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if not self.name or "@" in self.name:
            raise SceneError(f"material name {self.name!r} must be non-empty and must not contain '@'")
        if self.thickness_m is not None and not (math.isfinite(self.thickness_m) and self.thickness_m > 0):
            raise SceneError(f"material {self.name!r}: thickness_m must be a positive number or None, "
                             f"got {self.thickness_m!r}")

    @property
    def key(self) -> str:
        """Name as stored in a scene: ``name`` for a half-space, ``name@thickness`` for a slab."""
        return self.name if self.thickness_m is None else f"{self.name}@{float(self.thickness_m)!r}"

    def with_thickness(self, thickness_m: float | None) -> Material:
        """The same material as a slab of ``thickness_m`` metres (None: half-space)."""
        return replace(self, thickness_m=None if thickness_m is None else float(thickness_m))

    def permittivity(self, frequency_Hz: float) -> complex:
        """Relative complex permittivity ``eps' - j eps''`` at ``frequency_Hz``.

        Warns (UserWarning) outside the material's ITU-R range, e.g. brick above 40 GHz.
        """
        if self.eps_complex_override is not None:
            return complex(self.eps_complex_override)
        if not (math.isfinite(frequency_Hz) and frequency_Hz > 0):
            raise SceneError(f"material {self.name!r}: frequency must be positive, got {frequency_Hz!r}")
        f_ghz = frequency_Hz / 1e9
        if self.valid_GHz is not None and not (self.valid_GHz[0] <= f_ghz <= self.valid_GHz[1]):
            warnings.warn(
                f"material {self.name!r}: ITU-R P.2040 defines it only for {self.valid_GHz[0]:g}-"
                f"{self.valid_GHz[1]:g} GHz; extrapolating to {f_ghz:g} GHz",
                UserWarning, stacklevel=2,
            )
        eps_real = self.a * f_ghz ** self.b
        sigma = self.c * f_ghz ** self.d
        return complex(eps_real, -17.98 * sigma / f_ghz)

    def conductivity(self, frequency_Hz: float) -> float:
        """Conductivity ``sigma`` in S/m at ``frequency_Hz`` (from the override if set)."""
        f_ghz = frequency_Hz / 1e9
        if self.eps_complex_override is not None:
            return -complex(self.eps_complex_override).imag * f_ghz / 17.98
        return self.c * f_ghz ** self.d

    def reflection(
        self, cos_theta_i: torch.Tensor | float, frequency_Hz: float,
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """``(Gamma_TE, Gamma_TM)`` of this material (half-space or slab) at the given incidence."""
        eps = self.permittivity(frequency_Hz)
        if self.thickness_m is None:
            return fresnel_coefficients(eps, cos_theta_i)
        return slab_reflection(eps, self.thickness_m, frequency_Hz, cos_theta_i)


def _itu(name: str, a: float, b: float, c: float, d: float, lo: float, hi: float) -> Material:
    return Material(name, a, b, c, d, valid_GHz=(lo, hi))


MATERIALS: dict[str, Material] = {
    m.name: m for m in (
        # ITU-R P.2040-3 Table 3 (a, b, c, d; frequency range in GHz).
        _itu("concrete", 5.24, 0.0, 0.0462, 0.7822, 1.0, 100.0),
        _itu("brick", 3.91, 0.0, 0.0238, 0.16, 1.0, 40.0),
        _itu("plasterboard", 2.73, 0.0, 0.0085, 0.9395, 1.0, 100.0),
        _itu("wood", 1.99, 0.0, 0.0047, 1.0718, 0.001, 100.0),
        _itu("glass", 6.31, 0.0, 0.0036, 1.3394, 0.1, 100.0),
        _itu("ceiling_board", 1.48, 0.0, 0.0011, 1.075, 1.0, 100.0),
        _itu("chipboard", 2.58, 0.0, 0.0217, 0.78, 1.0, 100.0),
        _itu("floorboard", 3.66, 0.0, 0.0044, 1.3515, 50.0, 100.0),
        _itu("metal", 1.0, 0.0, 1e7, 0.0, 1.0, 100.0),
        # Dry human skin at 60 GHz from the Gabriel et al. (1996) parametric model
        # (C. Gabriel, S. Gabriel, E. Corthout, "The dielectric properties of biological tissues",
        # Phys. Med. Biol. 41, 1996), as tabulated by T. Wu, T. S. Rappaport, C. M. Collins,
        # "Safe for generations to come", IEEE Microwave Magazine 16(2), 2015: 7.98 - j10.90.
        # Used unchanged across the 57-64 GHz band (it varies by a few % there).
        Material("skin", 7.98, 0.0, 0.0, 0.0, eps_complex_override=complex(7.98, -10.90)),
        # Free space: Gamma = 0 exactly at every angle (a perfect absorber, for tests and for
        # surfaces that should not scatter).
        Material("absorber", 1.0, 0.0, 0.0, 0.0),
    )
}
"""Built-in materials by name. Add your own with :func:`register_material`."""


def register_material(material: Material, *, overwrite: bool = False) -> None:
    """Add ``material`` to :data:`MATERIALS` so scenes can name it.

    Raises:
        SceneError: the name exists and ``overwrite`` is False, or the material carries a
            thickness (thickness belongs to the surface: use ``name@thickness``).
    """
    if material.thickness_m is not None:
        raise SceneError(f"register_material: register {material.name!r} without thickness; "
                         f"name surfaces '{material.name}@<metres>' instead")
    if material.name in MATERIALS and not overwrite:
        raise SceneError(f"register_material: material {material.name!r} already exists (overwrite=True)")
    MATERIALS[material.name] = material


def parse_material_key(key: str) -> tuple[str, float | None]:
    """Split ``"name"`` or ``"name@thickness_m"`` into ``(name, thickness_m or None)``."""
    if not isinstance(key, str):
        raise SceneError(f"material name must be a string, got {type(key).__name__}")
    name, sep, rest = key.partition("@")
    name = name.strip()
    if not sep:
        return name, None
    try:
        thickness = float(rest.strip().removesuffix("m"))
    except ValueError:
        raise SceneError(f"material {key!r}: thickness after '@' must be a number of metres") from None
    if not (math.isfinite(thickness) and thickness > 0):
        raise SceneError(f"material {key!r}: thickness must be positive, got {thickness!r}")
    return name, thickness


def get_material(name: str) -> Material:
    """The material called ``name`` (``"name"`` or ``"name@thickness_m"``).

    Raises:
        SceneError: unknown name (the message lists the known ones) or a bad thickness.
    """
    if isinstance(name, Material):
        return name
    base, thickness = parse_material_key(name)
    try:
        material = MATERIALS[base]
    except KeyError:
        raise SceneError(
            f"unknown material {base!r}; known materials: {', '.join(sorted(MATERIALS))}"
        ) from None
    return material if thickness is None else material.with_thickness(thickness)


def material_table(
    names: Sequence[str],
    frequency_Hz: float,
    *,
    device: torch.device | str | None = None,
    dtype: torch.dtype = torch.float32,
) -> tuple[torch.Tensor, torch.Tensor]:
    """Per-material tensors for :func:`reflection_coefficients`.

    Args:
        names: material keys, e.g. ``SceneGeometry.materials``.
        frequency_Hz: frequency at which permittivities are evaluated (the carrier).
        device: device of the returned tensors.
        dtype: real dtype; the permittivity is the matching complex dtype.

    Returns:
        ``(eps, thickness_m)``: ``(M,)`` complex permittivities and ``(M,)`` real thicknesses,
        NaN for half-spaces.
    """
    mats = [get_material(n) for n in names]
    eps = torch.tensor([m.permittivity(frequency_Hz) for m in mats], dtype=_complex_of(dtype), device=device)
    thick = torch.tensor([math.nan if m.thickness_m is None else m.thickness_m for m in mats],
                         dtype=dtype, device=device)
    return eps, thick


def _complex_of(dtype: torch.dtype) -> torch.dtype:
    if dtype.is_complex:
        return dtype
    return torch.complex128 if dtype == torch.float64 else torch.complex64


def _prepare(eps: torch.Tensor | complex, cos_theta_i: torch.Tensor | float) -> tuple[torch.Tensor, torch.Tensor]:
    """Complex eps and clamped real cos on one device, at the precision of the tensor inputs.

    Python scalars do not set the precision; a float64/complex128 tensor anywhere makes the
    result complex128 (precision the caller asked for is never dropped silently).
    """
    cos = torch.as_tensor(cos_theta_i)
    if not cos.is_floating_point():
        cos = cos.to(torch.get_default_dtype())
    real = cos.dtype
    if isinstance(eps, torch.Tensor):
        eps_real = eps.real.dtype if eps.is_complex() else eps.dtype
        if eps_real.is_floating_point:
            real = torch.promote_types(real, eps_real) if isinstance(cos_theta_i, torch.Tensor) else eps_real
        device = cos.device if isinstance(cos_theta_i, torch.Tensor) else eps.device
        eps_t = eps.to(device=device, dtype=_complex_of(real))
    else:
        device = cos.device
        eps_t = torch.as_tensor(complex(eps), dtype=_complex_of(real), device=device)
    cos = cos.to(device=device, dtype=real)
    return eps_t, cos.abs().clamp(_COS_MIN, 1.0)


def _half_space(eps: torch.Tensor, cos: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """``(Gamma_TE, Gamma_TM, sqrt(eps - sin^2))`` for a half-space."""
    # eps - sin^2 written as (eps - 1) + cos^2 so that eps = 1 gives exactly cos^2 (no cancellation).
    root = torch.sqrt((eps - 1) + cos * cos)  # principal root: Re >= 0, Im <= 0 for a lossy medium
    gamma_te = (cos - root) / (cos + root)
    gamma_tm = (eps * cos - root) / (eps * cos + root)
    return gamma_te, gamma_tm, root


def fresnel_coefficients(
    eps: torch.Tensor | complex, cos_theta_i: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor]:
    """Fresnel reflection of a plane wave from air onto a half-space (ITU-R P.2040).

    Args:
        eps: relative complex permittivity ``eps' - j eps''`` (any shape broadcastable with
            ``cos_theta_i``).
        cos_theta_i: cosine of the incidence angle from the surface normal (sign ignored).

    Returns:
        ``(Gamma_TE, Gamma_TM)`` complex field reflection coefficients, broadcast shape, complex64
        for float32 input and complex128 for float64 (signs: ``docs/scenes.md``).
    """
    eps_t, cos = _prepare(eps, cos_theta_i)
    gamma_te, gamma_tm, _ = _half_space(eps_t, cos)
    return gamma_te, gamma_tm


def _slab(
    eps: torch.Tensor | complex,
    thickness_m: torch.Tensor | float,
    frequency_Hz: torch.Tensor | float,
    cos_theta_i: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
    """``(R_TE, R_TM, T_TE, T_TM)`` of a slab in air (ITU-R P.2040 single slab)."""
    eps_t, cos = _prepare(eps, cos_theta_i)
    r_te, r_tm, root = _half_space(eps_t, cos)
    d = torch.as_tensor(thickness_m, device=cos.device).to(cos.dtype)
    f = torch.as_tensor(frequency_Hz, device=cos.device).to(cos.dtype)
    # Electrical thickness q = (2 pi d / lambda) sqrt(eps - sin^2): the phase (and, through the
    # negative imaginary part of the root, the loss) of one crossing of the slab.
    q = (2 * math.pi / SPEED_OF_LIGHT) * (d * f) * root
    e1 = torch.exp(-1j * q)
    e2 = e1 * e1
    out = []
    for r in (r_te, r_tm):
        den = 1 - r * r * e2
        out.append((r * (1 - e2) / den, (1 - r * r) * e1 / den))
    return out[0][0], out[1][0], out[0][1], out[1][1]


def slab_reflection(
    eps: torch.Tensor | complex,
    thickness_m: torch.Tensor | float,
    frequency_Hz: torch.Tensor | float,
    cos_theta_i: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor]:
    """Reflection of a homogeneous slab in air, all internal reflections summed (ITU-R P.2040-3).

    Phase reference: the slab's front face. A thick lossy slab tends to the half-space value.

    Args:
        eps: relative complex permittivity of the slab.
        thickness_m: slab thickness in metres.
        frequency_Hz: frequency (sets the wavelength).
        cos_theta_i: cosine of the incidence angle (sign ignored).

    Returns:
        ``(Gamma_TE, Gamma_TM)``, broadcast over all arguments.
    """
    r_te, r_tm, _, _ = _slab(eps, thickness_m, frequency_Hz, cos_theta_i)
    return r_te, r_tm


def slab_transmission(
    eps: torch.Tensor | complex,
    thickness_m: torch.Tensor | float,
    frequency_Hz: torch.Tensor | float,
    cos_theta_i: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor]:
    """Field transmission ``(T_TE, T_TM)`` through a slab in air (ITU-R P.2040-3), as :func:`slab_reflection`."""
    _, _, t_te, t_tm = _slab(eps, thickness_m, frequency_Hz, cos_theta_i)
    return t_te, t_tm


def reflection_coefficients(
    material_eps: torch.Tensor,
    material_thickness: torch.Tensor,
    face_material: torch.Tensor,
    cos_theta: torch.Tensor,
    frequency_Hz: torch.Tensor | float,
) -> tuple[torch.Tensor, torch.Tensor]:
    """``(Gamma_TE, Gamma_TM)`` per hit, choosing half-space or slab from each face's material.

    Args:
        material_eps: ``(M,)`` complex permittivities (see :func:`material_table`).
        material_thickness: ``(M,)`` thicknesses in metres; NaN, 0, negative or inf = half-space.
        face_material: ``(...)`` long material index of each hit (or face).
        cos_theta: ``(...)`` cosine of the incidence angle of each hit (sign ignored).
        frequency_Hz: scalar or broadcastable tensor, for the slab phase.

    Returns:
        Complex ``(...)`` tensors, the precision of ``cos_theta``.
    """
    eps = material_eps.to(cos_theta.device)[face_material]
    thick = material_thickness.to(device=cos_theta.device, dtype=cos_theta.dtype)[face_material]
    is_slab = torch.isfinite(thick) & (thick > 0)
    # Evaluate the slab formula with a harmless thickness where the face is a half-space, so no
    # NaN/0-by-0 ever enters the graph (torch.where would otherwise propagate NaN gradients).
    safe_thick = torch.where(is_slab, thick, torch.ones_like(thick))
    r_te, r_tm, _ = _half_space(*_prepare(eps, cos_theta))
    s_te, s_tm, _, _ = _slab(eps, safe_thick, frequency_Hz, cos_theta)
    return torch.where(is_slab, s_te, r_te), torch.where(is_slab, s_tm, r_tm)


__all__ = [
    "MATERIALS",
    "Material",
    "fresnel_coefficients",
    "get_material",
    "material_table",
    "parse_material_key",
    "reflection_coefficients",
    "register_material",
    "slab_reflection",
    "slab_transmission",
]
