"""The diagnosis loop on captures with effects nobody declared.

The "measured" captures come from :mod:`numpy_capture`, a NumPy generator written for these tests
from the physics (it shares no code with ``radaraug.sensor``): the base chain there mirrors the
library's default (front-end gain, leakage, ADC-side noise, filters, DC, ADC), and on top of it
each test adds effects the loop is not told about, with random parameters drawn per seed.
Checked: the loop adds the right effect first, recovers its parameters within the tolerances
below, at least halves the held-out error left after the base refit; adds nothing to a capture
without an extra effect; reports an effect outside the catalog as ``unexplained`` at the right
range and Doppler. Scene-mode tests use a scene of point scatterers (no ray tracing).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

from radaraug import RadarConfig
from radaraug.config import SPEED_OF_LIGHT
from radaraug.diagnosis import SearchSettings, compute_views, diagnose, view_errors, write_report
from radaraug.diagnosis.diagnose import verdicts
from radaraug.diagnosis.search import Search
from radaraug.diagnosis.twin_source import TwinSource
from radaraug.sensor import FMCWReceiver, Paths
from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS, FRONT_END_GAIN_DB, LEAKAGE_COUPLING_DB
from radaraug.sensor.profile import TwinProfile

from .numpy_capture import generate, random_effect, save_capture

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=32, chirp_repetition_time_s=200e-6,
                             frame_repetition_time_s=0.01)
FRAMES = 40
SETTINGS = SearchSettings(sim_frames=16)
# The library's default base chain, in the generator's terms (declared: the loop refits it anyway).
BASE = dict(front_end_gain_dB=FRONT_END_GAIN_DB, leakage_coupling_dB=tuple(LEAKAGE_COUPLING_DB[a] for a in (1, 2, 3)),
            filter_method="steady")
BASE_EFFECTS = [{"name": "adc_noise", "rms_counts": ADC_NOISE_RMS_COUNTS},
                {"name": "phase_noise", "freq_noise_rms_Hz": 100e3, "corner_Hz": 200e3}]
DOPPLER_BIN_HZ = 1 / (CFG.num_chirps_per_frame * CFG.chirp_repetition_time_s)


def _capture(tmp_path, effects, seed, scene=()):
    x = generate(CFG, FRAMES, seed=seed, effects=BASE_EFFECTS + list(effects), scene=list(scene), **BASE)
    path = tmp_path / f"capture-{seed}.h5"
    save_capture(path, CFG, x)
    return path


def _diagnose(tmp_path, effects, seed):
    return diagnose(_capture(tmp_path, effects, seed), max_frames=FRAMES, settings=SETTINGS)


def _truth(name, seed):
    e = random_effect(name, CFG, np.random.default_rng(seed))
    return {k: v for k, v in e.items() if k != "name"}, e


def test_views_are_zero_for_identical_frames_and_follow_a_noise_step():
    g = torch.Generator().manual_seed(0)
    x = 0.01 * torch.randn(8, 3, 32, 64, generator=g, dtype=torch.float64)
    v = compute_views(x, CFG)
    assert all(e == 0.0 for e in view_errors(v, v).values())
    # +3.01 dB of white noise power moves the noise-floor view by 3.01 dB at every range bin.
    errs = view_errors(compute_views(x * math.sqrt(2), CFG), v)
    assert errs["noise_floor"] == pytest.approx(10 * math.log10(2), abs=0.02)
    assert errs["rd_histogram"] == pytest.approx(10 * math.log10(2), abs=0.02)


@pytest.mark.parametrize("seed", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_no_undeclared_effect_adds_nothing(tmp_path, seed):
    d = _diagnose(tmp_path, [], seed)
    assert d.result.steps == []
    assert d.result.after.overall < 0.6
    assert d.unexplained == []


@pytest.mark.parametrize("seed", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_spur_tone_found_first_and_fitted(tmp_path, seed):
    truth, e = _truth("spur_tone", seed)
    d = _diagnose(tmp_path, [e], seed)
    r = d.result
    assert r.steps[0]["effect"] == "spur_tone"
    p = r.steps[0]["params"]
    assert abs(p["freq_Hz"] - truth["freq_Hz"]) < DOPPLER_BIN_HZ  # within one Doppler bin's worth
    assert p["amplitude_counts"] == pytest.approx(float(np.mean(truth["amplitude_counts"])), rel=0.3)
    assert r.after.overall <= 0.5 * r.base.overall


@pytest.mark.parametrize("seed", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_frame_drift_found_first_and_fitted(tmp_path, seed):
    truth, e = _truth("frame_drift", seed)
    r = _diagnose(tmp_path, [e], seed).result
    assert r.steps[0]["effect"] == "frame_drift"
    p = r.steps[0]["params"]
    assert p["dc_rms_counts"] == pytest.approx(truth["dc_rms_counts"], rel=0.5, abs=1.0)
    assert abs(p["gain_rms_dB"] - truth["gain_rms_dB"]) < 0.5
    assert r.after.overall <= 0.5 * r.base.overall


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 2])
def test_vibrating_clutter_found_first_and_fitted(tmp_path, seed):
    truth, e = _truth("vibrating_clutter", seed)
    r = _diagnose(tmp_path, [e], seed).result
    assert r.steps[0]["effect"] == "vibrating_clutter"
    p = r.steps[0]["params"]
    assert abs(p["vibration_Hz"] - truth["vibration_Hz"]) < DOPPLER_BIN_HZ
    assert abs(p["range_m"] - truth["range_m"]) <= CFG.range_resolution_m
    # With the static scene estimated from the capture, level and displacement trade off; what the
    # data pins is the first sideband's power, level + 20 log10 J1(beta).
    from scipy.special import jv

    def sideband_db(q):
        return q["level_dB"] + 20 * math.log10(jv(1, 4 * math.pi * q["displacement_m"] / CFG.wavelength_m))

    assert abs(sideband_db(p) - sideband_db(truth)) < 4.0
    assert r.after.overall <= 0.5 * r.base.overall


@pytest.mark.slow
def test_two_undeclared_effects_both_found(tmp_path):
    seed = 1
    rng = np.random.default_rng(seed)
    effects = [random_effect("spur_tone", CFG, rng), random_effect("frame_drift", CFG, rng)]
    r = _diagnose(tmp_path, effects, seed).result
    assert {s["effect"] for s in r.steps[:2]} == {"spur_tone", "frame_drift"}
    assert r.after.overall <= 0.5 * r.base.overall


@pytest.mark.slow
def test_effect_outside_the_catalog_is_unexplained_at_its_range_and_doppler(tmp_path):
    seed = 3
    target = {"name": "moving_target", "range_m": 3.0, "speed_m_s": 1.2, "level_dB": -80.0}
    d = _diagnose(tmp_path, [target], seed)
    rd = [u for u in d.unexplained if u["view"] == "rd_map" and u["kind"] == "excess"]
    assert rd, d.unexplained
    # Where the target is during the held-out half (frames 20..39).
    r0 = 3.0 + 1.2 * 20 * CFG.frame_repetition_time_s
    r1 = 3.0 + 1.2 * 40 * CFG.frame_repetition_time_s
    hit = [u for u in rd if u["range_span_m"][0] - CFG.range_resolution_m <= r1
           and u["range_span_m"][1] + CFG.range_resolution_m >= r0
           and abs(u["velocity_m_s"] - 1.2) <= 1.5 * CFG.velocity_resolution_m_s]
    assert hit, rd


def test_report_and_profile_files(tmp_path):
    truth, e = _truth("spur_tone", 1)
    d = _diagnose(tmp_path, [e], 1)
    out = write_report(d, tmp_path / "report", figures=True)
    import json

    rep = json.loads((out / "report.json").read_text())
    for key in ("capture", "scene", "error_before", "error_after", "steps", "unexplained"):
        assert key in rep
    assert rep["scene"] is None and rep["mode"] == "estimated"
    assert rep["error_after"]["units"]["overall"].startswith("dB")
    assert set(rep["error_before"]["views"]) >= {"noise_floor", "rd_histogram", "adc_histogram", "lines"}
    assert rep["steps"][0]["effect"] == "spur_tone" and "error_before" in rep["steps"][0]
    assert (out / "summary.md").read_text().startswith("# Diagnosis")
    assert (out / "view_noise_floor.png").stat().st_size > 1000
    prof = TwinProfile.load(out / "profile.json")
    assert "spur_tone" in prof.effect_names and "tx_rx_leakage" in prof.effect_names
    rx = prof.receiver(CFG.replace(if_gain_dB=45))
    assert rx.effect("if_gain").gain_dB is None  # the IF gain follows the config it is applied to


# ----------------------------------------------------------------------------- scene mode
# Two points: a ghost of each (multipath) is then not the same as one extra scatterer.
SCENE = [{"range_m": 2.0, "level_dB": -70.0, "phase_rad": 0.4}, {"range_m": 3.1, "level_dB": -74.0, "phase_rad": -1.0}]


def _scene_paths(points):
    """Point scatterers as Paths ``(P, RX)`` in the receiver's convention (broadside: same delay
    on every RX; the IF takes the scattering phase conjugated, so the phase enters as exp(-j p))."""
    d = torch.tensor([[2 * p["range_m"] / SPEED_OF_LIGHT] * CFG.num_rx for p in points], dtype=torch.float64)
    a = torch.tensor([[10 ** (p["level_dB"] / 20) * complex(math.cos(p["phase_rad"]), -math.sin(p["phase_rad"]))]
                      * CFG.num_rx for p in points], dtype=torch.complex128)
    return Paths(d, torch.zeros_like(d), a)


def _scene_search(tmp_path, effects, seed):
    x = generate(CFG, FRAMES, seed=seed, effects=BASE_EFFECTS + effects, scene=SCENE, **BASE)
    fr = torch.as_tensor(x.astype(np.float64)) * 2 / 4095 - 1
    rx = FMCWReceiver(CFG)
    src = TwinSource(CFG, static_paths=_scene_paths(SCENE), tx_power_dBm=rx.tx_power_dBm,
                     front_end_gain_dB=rx.front_end_gain_dB)
    s = Search(src, fr[: FRAMES // 2], fr[FRAMES // 2:], SETTINGS)
    return s.run(rx.to_dict()["effects"])


def test_scene_mode_finds_an_undeclared_static_scatterer(tmp_path):
    extra = {"name": "static_clutter", "range_m": 4.3, "level_dB": -80.0, "phase_rad": 1.0}
    r = _scene_search(tmp_path, [extra], 5)
    assert r.steps[0]["effect"] == "static_clutter"
    p = r.steps[0]["params"]
    assert abs(p["range_m"] - 4.3) <= CFG.range_resolution_m
    assert abs(p["level_dB"] - -80.0) < 3.0
    assert r.after.overall <= 0.5 * r.base.overall


def test_scene_mode_finds_rx_gain_mismatch(tmp_path):
    extra = {"name": "rx_gain_phase_mismatch", "gain_dB": [0.0, -4.0, 3.0], "phase_rad": [0.0, 1.2, -0.9]}
    r = _scene_search(tmp_path, [extra], 6)
    assert r.steps[0]["effect"] == "rx_gain_phase_mismatch"
    p = r.steps[0]["params"]
    np.testing.assert_allclose(np.array(p["gain_dB"]) - p["gain_dB"][0], [0.0, -4.0, 3.0], atol=0.6)
    dphi = np.angle(np.exp(1j * (np.array(p["phase_rad"]) - p["phase_rad"][0] - np.array([0.0, 1.2, -0.9]))))
    assert np.abs(dphi).max() < 0.25
    assert r.after.overall <= 0.5 * r.base.overall


@pytest.mark.slow
def test_scene_mode_on_a_ray_traced_corridor_finds_an_undeclared_spur(tmp_path):
    """End to end through the command line: the library's twin of the corridor with a spur the loop
    is not told about (set through a twin profile), diagnosed with the corridor as its scene."""
    from radaraug.cli import main
    from radaraug.sensor.effects import SpurTone, insert_in_order

    cfg = RadarConfig.bgt60tr13c()
    effects = insert_in_order(list(FMCWReceiver(cfg).effects), SpurTone(freq_Hz=151.7e3, amplitude_counts=2.0))
    TwinProfile(FMCWReceiver(cfg, effects=effects).to_dict(), {"capture": "truth"}).save(tmp_path / "truth.json")
    cap = tmp_path / "corridor.h5"
    assert main(["simulate", "corridor", "--frames", "40", "--seed", "2", "-o", str(cap),
                 "--profile", str(tmp_path / "truth.json")]) == 0
    assert main(["diagnose", str(cap), "--scene", "corridor", "-o", str(tmp_path / "rep"), "--max-frames", "40",
                 "--no-figures"]) == 0
    import json

    rep = json.loads((tmp_path / "rep" / "report.json").read_text())
    assert rep["mode"] == "scene" and rep["scene"]  # the scene's own name
    step = rep["steps"][0]
    assert step["effect"] == "spur_tone"
    assert abs(step["params"]["freq_Hz"] - 151.7e3) < 1 / (cfg.num_chirps_per_frame * cfg.chirp_repetition_time_s)
    assert step["params"]["amplitude_counts"] == pytest.approx(2.0, rel=0.2)
    assert rep["error_after"]["overall"] <= 0.5 * rep["error_base_refit"]["overall"]


def test_a_missing_effect_is_named():
    from radaraug.diagnosis.catalog import ParamSpec, get_param, require
    from radaraug.errors import CalibrationError
    from radaraug.sensor.effects import Prior

    chain = [{"name": "thermal_noise", "params": {"noise_figure_dB": 12.0}}]
    assert require(chain, "thermal_noise") is chain[0]
    with pytest.raises(CalibrationError, match="no 'dc_offset'.*thermal_noise"):
        get_param(chain, "dc_offset", ParamSpec("level_counts", Prior(0.0, 1.0)))


def test_bounded_simplex_finds_closed_form_minima():
    """The search's optimizer (SciPy's bounded Nelder-Mead): an interior minimum and one on a bound."""
    from radaraug.diagnosis.search import nelder_mead

    calls = []

    def bowl(u):
        calls.append(u)
        return (u[0] - 0.3) ** 2 + 4 * (u[1] + 1.5) ** 2

    x, fx = nelder_mead(bowl, [0.0, 0.0], [0.5, 0.5], [-1.0, -1.0], [1.0, 1.0], max_evals=200)
    assert x[0] == pytest.approx(0.3, abs=1e-3) and x[1] == pytest.approx(-1.0, abs=1e-6)  # y pinned at its bound
    assert fx == pytest.approx(1.0, abs=1e-5)
    assert len(calls) <= 200 + 2 and all(-1 <= v <= 1 for u in calls for v in u)


def test_uncertainty_is_the_closed_form_of_a_parabola():
    """sigma = sqrt(2 noise / curvature): on an objective k (u - u0)^2 + c it is sqrt(noise / k)."""
    import math
    from types import SimpleNamespace

    from radaraug.config import RadarConfig
    from radaraug.diagnosis.catalog import ParamSpec, get_param
    from radaraug.diagnosis.search import Search
    from radaraug.sensor.effects.base import Prior

    k, u0, noise = 3.0, math.log10(2.0), 0.05
    spec = ParamSpec("amplitude_counts", Prior(0.05, 200.0, "log"))
    flat = ParamSpec("phase_rad", Prior(-math.pi, math.pi))
    chain = [{"name": "spur_tone", "params": {"freq_Hz": 1e5, "amplitude_counts": 2.0, "phase_rad": 0.0}}]
    search = Search.__new__(Search)
    search.config = RadarConfig.bgt60tr13c()
    search.fit_score = lambda ch, room=None: SimpleNamespace(
        overall=k * (math.log10(get_param(ch, "spur_tone", spec)) - u0) ** 2 + 0.7)
    out = search.uncertainty(chain, [("spur_tone", spec), ("spur_tone", flat)], None, noise)
    sig = math.sqrt(noise / k)
    assert out["amplitude_counts"] == pytest.approx([2.0 * 10**-sig, 2.0 * 10**sig], rel=1e-6)
    assert out["phase_rad"] is None  # the objective does not see it: not identified


def test_declared_leakage_at_other_parameters_is_refitted_and_reported(tmp_path):
    """A leakage 7 dB stronger than declared: not an undeclared effect, but the profile takes its level."""
    stronger = dict(BASE, leakage_coupling_dB=tuple(c + 7.0 for c in BASE["leakage_coupling_dB"]))
    x = generate(CFG, FRAMES, seed=1, effects=BASE_EFFECTS, scene=[], **stronger)
    path = tmp_path / "leak.h5"
    save_capture(path, CFG, x)
    d = diagnose(path, max_frames=FRAMES, settings=SETTINGS)
    assert [s["effect"] for s in d.result.steps] == []
    (rd,) = d.refitted_declared
    assert rd["effect"] == "tx_rx_leakage"
    shift = [a - b for a, b in zip(rd["params_after"]["coupling_dB"], rd["params_before"]["coupling_dB"])]
    assert shift[0] == pytest.approx(7.0, abs=1.5)  # RX1, where the leakage stands over the noise
    coupling = next(e for e in d.profile.to_dict()["receiver"]["effects"] if e["name"] == "tx_rx_leakage")
    assert coupling["params"]["coupling_dB"] == rd["params_after"]["coupling_dB"]
    verdict = next(v for v in verdicts(d) if v["effect"] == "tx_rx_leakage")
    assert verdict["verdict"] == "declared, refitted" and "refitted" in verdict["text"]


def test_rx_mismatch_without_static_returns_is_named_from_the_noise(tmp_path):
    """No static return to compare: a receiver 4 dB down in its (thermal-dominated) noise is named."""
    cfg = RadarConfig.bgt60tr13c(if_gain_dB=48)  # thermal noise over the ADC side's
    eff = BASE_EFFECTS + [{"name": "rx_gain_phase_mismatch", "gain_dB": [0.0, -4.0, 0.0], "phase_rad": [0.0, 0.3, -0.2]}]
    path = tmp_path / "rx.h5"
    save_capture(path, cfg, generate(cfg, 16, seed=1, effects=eff, scene=[], **BASE))
    d = diagnose(path, max_frames=16, settings=SETTINGS)
    assert [s["effect"] for s in d.result.steps] == ["rx_gain_phase_mismatch"]
    # the ADC-side noise, after the mismatch, dilutes it: the noise shows part of the 4 dB
    assert -4.5 < d.evidence["rx_gain_phase_mismatch"].capture.params["gain_dB_rx2"] < -1.5


def test_the_lo_noise_starts_from_its_skirt_and_is_kept_on_a_weak_carrier():
    """The signature's LO noise starts the search; a weak carrier keeps it, a strong one moves it x/÷ 1.26 at most."""
    from radaraug.config import RadarConfig
    from radaraug.diagnosis.catalog import PHASE_NOISE_REL, Context, catalog

    cand = next(c for c in catalog() if c.name == "phase_noise")
    ctx = Context(RadarConfig.bgt60tr13c(), "estimated", [], None, None, None)  # type: ignore[arg-type]
    [start] = cand.starts(ctx)[:1]
    assert start["freq_noise_rms_Hz"] == pytest.approx(30e3)  # no signature: the default's grid
    assert cand.specs(ctx, start)[0].prior.hi == 3e6
    for snr, kept in ((18.0, True), (42.0, False)):
        ctx.measured = {"phase_noise": {"freq_noise_rms_Hz": 1.5e6, "carrier_snr_dB": snr}}
        assert cand.starts(ctx) == [{"freq_noise_rms_Hz": 1.5e6}]
        specs = cand.specs(ctx, cand.starts(ctx)[0])
        if kept:
            assert specs == []
        else:
            assert [s.prior.lo for s in specs] == [pytest.approx(1.5e6 / 10**PHASE_NOISE_REL)]
            assert specs[0].prior.hi == pytest.approx(min(1.5e6 * 10**PHASE_NOISE_REL, 3e6))


