"""The independent NumPy capture generator against closed forms (it is the calibration tests' truth)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import jv

from radaraug.config import RadarConfig
from radaraug.io import open_capture

from .numpy_capture import (
    EFFECT_NAMES,
    EFFECT_PARAMS,
    _lo_frequency_noise,
    generate,
    random_effect,
    save_capture,
)

C = 299_792_458.0
K_B = 1.380649e-23
FULL = 4095.0
G_FE = 10 ** (49 / 20)
P_TX = 1e-3 * 10 ** (5 / 10)
QUIET = dict(noise_figure_dB=-np.inf, leakage_coupling_dB=-np.inf)  # no thermal noise, no leakage


@pytest.fixture(scope="module")
def cfg() -> RadarConfig:
    return RadarConfig.bgt60tr13c()


def hp(cfg: RadarConfig, f):
    x = 1j * np.asarray(f, dtype=float) / cfg.effective_hp_cutoff_Hz
    return x / (1 + x)


def aaf(cfg: RadarConfig, f):
    return 1 / (1 + 1j * np.asarray(f, dtype=float) / cfg.effective_aaf_cutoff_Hz)


def peak_counts(cfg: RadarConfig, level_dB: float, f_Hz: float) -> complex:
    """Complex peak amplitude in counts of a path at ``level_dB`` re TX beating at ``f_Hz``."""
    a = math.sqrt(2 * P_TX * 10 ** (level_dB / 10)) * G_FE * 10 ** (cfg.if_gain_dB / 20) * FULL / 2
    return a * hp(cfg, f_Hz) * aaf(cfg, f_Hz)


def spectrum(counts: np.ndarray) -> np.ndarray:
    """Range spectrum ``rfft / N`` (rectangular window) of the counts without their mean."""
    x = counts.astype(np.float64)
    return np.fft.rfft(x - x.mean(axis=-1, keepdims=True), axis=-1) / x.shape[-1]


@pytest.mark.parametrize("method", ["analog", "steady", "circular"])
def test_static_point_level_phase_and_bin(cfg, method):
    k = 40  # exactly on a range bin: f_b = S * 2R / c = k fs / N
    r = k * cfg.range_resolution_m
    level, phase = -80.0, 0.7
    counts = generate(
        cfg,
        1,
        seed=0,
        scene=[{"range_m": r, "level_dB": level, "phase_rad": phase}],
        filter_method=method,
        **QUIET,
    )
    assert counts.shape == (1, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    assert counts.dtype == np.uint16
    X = spectrum(counts)[0]  # (rx, chirps, bins)
    assert np.all(np.argmax(np.abs(X[..., 1:]), axis=-1) + 1 == k)
    f_b = k * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    want = peak_counts(cfg, level, f_b)
    tau = 2 * r / C
    want_phase = 2 * np.pi * (cfg.sampled_start_frequency_Hz * tau - cfg.slope_Hz_per_s * tau**2 / 2) + phase
    want_phase += np.angle(want)
    got = X[..., k]
    np.testing.assert_allclose(np.abs(got), abs(want) / 2, rtol=3e-3)  # a real tone reads A/2
    np.testing.assert_allclose(np.angle(got * np.exp(-1j * want_phase)), 0.0, atol=6e-3)


def _bilinear_reference(x: np.ndarray, fc: float, fs: float, highpass: bool) -> np.ndarray:
    """First-order RC filter by the bilinear transform at a very high rate, from zero state."""
    wc = 2 * math.pi * fc
    k = wc / math.tan(math.pi * fc / fs)
    b0 = (k if highpass else wc) / (k + wc)
    b1 = -b0 if highpass else b0
    a1 = (k - wc) / (k + wc)
    y = np.empty_like(x)
    xp = yp = 0.0
    for n, xn in enumerate(x.tolist()):
        yp = b0 * xn + b1 * xp + a1 * yp
        y[n] = yp
        xp = xn
    return y


def test_analog_chain_matches_oversampled_rc_simulation(cfg):
    """Leakage + two targets against the RC filters simulated at 100x the ADC rate from the ramp start."""
    scene = [
        {"range_m": 8.0, "level_dB": -75.0, "phase_rad": 0.3},
        {"range_m": 19.0, "level_dB": -78.0, "phase_rad": 1.0},
    ]
    leak_db, leak_ph = -56.3, 2.2
    counts = (
        generate(
            cfg,
            1,
            seed=0,
            scene=scene,
            noise_figure_dB=-np.inf,
            leakage_coupling_dB=leak_db,
            leak_phase_rad=leak_ph,
            dc_counts=2000.0,
        )[0, 0, 0].astype(float)
        - 2000.0
    )
    os_ = 100
    fs, n, t_d = cfg.sample_rate_Hz, cfg.num_samples_per_chirp, cfg.adc_delay_s
    fso = fs * os_
    tt = np.arange(int(round((t_d + n / fs) * fso)) + 1) / fso - t_d  # fast time; ramp starts at -t_d
    x = np.zeros_like(tt)
    for r, level, ph in [(0.04, leak_db, leak_ph)] + [
        (s["range_m"], s["level_dB"], s["phase_rad"]) for s in scene
    ]:
        tau = 2 * r / C
        a = math.sqrt(2 * P_TX * 10 ** (level / 10)) * G_FE
        x += a * np.cos(
            2
            * np.pi
            * (
                cfg.sampled_start_frequency_Hz * tau
                + cfg.slope_Hz_per_s * tau * tt
                - cfg.slope_Hz_per_s * tau**2 / 2
            )
            + ph
        )
    y = _bilinear_reference(x, cfg.effective_hp_cutoff_Hz, fso, True) * 10 ** (cfg.if_gain_dB / 20)
    y = _bilinear_reference(y, cfg.effective_aaf_cutoff_Hz, fso, False)
    ref = y[np.round((np.arange(n) / fs + t_d) * fso).astype(int)] * FULL / 2
    assert abs(ref[0]) > 100  # the start-up transient is large ...
    err = counts - ref
    assert np.max(np.abs(err)) < 4.0  # ... and reproduced to a few counts (quantization 0.5)
    assert np.std(err[8:]) < 0.5


def _noise_gain(cfg: RadarConfig) -> float:
    """Mean of |H_hp H_aaf|^2 over 0..fs/2 (closed-form integral)."""
    a, b, band = cfg.effective_hp_cutoff_Hz, cfg.effective_aaf_cutoff_Hz, cfg.sample_rate_Hz / 2
    return b**2 / (b**2 - a**2) * (b * math.atan(band / b) - a * math.atan(band / a)) / band


@pytest.mark.parametrize("method", ["analog", "circular"])
def test_thermal_noise_rms_through_the_filters(cfg, method):
    nf = 12.0
    counts = generate(cfg, 4, seed=3, noise_figure_dB=nf, filter_method=method).astype(np.float64)
    resid = counts - counts.mean(axis=(0, 2), keepdims=True)  # drops leakage, its transient, DC
    n_avg = counts.shape[0] * counts.shape[2]
    got = resid.var(axis=(0, 2, 3)) * n_avg / (n_avg - 1)
    sigma = math.sqrt(K_B * 290 * 10 ** (nf / 10) * cfg.sample_rate_Hz / 2) * G_FE
    sigma *= 10 ** (cfg.if_gain_dB / 20) * FULL / 2
    want = sigma**2 * _noise_gain(cfg) + 1 / 12  # + quantization
    assert 3.0 < math.sqrt(want) < 6.0
    np.testing.assert_allclose(got, want, rtol=0.03)


def test_adc_noise_adds_aaf_shaped_power(cfg):
    base = generate(cfg, 2, seed=4).astype(float)
    more = generate(cfg, 2, seed=4, effects=[{"name": "adc_noise", "rms_counts": 8.0}]).astype(float)

    def var(c):
        return (c - c.mean(axis=(0, 2), keepdims=True)).var(axis=(0, 2, 3))

    fl, band = cfg.effective_aaf_cutoff_Hz, cfg.sample_rate_Hz / 2
    want = 8.0**2 * fl / band * math.atan(band / fl)
    np.testing.assert_allclose(var(more) - var(base), want, rtol=0.05)


def test_spur_bin_amplitude_and_absolute_time_phase(cfg):
    k = 37
    f_sp = k * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    amps = np.array([30.0, 40.0, 50.0])
    # Thermal noise on: it dithers the ADC (without it the rounding error is correlated with the tone).
    counts = generate(
        cfg,
        2,
        seed=0,
        leakage_coupling_dB=-np.inf,
        effects=[{"name": "spur_tone", "freq_Hz": f_sp, "amplitude_counts": list(amps), "phase_rad": 0.4}],
    )
    X = spectrum(counts)[..., k]  # (F, rx, M)
    t0 = (
        np.arange(2)[:, None] * cfg.frame_repetition_time_s
        + np.arange(cfg.num_chirps_per_frame)[None, :] * cfg.chirp_repetition_time_s
        + cfg.adc_delay_s
    )
    aligned = X * np.exp(-1j * (2 * np.pi * f_sp * t0[:, None, :] + 0.4))  # tone locked to absolute time
    np.testing.assert_allclose(np.abs(aligned.mean(axis=(0, 2))), amps / 2, rtol=0.01)
    assert np.max(np.abs(np.angle(aligned))) < 0.1


@pytest.mark.parametrize("doppler_bins", [3, -5])
def test_moving_target_doppler_bin(cfg, doppler_bins):
    k = 40
    v = doppler_bins * cfg.velocity_resolution_m_s  # Doppler 2 v / lambda on a Doppler bin
    counts = generate(
        cfg,
        1,
        seed=0,
        effects=[
            {
                "name": "moving_target",
                "range_m": k * cfg.range_resolution_m,
                "speed_m_s": v,
                "level_dB": -80.0,
            }
        ],
        **QUIET,
    )
    slow = spectrum(counts)[0, :, :, k]  # (rx, M)
    rd = np.abs(np.fft.fft(slow, axis=-1))
    m = cfg.num_chirps_per_frame
    assert np.all(np.argmax(rd, axis=-1) == doppler_bins % m)  # receding (v > 0) -> positive Doppler
    assert np.all(rd.max(axis=-1) > 10 * np.sort(rd, axis=-1)[:, -2])


def test_vibrating_clutter_sidebands_are_bessel(cfg):
    k, m = 40, cfg.num_chirps_per_frame
    fv = 4 / (m * cfg.chirp_repetition_time_s)  # on Doppler bin 4
    fs, n = cfg.sample_rate_Hz, cfg.num_samples_per_chirp
    t_n = np.arange(n) / fs
    f_rf = cfg.sampled_start_frequency_Hz + cfg.slope_Hz_per_s * t_n  # RF frequency at each sample
    disp = 1.2 * C / (4 * np.pi * f_rf.mean())  # modulation index ~1.2
    counts = generate(
        cfg,
        1,
        seed=0,
        filter_method="steady",
        effects=[
            {
                "name": "vibrating_clutter",
                "range_m": k * cfg.range_resolution_m,
                "level_dB": -80.0,
                "displacement_m": disp,
                "vibration_Hz": fv,
                "phase_rad": 0.5,
            }
        ],
        **QUIET,
    )
    dop = np.abs(np.fft.fft(spectrum(counts)[0, :, :, k], axis=-1))  # (rx, M)
    beta = 4 * np.pi * disp * f_rf / C  # per sample; sideband j is averaged over the chirp
    for j in (1, 2):
        want = np.abs(np.mean(jv(j, beta) * np.exp(2j * np.pi * j * fv * t_n))) / np.abs(np.mean(jv(0, beta)))
        np.testing.assert_allclose(dop[:, 4 * j] / dop[:, 0], want, rtol=0.01)
        np.testing.assert_allclose(dop[:, -4 * j] / dop[:, 0], want, rtol=0.01)


def test_chirp_nonlinearity_sidebands_are_bessel(cfg):
    k, kr = 60, 8
    fs, n = cfg.sample_rate_Hz, cfg.num_samples_per_chirp
    r, ripple, dev = k * cfg.range_resolution_m, kr * fs / n, 2e6
    counts = generate(
        cfg,
        1,
        seed=0,
        filter_method="steady",
        scene=[{"range_m": r, "level_dB": -80.0}],
        effects=[{"name": "chirp_nonlinearity", "deviation_Hz": dev, "ripple_Hz": ripple, "phase_rad": 1.1}],
        **QUIET,
    )
    X = np.abs(spectrum(counts)[0, 0, 0])
    beta = 2 * dev / ripple * math.sin(math.pi * ripple * 2 * r / C)
    chain = np.abs(hp(cfg, np.arange(len(X)) * fs / n) * aaf(cfg, np.arange(len(X)) * fs / n))
    for j in (1, 2):
        for side in (j, -j):
            got = (X[k + side * kr] / chain[k + side * kr]) / (X[k] / chain[k])
            np.testing.assert_allclose(got, abs(jv(j, beta) / jv(0, beta)), rtol=0.01)


def test_multipath_ghost_and_rx_mismatch(cfg):
    k, dk = 40, 12
    res = cfg.range_resolution_m
    gains, phases = [0.0, 2.0, -1.5], [0.0, 0.8, -1.2]
    effects = [
        {"name": "multipath", "extra_range_m": dk * res, "level_dB": -6.0, "phase_rad": 0.9},
        {"name": "rx_gain_phase_mismatch", "gain_dB": gains, "phase_rad": phases},
    ]
    counts = generate(
        cfg, 1, seed=0, scene=[{"range_m": k * res, "level_dB": -80.0}], effects=effects, **QUIET
    )
    X = spectrum(counts)[0, :, 0]  # (rx, bins)
    f = np.array([k, k + dk]) * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    h = hp(cfg, f) * aaf(cfg, f)
    ghost_ratio = np.abs(X[:, k + dk] / h[1]) / np.abs(X[:, k] / h[0])
    np.testing.assert_allclose(ghost_ratio, 10 ** (-6 / 20), rtol=0.01)
    rx_ratio = X[:, k] / X[0, k]
    want = 10 ** (np.array(gains) / 20) * np.exp(1j * np.array(phases))
    np.testing.assert_allclose(np.abs(rx_ratio), np.abs(want), rtol=5e-3)
    np.testing.assert_allclose(np.angle(rx_ratio / want), 0.0, atol=5e-3)


def test_dc_levels(cfg):
    dc = (1000.0, 2047.5, 3000.0)
    counts = generate(cfg, 2, seed=1, dc_counts=dc, leakage_coupling_dB=-np.inf)
    np.testing.assert_allclose(counts.mean(axis=(0, 2, 3)), dc, atol=0.1)


def test_frame_drift_statistics(cfg):
    k, frames = 40, 60
    effects = [{"name": "frame_drift", "gain_rms_dB": 1.0, "dc_rms_counts": 5.0}]
    counts = generate(
        cfg,
        frames,
        seed=2,
        scene=[{"range_m": k * cfg.range_resolution_m, "level_dB": -80.0}],
        effects=effects,
        **QUIET,
    )
    gain_dB = 20 * np.log10(np.abs(spectrum(counts)[:, 0, :, k]).mean(axis=-1))
    assert 0.7 < np.std(gain_dB) < 1.3
    assert np.all(
        np.ptp(20 * np.log10(np.abs(spectrum(counts)[:, :, :, k])), axis=(1, 2)) < 0.05
    )  # within a frame
    dc = counts.astype(float).mean(axis=(2, 3)) - np.array([1620.0, 1945.0, 2067.5])
    assert 3.5 < np.std(dc) < 6.5


def test_interference_bursts(cfg):
    amp = 300.0
    eff = {"name": "interference", "probability": 0.25, "amplitude_counts": amp, "duration_s": 20e-6}
    base = generate(cfg, 4, seed=7, **QUIET).astype(float)
    counts = generate(cfg, 4, seed=7, effects=[eff], **QUIET).astype(float)
    peak = np.abs(counts - base).max(axis=-1)  # (F, rx, M)
    hit = peak[:, 0] > 20
    assert np.all((peak > 20) == hit[:, None, :])  # the same burst on every RX
    assert 0.17 < hit.mean() < 0.33
    # Peak of the Hann envelope is mid-burst, where the sweep is at fs / 4 and the AAF passes |H|.
    want = amp * abs(aaf(cfg, cfg.sample_rate_Hz / 4))
    np.testing.assert_allclose(np.median(peak[:, 0][hit]), want, rtol=0.1)


def test_lo_frequency_noise_rms_and_spectrum(cfg):
    rng = np.random.default_rng(0)
    fs, corner = cfg.sample_rate_Hz, 50e3
    nu = _lo_frequency_noise(rng, (8, 64), 288, fs, 200e3, corner)
    assert nu.shape == (8, 64, 288)
    np.testing.assert_allclose(nu.std(), 200e3, rtol=0.03)
    psd = (np.abs(np.fft.rfft(nu, axis=-1)) ** 2).mean(axis=(0, 1))
    f = np.fft.rfftfreq(288, 1 / fs)
    low = psd[(f > 0) & (f < 0.2 * corner)].mean()
    at_corner = psd[np.argmin(np.abs(f - corner))]
    assert 0.35 < at_corner / low < 0.65  # Lorentzian: half power at the corner


def test_phase_noise_spreads_a_strong_path(cfg):
    k = 60
    scene = [{"range_m": k * cfg.range_resolution_m, "level_dB": -70.0}]
    quiet = np.abs(spectrum(generate(cfg, 1, seed=0, scene=scene, **QUIET)))[0, 0]
    noisy = np.abs(
        spectrum(
            generate(
                cfg,
                1,
                seed=0,
                scene=scene,
                effects=[{"name": "phase_noise", "freq_noise_rms_Hz": 400e3, "corner_Hz": 100e3}],
                **QUIET,
            )
        )
    )[0, 0]
    skirt = np.r_[k - 12 : k - 2, k + 3 : k + 13]
    assert noisy[:, skirt].mean() > 10 * quiet[:, skirt].mean()
    sigma = 2 * np.pi * 2 * scene[0]["range_m"] / C * 400e3  # rms phase, rad
    # The carrier bin averages e^{j theta} over the chirp; for a Gaussian phase E e^{j theta} = exp(-sigma^2 / 2).
    np.testing.assert_allclose(noisy[:, k].mean() / quiet[:, k].mean(), math.exp(-(sigma**2) / 2), rtol=0.05)


def test_clipping_stays_in_code_range(cfg):
    counts = generate(cfg, 1, seed=0, scene=[{"range_m": 3.0, "level_dB": -40.0}])
    assert counts.dtype == np.uint16
    assert counts.min() == 0 and counts.max() == 4095


def test_seed_reproducibility_and_separate_streams(cfg):
    rng = np.random.default_rng(11)
    effects = [random_effect(name, cfg, rng) for name in EFFECT_NAMES]
    scene = [{"range_m": 4.0, "level_dB": -80.0, "phase_rad": 0.2}]
    a = generate(cfg, 2, seed=5, effects=effects, scene=scene)
    b = generate(cfg, 2, seed=5, effects=effects, scene=scene)
    c = generate(cfg, 2, seed=6, effects=effects, scene=scene)
    np.testing.assert_array_equal(a, b)
    assert np.any(a != c)
    # Adding a deterministic effect leaves every random draw as it was.
    spur = {"name": "spur_tone", "freq_Hz": 123e3, "amplitude_counts": 50.0, "phase_rad": 0.0}
    plain = generate(cfg, 2, seed=5).astype(float)
    with_spur = generate(cfg, 2, seed=5, effects=[spur]).astype(float)
    t = (
        np.arange(2)[:, None, None, None] * cfg.frame_repetition_time_s
        + np.arange(cfg.num_chirps_per_frame)[None, None, :, None] * cfg.chirp_repetition_time_s
        + cfg.adc_delay_s
        + np.arange(cfg.num_samples_per_chirp) / cfg.sample_rate_Hz
    )
    assert np.max(np.abs(with_spur - plain - 50.0 * np.cos(2 * np.pi * 123e3 * t))) <= 1.0


def test_random_effects_are_complete_and_run(cfg):
    rng = np.random.default_rng(0)
    for name in EFFECT_NAMES:
        required, optional = EFFECT_PARAMS[name]
        for _ in range(20):
            e = random_effect(name, cfg, rng)
            assert e["name"] == name
            assert set(required) <= set(e) - {"name"} <= set(required) | set(optional)
    e = {name: random_effect(name, cfg, rng) for name in EFFECT_NAMES}
    assert 0 < e["spur_tone"]["freq_Hz"] < cfg.sample_rate_Hz / 2
    assert e["vibrating_clutter"]["vibration_Hz"] < 0.5 / cfg.chirp_repetition_time_s
    assert abs(e["moving_target"]["speed_m_s"]) < cfg.max_velocity_m_s
    counts = generate(cfg, 3, seed=1, effects=list(e.values()), scene=[{"range_m": 3.0, "level_dB": -80.0}])
    assert counts.shape == (3, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    with pytest.raises(ValueError, match="unknown effect"):
        generate(cfg, 1, seed=0, effects=[{"name": "no_such_effect"}])
    with pytest.raises(ValueError, match="missing"):
        generate(cfg, 1, seed=0, effects=[{"name": "spur_tone", "freq_Hz": 1e5}])


def test_save_capture_round_trip(cfg, tmp_path):
    counts = generate(cfg, 2, seed=0)
    path = tmp_path / "capture.h5"
    save_capture(path, cfg, counts)
    cap = open_capture(path)
    try:
        raw = cap.read(as_float=False).numpy()
        floats = cap.read().numpy()
        assert cap.config == cfg
    finally:
        cap.close()
    np.testing.assert_array_equal(raw, counts)
    np.testing.assert_allclose(floats, 2 * counts / 4095.0 - 1, atol=1e-6)
