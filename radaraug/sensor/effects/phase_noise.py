"""LO phase noise, decorrelated by each path's delay (the FMCW range-correlation effect).

A path's residual phase noise is ``phi(t) - phi(t - tau) ~= 2 pi tau nu(t)``, ``nu`` the LO's frequency noise
(linearised, valid indoors): a skirt around strong returns, growing with their delay. ``nu`` is Gaussian with
a Lorentzian spectrum along fast time, independent between chirps and common to all RX.
"""

from __future__ import annotations

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, modulate_strongest_paths, register


@register
class PhaseNoise(Effect):
    """Residual LO phase noise on the ``num_paths`` strongest paths (by ``|C| tau``, per frame).

    Args:
        freq_noise_rms_Hz: RMS of the LO frequency noise ``nu``.
        corner_Hz: corner of its Lorentzian spectrum ``1 / (1 + (f / corner)^2)``.
        num_paths: how many of the strongest paths get the skirt (a cost knob; weaker ones sit under the noise).
    """

    name = "phase_noise"
    kind = "modulating"
    param_names = ("freq_noise_rms_Hz", "corner_Hz", "num_paths")
    freq_noise_rms_Hz: torch.Tensor
    corner_Hz: torch.Tensor
    num_paths: torch.Tensor
    PRIORS = {"freq_noise_rms_Hz": Prior(1e3, 3e6, "log"), "corner_Hz": Prior(1e3, 1e6, "log")}

    def __init__(
        self,
        freq_noise_rms_Hz: float | torch.Tensor = 100e3,
        corner_Hz: float | torch.Tensor = 200e3,
        num_paths: int = 4,
    ) -> None:
        super().__init__(freq_noise_rms_Hz=freq_noise_rms_Hz, corner_Hz=corner_Hz, num_paths=int(num_paths))

    def forward(self, state: ChainState) -> None:
        """Add the phase noise's frequency-modulated copies of the ``num_paths`` strongest paths."""
        k = min(int(self.num_paths), state.coef.shape[-1])
        if k:
            modulate_strongest_paths(state, k, self._frequency_noise(state))

    def _frequency_noise(self, state: ChainState) -> torch.Tensor:
        """``nu(m, n)`` in Hz, ``(…, 1, M, N)``."""
        N = state.timing.num_samples
        shape = (*state.batch_shape, 1, state.timing.num_chirps, N)
        f = state.fft_freqs_Hz().to(state.dtype)
        h = 1 / torch.sqrt(1 + (f / state.param(self.corner_Hz)) ** 2)
        # Normalise so the filtered process has the requested RMS (circular filter, two-sided sum).
        w = torch.full_like(h, 2.0)
        w[0] = 1.0
        if N % 2 == 0:
            w[-1] = 1.0
        gain = torch.sqrt((w * h**2).sum() / N)
        white = state.randn(shape)
        nu = torch.fft.irfft(torch.fft.rfft(white, dim=-1) * h, n=N, dim=-1)
        return nu * (state.param(self.freq_noise_rms_Hz) / gain)
