"""The base refit's physical bounds and the check that reports a diagnosis leaning on them."""

from __future__ import annotations

import math

import pytest

from radaraug.diagnosis.base_bounds import BASE_BOUNDS, bounded, check_base
from radaraug.diagnosis.diagnose import closest_effects
from radaraug.diagnosis.evidence import Evidence
from radaraug.diagnosis.signatures import Signature
from radaraug.sensor.effects.base import Prior


def _chain(nf: float, adc: float) -> list[dict]:
    return [{"name": "thermal_noise", "params": {"noise_figure_dB": nf}},
            {"name": "adc_noise", "params": {"rms_counts": adc}}]


def test_bounds_narrow_the_priors_and_leave_others_alone():
    wide = Prior(0.0, 45.0)
    b = bounded("thermal_noise", "noise_figure_dB", wide)
    assert (b.lo, b.hi) == (6.0, 18.0)
    assert bounded("thermal_noise", "other", wide) == wide
    assert bounded("adc_noise", "rms_counts", Prior(0.01, 50.0, "log")).scale == "log"
    assert BASE_BOUNDS[("adc_noise", "rms_counts")].hi == 4.0


def test_check_flags_a_bound_and_a_global_change_for_a_local_residual():
    local = [{"view": "rd_map", "kind": "excess", "size_dB": 33.0, "range_m": 3.1, "velocity_m_s": 0.4}]
    fine = check_base(_chain(12.0, 1.75), _chain(13.0, 1.9), local)
    assert all(b["ok"] for b in fine) and [b["at_bound"] for b in fine] == [None, None]
    bad = {b["effect"]: b for b in check_base(_chain(12.0, 1.75), _chain(18.0, 4.0), local)}
    assert bad["thermal_noise"]["at_bound"] == "upper" and bad["thermal_noise"]["noise_rise_dB"] == 6.0
    assert bad["adc_noise"]["noise_rise_dB"] == pytest.approx(20 * math.log10(4.0 / 1.75), abs=0.01)
    assert bad["adc_noise"]["global_for_local"] and not bad["adc_noise"]["ok"]
    assert "global change stands in for a local effect" in bad["adc_noise"]["text"]
    # the same rise without a localized residual left is only a bound
    alone = {b["effect"]: b for b in check_base(_chain(12.0, 1.75), _chain(16.0, 1.75), [])}
    assert alone["thermal_noise"]["ok"] and not alone["thermal_noise"]["global_for_local"]


def test_unexplained_items_name_the_closest_effects_and_why_not():
    def absent(name: str, why: str) -> Evidence:
        return Evidence(name, False, "intrinsic", 0.0, why, Signature(name, 0.0, False, {}, why))

    ev = {"spur_tone": absent("spur_tone", "no line off zero Doppler; no ridge (best ...)"),
          "vibrating_clutter": absent("vibrating_clutter", "no symmetric Doppler pair")}
    items = [{"view": "rd_map", "kind": "excess", "range_m": 3.1, "velocity_m_s": 0.8, "size_dB": 43.0, "cells": 9},
             {"view": "noise_floor", "kind": "excess", "range_m": 0.2, "velocity_m_s": None, "size_dB": 5.0,
              "cells": 2}]
    out = closest_effects(items, ev)
    moving = {c["effect"]: c for c in out[0]["closest"]}
    assert moving["spur_tone"]["measured"].startswith("no line") and moving["spur_tone"]["present"] is False
    assert moving["interference"]["measured"] == "no signature run"
    assert [c["effect"] for c in out[1]["closest"]][0] == "if_highpass"
    assert closest_effects(items, None)[0]["closest"][0]["present"] is None
