"""Mutual interference: another FMCW radar's ramps crossing ours.

When an interferer's ramp crosses our ramp, their difference frequency sweeps through the IF
band for a few microseconds: a short chirp-like burst in the samples, at an uncorrelated time
in each chirp. In the range-Doppler map it raises a broadband floor in the chirps it hits.
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

    Each chirp of each frame independently gets a burst with probability ``probability``::

        x(t) = A w(t - t0) cos(2 pi (f_a (t - t0) + k (t - t0)^2 / 2) + phi)

    with ``w`` a Hann window of length ``duration_s``, ``f_a = -fs/2`` and
    ``k = fs / duration_s``: the instantaneous frequency sweeps from ``-fs/2`` through zero (the
    crossing, at the burst's centre) to ``+fs/2``, so the real burst covers the IF band twice.
    The crossing time (burst centre ``t0 + duration_s / 2``) is uniform over the chirp's ADC
    window; a burst near either end is cut by the window. The waveform is common to all RX (one
    interferer, one crossing time), with an independent uniform phase ``phi`` per RX and chirp
    (the RX see the interferer from one direction, but its carrier phase is unknown). All draws
    come from the call's generator. Expected burst energy over the phase: ``A^2 / 2 * sum w^2``,
    ``sum w^2 ~= 3/8 duration_s fs`` for a burst inside the window. Place it after ``if_gain``
    (the burst's level is given at that point) and before ``adc_noise``; the anti-alias filter
    then shapes it. Gradients reach ``amplitude_counts`` and ``duration_s``, not the
    probability (a Bernoulli draw).

    Args:
        probability: chance that a chirp gets a burst, in [0, 1]. Default 0.05 (*assumed*).
        amplitude_counts: peak burst amplitude ``A`` in ADC counts. Default 100 (*assumed*).
        duration_s: burst length, s (> 0). Default 5 us (*assumed*: the time the difference
            frequency takes to cross the IF band depends on both radars' slopes).

    Priors: ``probability`` in [0, 1] (linear), ``amplitude_counts`` in [1, 2000] counts (log),
    ``duration_s`` in [0.2, 30] us (log).
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
