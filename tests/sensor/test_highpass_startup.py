"""The IF high-pass' start-up transient against the exact response of first-order sections started at rest."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, InputTensorError
from radaraug.sensor.chain_state import startup_coefficients
from radaraug.sensor.effects import ADCClipping, AntiAliasLowPass, IFHighPass, effect_from_dict
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver


def _sections_from_rest(x: np.ndarray, dt: float, cutoff_Hz: float, order: int, highpass: bool = True) -> np.ndarray:
    """``order`` RC sections from rest, exact for an input linear between grid points.

    Each has the capacitor state ``v' = a (x - v)``, ``v(0) = 0``; a high-pass section outputs ``x - v``,
    a low-pass one ``v``.
    """
    a = 2 * math.pi * cutoff_Hz
    e = math.exp(-a * dt)
    for _ in range(order):
        v = np.zeros_like(x)
        slope = np.diff(x) / dt
        for i in range(1, len(x)):
            v[i] = x[i] - slope[i - 1] / a + (v[i - 1] - x[i - 1] + slope[i - 1] / a) * e
        x = x - v if highpass else v
    return x


def _one_path(config: RadarConfig, range_m: float) -> Paths:
    tau = 2 * range_m / 299_792_458.0
    rx = config.num_rx
    amp = torch.full((1, rx), 1e-3 * complex(math.cos(0.7), math.sin(0.7)), dtype=torch.complex128)
    return Paths(torch.full((1, rx), tau, dtype=torch.float64), torch.zeros(1, rx, dtype=torch.float64), amp)


@pytest.mark.parametrize(("order", "lowpass"), [(1, 0), (2, 0), (3, 0), (1, 1), (2, 2)])
@pytest.mark.parametrize("range_m", [0.04, 0.6, 2.5])
def test_transient_equals_sections_started_at_rest(order: int, lowpass: int, range_m: float) -> None:
    """The high-pass sections, then (``lowpass`` > 0) that many anti-alias sections at 500 kHz."""
    config = RadarConfig.bgt60tr13c()
    fc, f_lp = 80e3, 500e3
    after = [AntiAliasLowPass(cutoff_Hz=f_lp, order=lowpass)] if lowpass else []
    receiver = FMCWReceiver(config, effects=[IFHighPass(cutoff_Hz=fc, order=order, startup=1), *after])
    steady = FMCWReceiver(config, effects=[IFHighPass(cutoff_Hz=fc, order=order), *after])
    paths = _one_path(config, range_m)
    got, ss = receiver(paths)[0, 0].numpy(), steady(paths)[0, 0].numpy()
    # The beat tone from the ramp start (t = 0), the ADC's first sample at adc_delay.
    tau = float(paths.delay_s[0, 0])
    coef = np.conj(complex(paths.amplitude[0, 0])) * math.sqrt(2 * receiver.tx_power_W) * receiver.front_end_gain
    f_first, slope, td, fs = (config.sampled_start_frequency_Hz, config.slope_Hz_per_s, config.adc_delay_s,
                              config.sample_rate_Hz)
    n = config.num_samples_per_chirp
    dt = 4e-9
    t = np.arange(0.0, td + (n - 1) / fs + dt, dt)
    x = np.real(coef * np.exp(2j * np.pi * (f_first * tau - 0.5 * slope * tau**2 + slope * tau * (t - td))))
    y = _sections_from_rest(x, dt, fc, order)
    if lowpass:
        y = _sections_from_rest(y, dt, f_lp, lowpass, highpass=False)
    ref = y[np.round((td + np.arange(n) / fs) / dt).astype(int)]
    scale = np.abs(ref).max()
    # Left out: the low-pass sections' own start-up on the tone, (b t)^(L-1) e^(-b t) at the first
    # sample (b = 2 pi 500 kHz, t = 3.1 us): 6e-5 for one section, 6e-4 for two.
    assert np.abs(got - ref).max() < 1e-3 * scale
    assert np.abs(ss - ref).max() > 0.05 * scale  # the steady state alone misses the start


def test_startup_coefficients_start_at_the_input() -> None:
    # The sections pass a jump at once: response at t = 0 is the input, H(j w) + A_1 = 1.
    beta = torch.tensor([0.3j, -2.0j, 10.0j, 0.0j], dtype=torch.complex128)
    for order in (1, 2, 4):
        h = (beta / (1 + beta)) ** order
        assert torch.allclose(h + startup_coefficients(beta, order)[0], torch.ones_like(beta), atol=1e-12)


def test_a_strong_near_path_clips_only_at_the_chirp_start() -> None:
    config = RadarConfig.bgt60tr13c()
    near = Paths(torch.full((1, config.num_rx), 2 * 0.02 / 299_792_458.0, dtype=torch.float64),
                 torch.zeros(1, config.num_rx, dtype=torch.float64),
                 torch.ones(1, config.num_rx, dtype=torch.complex128))
    # A leakage-like path (~1 kHz beat): the sections start from its full value and decay with
    # 1 / (2 pi fc) = 2 us, so its first sample is ~20x its (high-passed) steady state.
    unit = FMCWReceiver(config, effects=[IFHighPass(startup=1)])(near)
    strong = dataclasses.replace(near, amplitude=near.amplitude * 3 / float(unit.abs().max()))
    for startup, clips in ((1, True), (0, False)):
        receiver = FMCWReceiver(config, effects=[IFHighPass(startup=startup), ADCClipping()])
        x = receiver(strong)
        railed = x.abs() >= 1.0
        assert bool(railed.any()) is clips
        if clips:
            assert not bool(railed[..., config.num_samples_per_chirp // 8:].any())


def test_description_round_trip_and_bad_values() -> None:
    on = IFHighPass(cutoff_Hz=90e3, order=2, startup=1)
    assert effect_from_dict(on.to_dict()).to_dict() == on.to_dict()
    assert "startup" not in IFHighPass().to_dict()["params"]  # older descriptions stay as they were
    with pytest.raises(ConfigError, match="startup"):
        IFHighPass(startup=2)
    config = RadarConfig.bgt60tr13c()
    per_rx = FMCWReceiver(config, effects=[IFHighPass(cutoff_Hz=[70e3, 80e3, 90e3], startup=1)])
    with pytest.raises(InputTensorError, match="one cutoff"):
        per_rx(_one_path(config, 1.0))


def test_static_signal_once_keeps_superposition() -> None:
    """The room's start-up, synthesized once (``static_signal`` / ``static_chirp``), adds as the paths would."""
    config = RadarConfig.bgt60tr13c()
    effects = [IFHighPass(startup=1, order=2), AntiAliasLowPass(order=2)]
    receiver = FMCWReceiver(config, effects=effects)
    room = Paths.cat([_one_path(config, r) for r in (0.03, 1.2, 4.0)])
    moving = dataclasses.replace(_one_path(config, 2.0), delay_rate=torch.full((1, config.num_rx), 2 * 1.5 / 299_792_458.0,
                                                                              dtype=torch.float64))
    whole = receiver(Paths.cat([room, moving]))
    parts = receiver(moving, static_signal=receiver.static_signal(room))
    assert torch.allclose(parts, whole, atol=1e-9 * float(whole.abs().max()))
    assert torch.allclose(receiver.static_chirp(room), receiver.static_signal(room)[..., 0, :], atol=1e-12)
