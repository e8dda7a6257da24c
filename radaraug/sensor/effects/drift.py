"""Frame-to-frame drift: a random gain and per-RX DC shift, constant within each frame.

Real captures are noisier frame to frame than across the chirps of a frame: gain and DC level wander
slowly (temperature, supply), negligibly within one frame, so they are drawn once per frame.
"""

from __future__ import annotations

import math

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, check_params, per_rx, register


@register
class FrameDrift(Effect):
    """Per-frame random gain (common to all RX) and per-RX DC shift.

    Each leading batch element is one frame. Everything present (signal, noise, static signal) is multiplied
    by ``10 ** (g / 20)``, ``g ~ Normal(0, gain_rms_dB)``, and each RX gets a DC shift ``~ Normal(0, dc_rms_counts)``
    counts; both are reparameterised, so gradients reach the RMS values. It acts on samples: place it after
    ``anti_alias_lowpass`` and before ``dc_offset``.

    Args:
        gain_rms_dB: RMS of the per-frame gain, dB. Default 0.1 dB (*assumed*).
        dc_rms_counts: per-RX (or scalar) RMS of the per-frame DC shift, ADC counts. Default 0.5 (*assumed*).
    """

    name = "frame_drift"
    kind = "nonlinear"
    param_names = ("gain_rms_dB", "dc_rms_counts")
    gain_rms_dB: torch.Tensor
    dc_rms_counts: torch.Tensor
    PRIORS = {"gain_rms_dB": Prior(0.0, 3.0), "dc_rms_counts": Prior(0.0, 20.0)}

    def __init__(
        self,
        gain_rms_dB: float | torch.Tensor = 0.1,
        dc_rms_counts: float | list | torch.Tensor = 0.5,
    ) -> None:
        super().__init__(gain_rms_dB=gain_rms_dB, dc_rms_counts=dc_rms_counts)
        check_params(self, nonnegative=("gain_rms_dB", "dc_rms_counts"))

    def forward(self, state: ChainState) -> None:
        """Scale by a random gain per frame and add a random DC shift per frame and RX."""
        x = state.materialize()
        batch = state.batch_shape
        g_db = state.param(self.gain_rms_dB) * state.randn((*batch, 1, 1, 1))
        dc_sigma = per_rx(state, self.dc_rms_counts, "dc_rms_counts", self.name) * state.float_per_count
        dc = dc_sigma[:, None, None] * state.randn((*batch, state.num_rx, 1, 1))
        state.samples = x * torch.exp(g_db * (math.log(10.0) / 20)) + dc