def test_an_unlocked_spur_starts_from_its_ridge_reading():
    """A ridge the spur signature read starts the search there; the frequency moves a twentieth of a bin at most."""
    from radaraug.config import RadarConfig
    from radaraug.diagnosis.catalog import Context, catalog

    cfg = RadarConfig.bgt60tr13c()
    cand = next(c for c in catalog() if c.name == "spur_tone")
    ctx = Context(cfg, "estimated", [], None, None, None,  # type: ignore[arg-type]
                  measured={"spur_tone": {"freq_Hz": 187.305e3, "amplitude_counts": 6.2, "locked": 0.0}})
    (start,) = cand.starts(ctx)
    assert start == {"freq_Hz": 187.305e3, "amplitude_counts": 6.2, "phase_rad": 0.0, "phase_jitter_rad": math.pi}
    freq = next(s for s in cand.specs(ctx, start) if s.name == "freq_Hz")
    bin_hz = cfg.sample_rate_Hz / cfg.num_samples_per_chirp
    assert freq.prior.hi - freq.prior.lo == pytest.approx(0.1 * bin_hz)


def test_a_drift_gain_its_signature_read_bounds_the_search():
    """A drift gain read off the static returns bounds the search to +-25 % of it; a reading under 0.15 dB does not."""
    from radaraug.config import RadarConfig
    from radaraug.diagnosis.catalog import DRIFT_GAIN_REL, Context, catalog

    cand = next(c for c in catalog() if c.name == "frame_drift")
    ctx = Context(RadarConfig.bgt60tr13c(), "estimated", [], None, None, None)  # type: ignore[arg-type]
    for gain, bounded in ((0.67, True), (0.05, False)):
        ctx.measured = {"frame_drift": {"gain_rms_dB": gain, "dc_rms_mean_counts": 3.9}}
        (start,) = cand.starts(ctx)
        (spec,) = cand.specs(ctx, start)  # the DC it measured is kept
        assert spec.name == "gain_rms_dB"
        if bounded:
            assert (spec.prior.lo, spec.prior.hi) == (pytest.approx(gain * (1 - DRIFT_GAIN_REL)),
                                                      pytest.approx(gain * (1 + DRIFT_GAIN_REL)))
        else:
            assert (spec.prior.lo, spec.prior.hi) == (0.0, 3.0)
