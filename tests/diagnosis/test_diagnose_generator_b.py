"""diagnose names the effect that is there, on captures of the second independent generator.

Generator B (``generator_b.py``) shares no code with the twin or the loop's own NumPy generator.
Each case carries the effects the config does not declare, alone or in pairs, at two radar
configs and two IF gains; the expected answer is the set of effects named in ``report.json``'s
steps (estimated mode: no scene). Two quick cases run by default, the whole table is slow.
"""

from __future__ import annotations

import json
import math

import pytest
import torch

from radaraug.diagnosis import diagnose, write_report
from radaraug.io import write_capture
from radaraug.units import float_to_counts

from .generator_b import CASES

_BY_NAME = {c[0]: c for c in CASES}


def _named(tmp_path, name: str, seed: int = 1):
    case = _BY_NAME[name]
    cfg, expected = case.config, case.expected
    x = torch.as_tensor(case.capture(seed))
    path = tmp_path / f"{name.replace('@', '_').replace('+', '_')}.h5"
    write_capture(path, float_to_counts(x) if x.is_floating_point() else x, cfg)
    diag = diagnose(path, max_frames=40)
    # named: added by the search, or declared and refitted at the parameters the capture shows
    named = diag.named_effects
    return diag, sorted(named), sorted(expected)


@pytest.mark.parametrize("name", ["control@B", "mismatch+leakage@B"])
def test_quick_cases_name_what_is_there(tmp_path, name):
    diag, named, expected = _named(tmp_path, name)
    assert named == expected
    out = write_report(diag, tmp_path / "report", figures=bool(expected))
    report = json.loads((out / "report.json").read_text())
    assert [s["effect"] for s in report["signatures"]] and len(report["verdict"]) >= len(expected)
    present = sorted(s["effect"] for s in report["signatures"] if s["present"])
    assert present == expected  # the evidence, effect by effect
    summary = (out / "summary.md").read_text()
    assert "Verdict per effect" in summary
    if expected:
        assert sorted(p.name for p in out.glob("signature_*.png")) == [f"signature_{e}.png" for e in expected]
        leak = diag.profile.to_dict()["receiver"]["effects"]
        # Estimated mode: the undeclared leakage moves the profile's coupling by what the capture shows.
        coupling = next(e for e in leak if e["name"] == "tx_rx_leakage")["params"]["coupling_dB"]
        assert max(coupling) < -50.0  # generator B's leakage sits ~24 dB under the declared -35.8 / -43.8 dB


@pytest.mark.parametrize("name", ["spur_tone@A", pytest.param("clipping+spur@A", marks=pytest.mark.slow)])
def test_a_locked_spur_keeps_the_alias_its_signature_measured(tmp_path, name):
    """At config A a chirp repeats every 391.55 us: aliases 2.55 kHz apart, 0.65 range bin, make one
    Doppler line. The fitted frequency is the one put in (187.3 kHz), not the next alias."""
    diag, named, _ = _named(tmp_path, name, seed=3)
    assert "spur_tone" in named
    spur = next(e for e in diag.profile.to_dict()["receiver"]["effects"] if e["name"] == "spur_tone")
    cfg = _BY_NAME[name].config
    assert abs(spur["params"]["freq_Hz"] - 187_300.0) <= cfg.sample_rate_Hz / cfg.num_samples_per_chirp / 4


def test_a_small_vibration_keeps_the_frequency_its_signature_measured(tmp_path):
    """At 128 x 32 a Doppler bin is 40 Hz: the pair's signature reads 420 Hz within 0.1 Hz; the fit keeps
    it within 2 % (the search alone had ended at 410 Hz)."""
    diag, named, expected = _named(tmp_path, "vibrating_clutter@B", seed=3)
    assert named == expected
    vib = next(e for e in diag.profile.to_dict()["receiver"]["effects"] if e["name"] == "vibrating_clutter")
    assert abs(vib["params"]["vibration_Hz"] - 420.0) <= 0.02 * 420.0


def test_a_large_vibration_keeps_the_band_edge_its_signature_measured(tmp_path):
    """6 mm at 25 Hz (f_v d = 0.150 m Hz) fills +-5 Doppler bins at 128 x 32: the band's edge gives the
    start, so the fit is a band (f_v d within 20 %), not a small-beta pair at the band's brightest cells."""
    diag, named, expected = _named(tmp_path, "vibration_band@B", seed=3)
    assert named == expected
    vib = next(e for e in diag.profile.to_dict()["receiver"]["effects"] if e["name"] == "vibrating_clutter")
    product = vib["params"]["vibration_Hz"] * vib["params"]["displacement_m"]
    assert product == pytest.approx(0.150, rel=0.2)


