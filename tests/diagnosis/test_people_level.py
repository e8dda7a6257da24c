"""People's level at matched range: a known RCS scale is recovered, no motion is refused, real recordings."""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.people_level import fit_people_level, mti_peaks, twin_walks
from radaraug.errors import CalibrationError

# The public 48 dB people recordings' chirp (1 GHz, 128 samples, 64 chirps, RX1), written out here so
# the tests need no recording.
CONFIG = RadarConfig.from_infineon({
    "rx_antennas": [1], "tx_antennas": [1], "tx_power_level": 31, "if_gain_dB": 48,
    "start_frequency_Hz": 60.5e9, "end_frequency_Hz": 61.5e9, "num_chirps_per_frame": 64,
    "num_samples_per_chirp": 128, "chirp_repetition_time_s": 391.55e-6, "frame_repetition_time_s": 0.1,
    "sample_rate_Hz": 2e6, "mimo_mode": "off",
})
SPAN = (1.0, 2.2)


@pytest.fixture(autouse=True)
def _one_thread():
    n = torch.get_num_threads()
    torch.set_num_threads(1)
    yield
    torch.set_num_threads(n)


def test_mti_peak_of_a_tone_is_its_closed_form_level():
    """A moving tone of amplitude A on range bin k: its MTI peak is 20 log10(A / 2) dBFS in bin k."""
    m, n, k, amp = 64, 128, 20, 0.01
    t = torch.arange(n, dtype=torch.float64)
    chirp = torch.arange(m, dtype=torch.float64)[:, None]
    x = amp * torch.cos(2 * math.pi * (k * t / n + 5 * chirp / m))  # Doppler bin 5 off zero
    frames = x.to(torch.float32)[None, None].expand(3, 1, m, n).clone()
    peaks, bins, _ = mti_peaks(frames)
    np.testing.assert_array_equal(bins, k)
    np.testing.assert_allclose(peaks, 20 * math.log10(amp / 2), atol=0.01)


@pytest.mark.parametrize("scale_dB", [6.0, -8.0])
def test_fit_recovers_a_known_rcs_scale(scale_dB):
    """A 'capture' of twin walkers whose RCS is scaled by X dB fits +X dB against the default twin.

    Closed form: the receiver is linear up to the ADC, so scaling every path amplitude by 10**(X/20)
    moves every peak well above the floor by X dB; the capture's walks use other gait phases and noise
    (another seed) than the twin's reference walks.
    """
    capture = twin_walks(CONFIG, SPAN, rcs_scale_dB=scale_dB, seed=1)
    fit = fit_people_level(capture, config=CONFIG, seed=0)
    assert fit.offset_dB == pytest.approx(scale_dB, abs=1.0)
    assert fit.spread_dB < 3.0
    assert abs(fit.capture_floor_dBFS - fit.twin_floor_dBFS) < 1.0
    assert min(fit.ranges_m) >= 0.6 and len(fit.ranges_m) == len(fit.capture_dBFS) == len(fit.twin_dBFS)
    d = fit.to_dict()
    assert d["db_convention"].startswith("dB = 20*log10") and isinstance(d["ranges_m"], list)


def test_twin_scale_moves_the_reference_not_the_capture():
    """Fitting against a twin scaled by +X dB lowers the offset by X dB (the same capture)."""
    capture = twin_walks(CONFIG, SPAN, seed=1)
    base = fit_people_level(capture, config=CONFIG, seed=0)
    scaled = fit_people_level(capture, config=CONFIG, seed=0, rcs_scale_dB=4.0)
    assert scaled.offset_dB == pytest.approx(base.offset_dB - 4.0, abs=0.5)


def test_no_moving_target_is_refused():
    from radaraug.scene.scene import Scene
    from radaraug.sim.twin import DigitalTwin

    twin = DigitalTwin(Scene.builtin("corridor"), config=CONFIG)
    empty = twin.simulate([], torch.arange(12, dtype=torch.float64) * 0.1, generators=torch.Generator().manual_seed(0))
    with pytest.raises(CalibrationError, match="no moving target"):
        fit_people_level(empty, config=CONFIG)


def test_empty_room_capture_sets_the_threshold():
    """With the empty room given, frames must beat its strongest MTI cell per range bin."""
    capture = twin_walks(CONFIG, SPAN, seed=1)
    with pytest.raises(CalibrationError, match="empty room"):
        fit_people_level(capture, config=CONFIG, empty=capture)  # nothing beats itself by 20 dB


def test_bad_sources_are_refused():
    with pytest.raises(CalibrationError, match="give its config"):
        fit_people_level(torch.zeros(4, 1, 64, 128))
    with pytest.raises(CalibrationError, match="path, a capture reader or a tensor"):
        fit_people_level(3.0)
    with pytest.raises(CalibrationError, match=r"\(F, rx, chirps, samples\)"):
        fit_people_level(torch.zeros(64, 128), config=CONFIG)


PEOPLE = {
    # recording: (fitted offset dB recorded in benchmarks/people_level_cpu.json, its tolerance)
    "recording_2022_05_25_18_48_07": (-5.6, 1.0),
    "recording_2022_05_25_18_52_43": (-6.4, 1.5),
}


@pytest.mark.real
@pytest.mark.parametrize("name", sorted(PEOPLE))
def test_public_people_recordings(real_data, name):
    """The walking people of the public 48 dB recordings against the twin: floors agree, level offset recorded."""
    path = real_data / "jjustin__ec-international-2022" / "recordings" / name
    fit = fit_people_level(path)
    expected, tol = PEOPLE[name]
    assert abs(fit.capture_floor_dBFS - fit.twin_floor_dBFS) < 1.0  # the noise side is pinned
    assert fit.offset_dB == pytest.approx(expected, abs=tol)
