"""Ray launching: a gnomonic grid of ray tubes from the TX antenna.

Directions ``(u, v, 1)`` in the radar frame on a regular grid of the plane ``z = 1``; each ray's tube is its
grid cell, spanned by ``s g1`` and ``s g2`` at unfolded length ``s``. Gnomonic cells project onto any plane
without gaps or overlap, so the tubes' footprints tile a wall and their PO integrals sum to the lit area's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from radaraug.errors import ConfigError


@dataclass
class RayTubes:
    """A bundle of ray tubes in world coordinates.

    Attributes:
        origins: ``(R, 3)`` start points.
        directions: ``(R, 3)`` unit directions.
        g1, g2: ``(R, 3)`` tube edge vectors per metre of unfolded path length.
        launch_dirs: ``(R, 3)`` unit launch directions in the radar frame (for the TX pattern).
    """

    origins: torch.Tensor
    directions: torch.Tensor
    g1: torch.Tensor
    g2: torch.Tensor
    launch_dirs: torch.Tensor


def ray_grid(
    num: int | tuple[int, int],
    half_angle_deg: float | tuple[float, float],
    origin: torch.Tensor,
    rotation: torch.Tensor,
    *,
    centre: tuple[float, float] = (0.0, 0.0),
) -> RayTubes:
    """Gnomonic ray-tube grid covering ``|u| <= tan(half_angle_x)``, ``|v| <= tan(half_angle_y)`` about ``centre``.

    Args:
        num: rays per axis ``n`` or ``(nu, nv)``.
        half_angle_deg: half field of view per axis, degrees (< 89).
        origin: ``(3,)`` world position of the TX phase centre (sets device and dtype).
        rotation: ``(3, 3)`` world-from-radar rotation.
        centre: ``(u0, v0)`` direction tangents of the grid centre (0, 0 = boresight).
    """
    nu, nv = (num, num) if isinstance(num, int) else num
    hx, hy = (half_angle_deg, half_angle_deg) if isinstance(half_angle_deg, (int, float)) else half_angle_deg
    if nu < 1 or nv < 1:
        raise ConfigError(f"ray grid needs at least 1 ray per axis, got {nu} x {nv}")
    if not (0 < hx < 89 and 0 < hy < 89):
        raise ConfigError(f"ray grid half angles must be in (0, 89) degrees, got {hx}, {hy}")
    dev, dt = origin.device, origin.dtype
    wu, wv = math.tan(math.radians(hx)), math.tan(math.radians(hy))
    du, dv = 2 * wu / nu, 2 * wv / nv
    u = centre[0] - wu + du * (torch.arange(nu, device=dev, dtype=dt) + 0.5)
    v = centre[1] - wv + dv * (torch.arange(nv, device=dev, dtype=dt) + 0.5)
    uu, vv = torch.meshgrid(u, v, indexing="ij")
    d_r = torch.stack([uu, vv, torch.ones_like(uu)], -1).reshape(-1, 3)
    norm = d_r.norm(dim=-1, keepdim=True)
    rot = rotation.to(device=dev, dtype=dt)
    ex, ey = rot[:, 0], rot[:, 1]
    dirs_r = d_r / norm
    return RayTubes(
        origins=origin.expand(d_r.shape[0], 3).contiguous(),
        directions=dirs_r @ rot.T,
        g1=(du / norm) * ex,
        g2=(dv / norm) * ey,
        launch_dirs=dirs_r,
    )
