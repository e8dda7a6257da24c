"""TX -> RX leakage: the on-chip/in-package coupling, a strong static path a few cm long."""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, per_rx, register, tone_amplitude


@register
class TxRxLeakage(Effect):
    """A static path at the RX port with power ``coupling * P_tx``, through every later stage like a target.

    Args:
        coupling_dB: per-RX (or scalar) power at the RX port relative to the TX power, dB.
        range_m: equivalent one-way range of the coupling (delay ``2 * range_m / c``).
        phase_rad: per-RX (or scalar) phase of the beat tone, radians.
    """

    name = "tx_rx_leakage"
    param_names = ("coupling_dB", "range_m", "phase_rad")
    coupling_dB: torch.Tensor
    range_m: torch.Tensor
    phase_rad: torch.Tensor
    PRIORS = {
        "coupling_dB": Prior(-100.0, -20.0),
        "range_m": Prior(0.005, 0.3),
        "phase_rad": Prior(-math.pi, math.pi),
    }

    def __init__(
        self,
        coupling_dB: float | list | torch.Tensor = -60.0,
        range_m: float | torch.Tensor = 0.04,
        phase_rad: float | list | torch.Tensor = 0.0,
    ) -> None:
        super().__init__(coupling_dB=coupling_dB, range_m=range_m, phase_rad=phase_rad)

    def forward(self, state: ChainState) -> None:
        """Add the leakage as a static path at ``range_m`` on every RX."""
        c = per_rx(state, self.coupling_dB, "coupling_dB", self.name)
        ph = per_rx(state, self.phase_rad, "phase_rad", self.name)
        amp = tone_amplitude(state, c)
        coef = torch.polar(amp, ph)[:, None]  # (RX, 1)
        delay = (2 * state.param(self.range_m) / SPEED_OF_LIGHT).reshape(1, 1).expand(state.num_rx, 1)
        state.add_paths(coef, delay, torch.zeros_like(delay))



