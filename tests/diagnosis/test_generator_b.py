"""Generator B (``tests/diagnosis/generator_b.py``): closed forms, independence, and the signatures on it."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch
from scipy.special import ndtr

from radaraug.diagnosis.signatures import SIGNATURE_EFFECTS, detect_all

from .generator_b import (
    CASES,
    CFG_A,
    CFG_B,
    OVERSAMPLE,
    butterworth_sos,
    make_capture,
    sos_power_response,
    thermal_psd_float,
)

ROOT = Path(__file__).resolve().parents[2]


def counts_of(x: np.ndarray, cfg) -> np.ndarray:
    return (x + 1) * cfg.adc_full_scale_counts / 2


# --------------------------------------------------------------------------- the generator itself
@pytest.mark.parametrize("cfg", [CFG_A, CFG_B], ids=["A", "B"])
@pytest.mark.parametrize("range_m", [1.3, 2.75, 4.4])
def test_point_scatterer_lands_in_its_range_bin(cfg, range_m):
    x = make_capture(cfg, seed=0, frames=1, scatterers=[((0.0, 0.0, range_m), 5.0)], thermal_noise=False,
                     adc_noise_counts=0.0)
    c = counts_of(x, cfg)[0].mean(axis=1)  # (R, N) mean chirp
    N = cfg.num_samples_per_chirp
    w = np.hanning(N + 1)[:N]
    spec = np.abs(np.fft.rfft((c - c.mean(axis=-1, keepdims=True)) * w, axis=-1))[:, : N // 2]
    # Beat f = S tau, tau = bistatic path / c (TX and RX a few mm off the origin): bin R / resolution.
    expect = range_m / cfg.range_resolution_m
    for r in range(cfg.num_rx):
        k = int(np.argmax(spec[r, 3:])) + 3
        assert abs(k - expect) <= 0.5 + 0.02, (k, expect)


def test_butterworth_sections_match_the_analog_magnitude():
    fs = OVERSAMPLE * 1e6
    f = np.array([20e3, 80e3, 150e3, 400e3])
    for order in (1, 2, 3):
        hp = sos_power_response(butterworth_sos(order, 80e3, fs, "high"), f, fs)
        x = (f / 80e3) ** (2 * order)
        assert np.allclose(10 * np.log10(hp), 10 * np.log10(x / (1 + x)), atol=0.15)
        assert 10 * np.log10(sos_power_response(butterworth_sos(order, 80e3, fs, "high"), [80e3], fs)[0]) \
            == pytest.approx(-3.01, abs=0.01)
    lp = sos_power_response(butterworth_sos(2, 500e3, fs, "low"), np.array([500e3]), fs)
    assert 10 * np.log10(lp[0]) == pytest.approx(-3.01, abs=0.01)


@pytest.mark.parametrize("cfg", [CFG_A, CFG_B], ids=["A", "B"])
def test_noise_floor_is_kTB_NF_times_the_gain_chain(cfg):
    """Mid-band PSD of thermal-noise-only frames against ``k T0 NF R (g_rf g_if 2 / V_pp)^2 |H|^2``."""
    x = make_capture(cfg, seed=1, frames=6, scatterers=[], adc_noise_counts=0.0)
    N, fs = cfg.num_samples_per_chirp, cfg.sample_rate_Hz
    w = np.hanning(N + 1)[:N]
    xf = x - x.mean(axis=-1, keepdims=True)
    X = np.fft.rfft(xf * w, axis=-1)
    psd = 2 * np.mean(np.abs(X) ** 2, axis=(0, 1, 2)) / (fs * np.sum(w**2))  # one-sided, float^2 / Hz
    f = np.fft.rfftfreq(N, 1 / fs)
    band = (f > 150e3) & (f < 350e3)
    expect = thermal_psd_float(cfg, f[band])
    err_db = 10 * np.log10(psd[band].mean() / expect.mean())
    assert abs(err_db) < 1.0, err_db


def test_clipping_fraction_matches_the_unclipped_spread():
    """With a smaller ADC range the same noise clips: fraction = Gaussian tails beyond the rails."""
    cfg = CFG_A
    full = cfg.adc_full_scale_counts
    kw = dict(seed=2, frames=4, scatterers=[], adc_noise_counts=0.0)
    ref = counts_of(make_capture(cfg, **kw), cfg)
    dc = ref.mean(axis=(0, 2, 3))  # per-RX DC level (counts)
    sigma = (ref - dc[None, :, None, None]).std(axis=(0, 2, 3))  # counts at the nominal 1 V range
    v_pp = 0.004  # 250x smaller range: noise of ~1000 counts
    clipped = counts_of(make_capture(cfg, {"adc_clipping": {"adc_range_Vpp": v_pp}}, **kw), cfg)
    s = sigma / v_pp
    expect = ndtr(-(dc + 0.5) / s) + ndtr(-(full - 0.5 - dc) / s)  # per RX
    got = ((clipped <= 0) | (clipped >= full)).mean(axis=(0, 2, 3))
    n = clipped[:, 0].size
    assert np.all(np.abs(got - expect) < 4 * np.sqrt(expect * (1 - expect) / n) + 2e-3), (got, expect)


def test_effects_are_validated():
    with pytest.raises(ValueError, match="no effect"):
        make_capture(CFG_B, {"multipath": {}}, frames=1)
    with pytest.raises(ValueError, match="missing"):
        make_capture(CFG_B, {"spur_tone": {"freq_Hz": 1e5}}, frames=1)


def test_variants_vary_what_they_claim_and_leave_the_plain_form_alone():
    """An unlocked spur keeps its power per chirp and loses its Doppler line; several slopes draw per burst."""
    spur = {"freq_Hz": 187_500.0, "amplitude_mV": 2.0, "phase_rad": 0.4}  # on a range bin at config B
    kw = {"seed": 3, "frames": 4, "scatterers": [], "thermal_noise": False, "adc_noise_counts": 0.0}
    plain = counts_of(make_capture(CFG_B, {}, **kw), CFG_B)  # the tone alone: the same capture without it
    locked = counts_of(make_capture(CFG_B, {"spur_tone": spur}, **kw), CFG_B) - plain
    unlocked = counts_of(make_capture(CFG_B, {"spur_tone": spur | {"unlocked": True}}, **kw), CFG_B) - plain
    k = round(spur["freq_Hz"] * CFG_B.num_samples_per_chirp / CFG_B.sample_rate_Hz)

    def line_share(c: np.ndarray) -> float:
        r = np.fft.rfft(c - c.mean(axis=-1, keepdims=True), axis=-1)[..., k]  # (F, R, M)
        return float((np.abs(np.fft.fft(r, axis=-1)) ** 2).max(axis=-1).sum() / (np.abs(r) ** 2).sum()
                     / CFG_B.num_chirps_per_frame)

    assert line_share(locked) > 0.95  # one Doppler line holds the tone
    assert line_share(unlocked) < 0.3  # spread over the Doppler bins
    power = [float((np.abs(np.fft.rfft(c, axis=-1)[..., k]) ** 2).mean()) for c in (locked, unlocked)]
    assert power[1] == pytest.approx(power[0], rel=0.05)  # the tone's power, only its Doppler spread changes
    inter = {"probability": 0.2, "power_dBm": -65.0, "duration_us": 20.0}
    one = make_capture(CFG_B, {"interference": inter}, seed=3, frames=2)
    np.testing.assert_array_equal(one, make_capture(CFG_B, {"interference": inter | {"duration_us": [20.0]}},
                                                    seed=3, frames=2))
    assert not np.array_equal(one, make_capture(CFG_B, {"interference": inter | {"duration_us": [5.0, 60.0]}},
                                                seed=3, frames=2))


def test_generator_b_imports_none_of_the_library_models():
    code = (
        "import sys; sys.path.insert(0, sys.argv[1]); import tests.diagnosis.generator_b as g; "
        "bad = [m for m in sys.modules if m.split('.')[:2] in (['radaraug', 'sim'], ['radaraug', 'raytrace'], "
        "['radaraug', 'sensor'], ['radaraug', 'scene']) "
        "or m.startswith('radaraug.testsets.independent') or m.endswith('numpy_capture')]; print(','.join(bad)); sys.exit(1 if bad else 0)"
    )
    out = subprocess.run([sys.executable, "-c", code, str(ROOT)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr


def test_cases_table():
    names = [c[0] for c in CASES]
    assert len(set(names)) == len(names)
    singles = {c[3][0] for c in CASES if len(c[3]) == 1}
    assert singles == set(SIGNATURE_EFFECTS)
    assert sum(len(c[3]) == 2 for c in CASES) == 6
    variants = [c for c in CASES if c[0].split("@")[0] in ("spur_unlocked", "interference_slopes", "vibration_band",
                                                            "phase_noise_weak_carrier", "leakage_clipping")]
    assert len(variants) == 15 and {c[3] for c in variants} == {("spur_tone",), ("interference",),
                                                                ("vibrating_clutter",), ("phase_noise",),
                                                                ("tx_rx_leakage",)}
    assert {c.name for c in CASES if c.scatterers is not None} == {f"phase_noise_weak_carrier@{k}" for k in ("A", "Ahi", "B")}
    assert sum(len(c[3]) == 0 for c in CASES) >= 2
    assert {c[1].num_samples_per_chirp for c in CASES} == {128, 256}


def test_control_and_one_effect_quickly():
    """A fast smoke test (the full table is the slow test below)."""
    cfg = CFG_B
    found = [s.effect for s in detect_all(torch.from_numpy(make_capture(cfg, seed=5, frames=16)), cfg) if s.present]
    assert found == []
    eff = {"spur_tone": {"freq_Hz": 187_300.0, "amplitude_mV": 1.5, "phase_rad": 0.4}}
    sigs = detect_all(torch.from_numpy(make_capture(cfg, eff, seed=5, frames=16)), cfg)
    assert [s.effect for s in sigs if s.present] == ["spur_tone"]


# --------------------------------------------------------------------------- the signatures on every case
@pytest.mark.slow
@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_signatures_name_exactly_the_effects_present(case):
    """Each case's effects are detected, and no other (the control: none)."""
    cfg, expected = case.config, case.expected
    sigs = detect_all(torch.from_numpy(case.capture(11)), cfg)
    found = {s.effect for s in sigs if s.present}
    detail = "; ".join(f"{s.effect}: {s.detail}" for s in sigs if s.present or s.effect in expected)
    assert set(expected) <= found, detail
    assert found == set(expected), detail


