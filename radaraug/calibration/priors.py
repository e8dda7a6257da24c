"""Priors of the twin's effect catalog from what ``diagnose`` measured on the calibration capture.

:func:`calibration_priors` gives each effect diagnose added a higher probability and ranges around
its fitted values; the others keep their physics priors. Bands rather than the fitted values, since
diagnose may name the wrong effect and test captures come later (``docs/simulation.md``, "Catalog
priors from the calibration capture").
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import Any

from radaraug.config import RadarConfig
from radaraug.sensor.profile import TwinProfile
from radaraug.sim.randomization import SCATTERER_ANTENNA_GAIN_DBI, TwinRandomization

PRIOR_PROBABILITY = 0.7
"""Per-item probability of an effect that diagnose found on the calibration capture."""

#: Catalog effects :func:`calibration_priors` can move (diagnose names -> randomization fields).
SUPPORTED = ("spur_tone", "interference", "vibrating_clutter", "rx_gain_phase_mismatch", "frame_drift", "phase_noise")


def _factor_band(value: float, factor: float, lo: float, hi: float) -> tuple[float, float]:
    """``(value / factor, value * factor)`` clipped to ``[lo, hi]`` (and kept non-empty)."""
    a = min(max(value / factor, lo), hi)
    b = min(max(value * factor, lo), hi)
    return (a, b) if b > a else (max(lo, b * 0.99), b)


def _fit_band(p: Mapping[str, Any], key: str, default: float, lo: float, hi: float,
              factor: float = 2.0) -> tuple[float, float]:
    """:func:`_factor_band` around the fitted ``p[key]`` (``default`` when it was not fitted)."""
    return _factor_band(_first(p.get(key, default)), factor, lo, hi)


def _band(value: float, half: float, lo: float, hi: float) -> tuple[float, float]:
    a, b = max(value - half, lo), min(value + half, hi)
    return (a, b) if b > a else (min(a, b), max(a, b) + 1e-9)


def _first(value: Any) -> float:
    return float(value[0] if isinstance(value, (list, tuple)) else value)


def _rcs_dBsm(config: RadarConfig, range_m: float, level_dB: float) -> float:
    """Inverse of the radar equation the randomization uses for its vibrating scatterer."""
    lam = float(config.wavelength_m)
    return (level_dB - 2 * SCATTERER_ANTENNA_GAIN_DBI - 20 * math.log10(lam) + 30 * math.log10(4 * math.pi)
            + 40 * math.log10(max(range_m, 1e-3)))


def added_effects(profile: TwinProfile) -> dict[str, dict[str, Any]]:
    """The effects diagnose added to the chain, with their fitted parameters (last of each name)."""
    added: Sequence[str] = profile.fitted_on.get("effects_added") or []
    params: dict[str, dict[str, Any]] = {}
    for e in profile.to_dict()["receiver"]["effects"]:
        if e.get("name") in added:
            params[str(e["name"])] = dict(e.get("params") or {})
    return params


def calibration_priors(profile: TwinProfile, base: TwinRandomization, config: RadarConfig,
                       probability: float = PRIOR_PROBABILITY) -> tuple[TwinRandomization, dict[str, Any]]:
    """``base`` with its effect catalog centred on what ``profile``'s diagnose added.

    Args:
        profile: the twin profile ``diagnose`` fitted on the calibration capture (no scene).
        base: the randomization to start from (its physics priors).
        config: the radar config of the calibration capture (and the twin).
        probability: the per-item probability of each effect found.

    Returns:
        The new randomization and a record of what changed (effect -> fields -> new values).
    """
    found = added_effects(profile)
    changes: dict[str, dict[str, Any]] = {}
    fs2 = float(config.sample_rate_Hz) / 2

    def prob(name: str) -> float:
        return max(float(getattr(base, name)), float(probability))

    for name, p in found.items():
        if name == "spur_tone" and "freq_Hz" in p:
            frac = _first(p["freq_Hz"]) / fs2
            changes[name] = {"spur_tone_probability": prob("spur_tone_probability"),
                             "spur_tone_freq_nyquist": _band(frac, 0.02, 0.0, 1.0),
                             "spur_tone_amplitude_counts": _fit_band(p, "amplitude_counts", 1.0, 0.05, 200.0)}
        elif name == "interference":
            changes[name] = {"interference_probability": prob("interference_probability"),
                             "interference_chirp_probability": _fit_band(p, "probability", 0.05, 1e-3, 1.0),
                             "interference_amplitude_counts": _fit_band(p, "amplitude_counts", 100.0, 1.0, 2000.0),
                             "interference_duration_s": _fit_band(p, "duration_s", 5e-6, 0.2e-6, 30e-6)}
        elif name == "vibrating_clutter" and "range_m" in p:
            r = _first(p["range_m"])
            rcs = _rcs_dBsm(config, r, _first(p.get("level_dB", -80.0)))
            changes[name] = {"vibrating_clutter_probability": prob("vibrating_clutter_probability"),
                             "vibrating_clutter_range_m": _band(r, 1.0, 0.3, 30.0),
                             "vibrating_clutter_rcs_dBsm": _band(rcs, 6.0, -40.0, 20.0),
                             "vibrating_clutter_displacement_m": _fit_band(p, "displacement_m", 1e-3, 1e-5, 5e-3),
                             "vibrating_clutter_Hz": _fit_band(p, "vibration_Hz", 20.0, 0.5,
                                                               1 / (2 * float(config.chirp_repetition_time_s)), 1.5)}
        elif name == "rx_gain_phase_mismatch":
            g_raw, ph_raw = p.get("gain_dB"), p.get("phase_rad")
            gains = [float(v) for v in (g_raw if isinstance(g_raw, list) else [0.0 if g_raw is None else g_raw])]
            phases = [math.degrees(float(v)) for v in
                      (ph_raw if isinstance(ph_raw, list) else [0.0 if ph_raw is None else ph_raw])]
            g_lo, g_hi = min(gains) - 0.5, max(gains) + 0.5
            ph_lo, ph_hi = max(min(phases) - 10.0, -180.0), min(max(phases) + 10.0, 180.0)
            changes[name] = {"rx_mismatch_probability": prob("rx_mismatch_probability"),
                             "rx_mismatch_gain_dB": (max(g_lo, -6.0), min(g_hi, 6.0)),
                             "rx_mismatch_phase_deg": (ph_lo, ph_hi)}
        elif name == "frame_drift":
            changes[name] = {"frame_drift_probability": prob("frame_drift_probability"),
                             "frame_drift_gain_rms_dB": _fit_band(p, "gain_rms_dB", 0.1, 0.0, 3.0),
                             "frame_drift_dc_rms_counts": _fit_band(p, "dc_rms_counts", 0.5, 0.0, 20.0)}
        elif name == "phase_noise" and "freq_noise_rms_Hz" in p:
            # Phase noise is drawn for every item (not a catalog effect): centre its range.
            changes[name] = {"phase_noise_rms_Hz": _factor_band(_first(p["freq_noise_rms_Hz"]), 2.0, 1e3, 3e6)}
    fields: dict[str, Any] = {}
    for c in changes.values():
        fields.update(c)
    new = dataclasses.replace(base, **fields) if fields else base
    record = {"found": sorted(found), "unsupported": sorted(set(found) - set(SUPPORTED)),
              "changes": {k: {f: list(v) if isinstance(v, tuple) else v for f, v in c.items()}
                          for k, c in changes.items()}}
    return new, record


def describe(record: Mapping[str, Any]) -> str:
    """One line for logs and reports."""
    if not record.get("found"):
        return "diagnose added no effect on the calibration capture: the catalog keeps its physics priors"
    return f"catalog priors moved to the calibration's {', '.join(record['changes'])}" + (
        f" (not in the catalog: {', '.join(record['unsupported'])})" if record.get("unsupported") else "")
