"""Effect-catalog priors from a calibration's diagnosis: ranges around the fitted values."""

from __future__ import annotations

import math

import pytest

from radaraug.config import RadarConfig
from radaraug.diagnosis.priors import PRIOR_PROBABILITY, added_effects, calibration_priors, describe
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import RxGainPhaseMismatch, SpurTone, VibratingClutter
from radaraug.sensor.profile import TwinProfile
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.catalog.vibrating_clutter import radar_equation_dB
from radaraug.sim.randomization import TwinRandomization


def _profile(config: RadarConfig, added: list[str]) -> TwinProfile:
    level = radar_equation_dB(config, 3.0, -5.0)  # a -5 dBsm fan at 3 m
    extra = [SpurTone(freq_Hz=212e3, amplitude_counts=2.0, phase_rad=0.3),
             VibratingClutter(range_m=3.0, level_dB=level, displacement_m=1e-3, vibration_Hz=25.0),
             RxGainPhaseMismatch(gain_dB=[0.0, 0.8, -0.4], phase_rad=[0.0, 0.2, -0.1])]
    rec = FMCWReceiver(config, effects=[*default_effects(config), *extra])
    return TwinProfile(rec.to_dict(), fitted_on={"effects_added": added, "capture": "empty.h5"})


def test_found_effects_get_ranges_around_their_fits() -> None:
    cfg = RadarConfig.bgt60tr13c()
    base = TwinRandomization()
    prof = _profile(cfg, ["spur_tone", "vibrating_clutter", "rx_gain_phase_mismatch"])
    assert set(added_effects(prof)) == {"spur_tone", "vibrating_clutter", "rx_gain_phase_mismatch"}
    new, record = calibration_priors(prof, base, cfg)
    frac = 212e3 / (cfg.sample_rate_Hz / 2)
    spur, fan, mismatch = (new.catalog[n] for n in ("spur_tone", "vibrating_clutter", "rx_gain_phase_mismatch"))
    lo, hi = spur.freq_nyquist
    assert lo < frac < hi and hi - lo == pytest.approx(0.04)
    assert spur.amplitude_counts == pytest.approx((1.0, 4.0))
    assert spur.probability == PRIOR_PROBABILITY
    # The vibrating scatterer's level goes back through the radar equation to the fan's RCS.
    assert fan.rcs_dBsm == pytest.approx((-11.0, 1.0), abs=1e-4)  # float32 level
    assert fan.range_m == pytest.approx((2.0, 4.0))
    g_lo, g_hi = mismatch.gain_dB
    assert g_lo == pytest.approx(-0.9) and g_hi == pytest.approx(1.3)
    assert mismatch.phase_deg[1] == pytest.approx(math.degrees(0.2) + 10)
    # Effects diagnose did not add keep their physics priors, and the other sections are untouched.
    assert new.catalog["interference"] == base.catalog["interference"]
    assert new.catalog["frame_drift"] == base.catalog["frame_drift"]
    assert (new.room, new.people, new.levels) == (base.room, base.people, base.levels)
    assert "spur_tone" in describe(record) and record["found"] == sorted(record["changes"])


def test_items_draw_the_fitted_spur() -> None:
    cfg = RadarConfig.bgt60tr13c()
    new, _ = calibration_priors(_profile(cfg, ["spur_tone"]), TwinRandomization(), cfg)
    hits = [d["spur_tone"] for d in (new.effects(0, i) for i in range(300)) if "spur_tone" in d]
    assert abs(len(hits) / 300 - PRIOR_PROBABILITY) < 0.08
    frac = 212e3 / (cfg.sample_rate_Hz / 2)
    assert all(abs(h["freq_nyquist"] - frac) <= 0.02 for h in hits)


def test_nothing_found_keeps_the_randomization() -> None:
    cfg = RadarConfig.bgt60tr13c()
    base = TwinRandomization()
    new, record = calibration_priors(_profile(cfg, []), base, cfg)
    assert new == base and record["found"] == []
    assert "physics priors" in describe(record)


def test_datamodule_refuses_unknown_priors() -> None:
    from radaraug.errors import ConfigError
    from radaraug.training import TwinSplits

    with pytest.raises(ConfigError, match="catalog_priors"):
        TwinSplits(catalog_priors="measured")  # type: ignore[arg-type]


def test_effects_draws_stay_reproducible_with_priors() -> None:
    cfg = RadarConfig.bgt60tr13c()
    new, _ = calibration_priors(_profile(cfg, ["spur_tone"]), TwinRandomization(), cfg)
    assert new.effects(3, 7) == new.effects(3, 7)
