"""The diagnosis loop fits the room's diffuse-scattering gain in scene mode.

The "captures" are the library's twin of a small corridor with a known diffuse gain; the loop
diagnoses them with the default (0 dB) twin. With the twin's own scatterer draw the gain is
recovered closely (the machinery: a candidate gain scales the synthesized diffuse signal, no
retrace); with another draw of the rough surfaces (a different ``diffuse_seed``) the loop can only
match the clutter statistically, and one realization against another carries an error of its own:
each range bin's diffuse field is complex Gaussian, so its power is exponential (5.6 dB standard
deviation in dB per bin), and a few strong near-range bins weigh most in the views. Measured over
24 independent pairs of draws (capture seed k, twin seed 1000 + k, +6 dB): mean error -0.74 dB,
standard deviation about 1.8 dB, largest 3.67 dB. Hence 3 dB for one pair (its measured error:
-0.74 dB), and the slow test checks the mean and RMS error over twelve pairs.
"""

from __future__ import annotations

import json

import pytest
import torch

from radaraug import RadarConfig
from radaraug.diagnosis import SearchSettings, diagnose, write_report
from radaraug.diagnosis.room import ROOM_STAGE
from radaraug.diagnosis.search import Search
from radaraug.diagnosis.twin_source import TwinSource
from radaraug.errors import CalibrationError
from radaraug.io import write_capture
from radaraug.scene.scene import Scene
from radaraug.sensor import FMCWReceiver
from radaraug.sensor.profile import TwinProfile
from radaraug.sim.twin import DigitalTwin
from radaraug.units import float_to_counts

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=32, chirp_repetition_time_s=200e-6,
                             frame_repetition_time_s=0.01)
FRAMES = 20
# The fast settings of test_search, without catalog steps: the gain is fitted with the base.
SETTINGS = SearchSettings(sim_frames=8, max_steps=0)
TRUE_GAIN_DB = 6.0


def _scene() -> Scene:
    return Scene.from_dict({
        "name": "small-corridor",
        "radar": {"config": CFG.to_dict(), "position": [0.1, 0.0, 1.2], "look_at": [5.0, 0.0, 1.2]},
        "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.7, "max_edge": 0.5},
        "people": [],
    })


def _capture(tmp_path, gain_dB: float, diffuse_seed: int | None, noise_seed: int = 3):
    """Frames of an independently set-up twin with a known diffuse gain, as an HDF5 capture."""
    opts = {"diffuse_gain_dB": gain_dB}
    if diffuse_seed is not None:
        opts["diffuse_seed"] = diffuse_seed
    truth = DigitalTwin(_scene(), config=CFG, tracer_options=opts)
    x = truth.simulate(None, truth.frame_times(range(FRAMES)), generators=torch.Generator().manual_seed(noise_seed))
    path = tmp_path / f"capture-{diffuse_seed}-{noise_seed}.h5"
    write_capture(path, float_to_counts(x, CFG.adc_bits).to(torch.uint16).numpy(), CFG)
    return path


def _source(**tracer_options) -> TwinSource:
    tr = DigitalTwin(_scene(), config=CFG, dtype=torch.float64, tracer_options=tracer_options).tracer
    rx = FMCWReceiver(CFG)
    return TwinSource(CFG, static_paths=tr.static_paths("specular"), diffuse_paths=tr.static_paths("diffuse"),
                      diffuse_gain_dB=tr.diffuse_gain_dB, tx_power_dBm=rx.tx_power_dBm,
                      front_end_gain_dB=rx.front_end_gain_dB)


def test_a_candidate_gain_equals_a_retrace_with_that_gain():
    """No retrace: S_spec + 10**(g/20) S_diff gives the frames of a room traced with gain g."""
    chain = FMCWReceiver(CFG).to_dict()["effects"]
    split = _source().frames(chain, 2, seed=5, room={"diffuse_gain_dB": 6.0})
    tr = DigitalTwin(_scene(), config=CFG, dtype=torch.float64, tracer_options={"diffuse_gain_dB": 6.0}).tracer
    rx = FMCWReceiver(CFG)
    whole = TwinSource(CFG, static_paths=tr.static_paths(), tx_power_dBm=rx.tx_power_dBm,
                       front_end_gain_dB=rx.front_end_gain_dB).frames(chain, 2, seed=5)
    torch.testing.assert_close(split, whole, rtol=0, atol=1e-9)
    with pytest.raises(CalibrationError, match="outside"):
        _source().frames(chain, 1, seed=0, room={"diffuse_gain_dB": 40.0})
    with pytest.raises(CalibrationError, match="cannot be varied"):
        _source(diffuse=False).frames(chain, 1, seed=0, room={"diffuse_gain_dB": 1.0})


def test_the_gain_is_a_base_parameter_only_when_the_room_scatters_diffusely():
    fr = torch.zeros(4, CFG.num_rx, CFG.num_chirps_per_frame, CFG.num_samples_per_chirp, dtype=torch.float64)
    chain = FMCWReceiver(CFG).to_dict()["effects"]
    with_room = Search(_source(), fr, fr, SETTINGS).base_specs(chain)
    assert [(s, p.name) for s, p in with_room if s == ROOM_STAGE] == [(ROOM_STAGE, "diffuse_gain_dB")]
    # The room's parameter never enters the receiver's chain.
    assert ROOM_STAGE not in [e["name"] for e in chain]
    without = Search(_source(diffuse=False), fr, fr, SETTINGS).base_specs(chain)
    assert all(s != ROOM_STAGE for s, _ in without)


