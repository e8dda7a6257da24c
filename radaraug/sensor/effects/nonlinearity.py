"""Chirp non-linearity: a periodic ripple of the ramp's instantaneous frequency.

The PLL's frequency error ``dF(t)`` repeats in every chirp and leaves the beat phase error
``~= 2 pi tau dF(t)`` (linearised like the phase noise): a sinusoidal ripple gives every strong return
*paired echoes* at ``+-ripple_Hz``, ``pi tau deviation_Hz`` relative to it.
"""

from __future__ import annotations

import math

import torch

from radaraug.errors import ConfigError
from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, check_params, modulate_strongest_paths, register


@register
class ChirpNonlinearity(Effect):
    """Sinusoidal ramp-frequency ripple ``dF(t) = deviation_Hz sin(2 pi ripple_Hz t + phase_rad)``.

    ``t`` is the fast time from the first ADC sample, the same in every chirp. The ``num_paths`` paths with the
    largest ``|C| tau`` gain ``Re{j 2 pi tau C exp(j Phi)} dF(t)``; the echo at ``beat + ripple_Hz`` has the
    ratio ``pi tau deviation_Hz exp(j phase_rad)`` to the tone, the one at ``beat - ripple_Hz``
    ``-pi tau deviation_Hz exp(-j phase_rad)``. Common to all RX. Place it right after ``phase_noise``.

    Args:
        deviation_Hz: peak frequency deviation of the ramp, Hz. Default 20 kHz (*assumed*).
        ripple_Hz: ripple frequency, Hz. Default 100 kHz (*assumed*).
        phase_rad: ripple phase at the first ADC sample.
        num_paths: how many of the strongest paths (by ``|C| tau``) get the echoes (a cost knob).
    """

    name = "chirp_nonlinearity"
    kind = "modulating"
    param_names = ("deviation_Hz", "ripple_Hz", "phase_rad", "num_paths")
    deviation_Hz: torch.Tensor
    ripple_Hz: torch.Tensor
    phase_rad: torch.Tensor
    num_paths: torch.Tensor
    PRIORS = {
        "deviation_Hz": Prior(1e3, 5e6, "log"),
        "ripple_Hz": lambda config: Prior(1e3, max(float(config.sample_rate_Hz) / 2, 2e3), "log"),
        "phase_rad": Prior(-math.pi, math.pi),
    }

    def __init__(
        self,
        deviation_Hz: float | torch.Tensor = 20e3,
        ripple_Hz: float | torch.Tensor = 100e3,
        phase_rad: float | torch.Tensor = 0.0,
        num_paths: int = 16,
    ) -> None:
        if int(num_paths) != num_paths or num_paths < 0:
            raise ConfigError(f"effect {self.name}: num_paths must be an integer >= 0, got {num_paths!r}")
        super().__init__(deviation_Hz=deviation_Hz, ripple_Hz=ripple_Hz, phase_rad=phase_rad,
                         num_paths=int(num_paths))
        check_params(self, single=("deviation_Hz", "ripple_Hz", "phase_rad"), nonnegative=("deviation_Hz",),
                     positive=("ripple_Hz",))

    def frequency_error_Hz(self, state: ChainState) -> torch.Tensor:
        """``dF`` at the ADC samples of a chirp, ``(N,)`` in the call's dtype."""
        tm = state.timing
        t = torch.arange(tm.num_samples, device=state.device, dtype=torch.float64) / tm.fs
        # Cycles in float64, reduced mod 1 before the cast, so float32 keeps the phase.
        phase = state.cycle_phase(self.ripple_Hz.to(device=state.device, dtype=torch.float64) * t)
        phase = phase + state.param(self.phase_rad)
        return state.param(self.deviation_Hz) * torch.sin(phase)

    def forward(self, state: ChainState) -> None:
        """Add the ripple's frequency-modulated copies of the ``num_paths`` strongest paths."""
        k = min(int(self.num_paths), state.coef.shape[-1])
        if k:
            tm = state.timing
            multiplier = self.frequency_error_Hz(state).reshape(1, 1, tm.num_samples).expand(1, tm.num_chirps, -1)
            modulate_strongest_paths(state, k, multiplier)
