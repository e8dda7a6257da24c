"""Thermal noise of the receiver, referred to the RX port: ``k T F (fs / 2)``.

The noise power in the ADC's Nyquist band ``fs / 2`` is ``k T0 F fs/2`` (-117 dBm for
``fs`` = 1 MHz before the noise figure), white, independent per RX, chirp and sample. It enters
at the front of the chain, so every later gain and filter shapes it. Noise above Nyquist that
the anti-alias filter lets through and the ADC folds back is not modelled (the noise figure
absorbs it when calibrated).
"""

from __future__ import annotations

import torch

from radaraug.sensor.chain import ChainState
from radaraug.sensor.effects.base import Effect, register

BOLTZMANN = 1.380649e-23
"""Boltzmann constant, J/K."""
T0_KELVIN = 290.0
"""Reference temperature of the noise figure, K."""


def thermal_noise_power_W(noise_figure_dB: float, sample_rate_Hz: float, temperature_K: float = T0_KELVIN) -> float:
    """``k T F fs / 2`` in watts."""
    return BOLTZMANN * temperature_K * 10 ** (noise_figure_dB / 10) * sample_rate_Hz / 2


@register
class ThermalNoise(Effect):
    """White Gaussian receiver noise, input-referred.

    Args:
        noise_figure_dB: receiver noise figure F.
        temperature_K: noise temperature of the source (290 K for the standard noise figure).
    """

    name = "thermal_noise"
    param_names = ("noise_figure_dB", "temperature_K")

    def __init__(self, noise_figure_dB: float | torch.Tensor = 12.0, temperature_K: float | torch.Tensor = T0_KELVIN) -> None:
        super().__init__()
        self._set(noise_figure_dB=noise_figure_dB, temperature_K=temperature_K)

    def apply(self, state: ChainState) -> None:
        nf = state.param(self.noise_figure_dB)
        temp = state.param(self.temperature_K)
        power = BOLTZMANN * temp * torch.pow(10.0, nf / 10) * (state.timing.fs / 2)
        sigma = torch.sqrt(power) * state.front_end_gain
        state.add_samples(sigma * state.randn(state.sample_shape))

