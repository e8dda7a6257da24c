"""Diffuse scattering of building materials: Degli-Esposti's effective-roughness (ER) model.

A material scatters ``S^2`` of its reflected power diffusely and keeps ``(1 - S^2)`` specular (field
factor ``sqrt(1 - S^2)``). Model, patterns, ``sigma0`` and the defaults' fit: ``docs/diffuse_clutter.md``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import torch

from radaraug.errors import SceneError
from radaraug.scene.materials import parse_material_key

PATTERNS = ("lambertian", "directive")


@dataclass(frozen=True)
class DiffuseScattering:
    """Effective-roughness parameters of one material.

    Args:
        S: scattering coefficient in ``[0, 1]``, a *field* ratio (``S^2`` of the reflected power is scattered).
        pattern: ``"lambertian"`` or ``"directive"`` (lobe around the specular direction).
        alpha_R: integer lobe exponent of the directive pattern (larger = narrower; Lambertian ignores it).
    """

    S: float = 0.0
    pattern: str = "lambertian"
    alpha_R: int = 4

    def __post_init__(self) -> None:
        if isinstance(self.S, bool) or not isinstance(self.S, (int, float)) or not (0.0 <= self.S <= 1.0):
            raise SceneError(f"diffuse scattering: S must be a number in [0, 1], got {self.S!r}")
        if self.pattern not in PATTERNS:
            raise SceneError(f"diffuse scattering: pattern must be one of {list(PATTERNS)}, got {self.pattern!r}")
        if isinstance(self.alpha_R, bool) or not isinstance(self.alpha_R, int) or not 0 <= self.alpha_R <= 64:
            raise SceneError(f"diffuse scattering: alpha_R must be an integer in [0, 64], got {self.alpha_R!r}")

    @property
    def specular_reduction(self) -> float:
        """Factor on the specular reflected *field*: ``sqrt(1 - S^2)``."""
        return math.sqrt(max(0.0, 1.0 - self.S * self.S))

    def to_dict(self) -> dict[str, Any]:
        """``{"S", "pattern", "alpha_R"}`` (as written in a scene file)."""
        return asdict(self)

    def pattern_value(
        self, cos_theta_s: torch.Tensor, cos_psi: torch.Tensor, cos_theta_i: torch.Tensor,
    ) -> torch.Tensor:
        """Normalized pattern ``f`` per steradian (0 behind the surface); broadcasts.

        Args:
            cos_theta_s: cosine of the scattering direction's angle from the lit-side normal.
            cos_psi: cosine of the angle between scattering and specular direction.
            cos_theta_i: cosine of the incidence angle (sets the directive normalization).
        """
        front = (cos_theta_s > 0).to(cos_theta_s.dtype)
        if self.pattern == "lambertian":
            return front * cos_theta_s.clamp_min(0) / math.pi
        lobe = ((1 + cos_psi) / 2).clamp_min(0) ** self.alpha_R
        return front * lobe / directive_norm(cos_theta_i, self.alpha_R)

    def sigma0(self, gamma2: torch.Tensor, cos_theta: torch.Tensor) -> torch.Tensor:
        """Monostatic diffuse RCS per unit area (m^2/m^2) at incidence ``cos_theta``.

        Args:
            gamma2: ``|Gamma|^2`` of the smooth surface at that incidence.
            cos_theta: cosine of the incidence angle (sign ignored).
        """
        c = cos_theta.abs().clamp(0, 1)
        if self.pattern == "lambertian":
            return 4 * self.S**2 * gamma2 * c * c
        # Monostatic: cos psi = cos 2 theta, so ((1 + cos psi) / 2)^a = cos^(2a) theta.
        return 4 * math.pi * self.S**2 * gamma2 * c * c ** (2 * self.alpha_R) / directive_norm(c, self.alpha_R)


def directive_norm(cos_theta_i: torch.Tensor, alpha_R: int) -> torch.Tensor:
    """``F(alpha_R, theta_i)``: integral of ``((1 + cos psi)/2)^alpha_R`` over the front hemisphere.

    Degli-Esposti et al. (2007)'s closed form, exact for integer ``alpha_R``.
    """
    c = cos_theta_i.abs().clamp(0, 1)
    s2 = (1 - c * c).clamp_min(0)
    total = torch.zeros_like(c)
    for j in range(alpha_R + 1):
        if j % 2 == 0:
            i_j = torch.full_like(c, 2 * math.pi / (j + 1))
        else:
            series = sum(math.comb(2 * w, w) / 4**w * s2**w for w in range((j - 1) // 2 + 1))
            i_j = 2 * math.pi / (j + 1) * c * series
        total = total + math.comb(alpha_R, j) * i_j
    return total / 2**alpha_R


# Defaults. Room finishes: one S fitted so that the paper corridor's zero-Doppler clutter at
# 1-5 m matches the real 48 dB recordings (docs/diffuse_clutter.md, "Fit", with the figures
# of S = 0.7 and 0.4 against the recordings). The level carries joints, sockets and fixtures a
# box corridor lacks, hence one value for every finish rather than a per-material roughness. At 60 GHz (lambda = 5 mm) plaster and concrete
# textures of 0.2-0.5 mm RMS already give S^2 = 1 - exp(-(4 pi h / lambda)^2) = 0.25-0.7 by the
# Kirchhoff criterion, the same range. Glass and metal are smooth (not fitted: a few % of the
# field). Skin and the absorber scatter nothing here (people are modelled elsewhere).
# Lambertian throughout: broad scatterers, no measured lobe to fit.
_FINISH = DiffuseScattering(0.7)
DIFFUSE_DEFAULTS: dict[str, DiffuseScattering] = {
    "concrete": _FINISH,
    "brick": _FINISH,
    "plasterboard": _FINISH,
    "wood": _FINISH,
    "glass": DiffuseScattering(0.05),
    "ceiling_board": _FINISH,
    "chipboard": _FINISH,
    "floorboard": _FINISH,
    "metal": DiffuseScattering(0.1),
    "skin": DiffuseScattering(0.0),
    "absorber": DiffuseScattering(0.0),
}
"""Default :class:`DiffuseScattering` per built-in material (by base name, any thickness)."""

FALLBACK = _FINISH
"""Used for materials without a default (a scene's own materials): the fitted finish value."""

ScatteringOverrides = Mapping[str, DiffuseScattering | Mapping[str, Any] | float]
"""Per-material diffuse-scattering overrides (``Scene.scattering``): each value as :func:`as_scattering` takes it."""


def as_scattering(value: DiffuseScattering | Mapping[str, Any] | float, where: str = "diffuse") -> DiffuseScattering:
    """A :class:`DiffuseScattering` from itself, a dict ``{S, pattern, alpha_R}`` or a number ``S``."""
    if isinstance(value, DiffuseScattering):
        return value
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return DiffuseScattering(float(value))
    if isinstance(value, Mapping):
        unknown = sorted(set(value) - {"S", "pattern", "alpha_R"})
        if unknown:
            raise SceneError(f"{where}: unknown key(s) {unknown}; allowed: ['S', 'alpha_R', 'pattern']")
        kw = dict(value)
        if "S" in kw and isinstance(kw["S"], int) and not isinstance(kw["S"], bool):
            kw["S"] = float(kw["S"])
        try:
            return DiffuseScattering(**kw)
        except SceneError as err:
            raise SceneError(f"{where}: {err}") from None
    raise SceneError(f"{where}: must be a number S or a mapping {{S, pattern, alpha_R}}, got {value!r}")


def get_scattering(
    key: str, overrides: ScatteringOverrides | None = None,
) -> DiffuseScattering:
    """Scattering of material ``key``: ``overrides[key]``, ``overrides[name]``, the default, or :data:`FALLBACK`."""
    name, _ = parse_material_key(key)
    overrides = overrides or {}
    for k in (key, name):
        if k in overrides:
            return as_scattering(overrides[k], f"diffuse scattering of {k!r}")
    return DIFFUSE_DEFAULTS.get(name, FALLBACK)


def specular_reduction(
    names: Sequence[str],
    overrides: ScatteringOverrides | None = None,
    *,
    device: torch.device | str | None = None,
    dtype: torch.dtype = torch.float32,
) -> torch.Tensor:
    """``(M,)`` specular field factor ``sqrt(1 - S^2)`` per material key (e.g. ``SceneGeometry.materials``).

    Multiplying a face's specular reflection by it makes specular + diffuse power the smooth surface's.
    """
    return torch.tensor([get_scattering(n, overrides).specular_reduction for n in names],
                        dtype=dtype, device=device)


__all__ = [
    "DIFFUSE_DEFAULTS",
    "FALLBACK",
    "PATTERNS",
    "ScatteringOverrides",
    "DiffuseScattering",
    "as_scattering",
    "directive_norm",
    "get_scattering",
    "specular_reduction",
]
