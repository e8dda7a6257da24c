"""A spurious tone at the ADC input (clock or switching-regulator spur), at absolute time or unlocked."""

from __future__ import annotations

import math

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, per_rx, register


@register
class SpurTone(Effect):
    """``A cos(2 pi f t + phi)`` added where the effect sits, ``t`` the absolute sample time.

    ``t = frame_start_s + m PRT + adc_delay + n / fs``: the spur keeps its phase from frame to frame and is not
    coherent with the chirps. An unlocked source gets a Gaussian random phase per chirp (same on every RX):
    its Doppler line keeps ``exp(-phase_jitter_rad**2)`` of the power, the rest a ridge over the Doppler bins.

    Args:
        freq_Hz: spur frequency.
        amplitude_counts: per-RX (or scalar) peak amplitude in ADC counts at this point.
        phase_rad: phase at ``t = 0``.
        phase_jitter_rad: RMS of the per-chirp random phase (0: locked to absolute time).
    """

    name = "spur_tone"
    param_names = ("freq_Hz", "amplitude_counts", "phase_rad", "phase_jitter_rad")
    freq_Hz: torch.Tensor
    amplitude_counts: torch.Tensor
    phase_rad: torch.Tensor
    phase_jitter_rad: torch.Tensor
    PRIORS = {
        "freq_Hz": lambda config: Prior(0.0, float(config.sample_rate_Hz) / 2),  # up to Nyquist
        "amplitude_counts": Prior(0.05, 200.0, "log"),
        "phase_rad": Prior(-math.pi, math.pi),
        "phase_jitter_rad": Prior(0.0, math.pi),
    }

    def __init__(
        self,
        freq_Hz: float | torch.Tensor = 100e3,
        amplitude_counts: float | list | torch.Tensor = 1.0,
        phase_rad: float | torch.Tensor = 0.0,
        phase_jitter_rad: float | torch.Tensor = 0.0,
    ) -> None:
        super().__init__(freq_Hz=freq_Hz, amplitude_counts=amplitude_counts, phase_rad=phase_rad,
                         phase_jitter_rad=phase_jitter_rad)

    def forward(self, state: ChainState) -> None:
        """Add the tone at the absolute time of every sample of the frame(s)."""
        cycles = self.freq_Hz.to(device=state.device, dtype=torch.float64) * state.sample_times_s()
        phase = state.cycle_phase(cycles) + state.param(self.phase_rad)
        if bool(self.phase_jitter_rad.detach().abs().max() > 0):  # a locked spur draws nothing
            jitter = state.randn((*state.batch_shape, 1, state.timing.num_chirps, 1))
            phase = phase + state.param(self.phase_jitter_rad) * jitter
        amp = per_rx(state, self.amplitude_counts, "amplitude_counts", self.name) * state.float_per_count
        state.add_samples(amp[:, None, None] * torch.cos(phase))
