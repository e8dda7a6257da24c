"""Free-space point targets as :class:`Paths` (radar equation), for tests, examples and benchmarks."""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.errors import InputTensorError
from radaraug.sensor.paths import Paths


def point_target_paths(
    config: RadarConfig,
    positions_m: torch.Tensor,
    velocities_m_s: torch.Tensor | None = None,
    rcs_m2: torch.Tensor | float = 1.0,
    *,
    antenna_gain_dBi: float = 0.0,
) -> Paths:
    """Paths of point scatterers in free space, in the radar's antenna frame.

    Bistatic per RX, amplitude from the radar equation ``|a|^2 = G_t G_r lambda^2 sigma / ((4 pi)^3 R_tx^2 R_rx^2)``
    (isotropic antennas, real: a point scatterer adds no phase).

    Args:
        config: radar configuration (wavelength, TX/RX positions).
        positions_m: ``(..., P, 3)`` target positions (x right, y up, z boresight), m.
        velocities_m_s: ``(..., P, 3)`` velocities, or None for static targets.
        rcs_m2: ``(..., P)`` or scalar radar cross-section, m^2.
        antenna_gain_dBi: gain of each of the TX and RX antennas.

    Returns:
        :class:`Paths` with ``(..., P, RX)`` tensors in ``positions_m``'s dtype and device.

    Raises:
        InputTensorError: a wrong shape, or a target on an antenna.
    """
    if not isinstance(positions_m, torch.Tensor) or positions_m.ndim < 2 or positions_m.shape[-1] != 3:
        raise InputTensorError("positions_m must be a (..., P, 3) tensor")
    p = positions_m
    dev, dt = p.device, p.dtype
    v = torch.zeros_like(p) if velocities_m_s is None else velocities_m_s.to(dev, dt)
    if v.shape != p.shape:
        raise InputTensorError(f"velocities_m_s has shape {tuple(v.shape)}, positions_m {tuple(p.shape)}")
    tx = torch.tensor(config.tx_position_m, dtype=dt, device=dev)
    rx = torch.tensor(config.rx_positions, dtype=dt, device=dev)  # (RX, 3)
    d_tx = p - tx  # (..., P, 3)
    d_rx = p[..., None, :] - rx  # (..., P, RX, 3)
    r_tx = d_tx.norm(dim=-1, keepdim=True)  # (..., P, 1)
    r_rx = d_rx.norm(dim=-1)  # (..., P, RX)
    if bool((r_tx == 0).any()) or bool((r_rx == 0).any()):
        raise InputTensorError("a point target sits on an antenna (zero range)")
    delay = (r_tx + r_rx) / SPEED_OF_LIGHT
    rate = ((d_tx * v).sum(-1, keepdim=True) / r_tx + (d_rx * v[..., None, :]).sum(-1) / r_rx) / SPEED_OF_LIGHT
    g = 10 ** (antenna_gain_dBi / 10)
    sigma = torch.as_tensor(rcs_m2, dtype=dt, device=dev)
    sigma = sigma[..., None] if sigma.ndim else sigma
    amp = torch.sqrt(g * g * config.wavelength_m**2 * sigma / ((4 * math.pi) ** 3 * r_tx**2 * r_rx**2))
    return Paths(delay_s=delay, delay_rate=rate, amplitude=amp.to(torch.complex128 if dt == torch.float64 else torch.complex64))
