"""Antenna power patterns of the radar's TX and RX elements (radar frame: z = boresight).

:class:`PatchAntenna` is an **assumption** (no exact BGT60TR13C gain is published): a lossless ``cos^q``
pattern with a 6 dBi peak by default (``docs/raytracer.md``, "Antenna").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import torch

from radaraug.errors import ConfigError


class Antenna(Protocol):
    """What the tracer needs of an antenna (TX and RX alike): its power gain toward directions."""

    def gain(self, directions: torch.Tensor) -> torch.Tensor:
        """Linear power gain toward ``directions`` ``(..., 3)`` given in the radar frame."""
        ...


@dataclass(frozen=True)
class PatchAntenna:
    """``G(theta) = G0 max(cos theta, 0)^q``, ``q = G0 / 2 - 1`` (lossless), with a back-lobe floor (linear power).

    Args:
        gain_dBi: peak gain at boresight, dBi (>= 3.01, the directivity of ``cos^0``).
        back_lobe_dB: floor relative to the peak, dB (<= 0).
    """

    gain_dBi: float = 6.0
    back_lobe_dB: float = -30.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.gain_dBi) and self.gain_dBi >= 10 * math.log10(2) - 1e-9):
            raise ConfigError(f"PatchAntenna: gain_dBi must be >= 3.01 dBi (cos^q pattern), got {self.gain_dBi}")
        if not self.back_lobe_dB <= 0:
            raise ConfigError(f"PatchAntenna: back_lobe_dB must be <= 0, got {self.back_lobe_dB}")

    @property
    def peak_gain(self) -> float:
        """Linear peak gain ``G0``."""
        return 10 ** (self.gain_dBi / 10)

    @property
    def exponent(self) -> float:
        """``q`` of the ``cos^q`` pattern."""
        return max(self.peak_gain / 2 - 1, 0.0)

    def gain(self, directions: torch.Tensor) -> torch.Tensor:
        """Linear power gain toward ``directions`` ``(..., 3)`` given in the radar frame."""
        cos = directions[..., 2] / directions.norm(dim=-1).clamp_min(1e-30)
        front = cos.clamp_min(0) ** self.exponent
        return self.peak_gain * front.clamp_min(10 ** (self.back_lobe_dB / 10))


@dataclass(frozen=True)
class IsotropicAntenna:
    """Gain 1 (0 dBi) in every direction: for closed-form checks of the radar equation."""

    def gain(self, directions: torch.Tensor) -> torch.Tensor:
        """Ones of shape ``directions.shape[:-1]``."""
        return torch.ones(directions.shape[:-1], dtype=directions.dtype, device=directions.device)