@pytest.mark.slow
def test_a_later_effect_refits_the_earlier_ones_it_was_imitated_by(tmp_path):
    """Phase noise is named first and takes the floor the bursts raise; once interference is added, the
    joint refit gives the bursts their share (seed 3: 1.89 dB after the pair without it, 1.42 with it)."""
    diag, named, expected = _named(tmp_path, "phase_noise+interference@A", seed=3)
    assert named == expected
    assert diag.result.after.overall < 1.6


def test_the_weak_carriers_lo_noise_is_read_off_its_skirt(tmp_path):
    """1.5 MHz of LO noise on a carrier ~16 dB over the floor at 128 x 32: named, and within 30 % (2.25 MHz
    when the views fitted it, trading the skirt against a floor the base refit could not reach)."""
    diag, named, expected = _named(tmp_path, "phase_noise_weak_carrier@B", seed=3)
    assert named == expected
    (step,) = diag.result.steps
    assert step["params_fitted"] == 0
    assert step["params"]["freq_noise_rms_Hz"] == pytest.approx(1.5e6, rel=0.3)


@pytest.mark.slow
def test_an_unlocked_spur_at_43_db_keeps_the_frequency_its_ridge_reads(tmp_path):
    """At 43 dB the views' ridge had let the search wander to 185.56 kHz (seed 1); the ridge's fine DFT reads 187.3."""
    diag, named, expected = _named(tmp_path, "spur_unlocked@Ahi", seed=1)
    assert named == expected
    (step,) = diag.result.steps
    cfg = next(c for c in CASES if c.name == "spur_unlocked@Ahi").config
    assert abs(step["params"]["freq_Hz"] - 187.3e3) < 0.25 * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    assert step["params"]["amplitude_counts"] == pytest.approx(6.143, rel=0.3)


def test_steeper_declared_highpass_is_refitted_with_its_parameters_before_and_after(tmp_path):
    """The declared first-order high-pass, where the capture's is a second-order Butterworth at 150 kHz.

    The twin's second order is two first-order sections: -3 dB at 150 kHz puts each at
    ``150 sqrt(sqrt(2) - 1)`` = 96.5 kHz.
    """
    from radaraug.diagnosis.diagnose import verdicts

    diag, named, expected = _named(tmp_path, "if_highpass@B")
    assert named == expected == ["if_highpass"]
    (step,) = diag.result.steps
    assert step["refit"] and step["params_before"]["order"] == 1 and step["params"]["order"] == 2
    assert step["params"]["cutoff_Hz"] == pytest.approx(150e3 * math.sqrt(math.sqrt(2) - 1), rel=0.2)
    text = next(v["text"] for v in verdicts(diag) if v["effect"] == "if_highpass")
    assert "declared, at other parameters" in text and "order=1" in text and "order=2" in text


@pytest.mark.slow
@pytest.mark.parametrize("name", [c[0] for c in CASES])
def test_every_case_names_what_is_there(tmp_path, name):
    _, named, expected = _named(tmp_path, name)
    assert named == expected


def test_clipping_by_gain_refits_the_gain_before_the_adc(tmp_path):
    """Generator B's ADC range at 0.12 V (nominal 1 V): 18.4 dB more gain before the rails.

    The base refit alone stays inside its physical noise bounds and leaves most of the error; the
    clipping step fits the gain before the ADC (the twin's ``system_gain``), which lifts the thermal
    noise over the ADC's own and drives the noise into the rails as in the capture; the static scene
    is the capture's mean chirp declipped (its plain mean is pulled towards the rails).
    """
    diag, named, expected = _named(tmp_path, "adc_clipping@B")
    assert named == expected == ["adc_clipping"]
    (step,) = diag.result.steps
    assert step["verdict"] == "clear" and step["params_before"] == {"gain_dB": 0.0}
    assert step["params"]["gain_dB"] > 18.0  # generator B's thermal floor also sits over the twin's
    assert step["error_after"] < 0.75 * step["error_before"]
    assert diag.result.after.overall < 0.5 * diag.result.before.overall  # 4.36 -> 0.30 dB at seed 1
    gain = next(e for e in diag.profile.to_dict()["receiver"]["effects"] if e["name"] == "system_gain")
    assert gain["params"]["gain_dB"] == pytest.approx(step["params"]["gain_dB"])
    from radaraug.diagnosis.diagnose import verdicts

    text = next(v["text"] for v in verdicts(diag) if v["effect"] == "adc_clipping")
    assert "declared, at other parameters: gain_dB=0 -> gain_dB=" in text