def test_diagnose_recovers_the_gain_of_the_twins_own_draw(tmp_path):
    """Same scatterers as the twin (its seed is derived from the room), gain +6 dB: measured 6.85 dB
    here (6.24 dB with another noise seed): what is left is the receiver noise of 10-frame halves
    and the system gain, fitted at the same time, trading against the room's gain."""
    diag = diagnose(_capture(tmp_path, TRUE_GAIN_DB, None), scene=_scene(), max_frames=FRAMES, settings=SETTINGS)
    got = diag.result.room_after["diffuse_gain_dB"]
    assert diag.result.room_before == {"diffuse_gain_dB": 0.0}
    assert abs(got - TRUE_GAIN_DB) < 1.5
    assert diag.result.base.overall < diag.result.before.overall
    # The profile carries it, and a twin built from the profile traces with it.
    out = write_report(diag, tmp_path / "rep", figures=False)
    rep = json.loads((out / "report.json").read_text())
    assert rep["room"]["fitted"] == ["diffuse_gain_dB"]
    assert rep["room"]["params_final"]["diffuse_gain_dB"] == pytest.approx(got)
    assert "diffuse_gain_dB" in (out / "summary.md").read_text()
    prof = TwinProfile.load(out / "profile.json")
    assert prof.room == {"diffuse_gain_dB": pytest.approx(got)}
    assert DigitalTwin(_scene(), config=CFG, profile=prof).tracer.diffuse_gain_dB == pytest.approx(got)
    # The caller's explicit tracer option wins over the profile's.
    assert DigitalTwin(_scene(), config=CFG, profile=prof,
                       tracer_options={"diffuse_gain_dB": -3.0}).tracer.diffuse_gain_dB == -3.0


def test_diagnose_fits_the_gain_of_another_draw_of_the_room(tmp_path):
    """A different rough-surface draw (seed 1): only the statistics can match (module docstring);
    measured 5.26 dB for 6."""
    diag = diagnose(_capture(tmp_path, TRUE_GAIN_DB, 1), scene=_scene(), max_frames=FRAMES, settings=SETTINGS)
    assert abs(diag.result.room_after["diffuse_gain_dB"] - TRUE_GAIN_DB) < 3.0


def test_a_room_without_diffuse_scattering_fits_no_room_parameter(tmp_path):
    diag = diagnose(_capture(tmp_path, 0.0, None), scene=_scene(), max_frames=FRAMES, settings=SETTINGS,
                    tracer_options={"diffuse": False})
    assert diag.result.room_after == {} and diag.profile.room == {}
    assert diag.report()["room"]["fitted"] == []


@pytest.mark.slow
def test_the_fitted_gain_is_unbiased_over_independent_draws(tmp_path):
    """Twelve pairs of independent draws (capture seed k, twin seed 1000 + k). Measured: mean error
    -1.02 dB, RMS 2.22 dB, largest 3.67 dB (with another twelve pairs: mean -0.46 dB, SD 1.57 dB):
    the fit leans low by 0.5-1 dB against another draw. Checked: the mean within 1.5 dB
    (sigma / sqrt(12) ~ 0.5 dB), the RMS error under 2.5 dB."""
    errors = []
    for k in range(41, 53):
        diag = diagnose(_capture(tmp_path, TRUE_GAIN_DB, k, noise_seed=k), scene=_scene(), max_frames=FRAMES,
                        settings=SETTINGS, tracer_options={"diffuse_seed": 1000 + k})
        errors.append(diag.result.room_after["diffuse_gain_dB"] - TRUE_GAIN_DB)
    e = torch.tensor(errors)
    assert abs(float(e.mean())) < 1.5
    assert float(e.pow(2).mean().sqrt()) < 2.5


def test_scene_mode_frames_are_the_twins_frames():
    """What the loop compares with a capture in scene mode is what the twin simulates, people and shadow included.

    The loop's source (diagnose's scene mode) holds the twin's traced room and its people's paths with their
    shadow corrections, and synthesizes them through each candidate chain; with the twin's own chain its frames
    equal :meth:`DigitalTwin.simulate`'s to float64 rounding (the shadow as correction paths there, through the
    static basis in the twin). The chain has no noise stages here: with more paths (the corrections) the noise
    stages draw their numbers in another order, so the two give other draws of the same noise.
    """
    from radaraug.diagnosis.diagnose import _source as diagnose_source
    from radaraug.scene.people import Walker
    from radaraug.sensor.defaults import default_effects

    scene = _scene()
    scene.people = [Walker(height_m=1.75, speed_m_s=1.2, start=(1.2, -0.3), heading_rad=0.15)]
    # No ADC rounding (float rounding moves codes) and no noise stages (their draws follow the path count)
    noisy = ("adc_quantization", "thermal_noise", "adc_noise", "phase_noise")
    rx = FMCWReceiver(CFG, effects=[e for e in default_effects(CFG) if e.name not in noisy])
    src, chain, _ = diagnose_source(CFG, scene, torch.zeros(1), sim_frames=2, rx=rx, tracer_options=None)
    twin = DigitalTwin(scene, config=CFG, receiver=rx, dtype=torch.float64)
    times = twin.frame_times(range(4))
    ours = src.frames(chain, 4, seed=11)
    theirs = twin.simulate(scene.people, times, generators=torch.Generator().manual_seed(11))
    empty = twin.simulate(None, times, generators=torch.Generator().manual_seed(11))
    people = (theirs - empty).abs().max()
    assert float(people) > 1e-3  # the walker and its shadow are in the frames compared
    torch.testing.assert_close(ours, theirs, rtol=0, atol=1e-9 * float(people))
