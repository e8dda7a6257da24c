"""The default chain reproduces the noise floor of real BGT60TR13C recordings at their own IF gain."""

from __future__ import annotations

import pytest

from radaraug.config import RadarConfig
from radaraug.diagnosis.noise_defaults import check_defaults, fit_noise_defaults, twin_floor_db
from radaraug.io.sample import sample_recording_path

TOLERANCE_DB = 3.0  # what the defaults promise (measured: within 0.3 dB on every public recording)


def _recordings(root):
    return sorted(p.parent for p in root.rglob("RadarIfxAvian_00/radar.npy"))


def test_bundled_recording_floor_within_3_db():
    (row,) = check_defaults([sample_recording_path()])
    assert abs(row["difference_db"]) <= TOLERANCE_DB, row


def test_every_public_recording_floor_within_3_db(real_data):
    rows = check_defaults(_recordings(real_data))
    assert {r["if_gain_dB"] for r in rows} >= {23, 38, 48}
    for r in rows:
        assert abs(r["difference_db"]) <= TOLERANCE_DB, r


def test_floor_follows_the_two_noise_sources():
    # Closed-form behaviour: at low IF gain the ADC side dominates (a 6 dB higher ADC-side RMS
    # raises the floor by ~6 dB; 6 dB more front-end gain hardly moves it); at high IF gain the
    # thermal part dominates (front-end gain moves the floor dB for dB).
    lo = RadarConfig.bgt60tr13c(if_gain_dB=18, num_samples_per_chirp=64, num_chirps_per_frame=16)
    hi = lo.replace(if_gain_dB=60)
    assert twin_floor_db(lo, adc_noise_rms_counts=3.5) - twin_floor_db(lo) == pytest.approx(6.0, abs=0.6)
    assert abs(twin_floor_db(lo, front_end_gain_dB=34.5) - twin_floor_db(lo)) < 1.0
    assert twin_floor_db(hi, front_end_gain_dB=34.5) - twin_floor_db(hi) == pytest.approx(6.0, abs=0.6)


def test_fit_recovers_the_shipped_constants_on_the_public_recordings(real_data):
    fit = fit_noise_defaults(_recordings(real_data), front_end_gains_dB=(26.5, 28.5, 30.5),
                             adc_rms_counts=(1.25, 1.75, 2.25))
    assert fit["front_end_gain_dB"] == 28.5 and fit["adc_noise_rms_counts"] == 1.75
    assert fit["worst_difference_db"] < 1.0


def test_too_few_chirps_for_a_floor_is_a_calibration_error():
    """With <= 4 chirps the RD floor (which leaves zero Doppler out) is undefined: a clear error,
    not ``float(None)``."""
    from radaraug.errors import CalibrationError

    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=4)
    with pytest.raises(CalibrationError, match="too few chirps per frame"):
        twin_floor_db(cfg, frames=1)