def test_leakage_clipping_at_the_chirp_start_halves_the_error(tmp_path):
    """A strong leakage's high-pass start-up clips the chirp starts: the declipped static scene gives
    the twin that start back, so its samples clip where the capture's do (2.58 -> 1.02 dB at seed 1)."""
    diag, named, expected = _named(tmp_path, "leakage_clipping@B")
    assert named == expected == ["tx_rx_leakage"]
    assert diag.result.after.overall < 0.5 * diag.result.before.overall


def test_interference_keeps_the_burst_share_its_signature_counted(tmp_path):
    """Generator B's interferer hits 8 % of the chirps: the step keeps the share the signature counted."""
    diag, named, expected = _named(tmp_path, "interference@B")
    assert named == expected == ["interference"]
    (step,) = diag.result.steps
    assert step["params"]["probability"] == pytest.approx(step["signature_params"]["probability"], abs=1e-6)
    assert step["params"]["probability"] == pytest.approx(0.08, rel=0.25)
    assert step["error_after"] < step["error_before"] / 2


def test_frame_drift_keeps_the_dc_wander_its_signature_measured(tmp_path):
    """Generator B's DC wanders 4 counts RMS per frame: the views barely see it, the frame means do.

    Fitted freely it ended at 0.6, 2.5 and 19.7 counts at the three settings; the step keeps the
    signature's RMS over the RX and fits the gain drift (0.6 dB RMS put in) from its measurement.
    """
    diag, named, expected = _named(tmp_path, "frame_drift@B")
    assert named == expected == ["frame_drift"]
    (step,) = diag.result.steps
    assert step["params"]["dc_rms_counts"] == pytest.approx(step["signature_params"]["dc_rms_mean_counts"], abs=1e-6)
    assert step["params"]["dc_rms_counts"] == pytest.approx(4.0, rel=0.2)
    assert step["params"]["gain_rms_dB"] == pytest.approx(0.6, rel=0.6)


def test_rx_mismatch_reports_the_gains_the_static_returns_measure(tmp_path):
    """Generator B's RX2/RX3 at +1.8/-2.2 dB re RX1, estimated mode at 128 x 32.

    The estimated static scene copies the capture's returns, so the views see the mismatch only in the
    noise, whose thermal share the twin (mostly ADC-side noise) lacks: fitted from the views the gains
    ended 1 dB too far. The step keeps them within 0.25 dB of what the returns measure.
    """
    diag, named, expected = _named(tmp_path, "rx_gain_phase_mismatch@B")
    assert named == expected == ["rx_gain_phase_mismatch"]
    (step,) = diag.result.steps
    p = step["params"]
    gains = p["gain_dB"][1:] if "gain_dB" in p else [p["gain_dB_rx2"], p["gain_dB_rx3"]]
    assert gains == pytest.approx([1.8, -2.2], abs=0.5)


@pytest.mark.slow
def test_highpass_the_views_cannot_tell_apart_reports_the_signature(tmp_path):
    """At 43 dB the refit to generator B's order-2 filter leaves the held-out error where it was.

    The profile keeps the declared stage; the step reports what the floor's shape measured
    (order 2, the sections' cutoff of a 150 kHz -3 dB point: 96.5 kHz), not the declaration again.
    """
    diag, named, expected = _named(tmp_path, "if_highpass@Ahi")
    assert named == expected == ["if_highpass"]
    (step,) = diag.result.steps
    assert step["params_before"]["order"] == 1
    assert step["params"]["order"] == 2
    assert step["params"]["cutoff_Hz"] == pytest.approx(150e3 * math.sqrt(math.sqrt(2) - 1), rel=0.1)
    if step["verdict"] == "signature only":  # not kept: the profile keeps the declared stage
        hp = next(e for e in diag.profile.to_dict()["receiver"]["effects"] if e["name"] == "if_highpass")
        assert hp["params"]["order"] == 1
