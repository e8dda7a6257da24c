"""Effect objects: registry, parameters, and each mechanism against its closed form."""

from __future__ import annotations

import json
import math

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import ConfigError
from radaraug.sensor import EFFECTS, FMCWReceiver, effect_from_dict
from radaraug.sensor.defaults import FRONT_END_GAIN_DB
from radaraug.sensor.effects import (
    IFGain,
    PhaseNoise,
    RxGainPhaseMismatch,
    SpurTone,
    SystemGain,
    TxRxLeakage,
)

DESIGN_NAMES = {
    "system_gain", "thermal_noise", "tx_rx_leakage", "phase_noise", "if_highpass", "anti_alias_lowpass",
    "adc_quantization", "adc_clipping", "dc_offset", "rx_gain_phase_mismatch", "chirp_nonlinearity",
    "spur_tone", "interference", "vibrating_clutter", "multipath", "static_clutter",
}


def test_registry_names_and_round_trip(cfg):
    # Registered beyond the design list: the IF gain, and the ADC-referred noise and frame drift
    # the diagnosis loop needs to explain measured noise.
    assert set(EFFECTS) - DESIGN_NAMES == {"if_gain", "adc_noise", "frame_drift"}
    rx = FMCWReceiver(cfg)
    assert [e.name for e in rx.effects] == [
        "tx_rx_leakage", "phase_noise", "thermal_noise", "system_gain", "if_highpass", "if_gain",
        "adc_noise", "anti_alias_lowpass", "dc_offset", "adc_quantization", "adc_clipping",
    ]
    text = json.dumps(rx.to_dict())
    back = FMCWReceiver.from_dict(cfg, json.loads(text))
    assert back.to_dict() == rx.to_dict()
    for e in rx.effects:
        again = type(e).from_params(e.params())
        assert again.to_dict() == e.to_dict()


def test_bad_effect_parameters_raise():
    with pytest.raises(ConfigError, match="unknown parameters"):
        SystemGain.from_params({"gain": 1.0})
    with pytest.raises(ConfigError, match="unknown effect"):
        effect_from_dict({"name": "flux_capacitor"})
    with pytest.raises(ConfigError, match="finite"):
        SystemGain(float("nan"))


def test_per_rx_parameter_length_checked(cfg, make_paths):
    rx = FMCWReceiver(cfg, effects=[RxGainPhaseMismatch(gain_dB=[0.0, 1.0])])
    with pytest.raises(ConfigError, match="RX channels"):
        rx(make_paths(cfg, [2.0]))


def test_receiver_kwargs_conflict_with_explicit_effects(cfg):
    with pytest.raises(ConfigError):
        FMCWReceiver(cfg, effects=[IFGain()], noise_figure_dB=10.0)
    with pytest.raises(ConfigError):
        FMCWReceiver(cfg, synthesis="magic")


