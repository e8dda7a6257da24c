"""Mutual interference: another FMCW radar's ramps crossing ours.

At a crossing the difference frequency sweeps through the IF band for a few microseconds: a short
chirp-like burst at an uncorrelated time in each chirp, which raises a broadband floor in the RD map.
"""

from __future__ import annotations

import math

import torch

from radaraug.errors import ConfigError
from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, check_params, register


@register
class Interference(Effect):
    """Random IF bursts of a crossing FMCW interferer, at most one per chirp.

    Each chirp independently gets, with probability ``probability``, a Hann-windowed sweep from ``-fs/2`` to
    ``+fs/2`` of length ``duration_s``, centred uniformly over the ADC window; same waveform on all RX, random
    phase per RX and chirp (waveform and energy: ``docs/receiver.md``, "The effect catalog"). Place it after
    ``if_gain`` and before ``adc_noise``. Gradients reach ``amplitude_counts`` and ``duration_s``, not the
    probability.

    Args:
        probability: chance that a chirp gets a burst, in [0, 1]. Default 0.05 (*assumed*).
        amplitude_counts: peak burst amplitude ``A`` in ADC counts. Default 100 (*assumed*).
        duration_s: burst length, s (> 0). Default 5 us (*assumed*: it depends on both radars' slopes).
    """

    name = "interference"
    param_names = ("probability", "amplitude_counts", "duration_s")
    probability: torch.Tensor
    amplitude_counts: torch.Tensor
    duration_s: torch.Tensor
    PRIORS = {
        "probability": Prior(0.0, 1.0),
        "amplitude_counts": Prior(1.0, 2000.0, "log"),
        "duration_s": Prior(0.2e-6, 30e-6, "log"),
    }

    def __init__(
        self,
        probability: float | torch.Tensor = 0.05,
        amplitude_counts: float | torch.Tensor = 100.0,
        duration_s: float | torch.Tensor = 5e-6,
    ) -> None:
        super().__init__(probability=probability, amplitude_counts=amplitude_counts, duration_s=duration_s)
        check_params(self, single=self.param_names, nonnegative=("amplitude_counts",),
                     positive=("duration_s",))
        if not 0.0 <= float(self.probability) <= 1.0:
            raise ConfigError(f"effect {self.name}: probability must be in [0, 1], got {probability!r}")

    def forward(self, state: ChainState) -> None:
        """Add a burst to each chirp with probability ``probability``, at a random time and phase."""
        tm = state.timing
        M, N, fs = tm.num_chirps, tm.num_samples, tm.fs
        per_chirp = (*state.batch_shape, 1, M, 1)
        hit = state.rand(per_chirp) < state.param(self.probability).detach()
        centre = state.rand(per_chirp) * (N / fs)
        phi = (2 * math.pi) * state.rand((*state.batch_shape, state.num_rx, M, 1))
        d = state.param(self.duration_s)
        t = torch.arange(N, device=state.device, dtype=state.dtype) / fs
        u = t - centre + d / 2  # time since the burst's start, (…, 1, M, N)
        inside = (u >= 0) & (u <= d)
        w = torch.where(inside, torch.sin(math.pi * u / d) ** 2, torch.zeros_like(u))
        # Sweep -fs/2 -> +fs/2 over the burst: f_a u + k u^2 / 2 = (fs / 2) u (u / d - 1) cycles.
        cycles = (fs / 2) * u * (u / d - 1)
        amp = state.param(self.amplitude_counts) * state.float_per_count
        burst = torch.where(hit & inside, amp * w, torch.zeros_like(w))
        state.add_samples(burst * torch.cos(2 * math.pi * cycles + phi))
