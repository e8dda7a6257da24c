"""Radar-side geometry and the radar equation in amplitude form, shared by every path builder.

A scatterer of complex root RCS ``s`` (``|s|^2 = sigma``) at ``r_t`` from the TX and ``r_r`` from the RX gives
``a = sqrt(G_t G_r) lambda s / ((4 pi)^(3/2) r_t r_r)`` (sqrt(W) at the RX port per sqrt(W) at the TX port).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from radaraug.config import RadarConfig
from radaraug.scene.geometry import RadarPose


@dataclass
class RadarGeometry:
    """World-frame TX/RX phase centres, axes and polarization of the radar.

    Attributes:
        tx: ``(3,)`` TX phase centre.
        rx: ``(RX, 3)`` RX phase centres, in the config's RX order.
        centre: ``(3,)`` mean of TX and RX (origin of shadow rays toward the radar).
        rotation: ``(3, 3)`` world-from-radar rotation.
        polarization: ``(3,)`` unit electric-field direction (world).
        wavelength: carrier wavelength, m.
    """

    tx: torch.Tensor
    rx: torch.Tensor
    centre: torch.Tensor
    rotation: torch.Tensor
    polarization: torch.Tensor
    wavelength: float

    @classmethod
    def build(cls, pose: RadarPose, config: RadarConfig, polarization: tuple[float, float, float],
              device: torch.device, dtype: torch.dtype) -> RadarGeometry:
        """From a pose and a config; ``polarization`` is given in the radar frame."""
        pos = pose.position.to(device=device, dtype=dtype)
        rot = pose.rotation.to(device=device, dtype=dtype)
        tx_r = torch.tensor(config.tx_position_m, device=device, dtype=dtype)
        rx_r = torch.tensor(config.rx_positions, device=device, dtype=dtype)
        tx = pos + rot @ tx_r
        rx = pos + rx_r @ rot.T
        pol = rot @ torch.tensor(polarization, device=device, dtype=dtype)
        pol = pol / pol.norm()
        centre = torch.cat([tx[None], rx]).mean(0)
        return cls(tx, rx, centre, rot, pol, config.wavelength_m)

    def to_radar_dirs(self, v: torch.Tensor) -> torch.Tensor:
        """World vectors ``(..., 3)`` -> radar-frame vectors (rotation only)."""
        return v @ self.rotation


def radar_amplitude(
    sqrt_rcs: torch.Tensor, r_t: torch.Tensor, r_r: torch.Tensor, gain_t: torch.Tensor,
    gain_r: torch.Tensor, wavelength: float,
) -> torch.Tensor:
    """Path amplitude ``sqrt(G_t G_r) lambda s / ((4 pi)^(3/2) r_t r_r)`` (bistatic radar equation); broadcasts."""
    k = wavelength / (4 * math.pi) ** 1.5
    return sqrt_rcs * (k * torch.sqrt(gain_t * gain_r) / (r_t * r_r))
