"""Receiver noise: thermal noise at the RX port (shaped by every later stage) and noise referred to the ADC."""

from __future__ import annotations

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, check_params, per_rx, register

BOLTZMANN = 1.380649e-23
"""Boltzmann constant, J/K."""
T0_KELVIN = 290.0
"""Reference temperature of the noise figure, K."""


def thermal_noise_power_W(noise_figure_dB: float, sample_rate_Hz: float, temperature_K: float = T0_KELVIN) -> float:
    """``k T F fs / 2`` in watts."""
    return BOLTZMANN * temperature_K * 10 ** (noise_figure_dB / 10) * sample_rate_Hz / 2


@register
class ThermalNoise(Effect):
    """White Gaussian receiver noise, input-referred, independent per RX, chirp and sample.

    Args:
        noise_figure_dB: receiver noise figure F.
        temperature_K: noise temperature of the source (290 K for the standard noise figure).
    """

    name = "thermal_noise"
    param_names = ("noise_figure_dB", "temperature_K")
    noise_figure_dB: torch.Tensor
    temperature_K: torch.Tensor
    PRIORS = {"noise_figure_dB": Prior(0.0, 45.0)}

    def __init__(self, noise_figure_dB: float | torch.Tensor = 12.0, temperature_K: float | torch.Tensor = T0_KELVIN) -> None:
        super().__init__(noise_figure_dB=noise_figure_dB, temperature_K=temperature_K)

    def forward(self, state: ChainState) -> None:
        """Add noise of power ``k T F fs/2`` per RX, scaled by the front-end gain."""
        nf = state.param(self.noise_figure_dB)
        temp = state.param(self.temperature_K)
        power = BOLTZMANN * temp * torch.pow(10.0, nf / 10) * (state.timing.fs / 2)
        sigma = torch.sqrt(power) * state.front_end_gain
        state.add_samples(sigma * state.randn(state.sample_shape))



@register
class ADCNoise(Effect):
    """White Gaussian noise on the ADC side of the IF gain (VGA output / ADC driver), independent per sample.

    A floor that does not scale with the IF gain: place it after ``if_gain`` and before ``anti_alias_lowpass``.

    Args:
        rms_counts: per-RX (or scalar) RMS in ADC counts over the Nyquist band, *before* the anti-alias
            filter. Default 0.5 counts (*assumed*).
    """

    name = "adc_noise"
    param_names = ("rms_counts",)
    rms_counts: torch.Tensor
    PRIORS = {"rms_counts": Prior(0.01, 50.0, "log")}

    def __init__(self, rms_counts: float | list | torch.Tensor = 0.5) -> None:
        super().__init__(rms_counts=rms_counts)
        check_params(self, nonnegative=("rms_counts",))

    def forward(self, state: ChainState) -> None:
        """Add white noise of ``rms_counts`` ADC codes (RMS) per RX."""
        sigma = per_rx(state, self.rms_counts, "rms_counts", self.name) * state.float_per_count
        state.add_samples(sigma[:, None, None] * state.randn(state.sample_shape))
