"""Absolute units of the receiver against closed forms: radar equation, R^-4, HPF, bins, noise, ADC."""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.sensor import FMCWReceiver
from radaraug.sensor.defaults import FRONT_END_GAIN_DB
from radaraug.sensor.effects import (
    ADCClipping,
    ADCQuantization,
    AntiAliasLowPass,
    DCOffset,
    IFGain,
    IFHighPass,
    SystemGain,
    ThermalNoise,
)

K_B, T0 = 1.380649e-23, 290.0


def radar_equation_amplitude(config, rcs, R):
    """|a| = sqrt(lambda^2 sigma / ((4 pi)^3 R^4)), isotropic antennas."""
    return math.sqrt(config.wavelength_m**2 * rcs / ((4 * math.pi) ** 3 * R**4))


def peak_tone(config, receiver, rd, make_paths, R, speed=0.0, amp=1.0):
    x = receiver(make_paths(config, [R], [speed], [amp]))
    return rd(x)


def test_tone_amplitude_matches_radar_equation(cfg, rd, make_paths):
    """On-bin static target: |X| = A/2, A = sqrt(2 P_tx |a|^2) * G_fe * G_IF * |H_hp| * |H_aaf|."""
    k, rcs = 40, 1.0
    R = k * cfg.range_resolution_m
    a = radar_equation_amplitude(cfg, rcs, R)
    rx = FMCWReceiver(cfg, effects=[IFHighPass(), IFGain(), AntiAliasLowPass()], tx_power_dBm=5.0)
    X = peak_tone(cfg, rx, rd, make_paths, R, amp=a)
    f = k * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    h2 = 1 / (1 + (80e3 / f) ** 2) / (1 + (f / 500e3) ** 2)
    A = math.sqrt(2 * 10 ** (5 / 10) / 1000 * a**2) * 10 ** ((FRONT_END_GAIN_DB + 33) / 20) * math.sqrt(h2)
    M = cfg.num_chirps_per_frame
    mag = X.abs()
    assert tuple(np.unravel_index(int(mag[0].argmax()), mag[0].shape)) == (k, M // 2)
    assert float(mag[0, k, M // 2]) == pytest.approx(A / 2, rel=1e-4)


def test_r4_law_and_highpass_in_rd_map(cfg, rd, make_paths):
    """Doubling range: -12.04 dB (radar equation) plus the first-order HPF ratio |H(2f)|^2/|H(f)|^2."""
    M = cfg.num_chirps_per_frame
    for effects, with_hp in (([IFGain()], False), ([IFHighPass(), IFGain()], True)):
        rx = FMCWReceiver(cfg, effects=effects)
        levels = []
        for k in (10, 20, 40):
            R = k * cfg.range_resolution_m
            X = peak_tone(cfg, rx, rd, make_paths, R, amp=radar_equation_amplitude(cfg, 1.0, R))
            levels.append(20 * math.log10(float(X[0, k, M // 2].abs())))
        for i, k in enumerate((10, 20)):
            expected = -40 * math.log10(2)
            if with_hp:
                f = k * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
                expected += 10 * math.log10((1 + (80e3 / f) ** 2) / (1 + (80e3 / (2 * f)) ** 2))
            assert levels[i + 1] - levels[i] == pytest.approx(expected, abs=1e-3)


def test_highpass_matches_measured_first_order_losses():
    """-16.9 dB at 0.5 m, -11.2 dB at 1 m, -6.0 dB at 2 m, -1.7 dB at 5 m (80 kHz, 22.99 kHz/m)."""
    config = RadarConfig.bgt60tr13c(adc_delay_s=0.0)
    assert config.beat_Hz_per_m == pytest.approx(22.99e3, rel=1e-3)
    rx = FMCWReceiver(config, effects=[IFHighPass()])
    hp = rx.effects[0]
    f = torch.tensor([0.5, 1.0, 2.0, 5.0], dtype=torch.float64) * config.beat_Hz_per_m
    state = type("S", (), {"device": torch.device("cpu"), "config": config})()
    loss = 20 * torch.log10(hp.response(f, state).abs())
    torch.testing.assert_close(loss, torch.tensor([-16.9, -11.2, -6.0, -1.7], dtype=torch.float64), atol=0.05, rtol=0)


@pytest.mark.parametrize("order", [1, 2, 3, 4])
def test_cascade_section_cutoff_puts_the_3db_point_where_asked(order):
    """``order`` sections at ``section_cutoff(f3, order)``: ``|H(f3)|^2 = 1/2`` exactly (closed form)."""
    from radaraug.sensor.effects.filters import highpass_response, section_cutoff

    f3 = torch.tensor([150e3], dtype=torch.float64)
    h = highpass_response(f3, torch.tensor(section_cutoff(150e3, order), dtype=torch.float64), order)
    assert float(h.abs().square()) == pytest.approx(0.5, rel=1e-12)
    assert section_cutoff(150e3, 1) == 150e3 and section_cutoff(155e3, 2) == pytest.approx(155e3 / 1.5538, rel=1e-4)


def test_range_and_doppler_bins_and_sign(cfg, rd, make_paths):
    """Range bin = beat / (fs / N) with beat = 2 R S / c + 2 v / lambda (the Doppler shift moves a
    fast target by a fraction of a bin); moving away (v > 0) lands at M//2 + round(v / v_res)
    after a plain FFT over chirps + fftshift."""
    rx = FMCWReceiver(cfg, effects=[])
    M = cfg.num_chirps_per_frame
    for R, v in ((3.0, 1.0), (7.5, -2.2), (12.0, 0.4)):
        mag = rd(rx(make_paths(cfg, [R], [v]))).abs()[0]
        k, d = np.unravel_index(int(mag.argmax()), mag.shape)
        beat = 2 * R * cfg.slope_Hz_per_s / SPEED_OF_LIGHT + 2 * v * cfg.sampled_start_frequency_Hz / SPEED_OF_LIGHT
        assert k == round(beat / (cfg.sample_rate_Hz / cfg.num_samples_per_chirp))
        assert abs(k - R / cfg.range_resolution_m) < 0.75
        assert d == M // 2 + round(v / cfg.velocity_resolution_m_s)
        assert cfg.velocity_axis_m_s()[d] == pytest.approx(v, abs=cfg.velocity_resolution_m_s / 2 + 1e-3)


def test_doppler_wraps_beyond_vmax(cfg, rd, make_paths):
    rx = FMCWReceiver(cfg, effects=[])
    M, vres = cfg.num_chirps_per_frame, cfg.velocity_resolution_m_s
    v = 1.5 * cfg.max_velocity_m_s  # aliases to -0.5 v_max
    mag = rd(rx(make_paths(cfg, [5.0], [v]))).abs()[0]
    _, d = np.unravel_index(int(mag.argmax()), mag.shape)
    aliased = (round(v / vres) + M // 2) % M
    assert d == aliased
    assert cfg.velocity_axis_m_s()[d] == pytest.approx(v - 2 * cfg.max_velocity_m_s, abs=vres)


def test_thermal_noise_rms_closed_form(small_cfg, make_paths):
    """White: sigma = sqrt(k T0 F fs/2) * G_fe * G_sys * G_IF, in counts x 4095/2."""
    nf, gain_sys = 10.0, 3.0
    rx = FMCWReceiver(small_cfg, effects=[ThermalNoise(nf), SystemGain(gain_sys), IFGain()])
    gen = torch.Generator().manual_seed(0)
    x = rx(make_paths(small_cfg, [1.0], amplitudes=[0.0]), generator=gen)  # no signal
    x = torch.cat([x] + [rx(make_paths(small_cfg, [1.0], amplitudes=[0.0]), generator=gen) for _ in range(9)])
    sigma = math.sqrt(K_B * T0 * 10 ** (nf / 10) * small_cfg.sample_rate_Hz / 2)
    sigma *= 10 ** ((FRONT_END_GAIN_DB + gain_sys + small_cfg.if_gain_dB) / 20)
    assert float(x.std()) == pytest.approx(sigma, rel=0.02)


def test_filtered_noise_rms_closed_form(small_cfg, make_paths):
    """With first-order HPF/AAF the variance is sigma^2 * mean over the FFT bins of |H|^2."""
    rx = FMCWReceiver(small_cfg, effects=[ThermalNoise(12.0), IFHighPass(), IFGain(), AntiAliasLowPass()])
    gen = torch.Generator().manual_seed(3)
    x = torch.cat([rx(make_paths(small_cfg, [1.0], amplitudes=[0.0]), generator=gen) for _ in range(10)])
    N, fs = small_cfg.num_samples_per_chirp, small_cfg.sample_rate_Hz
    f = np.fft.fftfreq(N, 1 / fs)
    h = (1j * f / 80e3) / (1 + 1j * f / 80e3) / (1 + 1j * f / 500e3)
    h2 = np.abs(h) ** 2
    h2[N // 2] = np.real(h[N // 2]) ** 2  # a real signal keeps only the real part at Nyquist
    sigma = math.sqrt(K_B * T0 * 10 ** 1.2 * fs / 2) * 10 ** ((FRONT_END_GAIN_DB + small_cfg.if_gain_dB) / 20)
    assert float(x.std()) == pytest.approx(sigma * math.sqrt(h2.mean()), rel=0.02)


def test_default_noise_pinned_to_measured_counts(make_paths):
    """Measured on a BGT60TR13C: 1.3-1.5 counts RMS slow-time noise at 23 dB IF gain (2 MHz, 64 samples)."""
    config = RadarConfig.bgt60tr13c(
        start_frequency_Hz=58e9, end_frequency_Hz=63.5e9, sample_rate_Hz=2e6, num_samples_per_chirp=64,
        num_chirps_per_frame=64, chirp_repetition_time_s=591.125e-6, frame_repetition_time_s=77.27e-3,
        if_gain_dB=23,
    )
    rx = FMCWReceiver(config)
    gen = torch.Generator().manual_seed(0)
    counts = rx.to_counts(make_paths(config, [1.0], amplitudes=[0.0]), generator=gen).to(torch.float64)
    slow_time_std = counts.std(dim=-2)  # over chirps, per RX and sample (the leakage is static)
    assert 1.3 <= float(slow_time_std.mean()) <= 1.5
    # DC levels (measured, docs/receiver.md: RX1 ~1600-1650, RX2 ~1920-1970, RX3 ~2065-2070); the leakage tone
    # (1.3 cycles per chirp here) shifts the per-chirp mean by up to ~100 codes on RX1.
    mean_codes = counts.mean(dim=(-1, -2))
    assert abs(float(mean_codes[0]) - 1620) < 150 and abs(float(mean_codes[2]) - 2067.5) < 60


def test_quantization_and_clipping(cfg, make_paths):
    rx = FMCWReceiver(cfg, effects=[IFGain(), DCOffset([1000.0, 2047.5, 3000.0]), ADCQuantization(), ADCClipping()])
    x = rx(make_paths(cfg, [1.0, 4.0], amplitudes=[3e-2, 3e-4]))
    codes = (x + 1) * 4095 / 2
    torch.testing.assert_close(codes, torch.round(codes), atol=1e-6, rtol=0)
    assert float(x.min()) == -1.0 and float(x.max()) == 1.0  # strong target: clips at both rails
    assert float(x.abs().max()) <= 1.0
    counts = rx.to_counts(x)
    assert counts.dtype == torch.uint16
    torch.testing.assert_close(counts.to(torch.float64) * 2 / 4095 - 1, x, atol=1e-9, rtol=0)


def test_dc_offset_exact(small_cfg, make_paths):
    rx = FMCWReceiver(small_cfg, effects=[DCOffset([1600.0, 2047.5, 2070.0])])
    x = rx(make_paths(small_cfg, [2.0], amplitudes=[0.0]))
    torch.testing.assert_close(x.mean(dim=(-1, -2)) * 4095 / 2 + 2047.5,
                               torch.tensor([1600.0, 2047.5, 2070.0], dtype=torch.float64))