def test_rx_mismatch_shifts_tone_phase_and_gain(cfg, rd, make_paths):
    k = 30
    R = k * cfg.range_resolution_m
    M = cfg.num_chirps_per_frame
    base = rd(FMCWReceiver(cfg, effects=[])(make_paths(cfg, [R])))[..., k, M // 2]
    mm = RxGainPhaseMismatch(gain_dB=[0.0, -6.0, 3.0], phase_rad=[0.0, 0.5, -1.0])
    out = rd(FMCWReceiver(cfg, effects=[mm])(make_paths(cfg, [R])))[..., k, M // 2]
    ratio = out / base
    torch.testing.assert_close(ratio.abs(), torch.tensor([1.0, 10 ** (-6 / 20), 10 ** (3 / 20)], dtype=torch.float64))
    torch.testing.assert_close(ratio.angle(), torch.tensor([0.0, 0.5, -1.0], dtype=torch.float64))


def test_leakage_tone_level(cfg, rd, make_paths):
    """A leakage path on a range bin reads sqrt(2 P_tx c) * G_fe / 2 (no filters)."""
    k = 3
    leak = TxRxLeakage(coupling_dB=[-40.0, -50.0, -60.0], range_m=k * cfg.range_resolution_m)
    rx = FMCWReceiver(cfg, effects=[leak], tx_power_dBm=0.0)
    X = rd(rx(make_paths(cfg, [5.0], amplitudes=[0.0])))[..., k, cfg.num_chirps_per_frame // 2].abs()
    expected = torch.tensor([math.sqrt(2e-3 * 10 ** (c / 10)) * 10 ** (FRONT_END_GAIN_DB / 20) / 2 for c in (-40, -50, -60)],
                            dtype=torch.float64)
    torch.testing.assert_close(X, expected, rtol=1e-6, atol=0)


def test_phase_noise_skirt_power_closed_form(cfg, make_paths):
    """Linearised residual phase 2 pi tau nu: extra power = (A^2 / 2) (2 pi tau nu_rms)^2."""
    R, nu = 10.0, 2e6
    paths = make_paths(cfg, [R], amplitudes=[1e-4])
    clean = FMCWReceiver(cfg, effects=[])(paths)
    rx = FMCWReceiver(cfg, effects=[PhaseNoise(freq_noise_rms_Hz=nu, corner_Hz=100e3, num_paths=1)])
    skirt = rx(paths, generator=torch.Generator().manual_seed(0)) - clean
    A = 1e-4 * math.sqrt(2 * rx.tx_power_W) * rx.front_end_gain
    tau = 2 * R / SPEED_OF_LIGHT
    expected = A**2 / 2 * (2 * math.pi * tau * nu) ** 2
    assert float(skirt.pow(2).mean()) == pytest.approx(expected, rel=0.1)


def test_spur_tone_level_and_frequency(small_cfg, rd):
    from radaraug.sensor import Paths

    f = 10 * small_cfg.sample_rate_Hz / small_cfg.num_samples_per_chirp
    rx = FMCWReceiver(small_cfg, effects=[SpurTone(freq_Hz=f, amplitude_counts=[4.0, 2.0, 1.0])])
    empty = Paths(torch.zeros(0, 3, dtype=torch.float64), torch.zeros(0, 3, dtype=torch.float64),
                  torch.zeros(0, 3, dtype=torch.complex128))
    x = rx(empty)
    rng = torch.fft.rfft(x, dim=-1).abs() / small_cfg.num_samples_per_chirp  # per chirp
    torch.testing.assert_close(rng[..., 10].mean(-1) * 4095, torch.tensor([4.0, 2.0, 1.0], dtype=torch.float64), rtol=1e-6, atol=0)


@pytest.mark.parametrize("jitter", [0.5, 1.2, 3.0])
def test_unlocked_spur_keeps_exp_minus_sigma_squared_in_its_line(small_cfg, jitter):
    """Closed form: a per-chirp Gaussian phase of RMS s keeps |E e^{j phi}|^2 = exp(-s^2) of the line's power.

    The line is the chirps' coherent sum along the locked tone's phase progression ``2 pi f m PRT``;
    of M chirps it holds ``exp(-s^2) + (1 - exp(-s^2)) / M`` of the power, the rest spreads over Doppler.
    """
    from radaraug.sensor import Paths

    cfg = small_cfg
    M, N = cfg.num_chirps_per_frame, cfg.num_samples_per_chirp
    f = 10 * cfg.sample_rate_Hz / N  # on range bin 10: no leakage into other bins
    empty = Paths(torch.zeros(0, 3, dtype=torch.float64), torch.zeros(0, 3, dtype=torch.float64),
                  torch.zeros(0, 3, dtype=torch.complex128))
    g = torch.Generator().manual_seed(3)
    rx = FMCWReceiver(cfg, effects=[SpurTone(freq_Hz=f, amplitude_counts=4.0, phase_jitter_rad=jitter)])
    r = torch.stack([torch.fft.rfft(rx(empty, generator=g), dim=-1)[..., 10] for _ in range(300)])  # (F, RX, M)
    m = torch.arange(M, dtype=torch.float64)
    demod = r * torch.exp(-2j * math.pi * f * m * cfg.chirp_repetition_time_s)
    line = demod.mean(-1).abs().square().mean() / r.abs().square().mean()
    expected = math.exp(-jitter**2) + (1 - math.exp(-jitter**2)) / M
    assert float(line) == pytest.approx(expected, abs=0.02)
    # jitter moves the power in Doppler and adds none: every chirp carries the tone's full amplitude
    torch.testing.assert_close(r.abs(), torch.full_like(r.abs(), 4.0 * (2 / 4095) * N / 2), rtol=1e-6, atol=0)
    # a locked spur draws nothing from the generator
    g1, g2 = torch.Generator().manual_seed(5), torch.Generator().manual_seed(5)
    FMCWReceiver(cfg, effects=[SpurTone(freq_Hz=f)])(empty, generator=g1)
    assert torch.equal(torch.rand(3, generator=g1), torch.rand(3, generator=g2))


def test_gradients_flow_to_effect_parameters(cfg, make_paths):
    rx = FMCWReceiver(cfg)
    gain = rx.effect("system_gain").gain_dB.requires_grad_()
    nf = rx.effect("thermal_noise").noise_figure_dB.requires_grad_()
    x = rx(make_paths(cfg, [3.0], amplitudes=[1e-3], dtype=torch.float32), generator=torch.Generator().manual_seed(0))
    x.pow(2).mean().backward()
    assert gain.grad is not None and float(gain.grad) > 0
    assert nf.grad is not None and torch.isfinite(nf.grad)


def test_spur_tone_uses_each_frames_own_start_in_a_batch(small_cfg):
    """A batch of frames with per-frame starts equals the frames simulated one by one."""
    from radaraug.errors import InputTensorError
    from radaraug.sensor import Paths

    f = 123_456.7  # not a whole number of cycles per frame period
    rx = FMCWReceiver(small_cfg, effects=[SpurTone(freq_Hz=f, amplitude_counts=3.0)])
    empty = Paths(torch.zeros(2, 0, 3, dtype=torch.float64), torch.zeros(2, 0, 3, dtype=torch.float64),
                  torch.zeros(2, 0, 3, dtype=torch.complex128))
    starts = torch.tensor([0.0, 0.1037], dtype=torch.float64)
    batch = rx(empty, frame_start_s=starts)
    for k in range(2):
        alone = rx(Paths(*(t[k] for t in (empty.delay_s, empty.delay_rate, empty.amplitude))),
                   frame_start_s=float(starts[k]))
        torch.testing.assert_close(batch[k], alone, rtol=0, atol=1e-12)
    assert not torch.allclose(batch[0], batch[1])
    with pytest.raises(InputTensorError, match="broadcast"):
        rx(empty, frame_start_s=torch.zeros(3))
    with pytest.raises(InputTensorError, match="NaN"):
        rx(empty, frame_start_s=torch.tensor([0.0, math.nan]))


def test_module_apply_works_on_receivers_and_effects():
    """``nn.Module.apply(fn)`` reaches every effect (effects implement ``forward(state)``)."""
    from radaraug.config import RadarConfig
    from radaraug.sensor.receiver import FMCWReceiver

    rx = FMCWReceiver(RadarConfig.bgt60tr13c())
    seen = []
    assert rx.apply(lambda m: seen.append(type(m).__name__)) is rx
    assert "FMCWReceiver" in seen and len(seen) > len(rx.effects)
