"""Scalar reflection coefficient of a face for the radar's linear polarization.

The TE and TM Fresnel coefficients (ITU-R P.2040) are blended by ``w_TE = |e . s|^2``:
``Gamma = w_TE Gamma_TE - (1 - w_TE) Gamma_TM``, -1 for metal at every angle. The polarization is not rotated
by bounces. See ``docs/raytracer.md``, "Shooting and bouncing rays".
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
    """``|e . s|^2``, ``s`` the unit normal of the plane of incidence; 0.5 at normal incidence (any weight fits)."""
    s = torch.linalg.cross(direction, normal.expand_as(direction), dim=-1)
    norm = s.norm(dim=-1)
    e = polarization.to(direction)
    w = ((s * e).sum(-1) / norm.clamp_min(1e-12)) ** 2
    return torch.where(norm > 1e-9, w.clamp(0, 1), torch.full_like(w, 0.5))
