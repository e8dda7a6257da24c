"""Physical bounds on the base refit, and the check that says when a diagnosis leaned on them.

Left free, the base refit absorbs power the catalog does not explain into noise (every error still
falls), so a failed diagnosis would look like a good one. The bounds are a BGT60TR13C's
(``docs/diagnosis.md``, "Base stages stay physical").
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from radaraug.diagnosis.catalog import Chain, _as_list, find
from radaraug.sensor.effects.base import Prior

BASE_BOUNDS: dict[tuple[str, str], Prior] = {
    ("thermal_noise", "noise_figure_dB"): Prior(6.0, 18.0),
    ("adc_noise", "rms_counts"): Prior(0.5, 4.0, "log"),
}
"""(effect, parameter) -> the range the base refit may use."""

NOISE_RISE_DB = 3.0
"""A base noise stage raised by more than this while a localized residual stays: a global change
standing in for a local effect."""

_AT_BOUND = 0.02  # within 2 % of the range (in the prior's scale) of a bound


def bounded(effect: str, param: str, prior: Prior) -> Prior:
    """``prior`` narrowed to :data:`BASE_BOUNDS` (unchanged for a parameter without a bound)."""
    b = BASE_BOUNDS.get((effect, param))
    if b is None:
        return prior
    return Prior(max(prior.lo, b.lo), min(prior.hi, b.hi), prior.scale)


def _unit(v: float, p: Prior) -> float:
    if p.scale == "log":
        return (math.log(v) - math.log(p.lo)) / (math.log(p.hi) - math.log(p.lo))
    return (v - p.lo) / (p.hi - p.lo)


def _rise_db(effect: str, before: float, after: float) -> float:
    """How much the stage's noise power rose (dB)."""
    if effect == "thermal_noise":
        return after - before
    return 20 * math.log10(max(after, 1e-12) / max(before, 1e-12))


def check_base(before: Chain, after: Chain, unexplained: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """One entry per bounded base parameter: declared and final value, and what is wrong with it.

    ``at_bound``: the refit stopped at a bound; ``global_for_local``: the stage's noise rose by more than
    :data:`NOISE_RISE_DB` while a localized residual (an RD-map item of ``unexplained``) remains. ``ok`` is
    False when either holds; ``text`` says it in one line.
    """
    local = [u for u in unexplained if u.get("view") == "rd_map" and u.get("kind") == "excess"]
    out = []
    for (effect, param), bound in BASE_BOUNDS.items():
        e0, e1 = find(before, effect), find(after, effect)
        if e0 is None or e1 is None or e1["params"].get(param) is None:
            continue
        v0 = float(_as_list(e0["params"][param], 1)[0])
        v1 = float(_as_list(e1["params"][param], 1)[0])
        u = _unit(v1, bound)
        at = "lower" if u <= _AT_BOUND else "upper" if u >= 1 - _AT_BOUND else None
        rise = _rise_db(effect, v0, v1)
        global_for_local = rise > NOISE_RISE_DB and bool(local)
        text = f"{effect}.{param}: declared {v0:.3g}, final {v1:.3g} (bounds {bound.lo:g}..{bound.hi:g})"
        if at:
            text += f"; stopped at the {at} bound: the capture asks for more than a physical {effect}"
        if global_for_local:
            text += (f"; noise raised {rise:.1f} dB while a localized residual remains "
                     f"({local[0]['size_dB']:+.1f} dB at {local[0]['range_m']} m): a global change stands in for a local effect")
        out.append({"effect": effect, "param": param, "declared": v0, "final": v1, "bounds": [bound.lo, bound.hi],
                    "at_bound": at, "noise_rise_dB": round(rise, 2), "global_for_local": global_for_local,
                    "ok": at is None and not global_for_local, "text": text})
    return out


__all__ = ["BASE_BOUNDS", "NOISE_RISE_DB", "bounded", "check_base"]