def test_single_effect_levels_are_recovered():
    """Parameter estimates of a few single-effect cases against generator B's settings."""
    cfg = CFG_A
    by = {c[0]: c for c in CASES}
    # Spur: frequency exact, amplitude in counts = mV / V_pp * full.
    eff = by["spur_tone@A"].effects
    sigs = {s.effect: s for s in detect_all(torch.from_numpy(make_capture(cfg, eff, seed=3, frames=12)), cfg)}
    sp = sigs["spur_tone"]
    assert sp.params["freq_Hz"] == pytest.approx(eff["spur_tone"]["freq_Hz"], abs=30)
    a = eff["spur_tone"]["amplitude_mV"] * 1e-3 / 1.0 * cfg.adc_full_scale_counts
    assert abs(20 * math.log10(sp.params["amplitude_counts"] / a)) < 0.5
    # RX mismatch: gains re RX1.
    eff = by["rx_gain_phase_mismatch@A"].effects
    sigs = {s.effect: s for s in detect_all(torch.from_numpy(make_capture(cfg, eff, seed=3, frames=12)), cfg)}
    g = eff["rx_gain_phase_mismatch"]["gain_dB"]
    for i in (1, 2):
        assert abs(sigs["rx_gain_phase_mismatch"].params[f"gain_dB_rx{i + 1}"] - g[i]) < 0.3
    # High-pass: cutoff and order.
    eff = by["if_highpass@A"].effects
    sigs = {s.effect: s for s in detect_all(torch.from_numpy(make_capture(cfg, eff, seed=3, frames=12)), cfg)}
    hp = sigs["if_highpass"].params
    assert hp["order"] == eff["if_highpass"]["order"]
    assert hp["cutoff_Hz"] == pytest.approx(eff["if_highpass"]["cutoff_Hz"], rel=0.15)
