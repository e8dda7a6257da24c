"""Fixtures for the receiver tests: configs and a plain FFT range-Doppler map."""

from __future__ import annotations

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.sensor import Paths


@pytest.fixture
def cfg() -> RadarConfig:
    """The paper's BGT60TR13C setting (3.1 us ADC delay)."""
    return RadarConfig.bgt60tr13c()


@pytest.fixture
def small_cfg() -> RadarConfig:
    """A small chirp for quick Monte-Carlo and exact-synthesis tests."""
    return RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, chirp_repetition_time_s=200e-6)


def rd_map(x: torch.Tensor) -> torch.Tensor:
    """Rectangular-window range-Doppler map: rFFT/N over samples (positive bins), FFT/M over
    chirps, fftshift on Doppler. Complex ``(..., RX, N//2, M)``. A real tone of peak amplitude A
    on a bin reads A/2."""
    N, M = x.shape[-1], x.shape[-2]
    r = torch.fft.fft(x - x.mean(dim=-1, keepdim=True), dim=-1)[..., : N // 2] / N
    d = torch.fft.fftshift(torch.fft.fft(r, dim=-2) / M, dim=-2)
    return d.transpose(-1, -2)


def monostatic_paths(
    config: RadarConfig,
    ranges_m: list[float],
    speeds_m_s: list[float] | None = None,
    amplitudes: list[complex] | None = None,
    dtype: torch.dtype = torch.float64,
    device: torch.device | str = "cpu",
) -> Paths:
    """Point targets seen identically by every RX (delay exactly 2R/c)."""
    P, RX = len(ranges_m), config.num_rx
    r = torch.tensor(ranges_m, dtype=torch.float64)
    v = torch.tensor(speeds_m_s if speeds_m_s is not None else [0.0] * P, dtype=torch.float64)
    a = torch.tensor(amplitudes if amplitudes is not None else [1.0] * P, dtype=torch.complex128)
    cdt = torch.complex64 if dtype == torch.float32 else torch.complex128
    return Paths(
        delay_s=(2 * r / SPEED_OF_LIGHT)[:, None].expand(P, RX).to(device, dtype),
        delay_rate=(2 * v / SPEED_OF_LIGHT)[:, None].expand(P, RX).to(device, dtype),
        amplitude=a[:, None].expand(P, RX).to(device, cdt),
    )


@pytest.fixture
def rd():
    """The :func:`rd_map` helper."""
    return rd_map


@pytest.fixture
def make_paths():
    """The :func:`monostatic_paths` helper."""
    return monostatic_paths
