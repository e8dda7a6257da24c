"""Priors of the twin's effect catalog from what ``diagnose`` measured on the calibration capture.

:func:`calibration_priors` gives each effect diagnose added a higher probability and ranges around
its fitted values (each catalog entry's ``centred_on``); the others keep their physics priors. Bands
rather than the fitted values, since diagnose may name the wrong effect and test captures come later
(``docs/simulation.md``, "Catalog priors from the calibration capture").
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from radaraug.config import RadarConfig
from radaraug.sensor.profile import TwinProfile
from radaraug.sim.catalog import BY_NAME
from radaraug.sim.catalog.base import factor_band, first
from radaraug.sim.randomization import TwinRandomization

PRIOR_PROBABILITY = 0.7
"""Per-item probability of an effect that diagnose found on the calibration capture."""

#: Effects :func:`calibration_priors` can move: the catalog's entries and the levels' phase noise.
SUPPORTED = (*BY_NAME, "phase_noise")


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
    sections: dict[str, dict[str, Any]] = {}
    for name, p in found.items():
        if name in base.catalog:
            entry = base.catalog[name]
            moved = entry.centred_on(p, config, max(entry.probability, float(probability)))
            if moved is not None:
                changes[name] = moved
                sections.setdefault("catalog", {})[name] = moved
        elif name == "phase_noise" and "freq_noise_rms_Hz" in p:
            # Phase noise is drawn for every item (a level, not a catalog effect): centre its range.
            changes[name] = {"phase_noise_rms_Hz": factor_band(first(p["freq_noise_rms_Hz"]), 2.0, 1e3, 3e6)}
            sections.setdefault("levels", {}).update(changes[name])
    new = base.replace(**sections) if sections else base
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
