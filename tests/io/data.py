"""Tiny synthetic captures made by code, with contents known in closed form.

* :func:`tone_counts`: a point target at a chosen range (a real IF tone at
  ``f_b = 2 * R * slope / c``) plus Gaussian noise, around a DC offset, as 12-bit counts.
* :func:`frame_pattern`: a deterministic frame that encodes its own index, so a reader that
  returns frames out of order, shifted or from the wrong file is caught.

Loaded by ``tests/io/conftest.py`` under a unique module name (``radaraug_tests_io_data``)
so it cannot clash with other test folders' helpers.
"""

from __future__ import annotations

import math

import numpy as np
import torch

from radaraug.config import RadarConfig


def tiny_config(**overrides: object) -> RadarConfig:
    """3 RX, 4 chirps x 32 samples at 1 MHz on 60-61 GHz: small enough for fast tests."""
    params: dict[str, object] = dict(
        start_frequency_Hz=60e9,
        end_frequency_Hz=61e9,
        sample_rate_Hz=1e6,
        num_samples_per_chirp=32,
        num_chirps_per_frame=4,
        chirp_repetition_time_s=100e-6,
        frame_repetition_time_s=0.01,
        rx_antennas=(1, 2, 3),
        tx_antennas=(1,),
        tx_power_level=31,
        if_gain_dB=33,
        hp_cutoff_Hz=80e3,
        aaf_cutoff_Hz=500e3,
    )
    params.update(overrides)
    return RadarConfig(**params)  # type: ignore[arg-type]


def tone_counts(
    config: RadarConfig,
    num_frames: int,
    *,
    range_bin: int = 5,
    amplitude_counts: float = 600.0,
    noise_counts: float = 1.5,
    dc_counts: float = 1900.0,
    seed: int = 0,
) -> np.ndarray:
    """uint16 counts ``(F, rx, chirps, samples)`` of a static target sitting exactly on ``range_bin``.

    The target range is ``range_bin * range_resolution_m``, so its beat frequency is
    ``range_bin * fs / N`` and all of its energy falls in that FFT bin.
    """
    g = torch.Generator().manual_seed(seed)
    n = config.num_samples_per_chirp
    t = torch.arange(n, dtype=torch.float64) / config.sample_rate_Hz
    range_m = range_bin * config.range_resolution_m
    f_beat = config.beat_Hz_per_m * range_m
    phase = 2 * math.pi * torch.rand(config.num_rx, 1, 1, generator=g, dtype=torch.float64)
    tone = amplitude_counts * torch.cos(2 * math.pi * f_beat * t + phase)
    shape = (num_frames, config.num_rx, config.num_chirps_per_frame, n)
    noise = noise_counts * torch.randn(shape, generator=g, dtype=torch.float64)
    counts = torch.round(dc_counts + tone + noise).clamp(0, config.adc_full_scale_counts)
    return counts.numpy().astype(np.uint16)


def frame_pattern(config: RadarConfig, index: int) -> np.ndarray:
    """Frame ``index`` as uint16 counts: sample ``j`` of the flattened frame is ``(7*index + j) % 4096``."""
    size = config.num_rx * config.num_chirps_per_frame * config.num_samples_per_chirp
    flat = (7 * index + np.arange(size)) % (config.adc_full_scale_counts + 1)
    return flat.reshape(config.num_rx, config.num_chirps_per_frame, config.num_samples_per_chirp).astype(
        np.uint16
    )


def pattern_counts(config: RadarConfig, num_frames: int, first: int = 0) -> np.ndarray:
    """Frames ``first .. first+num_frames-1`` of :func:`frame_pattern`, stacked."""
    return np.stack([frame_pattern(config, first + i) for i in range(num_frames)])
