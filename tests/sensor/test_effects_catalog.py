"""The calibration catalog's effects, priors and hardware order, against closed forms.

Each mechanism is checked against what physics or the stated model predicts (radar-equation
levels, Bessel sideband levels, paired-echo ratios, filter noise bandwidths, Hann burst energy),
never against the code's own earlier output.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import torch
from scipy.special import jv

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import ConfigError, InputTensorError
from radaraug.sensor import EFFECTS, HARDWARE_ORDER, FMCWReceiver, Paths, effect_from_dict, insert_in_order
from radaraug.sensor.defaults import FRONT_END_GAIN_DB, default_effects
from radaraug.sensor.effects import (
    ADCClipping,
    ADCNoise,
    AntiAliasLowPass,
    ChirpNonlinearity,
    DCOffset,
    Effect,
    FrameDrift,
    IFGain,
    IFHighPass,
    Interference,
    Multipath,
    Prior,
    StaticClutter,
    SystemGain,
    ThermalNoise,
    TxRxLeakage,
    VibratingClutter,
)

NEW = (ADCNoise, FrameDrift, ChirpNonlinearity, StaticClutter, VibratingClutter, Multipath, Interference)
G_FE = 10 ** (FRONT_END_GAIN_DB / 20)
COUNTS = 4095 / 2  # ADC counts per SDK float unit


def empty_paths(config, batch: tuple[int, ...] = (), dtype=torch.float64, device="cpu") -> Paths:
    cdt = torch.complex64 if dtype == torch.float32 else torch.complex128
    shape = (*batch, 0, config.num_rx)
    return Paths(torch.zeros(shape, dtype=dtype, device=device), torch.zeros(shape, dtype=dtype, device=device),
                 torch.zeros(shape, dtype=cdt, device=device))


def tone_amplitude(level_dB: float, tx_power_dBm: float = 0.0) -> float:
    """Peak ADC-float amplitude of a path ``level_dB`` below the TX power: sqrt(2 P_tx L) G_fe."""
    return math.sqrt(2 * 10 ** (tx_power_dBm / 10) / 1000 * 10 ** (level_dB / 10)) * G_FE


def dirichlet(delta: float, n: int) -> complex:
    """(1/N) sum_n exp(j 2 pi delta n / N): a tone ``delta`` bins off a rectangular-window FFT bin."""
    k = np.arange(n)
    return complex(np.exp(2j * np.pi * delta * k / n).mean())


# --------------------------------------------------------------------------- order and priors
def test_hardware_order_lists_every_registered_effect_once(cfg):
    assert len(HARDWARE_ORDER) == len(set(HARDWARE_ORDER))
    assert set(HARDWARE_ORDER) == set(EFFECTS)
    names = [e.name for e in default_effects(cfg)]
    assert names == sorted(names, key=HARDWARE_ORDER.index)  # the default chain is in hardware order


def test_insert_in_order_places_replaces_and_copies(cfg):
    chain = default_effects(cfg)
    before = list(chain)
    out = insert_in_order(chain, Multipath())
    assert out[0].name == "multipath" and chain == before  # input list untouched
    out = insert_in_order(out, ADCNoise())
    out = insert_in_order(out, FrameDrift())
    out = insert_in_order(out, StaticClutter())
    out = insert_in_order(out, ChirpNonlinearity())
    out = insert_in_order(out, Interference())
    names = [e.name for e in out]
    assert names == [
        "multipath", "tx_rx_leakage", "static_clutter", "phase_noise", "chirp_nonlinearity", "thermal_noise",
        "system_gain", "if_highpass", "if_gain", "interference", "adc_noise", "anti_alias_lowpass",
        "frame_drift", "dc_offset", "adc_quantization", "adc_clipping",
    ]
    new_leak = TxRxLeakage(coupling_dB=-40.0)
    out2 = insert_in_order(out, new_leak)
    assert [e.name for e in out2] == names and out2[1] is new_leak
    assert [e.name for e in insert_in_order([], SystemGain())] == ["system_gain"]
    assert [e.name for e in insert_in_order([ADCClipping()], DCOffset())] == ["dc_offset", "adc_clipping"]

    class Custom(Effect):
        name = "custom_stage"

    custom = Custom()
    mixed = insert_in_order([SystemGain(), custom, IFGain()], IFHighPass())
    assert [e.name for e in mixed] == ["system_gain", "custom_stage", "if_highpass", "if_gain"]
    with pytest.raises(ConfigError, match="HARDWARE_ORDER"):
        insert_in_order(chain, custom)


def test_prior_validation_and_mapping():
    with pytest.raises(ConfigError):
        Prior(1.0, 0.0)
    with pytest.raises(ConfigError):
        Prior(0.0, 1.0, "log")
    with pytest.raises(ConfigError):
        Prior(0.0, 1.0, "exp")
    with pytest.raises(ConfigError):
        Prior(0.0, math.inf)
    p = Prior(10.0, 1000.0, "log")
    assert p.from_unit(0.0) == pytest.approx(10.0) and p.from_unit(0.5) == pytest.approx(100.0)
    assert p.contains(10.0) and p.contains(1000.0) and not p.contains(9.99)
    assert Prior(-1.0, 3.0).from_unit(0.25) == pytest.approx(0.0)


EXPECTED_SEARCHED = {
    "system_gain": {"gain_dB"},
    "thermal_noise": {"noise_figure_dB"},
    "tx_rx_leakage": {"coupling_dB", "range_m", "phase_rad"},
    "phase_noise": {"freq_noise_rms_Hz", "corner_Hz"},
    "if_highpass": {"cutoff_Hz"},
    "anti_alias_lowpass": {"cutoff_Hz"},
    "dc_offset": {"level_counts"},
    "rx_gain_phase_mismatch": {"gain_dB", "phase_rad"},
    "spur_tone": {"freq_Hz", "amplitude_counts", "phase_rad", "phase_jitter_rad"},
    "if_gain": set(),
    "adc_quantization": set(),
    "adc_clipping": set(),
    "adc_noise": {"rms_counts"},
    "frame_drift": {"gain_rms_dB", "dc_rms_counts"},
    "chirp_nonlinearity": {"deviation_Hz", "ripple_Hz", "phase_rad"},
    "static_clutter": {"range_m", "level_dB", "phase_rad"},
    "vibrating_clutter": {"range_m", "level_dB", "displacement_m", "vibration_Hz", "phase_rad"},
    "multipath": {"extra_range_m", "level_dB", "phase_rad"},
    "interference": {"probability", "amplitude_counts", "duration_s"},
}


@pytest.mark.parametrize("which", ["cfg", "small_cfg"])
def test_every_effect_has_valid_priors_containing_its_defaults(which, request):
    config = request.getfixturevalue(which)
    config_value = {  # parameters whose default None means "take it from the config"
        ("if_highpass", "cutoff_Hz"): config.effective_hp_cutoff_Hz,
        ("anti_alias_lowpass", "cutoff_Hz"): config.effective_aaf_cutoff_Hz,
    }
    assert set(EXPECTED_SEARCHED) == set(EFFECTS)
    for name, cls in EFFECTS.items():
        priors = cls.priors(config)
        assert set(priors) == EXPECTED_SEARCHED[name], name
        assert set(priors) <= set(cls.param_names), name
        for pname, prior in priors.items():
            assert isinstance(prior, Prior)
            assert prior.lo < prior.hi and (prior.scale == "lin" or prior.lo > 0), (name, pname)
            value = cls().params()[pname]
            values = [config_value[(name, pname)]] if value is None else value.reshape(-1).tolist()
            assert all(prior.contains(v) for v in values), (name, pname, values, prior)
    assert EFFECTS["spur_tone"].priors(config)["freq_Hz"].hi == config.sample_rate_Hz / 2
    assert EFFECTS["static_clutter"].priors(config)["range_m"].hi == pytest.approx(config.max_range_m)


# --------------------------------------------------------------------------- serialisation and validation
ROUND_TRIP = [
    ADCNoise(rms_counts=[0.3, 1.0, 2.5]),
    FrameDrift(gain_rms_dB=0.4, dc_rms_counts=[1.0, 2.0, 3.0]),
    ChirpNonlinearity(deviation_Hz=3e5, ripple_Hz=40e3, phase_rad=0.3, num_paths=5),
    StaticClutter(range_m=[1.0, 2.5], level_dB=[-70.0, -90.0], phase_rad=0.2),
    StaticClutter(range_m=1.5, level_dB=-60.0),
    VibratingClutter(range_m=2.0, level_dB=-75.0, displacement_m=1e-3, vibration_Hz=33.0, phase_rad=1.0),
    Multipath(extra_range_m=[0.7, 1.9], level_dB=[-6.0, -12.0], phase_rad=[0.0, 3.0]),
    Interference(probability=0.2, amplitude_counts=300.0, duration_s=4e-6),
]


@pytest.mark.parametrize("effect", ROUND_TRIP, ids=lambda e: e.name)
def test_new_effects_round_trip_through_json(effect):
    data = json.loads(json.dumps(effect.to_dict()))
    back = effect_from_dict(data)
    assert type(back) is type(effect) and back.to_dict() == effect.to_dict()
    assert type(effect).from_params(effect.params()).to_dict() == effect.to_dict()
    assert data["params"] and all(not isinstance(v, torch.Tensor) for v in data["params"].values())


@pytest.mark.parametrize(
    "make",
    [
        lambda: StaticClutter(level_dB=math.nan),
        lambda: StaticClutter(range_m=[1.0, 2.0], level_dB=[-60.0, -70.0, -80.0]),
        lambda: StaticClutter(range_m=-1.0),
        lambda: StaticClutter(range_m=[], level_dB=[]),
        lambda: StaticClutter(range_m=[[1.0]]),
        lambda: VibratingClutter(displacement_m=-1e-3),
        lambda: VibratingClutter(vibration_Hz=0.0),
        lambda: VibratingClutter(range_m=[1.0, 2.0], vibration_Hz=[10.0, 20.0, 30.0]),
        lambda: Multipath(extra_range_m=-0.1),
        lambda: Multipath(level_dB=math.inf),
        lambda: ChirpNonlinearity(ripple_Hz=0.0),
        lambda: ChirpNonlinearity(deviation_Hz=-1.0),
        lambda: ChirpNonlinearity(num_paths=-1),
        lambda: ChirpNonlinearity(deviation_Hz=[1e3, 2e3]),
        lambda: Interference(probability=1.5),
        lambda: Interference(duration_s=0.0),
        lambda: Interference(amplitude_counts=-1.0),
        lambda: ADCNoise(rms_counts=-0.1),
        lambda: ADCNoise(rms_counts="loud"),
        lambda: FrameDrift(gain_rms_dB=-0.5),
        lambda: FrameDrift(dc_rms_counts=math.nan),
    ],
)
def test_bad_values_raise_config_error(make):
    with pytest.raises(ConfigError):
        make()


def test_per_rx_lengths_checked_at_call(small_cfg):
    for eff in (ADCNoise(rms_counts=[1.0, 2.0]), FrameDrift(dc_rms_counts=[1.0, 2.0])):
        with pytest.raises(ConfigError, match="RX channels"):
            FMCWReceiver(small_cfg, effects=[eff])(empty_paths(small_cfg))


# --------------------------------------------------------------------------- clutter
def test_static_clutter_level_range_bin_and_phase(cfg, rd):
    """Scatterers at range bins 30 and 50 read sqrt(2 P_tx L) G_fe / 2 there, on every RX."""
    res, M = cfg.range_resolution_m, cfg.num_chirps_per_frame
    assert cfg.beat_Hz_per_m * res == pytest.approx(cfg.sample_rate_Hz / cfg.num_samples_per_chirp)
    levels = [-70.0, -95.0]
    eff = StaticClutter(range_m=[30 * res, 50 * res], level_dB=levels, phase_rad=0.0)
    X = rd(FMCWReceiver(cfg, effects=[eff], tx_power_dBm=0.0)(empty_paths(cfg)))
    mag = X.abs()
    for k, lvl in zip((30, 50), levels):
        torch.testing.assert_close(mag[:, k, M // 2], torch.full((3,), tone_amplitude(lvl) / 2, dtype=torch.float64),
                                   rtol=1e-6, atol=0)
    assert int(mag[0, :, M // 2].argmax()) == 30
    assert float(mag[0, :, M // 2 + 1:].max()) < 1e-9 * float(mag.max())  # static: zero Doppler only
    # One scatterer given as plain numbers (K = 1); its phase adds to the beat tone's.
    one = [FMCWReceiver(cfg, effects=[StaticClutter(range_m=30 * res, level_dB=-70.0, phase_rad=p)],
                        tx_power_dBm=0.0)(empty_paths(cfg)) for p in (0.0, 0.8)]
    ratio = rd(one[1])[:, 30, M // 2] / rd(one[0])[:, 30, M // 2]
    torch.testing.assert_close(ratio, torch.polar(torch.ones(3, dtype=torch.float64),
                                                  torch.full((3,), 0.8, dtype=torch.float64)))


def test_vibrating_clutter_bessel_sidebands_and_doppler_sign(cfg, rd):
    """Doppler lines at k * f_vib with amplitude J_k(beta) and phase k (w t_1 + phi).

    With the carrier's beat tone ``C exp(j 2 pi kr n / N)`` (``C = A exp(j 2 pi (f0 tau - S tau^2/2))``,
    the documented phase model) and ``exp(j beta sin(w t + phi)) = sum_k J_k exp(j k (w t + phi))``,
    the cell (kr, Doppler line k) of the rectangular RD map holds
    ``1/2 exp(j k theta) [C J_k D(d_k) + conj(C) J_-k D(d_k - 2 kr)]``: ``theta = w t_1 + phi``,
    ``t_1`` = frame start + ADC delay (the first sample's time), ``D`` the range-FFT Dirichlet
    factor, ``d_k = k f_vib N / fs`` the line's fast-time offset in bins, the second term the
    real signal's negative-frequency image. The +1 line sits at *positive* Doppler, like a
    target moving away.
    """
    M, N, T = cfg.num_chirps_per_frame, cfg.num_samples_per_chirp, cfg.chirp_repetition_time_s
    kr, step = 20, 2
    f_vib = step / (M * T)  # two Doppler bins
    beta, phi, t_frame, level = 1.7, 0.4, 0.0123, -70.0
    R = kr * cfg.range_resolution_m
    eff = VibratingClutter(range_m=R, level_dB=level, displacement_m=beta * cfg.wavelength_m / (4 * math.pi),
                           vibration_Hz=f_vib, phase_rad=phi)
    X = rd(FMCWReceiver(cfg, effects=[eff], tx_power_dBm=0.0)(empty_paths(cfg), frame_start_s=t_frame))[0, kr]
    # Parameters are stored in the default dtype (float32): use the stored values.
    R, f_vib, beta = float(eff.range_m), float(eff.vibration_Hz), float(eff.displacement_m) * 4 * math.pi / cfg.wavelength_m
    tau = 2 * R / SPEED_OF_LIGHT
    cycles = cfg.sampled_start_frequency_Hz * tau - cfg.slope_Hz_per_s * tau**2 / 2
    C = tone_amplitude(level) * np.exp(2j * np.pi * (cycles - round(cycles)))
    theta = 2 * math.pi * f_vib * (t_frame + cfg.adc_delay_s) + phi
    for k in range(-5, 6):
        d = k * f_vib * N / cfg.sample_rate_Hz
        expected = 0.5 * np.exp(1j * k * theta) * (
            C * jv(k, beta) * dirichlet(d, N) + np.conj(C) * jv(-k, beta) * dirichlet(d - 2 * kr, N))
        got = complex(X[M // 2 + step * k])
        assert abs(got - expected) < 1e-6 * abs(C), (k, got, expected)
    assert abs(X[M // 2 + step]) > 1e4 * abs(X[M // 2 + 1])  # nothing between the lines


def test_vibrating_clutter_is_continuous_across_frames(small_cfg):
    """The second half of a 32-chirp frame equals a 16-chirp frame starting 16 PRTs later."""
    T = small_cfg.chirp_repetition_time_s
    eff = VibratingClutter(range_m=1.0, level_dB=-60.0, displacement_m=2e-3, vibration_Hz=173.0, phase_rad=0.3)
    long_cfg = small_cfg.replace(num_chirps_per_frame=32)
    t0 = 1234.5678  # large absolute time: the phase must survive float rounding
    long = FMCWReceiver(long_cfg, effects=[eff])(empty_paths(long_cfg), frame_start_s=t0)
    rx = FMCWReceiver(small_cfg, effects=[eff])
    second = rx(empty_paths(small_cfg), frame_start_s=t0 + 16 * T)
    scale = float(long.abs().max())
    # float64 time at t0 ~ 1e3 s resolves ~1e-13 s: phases agree to ~1e-9 rad.
    torch.testing.assert_close(second, long[..., 16:, :], rtol=0, atol=1e-8 * scale)
    # A batch with one start per frame equals the frames one by one.
    starts = torch.tensor([t0, t0 + 16 * T], dtype=torch.float64)
    batch = rx(empty_paths(small_cfg, (2,)), frame_start_s=starts)
    torch.testing.assert_close(batch[1], second, rtol=0, atol=1e-8 * scale)
    torch.testing.assert_close(batch[0], long[..., :16, :], rtol=0, atol=1e-8 * scale)


def test_multipath_ghost_range_and_level_and_no_leakage_ghost(cfg, rd, make_paths):
    res, M = cfg.range_resolution_m, cfg.num_chirps_per_frame
    paths = make_paths(cfg, [30 * res], amplitudes=[1e-4])
    rx = FMCWReceiver(cfg, effects=[Multipath(extra_range_m=12 * res, level_dB=-6.0, phase_rad=1.0)])
    X = rd(rx(paths)).abs()[..., M // 2]
    torch.testing.assert_close(X[:, 42] / X[:, 30], torch.full((3,), 10 ** (-6 / 20), dtype=torch.float64), rtol=1e-6, atol=0)
    assert int(X[0, 35:].argmax()) + 35 == 42
    # Placed first, the leakage added after it gets no ghost.
    rx = FMCWReceiver(cfg, effects=[Multipath(extra_range_m=12 * res, level_dB=-3.0), TxRxLeakage(range_m=3 * res)])
    X = rd(rx(make_paths(cfg, [5.0], amplitudes=[0.0]))).abs()[0, :, M // 2]
    assert float(X[15]) < 1e-6 * float(X[3])  # a ghost would read 10**(-3/20) of it


def test_static_signal_equals_joint_with_catalog_effects(cfg, make_paths):
    """Superposition holds with multipath (linear) and the additive/drift catalog effects in the chain."""
    res = cfg.range_resolution_m
    chain = [e for e in default_effects(cfg) if e.name not in ("phase_noise", "adc_quantization")]
    for eff in (Multipath(extra_range_m=[0.6, 1.3], level_dB=[-4.0, -9.0], phase_rad=[0.5, 2.0]),
                StaticClutter(range_m=[2.0, 7.0], level_dB=-85.0), VibratingClutter(range_m=4.0, level_dB=-80.0),
                Interference(probability=0.3), ADCNoise(rms_counts=1.0), FrameDrift(gain_rms_dB=0.5, dc_rms_counts=2.0)):
        chain = insert_in_order(chain, eff)
    rx = FMCWReceiver(cfg, effects=chain)
    static = make_paths(cfg, [10 * res + 0.03, 25 * res], amplitudes=[3e-4, 1e-4])
    moving = make_paths(cfg, [40 * res], speeds_m_s=[1.1], amplitudes=[2e-4])
    joint = rx(Paths.cat([static, moving]), generator=torch.Generator().manual_seed(3))
    cached = rx(moving, generator=torch.Generator().manual_seed(3), static_signal=rx.static_signal(static))
    torch.testing.assert_close(cached, joint, rtol=0, atol=1e-9 * float(joint.abs().max()))


# --------------------------------------------------------------------------- chirp non-linearity
def test_chirp_nonlinearity_paired_echoes(cfg, rd, make_paths):
    """Echoes at beat +- ripple with ratios +pi tau dF exp(j phi) and -pi tau dF exp(-j phi)."""
    res, M, N = cfg.range_resolution_m, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp
    kr, kq = 40, 9
    ripple = kq * cfg.sample_rate_Hz / N  # on a range bin
    dev, phi = 150e3, 0.7
    tau = 2 * kr * res / SPEED_OF_LIGHT
    eff = ChirpNonlinearity(deviation_Hz=dev, ripple_Hz=ripple, phase_rad=phi, num_paths=1)
    X = rd(FMCWReceiver(cfg, effects=[eff])(make_paths(cfg, [kr * res], amplitudes=[1e-4])))[:, :, M // 2]
    a = math.pi * tau * dev
    up = X[:, kr + kq] / X[:, kr]
    down = X[:, kr - kq] / X[:, kr]
    torch.testing.assert_close(up, torch.full((3,), a * complex(math.cos(phi), math.sin(phi)), dtype=torch.complex128),
                               rtol=1e-6, atol=0)
    torch.testing.assert_close(down, torch.full((3,), -a * complex(math.cos(phi), -math.sin(phi)),
                                                dtype=torch.complex128), rtol=1e-6, atol=0)


def test_chirp_nonlinearity_picks_the_strongest_paths(cfg, rd, make_paths):
    res, M, N = cfg.range_resolution_m, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp
    ripple = 6 * cfg.sample_rate_Hz / N
    paths = make_paths(cfg, [20 * res, 60 * res], amplitudes=[1e-4, 1e-3])  # the far one is stronger
    eff = ChirpNonlinearity(deviation_Hz=1e6, ripple_Hz=ripple, num_paths=1)
    X = rd(FMCWReceiver(cfg, effects=[eff])(paths)).abs()[0, :, M // 2]
    assert float(X[66]) > 1e-3 * float(X[60]) and float(X[26]) < 1e-9 * float(X[60])


# --------------------------------------------------------------------------- noise, drift, interference
def lowpass_noise_factor(fc: float, fs: float, n: int) -> float:
    """Mean power gain of a first-order low-pass over the real-FFT bins of an N-sample chirp.

    Circular filtering of white noise: sum of |H(f_k)|^2 over the N two-sided bins divided by N.
    The Nyquist bin of a real FFT keeps only Re{H}, so it contributes Re{H}^2.
    """
    f = np.arange(n // 2 + 1) * fs / n
    h = 1 / (1 + 1j * f / fc)
    p = 2 * np.abs(h) ** 2
    p[0] = abs(h[0]) ** 2
    p[-1] = h[-1].real ** 2
    return float(p.sum() / n)


def test_adc_noise_level_through_the_aaf_and_independent_of_if_gain(cfg):
    rms = 3.0
    fac = lowpass_noise_factor(cfg.effective_aaf_cutoff_Hz, cfg.sample_rate_Hz, cfg.num_samples_per_chirp)
    outs = []
    for gain in (0.0, 30.0):
        rx = FMCWReceiver(cfg, effects=[IFHighPass(), IFGain(gain), ADCNoise(rms_counts=rms), AntiAliasLowPass()])
        outs.append(rx(empty_paths(cfg, (3,)), generator=torch.Generator().manual_seed(7)))
    torch.testing.assert_close(outs[0], outs[1], rtol=0, atol=0)  # the IF gain does not touch it
    std = float(outs[0].std()) * COUNTS
    assert std == pytest.approx(rms * math.sqrt(fac), rel=0.02)
    # Independent RX (no common component).
    x = outs[0].transpose(0, 1).reshape(3, -1)
    assert float(torch.corrcoef(x).fill_diagonal_(0).abs().max()) < 0.02


def test_frame_drift_statistics_and_within_frame_constancy(small_cfg, make_paths):
    """Per frame: one gain for all RX with 20 log10 g ~ N(0, 1 dB), per-RX DC ~ N(0, sigma_rx)."""
    B, res = 800, small_cfg.range_resolution_m
    paths = make_paths(small_cfg, [7 * res], amplitudes=[1e-3]).map(lambda t: t.expand(B, *t.shape))
    clean = FMCWReceiver(small_cfg, effects=[])(paths)
    sig = [2.0, 5.0, 0.0]
    rx = FMCWReceiver(small_cfg, effects=[FrameDrift(gain_rms_dB=1.0, dc_rms_counts=sig)])
    x = rx(paths, generator=torch.Generator().manual_seed(11))
    c = clean - clean.mean(dim=(-1, -2), keepdim=True)
    g = ((x - x.mean(dim=(-1, -2), keepdim=True)) * c).sum((-1, -2)) / (c * c).sum((-1, -2))  # (B, RX)
    torch.testing.assert_close(g, g[:, :1].expand_as(g), rtol=1e-9, atol=0)  # common to all RX
    g_db = 20 * torch.log10(g[:, 0])
    assert float(g_db.std()) == pytest.approx(1.0, rel=0.1)
    assert abs(float(g_db.mean())) < 4 / math.sqrt(B)
    dc = (x - g[..., None, None] * clean)  # constant within a frame
    torch.testing.assert_close(dc, dc[..., :1, :1].expand_as(dc), rtol=0, atol=1e-12)
    dc_counts = dc[..., 0, 0] * COUNTS  # (B, RX)
    torch.testing.assert_close(dc_counts.std(dim=0), torch.tensor(sig, dtype=torch.float64), rtol=0.1, atol=1e-12)
    assert abs(float(torch.corrcoef(dc_counts[:, :2].T)[0, 1])) < 0.15  # independent RX


def hann_burst_energy_expectation(duration: float, fs: float, n: int) -> float:
    """E over a burst centre uniform in [0, N/fs) of sum_n w(t_n - t0)^2 (Hann, sin^2), t0 = centre - d/2."""
    centres = np.linspace(0, n / fs, 40001)[:-1]
    t = np.arange(n) / fs
    u = t[None, :] - centres[:, None] + duration / 2
    w = np.where((u >= 0) & (u <= duration), np.sin(np.pi * u / duration) ** 2, 0.0)
    return float((w**2).sum(axis=1).mean())


def test_interference_rate_energy_and_off(small_cfg):
    B, M, N, fs = 200, small_cfg.num_chirps_per_frame, small_cfg.num_samples_per_chirp, small_cfg.sample_rate_Hz
    p, A, d = 0.3, 200.0, 20e-6
    rx = FMCWReceiver(small_cfg, effects=[Interference(probability=p, amplitude_counts=A, duration_s=d)])
    x = rx(empty_paths(small_cfg, (B,)), generator=torch.Generator().manual_seed(5)) * COUNTS
    energy = x.pow(2).sum(-1)  # (B, RX, M)
    hit = energy > 1e-12
    assert torch.equal(hit, hit[:, :1].expand_as(hit))  # one crossing for all RX
    frac = float(hit[:, 0].double().mean())
    assert abs(frac - p) < 4 * math.sqrt(p * (1 - p) / (B * M))
    # Over the random phase, E[sum x^2] = A^2 / 2 * E[sum w^2].
    expected = A**2 / 2 * hann_burst_energy_expectation(d, fs, N)
    assert float(energy[hit].mean()) == pytest.approx(expected, rel=0.03)
    assert float(x.abs().max()) <= A * (1 + 1e-6)
    # A burst inside the window sweeps the whole band: its energy is spread over many bins.
    spec = torch.fft.rfft(x, dim=-1).abs().pow(2)[hit]
    assert float((spec.max(-1).values / spec.sum(-1)).median()) < 0.2
    off = FMCWReceiver(small_cfg, effects=[Interference(probability=0.0, amplitude_counts=A)])
    assert float(off(empty_paths(small_cfg, (4,)), generator=torch.Generator().manual_seed(0)).abs().max()) == 0.0
    every = FMCWReceiver(small_cfg, effects=[Interference(probability=1.0, duration_s=5e-6)])
    assert bool((every(empty_paths(small_cfg, (2,))).pow(2).sum(-1) > 0).all())


# --------------------------------------------------------------------------- gradients, dtypes, devices
GRAD_CASES = [
    (lambda cfg: StaticClutter(range_m=[1.1, 2.3], level_dB=-70.0, phase_rad=0.3), ("range_m", "level_dB", "phase_rad")),
    (lambda cfg: VibratingClutter(range_m=1.3, level_dB=-70.0, displacement_m=1e-3, vibration_Hz=300.0),
     ("range_m", "level_dB", "displacement_m", "vibration_Hz", "phase_rad")),
    (lambda cfg: Multipath(extra_range_m=0.8, level_dB=-6.0, phase_rad=0.2), ("extra_range_m", "level_dB", "phase_rad")),
    (lambda cfg: ChirpNonlinearity(deviation_Hz=2e5, ripple_Hz=70e3, phase_rad=0.2), ("deviation_Hz", "ripple_Hz", "phase_rad")),
    (lambda cfg: Interference(probability=1.0, amplitude_counts=50.0, duration_s=6e-6), ("amplitude_counts", "duration_s")),
    (lambda cfg: ADCNoise(rms_counts=2.0), ("rms_counts",)),
    (lambda cfg: FrameDrift(gain_rms_dB=0.5, dc_rms_counts=2.0), ("gain_rms_dB", "dc_rms_counts")),
]


@pytest.mark.parametrize("make,names", GRAD_CASES, ids=[c[1][0] + "-" + str(i) for i, c in enumerate(GRAD_CASES)])
def test_gradients_reach_parameters(small_cfg, make_paths, make, names):
    eff = make(small_cfg)
    for n in names:
        getattr(eff, n).requires_grad_()
    rx = FMCWReceiver(small_cfg, effects=[eff, AntiAliasLowPass()])
    paths = make_paths(small_cfg, [1.7, 3.1], amplitudes=[3e-4, 1e-4], dtype=torch.float32)
    x = rx(paths, generator=torch.Generator().manual_seed(2))
    weights = torch.randn(x.shape, generator=torch.Generator().manual_seed(9))
    (x * weights).sum().backward()
    for n in names:
        grad = getattr(eff, n).grad
        assert grad is not None and bool(torch.isfinite(grad).all()) and float(grad.abs().sum()) > 0, n


DETERMINISTIC = [
    lambda: StaticClutter(range_m=[1.1, 2.3], level_dB=[-70.0, -75.0]),
    lambda: VibratingClutter(range_m=[1.3, 2.0], level_dB=-70.0, displacement_m=[1e-3, 3e-3], vibration_Hz=[300.0, 45.0]),
    lambda: Multipath(extra_range_m=0.8, level_dB=-6.0),
    lambda: ChirpNonlinearity(deviation_Hz=2e5, ripple_Hz=70e3),
]
DEVICES = ["cpu"] + (["cuda"] if torch.cuda.is_available() else [])


@pytest.mark.parametrize("device", DEVICES)
@pytest.mark.parametrize("make", DETERMINISTIC, ids=["static", "vibrating", "multipath", "chirp"])
def test_dtypes_devices_and_batches_agree(small_cfg, make_paths, device, make):
    """float32 ~ float64, CPU ~ CUDA, and a batch of frames equals the frames one by one."""
    rx = FMCWReceiver(small_cfg, effects=[make(), IFHighPass(), AntiAliasLowPass()]).to(device)
    ref = FMCWReceiver(small_cfg, effects=[make(), IFHighPass(), AntiAliasLowPass()])(
        make_paths(small_cfg, [1.7, 3.1], [0.0, 1.0], [3e-4, 1e-4]))
    scale = float(ref.abs().max())
    # float32 paths quantize the delay (phase error ~1e-4 of the peak before any effect).
    for dtype, tol in ((torch.float64, 1e-9), (torch.float32, 1e-3)):
        x = rx(make_paths(small_cfg, [1.7, 3.1], [0.0, 1.0], [3e-4, 1e-4], dtype=dtype, device=device))
        assert x.dtype == dtype and x.device.type == device
        torch.testing.assert_close(x.cpu().double(), ref, rtol=0, atol=tol * scale)
    batch = make_paths(small_cfg, [1.7, 3.1], [0.0, 1.0], [3e-4, 1e-4], device=device).map(
        lambda t: torch.stack([t, t * 0.5]) if t.is_complex() else torch.stack([t, t]))
    xb = rx(batch).cpu()
    assert xb.shape == (2, *ref.shape)
    torch.testing.assert_close(xb[0], ref, rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("device", DEVICES)
def test_random_effects_run_on_each_device_and_dtype(small_cfg, device):
    chain = [ThermalNoise(), Interference(probability=0.5), ADCNoise(), AntiAliasLowPass(), FrameDrift()]
    rx = FMCWReceiver(small_cfg, effects=chain).to(device)
    for dtype in (torch.float32, torch.float64):
        gen = torch.Generator(device=device).manual_seed(0)
        x = rx(empty_paths(small_cfg, (2,), dtype=dtype, device=device), generator=gen)
        assert x.dtype == dtype and x.shape == (2, 3, 16, 64) and bool(torch.isfinite(x).all())
        again = rx(empty_paths(small_cfg, (2,), dtype=dtype, device=device), generator=gen.manual_seed(0))
        assert torch.equal(x, again)  # every draw comes from the call's generator
    if device == "cuda":
        with pytest.raises(InputTensorError, match="generator"):
            rx(empty_paths(small_cfg, device=device), generator=torch.Generator().manual_seed(0))
