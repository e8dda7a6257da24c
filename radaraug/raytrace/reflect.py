"""Scalar reflection coefficient of a face for the radar's linear polarization.

The tracer carries one complex amplitude per ray (a scalar field), not a polarization vector.
At each hit the TE and TM Fresnel coefficients (ITU-R P.2040, from
:mod:`radaraug.scene.materials`) are blended by how much of the radar's electric-field direction
``e`` is perpendicular to the plane of incidence::

    w_TE  = |e . s|^2,   s = unit(d x n)        (d: ray direction, n: face normal)
    Gamma = w_TE * Gamma_TE - (1 - w_TE) * Gamma_TM

The minus sign undoes the mirrored TM reference of P.2040 (``Gamma_TM = -Gamma_TE`` at normal
incidence), so that ``Gamma`` is the co-polar field ratio relative to what a perfect conductor
does: ``-1`` for metal at every angle, ``Gamma_TE`` at normal incidence for any material. The
polarization direction is not rotated by the bounces (an approximation that is exact for TE or
TM incidence on a set of parallel or perpendicular walls, the common corridor case).
"""

from __future__ import annotations

import torch

from radaraug.scene.materials import material_table, reflection_coefficients


class FaceReflectivity:
    """Per-material permittivity tables of a scene, evaluated at one frequency.

    Args:
        materials: material keys (``SceneGeometry.materials``).
        frequency_Hz: evaluation frequency (the carrier).
        device, dtype: of the returned coefficients (complex of ``dtype``).
    """

    def __init__(self, materials: tuple[str, ...], frequency_Hz: float, device: torch.device,
                 dtype: torch.dtype) -> None:
        self.frequency_Hz = float(frequency_Hz)
        self.eps, self.thickness = material_table(list(materials) or ["metal"], frequency_Hz,
                                                  device=device, dtype=dtype)

    def __call__(
        self, face_material: torch.Tensor, cos_theta: torch.Tensor, direction: torch.Tensor,
        normal: torch.Tensor, polarization: torch.Tensor,
    ) -> torch.Tensor:
        """Scalar co-polar ``Gamma`` per hit.

        Args:
            face_material: ``(...)`` material index of each hit face.
            cos_theta: ``(...)`` cosine of the incidence angle (sign ignored).
            direction: ``(..., 3)`` unit incident ray directions.
            normal: ``(..., 3)`` unit face normals.
            polarization: ``(3,)`` unit electric-field direction of the radar (world frame).
        """
        g_te, g_tm = reflection_coefficients(self.eps, self.thickness, face_material, cos_theta,
                                             self.frequency_Hz)
        w_te = te_weight(direction, normal, polarization)
        return w_te * g_te - (1 - w_te) * g_tm


def te_weight(direction: torch.Tensor, normal: torch.Tensor, polarization: torch.Tensor) -> torch.Tensor:
    """``|e . s|^2`` with ``s`` the unit normal of the plane of incidence; 0.5 at normal incidence.

    At normal incidence the plane of incidence is undefined, but there ``Gamma_TE = -Gamma_TM``
    so any weight gives the same ``Gamma``.
    """
    s = torch.linalg.cross(direction, normal.expand_as(direction), dim=-1)
    norm = s.norm(dim=-1)
    e = polarization.to(direction)
    w = ((s * e).sum(-1) / norm.clamp_min(1e-12)) ** 2
    return torch.where(norm > 1e-9, w.clamp(0, 1), torch.full_like(w, 0.5))
