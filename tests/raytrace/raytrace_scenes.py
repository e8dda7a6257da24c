"""Small closed-form scenes shared by the ray-tracer tests."""

from __future__ import annotations

import math

import torch

from radaraug.config import RadarConfig
from radaraug.scene.geometry import SceneGeometry


def monostatic_config() -> RadarConfig:
    """BGT60TR13C chirp with TX and the single RX at the antenna-frame origin (exact monostatic)."""
    return RadarConfig.bgt60tr13c(rx_antennas=(1,), rx_positions_m=((0.0, 0.0, 0.0),), tx_position_m=(0.0, 0.0, 0.0))


def quad(p0: torch.Tensor, e1: torch.Tensor, e2: torch.Tensor) -> torch.Tensor:
    """Two triangles ``(2, 3, 3)`` of the parallelogram ``p0 + [0,1] e1 + [0,1] e2``."""
    q = [p0, p0 + e1, p0 + e1 + e2, p0 + e2]
    return torch.stack([torch.stack([q[0], q[1], q[2]]), torch.stack([q[0], q[2], q[3]])])


def soup(triangles: torch.Tensor, materials: tuple[str, ...] = ("metal",),
         face_material: torch.Tensor | None = None) -> SceneGeometry:
    """A SceneGeometry from a triangle soup ``(F, 3, 3)``."""
    f = triangles.shape[0]
    return SceneGeometry(
        vertices=triangles.reshape(-1, 3),
        faces=torch.arange(3 * f).reshape(f, 3),
        face_material=torch.zeros(f, dtype=torch.long) if face_material is None else face_material,
        materials=materials,
    )


def box_room(lo, hi, materials=("floorboard", "ceiling_board", "concrete", "metal")) -> SceneGeometry:
    """Axis-aligned box: floor, ceiling, side walls (y), end walls (x) with 4 materials."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = torch.tensor([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                      [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], dtype=torch.float64)
    f = torch.tensor([[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6], [0, 4, 5], [0, 5, 1], [3, 2, 6], [3, 6, 7],
                      [0, 3, 7], [0, 7, 4], [1, 5, 6], [1, 6, 2]])
    fm = torch.tensor([0, 0, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3])
    return SceneGeometry(v, f, fm, materials)


def rotation_taking(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """Rotation matrix mapping unit vector ``a`` to unit vector ``b`` (Rodrigues)."""
    v = torch.linalg.cross(a, b)
    s, c = v.norm(), (a * b).sum()
    k = torch.tensor([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], dtype=a.dtype)
    return torch.eye(3, dtype=a.dtype) + k + k @ k * ((1 - c) / s**2)


def carrier_sum(paths, frequency_Hz: float, rx: int = 0) -> complex:
    """Coherent sum of the paths at the carrier for one RX (what the receiver does at f_c)."""
    a = paths.amplitude[..., rx] * torch.exp(-2j * math.pi * frequency_Hz * paths.delay_s[..., rx].double())
    if paths.mask is not None:
        a = torch.where(paths.mask, a, torch.zeros_like(a))
    return complex(a.sum())
