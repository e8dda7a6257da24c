"""Fixtures and signal builders for the transform tests."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig


@pytest.fixture
def cfg() -> RadarConfig:
    """The paper's configuration, with fewer samples and chirps to keep the tests fast."""
    return RadarConfig.bgt60tr13c(num_samples_per_chirp=128, num_chirps_per_frame=32, sample_rate_Hz=0.5e6)


def beat_cube(
    cfg: RadarConfig, r0_m: float, v_m_s: float, amplitude: float = 0.5, n_rx: int = 1
) -> torch.Tensor:
    """Raw cube (rx, chirps, samples) of one point target from the beat-signal formula.

    IF = A cos(2 pi (f_c tau + S t tau - S tau**2 / 2)), tau = 2 (R0 + v (m T_c + t)) / c, with t the
    time since the ramp start (ADC delay included) and f_c the ramp start frequency.
    """
    n = cfg.num_samples_per_chirp
    t = cfg.adc_delay_s + torch.arange(n, dtype=torch.float64) / cfg.sample_rate_Hz
    m = torch.arange(cfg.num_chirps_per_frame, dtype=torch.float64)[:, None]
    tau = 2 * (r0_m + v_m_s * (m * cfg.chirp_repetition_time_s + t)) / SPEED_OF_LIGHT
    s = cfg.slope_Hz_per_s
    phase = 2 * math.pi * (cfg.start_frequency_Hz * tau + s * t * tau - s * tau**2 / 2)
    return (amplitude * torch.cos(phase)).expand(n_rx, -1, -1).clone()
