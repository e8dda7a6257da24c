"""Gain stages: residual system gain, the IF gain (VGA) and per-RX gain/phase mismatch."""

from __future__ import annotations

import math

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, per_rx, register


def db_to_amplitude(db: torch.Tensor) -> torch.Tensor:
    """``10 ** (dB / 20)``, differentiable."""
    return torch.pow(10.0, db / 20)


@register
class SystemGain(Effect):
    """A flat gain on everything present (signal and noise), in dB: the residual a calibration fits.

    Args:
        gain_dB: scalar gain in dB.
    """

    name = "system_gain"
    kind = "linear"
    param_names = ("gain_dB",)
    gain_dB: torch.Tensor
    PRIORS = {"gain_dB": Prior(-30.0, 30.0)}

    def __init__(self, gain_dB: float | torch.Tensor = 0.0) -> None:
        super().__init__(gain_dB=gain_dB)

    def forward(self, state: ChainState) -> None:
        """Scale everything present by ``gain_dB``."""
        g = db_to_amplitude(state.param(self.gain_dB)).expand(state.num_rx)
        state.apply_linear(rx_gain=g)


@register
class IFGain(Effect):
    """The IF gain (BGT60: high-pass stage 18/30 dB + VGA 0..30 dB), applied after the high-pass.

    Args:
        gain_dB: gain in dB; ``None`` takes ``config.if_gain_dB`` at call time (a recorded setting, not searched).
    """

    name = "if_gain"
    kind = "linear"
    param_names = ("gain_dB",)
    gain_dB: torch.Tensor | None

    def __init__(self, gain_dB: float | torch.Tensor | None = None) -> None:
        super().__init__(gain_dB=gain_dB)

    def forward(self, state: ChainState) -> None:
        """Scale everything present by ``gain_dB`` (the radar config's IF gain when None)."""
        db = (
            torch.tensor(float(state.config.if_gain_dB), device=state.device, dtype=state.dtype)
            if self.gain_dB is None
            else state.param(self.gain_dB)
        )
        state.apply_linear(rx_gain=db_to_amplitude(db).expand(state.num_rx))


@register
class RxGainPhaseMismatch(Effect):
    """Per-RX complex gain ``10**(gain_dB/20) * exp(j phase_rad)`` (channel imbalance).

    The phase adds to each real IF tone's phase.

    Args:
        gain_dB: per-RX (or scalar) gain offsets in dB.
        phase_rad: per-RX (or scalar) phase offsets in radians.
    """

    name = "rx_gain_phase_mismatch"
    kind = "linear"
    param_names = ("gain_dB", "phase_rad")
    gain_dB: torch.Tensor
    phase_rad: torch.Tensor
    PRIORS = {"gain_dB": Prior(-6.0, 6.0), "phase_rad": Prior(-math.pi, math.pi)}

    def __init__(self, gain_dB: float | list | torch.Tensor = 0.0, phase_rad: float | list | torch.Tensor = 0.0) -> None:
        super().__init__(gain_dB=gain_dB, phase_rad=phase_rad)

    def forward(self, state: ChainState) -> None:
        """Multiply each RX by its complex gain."""
        amp = db_to_amplitude(per_rx(state, self.gain_dB, "gain_dB", self.name))
        ph = per_rx(state, self.phase_rad, "phase_rad", self.name)
        state.apply_linear(rx_gain=torch.polar(amp, ph))
