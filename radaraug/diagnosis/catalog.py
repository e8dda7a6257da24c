"""The effect catalog the loop searches: which parameters of each effect it fits, and where to start.

A :class:`Candidate` names a registered receiver effect (:data:`radaraug.sensor.EFFECTS`), its searched
parameters (:class:`ParamSpec`, each with a prior range) and its starts: read off the residual where
it says something (a spur's range and Doppler bin give its frequency), a coarse grid where it does
not. A candidate already in the chain is a refit; each is inserted at its place in
:data:`radaraug.sensor.effects.HARDWARE_ORDER`.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.diagnosis.signatures import doppler_band_widths
from radaraug.diagnosis.views import Views, _db
from radaraug.errors import CalibrationError
from radaraug.sensor.effects import EFFECTS
from radaraug.sensor.effects.base import Prior, hardware_position

Chain = list[dict[str, Any]]

BASE_STAGES = ("thermal_noise", "system_gain", "if_highpass", "anti_alias_lowpass", "adc_noise", "dc_offset")
"""The base chain, refitted before any catalog effect is tried."""


NOISE_BASE = (("thermal_noise", "noise_figure_dB"), ("adc_noise", "rms_counts"), ("if_highpass", "cutoff_Hz"),
              ("anti_alias_lowpass", "cutoff_Hz"))
"""Base parameters a new noise source is fitted together with: the base refit has already bent
them to imitate it (a higher floor, another shape), so they must be free to move back."""


@dataclass(frozen=True)
class ParamSpec:
    """One searched parameter: ``effect.params[name]`` (element ``index`` of a per-RX list)."""

    name: str
    prior: Prior
    index: int | None = None


@dataclass
class Context:
    """What a candidate may look at to choose its starts."""

    config: RadarConfig
    mode: str
    chain: Chain
    capture: Views
    twin: Views
    probe: Callable[[Chain], Views]
    measured: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    """Each present signature's own measurement of its effect, by effect name."""

    def excess_db(self) -> torch.Tensor:
        """Capture over twin frame-averaged RD power, RX-averaged, ``(range, doppler)`` dB."""
        return _db(self.capture.stats.power.mean(dim=0)) - _db(self.twin.stats.power.mean(dim=0))

    def range_m(self, k: float) -> float:
        """Range (m) of range bin ``k`` (fractional bins too)."""
        return float(k) * self.config.range_resolution_m


@dataclass
class Candidate:
    """An effect the loop can add (or refit), its searched parameters and its starts."""

    name: str
    specs: Callable[[Context, dict[str, Any]], list[ParamSpec]]
    starts: Callable[[Context], list[dict[str, Any]]]
    modes: tuple[str, ...] = ("scene", "estimated")
    joint: tuple[tuple[str, str], ...] = ()
    """Parameters of other stages fitted together with this one, ``(effect, parameter)``: a new
    noise source trades off against the thermal noise's level."""


# --------------------------------------------------------------------------- chain helpers
def find(chain: Chain, name: str) -> dict[str, Any] | None:
    """The effect dict called ``name`` in ``chain`` (None when absent)."""
    return next((e for e in chain if e["name"] == name), None)


def require(chain: Chain, name: str) -> dict[str, Any]:
    """The effect dict called ``name`` in ``chain``; :class:`CalibrationError` when absent."""
    e = find(chain, name)
    if e is None:
        raise CalibrationError(f"the effect chain has no {name!r} (it has {[x['name'] for x in chain]})")
    return e


def with_effect(chain: Chain, name: str, params: Mapping[str, Any]) -> Chain:
    """A copy of ``chain`` with effect ``name`` set to ``params`` (merged, or inserted in hardware order)."""
    out = copy.deepcopy(chain)
    cur = find(out, name)
    if cur is not None:
        cur["params"].update(copy.deepcopy(dict(params)))
        return out
    # Every registered effect builds with its defaults (tested), which fill what ``params`` leaves out.
    new = {"name": name, "params": {**EFFECTS[name]().to_dict()["params"], **copy.deepcopy(dict(params))}}
    out.insert(hardware_position([e["name"] for e in out], name), new)
    return out


def get_param(chain: Chain, name: str, spec: ParamSpec) -> float:
    """Current value of ``spec`` in effect ``name``."""
    v = require(chain, name)["params"][spec.name]
    if isinstance(v, list):
        return float(v[spec.index if spec.index is not None else 0])
    return float(v)


def set_params(chain: Chain, name: str, specs: Sequence[ParamSpec], values: Sequence[float], num_rx: int) -> Chain:
    """A copy of ``chain`` with the searched parameters of effect ``name`` set to ``values``."""
    out = copy.deepcopy(chain)
    eff = require(out, name)
    for spec, val in zip(specs, values):
        cur = eff["params"].get(spec.name)
        if spec.index is None:
            eff["params"][spec.name] = float(val) if not isinstance(cur, list) else [float(val)] * len(cur)
        else:
            lst = list(cur) if isinstance(cur, list) else [float(cur if cur is not None else 0.0)] * num_rx
            lst[spec.index] = float(val)
            eff["params"][spec.name] = lst
    return out


def _priors(ctx: Context, name: str) -> dict[str, Prior]:
    return EFFECTS[name].priors(ctx.config)


def _around(value: float, prior: Prior, rel: float | None = None, half: float | None = None) -> Prior:
    """A narrower prior around ``value``: x/÷ 10**rel (log) or +- half (lin), inside ``prior``."""
    if prior.scale == "log" and rel is not None:
        lo, hi = value / 10**rel, value * 10**rel
    else:
        h = half if half is not None else (prior.hi - prior.lo) / 8
        lo, hi = value - h, value + h
    lo, hi = max(lo, prior.lo), min(hi, prior.hi)
    if not lo < hi:
        return prior
    return Prior(lo, hi, prior.scale)


def _narrow(ctx: Context, name: str, start: dict[str, Any], pname: str, **around: float) -> ParamSpec:
    """Parameter ``pname`` of effect ``name`` searched in a range :func:`_around` its start."""
    return ParamSpec(pname, _around(start[pname], _priors(ctx, name)[pname], **around))


def _plain_specs(name: str, *pnames: str, kept: tuple[str, ...] = ()) -> Callable[[Context, dict[str, Any]],
                                                                                     list[ParamSpec]]:
    """Specs of ``pnames`` over the effect's own prior ranges, whatever the start.

    ``kept``: parameters left at their start when the effect's signature measured them
    (:attr:`Context.measured`).
    """

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        skip = kept if ctx.measured.get(name) else ()
        return [ParamSpec(p, _priors(ctx, name)[p]) for p in pnames if p not in skip]

    return specs


# --------------------------------------------------------------------------- residual reading
def _line_peaks(excess: torch.Tensor, k: int, min_db: float) -> list[tuple[int, int, float]]:
    """Up to ``k`` (row, col, dB) local maxima of ``excess`` off zero Doppler and range bin 0, at least ``min_db``.

    Lines a few Doppler bins from zero count: the static scene is matched in the excess map.
    """
    e = excess.clone()
    e[:, e.shape[1] // 2] = -math.inf
    e[:1] = -math.inf
    out: list[tuple[int, int, float]] = []
    flat = e.flatten()
    order = torch.argsort(flat, descending=True)
    taken = torch.zeros_like(e, dtype=torch.bool)
    for idx in order[: 4096].tolist():
        v = float(flat[idx])
        if v < min_db or len(out) >= k:
            break
        r, c = divmod(idx, e.shape[1])
        if taken[max(r - 2, 0): r + 3, max(c - 2, 0): c + 3].any():
            continue
        taken[r, c] = True
        out.append((r, c, v))
    return out


def _sub_bin(power: torch.Tensor, r: int, d: int) -> float:
    """Fractional range bin of a peak at row ``r`` (column ``d``), clipped to +-0.5, from a parabola in log power."""
    if not 0 < r < power.shape[0] - 1:
        return float(r)
    a, b, c = (math.log(max(float(power[k, d]), 1e-30)) for k in (r - 1, r, r + 1))
    den = a - 2 * b + c
    return r + (max(min(0.5 * (a - c) / den, 0.5), -0.5) if den < 0 else 0.0)


def _level_probe(ctx: Context, name: str, params: dict[str, Any], r: int, col: int,
                 target_db: float) -> dict[str, Any] | None:
    """``params`` with the level that puts the effect's RD power at cell (r, col) ``target_db`` above the twin.

    The level is in dB, the effect's ``level_dB``: one simulation at the current level, then linear
    scaling. None when the effect adds nothing there, or the capture is not above the twin.
    """
    p_with = float(ctx.probe(with_effect(ctx.chain, name, params)).stats.power.mean(dim=0)[r, col])
    p_without = float(ctx.twin.stats.power.mean(dim=0)[r, col])
    gain = p_with - p_without
    want = p_without * (10 ** (target_db / 10) - 1)
    if gain <= 0 or want <= 0:
        return None
    return {**params, "level_dB": float(params["level_dB"]) + 10 * math.log10(want / gain)}


def _static_excess(ctx: Context, *masked: slice) -> tuple[int, float, float] | None:
    """The zero-Doppler range bin where the capture most exceeds the twin, outside the ``masked`` bins.

    Returns the bin, the excess (dB) and the capture's frame-averaged power there; None under 3 dB.
    """
    ex = ctx.excess_db()
    prof = ex[:, ex.shape[1] // 2].clone()
    for bins in masked:
        prof[bins] = -math.inf
    r = int(prof.argmax())
    if float(prof[r]) < 3.0:
        return None
    return r, float(prof[r]), float(ctx.capture.stats.power.mean(dim=0)[r, ex.shape[1] // 2])


# --------------------------------------------------------------------------- candidates
def _range_level_specs(name: str, range_key: str) -> Callable[[Context, dict[str, Any]], list[ParamSpec]]:
    """Specs of a scatterer-like effect: a range within one range bin of its start, a level within 6 dB."""

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        return [_narrow(ctx, name, start, range_key, half=ctx.config.range_resolution_m),
                _narrow(ctx, name, start, "level_dB", half=6.0)]

    return specs


def _noise_like(name: str, pname: str, grid: Sequence[float], factors: Sequence[float] = (1.0, 0.3, 3.0),
                joint: tuple[tuple[str, str], ...] = ()) -> Candidate:
    """A one-parameter level: starts at ``factors`` times its value in the chain, else on ``grid``."""

    def starts(ctx: Context) -> list[dict[str, Any]]:
        cur = find(ctx.chain, name)
        if cur is not None:
            v = _as_list(cur["params"][pname], 1)[0]
            return [{pname: v * f} for f in factors]
        return [{pname: g} for g in grid]

    return Candidate(name, _plain_specs(name, pname), starts, joint=joint)


def _spur() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        m = ctx.measured.get("spur_tone")
        if m and "doppler_bin" in m:
            # A locked line: the signature's fine DFT over fast time and its Doppler bin fixed the alias,
            # which the views cannot (aliases 1/T apart make the same Doppler line; measured: the search
            # moved generator B's 187.30 kHz spur to 189.87 kHz, one 1/T over, from this start's
            # neighbours). The search then moves it within half a Doppler bin.
            return [{"freq_Hz": float(m["freq_Hz"]), "amplitude_counts": float(m["amplitude_counts"]),
                     "phase_rad": 0.0}]
        if (ridge := _measured_ridge(ctx)) is not None:
            # An unlocked spur's ridge: the signature's fine DFT over fast time read its frequency and amplitude
            # (the views' ridge, summed over Doppler, let the search wander half a bin at 43 dB).
            return [{"freq_Hz": float(ridge["freq_Hz"]), "amplitude_counts": float(ridge["amplitude_counts"]),
                     "phase_rad": 0.0, "phase_jitter_rad": math.pi}]
        cfg = ctx.config
        ex = ctx.excess_db()
        M = ex.shape[1]
        out = []
        cap = ctx.capture.stats.power.mean(dim=0)
        bin_hz = cfg.sample_rate_Hz / cfg.num_samples_per_chirp
        T = cfg.chirp_repetition_time_s
        for r, d, _v in _line_peaks(ex, 2, 6.0):
            # Sub-bin frequency from the Hann peak's neighbours (parabola on log power), then the
            # Doppler bin picks among the aliases 1/T apart; the neighbouring aliases are starts too.
            f_est = _sub_bin(cap, r, d) * bin_hz
            amp = 2 * math.sqrt(float(cap[r, d])) * cfg.adc_full_scale_counts / 2
            for sign in (1, -1):
                frac = sign * (d - M // 2) / M
                j = round(f_est * T - frac)
                for dj in (0, -1, 1):
                    f = (j + dj + frac) / T
                    if abs(f - f_est) <= bin_hz and 0 < f < cfg.sample_rate_Hz / 2:
                        out.append({"freq_Hz": f, "amplitude_counts": amp, "phase_rad": 0.0})
        return out + _ridge_start(ctx, ex, cap, bin_hz)

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        if start.get("phase_jitter_rad", 0.0) > 0:  # unlocked: only the fast-time frequency shows
            # within a twentieth of a range bin when the ridge signature read it (its closed-form test)
            half = (0.05 if _measured_ridge(ctx) is not None else 0.5) * ctx.config.sample_rate_Hz / ctx.config.num_samples_per_chirp
        else:
            half = 0.5 / (ctx.config.num_chirps_per_frame * ctx.config.chirp_repetition_time_s)
        return [_narrow(ctx, "spur_tone", start, "freq_Hz", half=half),
                _narrow(ctx, "spur_tone", start, "amplitude_counts", rel=0.7)]

    return Candidate("spur_tone", specs, starts)


def _measured_ridge(ctx: Context) -> Mapping[str, float] | None:
    """The spur signature's reading when it found an unlocked spur's ridge (None otherwise)."""
    m = ctx.measured.get("spur_tone")
    return m if m and m.get("locked") == 0.0 and "freq_Hz" in m else None


def _ridge_start(ctx: Context, ex: torch.Tensor, cap: torch.Tensor, bin_hz: float,
                 min_db: float = 6.0) -> list[dict[str, Any]]:
    """An unlocked spur's start from a ridge: one range row raised over every Doppler bin.

    The row's median excess must stand ``min_db`` over the twin and 4 dB over the rows 3 bins away; its
    tone power is the row's excess summed over Doppler over the Hann noise bandwidth (1.5 bins).
    """
    K, M = ex.shape
    if K < 8:
        return []
    keep = torch.ones(M, dtype=torch.bool, device=ex.device)
    keep[max(M // 2 - 1, 0): M // 2 + 2] = False
    row = ex[:, keep].median(dim=1).values
    r = int(row[2: K - 1].argmax()) + 2
    side = max(float(row[j]) for j in (r - 3, r + 3) if 0 <= j < K)
    if float(row[r]) < min_db or float(row[r]) - side < 4.0:
        return []
    twin = ctx.twin.stats.power.mean(dim=0)
    spread = (cap - twin).clamp_min(0.0)[:, keep].sum(dim=1, keepdim=True) / 1.5  # (K, 1)
    f = _sub_bin(spread, r, 0) * bin_hz
    amp = 2 * math.sqrt(float(spread[r, 0])) * ctx.config.adc_full_scale_counts / 2
    return [{"freq_Hz": f, "amplitude_counts": amp, "phase_rad": 0.0, "phase_jitter_rad": math.pi}]


def _static_clutter() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        peak = _static_excess(ctx, slice(0, 1))
        if peak is None:
            return []
        r, excess, _ = peak
        M = ctx.capture.stats.power.shape[-1]
        rr = ctx.range_m(_sub_bin(ctx.capture.stats.power.mean(dim=0), r, M // 2))
        params = {"range_m": rr, "level_dB": -90.0, "phase_rad": 0.0}
        probed = _level_probe(ctx, "static_clutter", params, r, M // 2, excess)
        return [] if probed is None else [probed]

    return Candidate("static_clutter", _range_level_specs("static_clutter", "range_m"), starts, modes=("scene",))


def _measured_pair_Hz(ctx: Context) -> float | None:
    """``f_v`` of a present Doppler-pair signature (its reading carries ``beta``; a band's does not), or None."""
    m = ctx.measured.get("vibrating_clutter") or {}
    return float(m["vibration_Hz"]) if "beta" in m and "vibration_Hz" in m else None


def _measured_band_v_max(ctx: Context) -> float | None:
    """``v_max`` (m/s) of a present Doppler-band signature (a vibration of ``beta >> 1``), or None."""
    m = ctx.measured.get("vibrating_clutter") or {}
    return float(m["v_max_m_s"]) if m.get("variant") == 1.0 and "v_max_m_s" in m else None


def _vibrating() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        cfg = ctx.config
        ex = ctx.excess_db()
        M = ex.shape[1]
        out = []
        if _measured_band_v_max(ctx) is not None:
            # The band's edge measured v_max = 2 pi f_v d; a small-beta pair would fit the band's
            # brightest cells instead (a pair at ~7 bins for a +-5-bin band at 32 chirps).
            return _band_starts(ctx, ex)
        measured = _measured_pair_Hz(ctx)
        for r, d, v in _line_peaks(ex, 1, 6.0):
            # The pair's signature read f_v to a fraction of a Doppler bin (each line's centre); the
            # residual's peak only to its bin.
            vib = measured if measured is not None else abs(d - M // 2) / (M * cfg.chirp_repetition_time_s)
            for beta in (0.5, 1.5):
                # An estimated static scene already holds the object's mean return: add only
                # what the vibration adds (carrier 0).
                params = {"range_m": ctx.range_m(_sub_bin(ctx.capture.stats.power.mean(dim=0), r, d)),
                          "level_dB": -90.0, "displacement_m": beta * cfg.wavelength_m / (4 * math.pi),
                          "vibration_Hz": vib, "phase_rad": 0.0, "carrier": 0.0 if ctx.mode == "estimated" else 1.0}
                probed = _level_probe(ctx, "vibrating_clutter", params, r, d, v)
                if probed is not None:
                    out.append(probed)
        return out + _band_starts(ctx, ex)

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        dopp = 1 / (ctx.config.num_chirps_per_frame * ctx.config.chirp_repetition_time_s)
        if _measured_pair_Hz(ctx) is not None:
            dopp /= 4  # measured: within a quarter bin of the signature's f_v
        f_v = start["vibration_Hz"]
        return [_narrow(ctx, "vibrating_clutter", start, "level_dB", half=8.0),
                _narrow(ctx, "vibrating_clutter", start, "displacement_m", rel=0.6),
                ParamSpec("vibration_Hz", Prior(max(f_v - dopp, 1e-3), f_v + dopp, "lin"))]

    return Candidate("vibrating_clutter", specs, starts)


def _band_starts(ctx: Context, ex: torch.Tensor, min_db: float = 6.0, min_bins: int = 3) -> list[dict[str, Any]]:
    """Starts of a large vibration from a Doppler band: a row raised from zero Doppler out to +-v_max.

    Only ``2 pi f_v d = v_max`` is identified, so the starts span ``f_v`` of 0.3, 1 and 3 Doppler bins
    with ``d = v_max / (2 pi f_v)``; ``v_max`` is the band signature's measured edge when present, else
    the residual's band width. The search refines both.
    """
    cfg = ctx.config
    K, M = ex.shape
    c = M // 2
    if K < 4 or c < 6:
        return []
    w_up, w_dn = doppler_band_widths(ex > min_db)
    w = torch.minimum(w_up, w_dn)
    w[:1] = 0
    r = int(w.argmax())
    width = int(w[r])
    if width < min_bins or max(int(w_up[r]), int(w_dn[r])) >= c - 3:
        return []
    dopp = 1 / (M * cfg.chirp_repetition_time_s)  # Hz per Doppler bin
    measured = _measured_band_v_max(ctx)
    v_max = measured if measured is not None else (width + 1) * dopp * cfg.wavelength_m / 2
    col = c + 2 + width // 2
    hi = _priors(ctx, "vibrating_clutter")["displacement_m"].hi
    out = []
    for f_v in (0.3 * dopp, dopp, 3 * dopp):
        params = {"range_m": ctx.range_m(r), "level_dB": -90.0, "displacement_m": min(v_max / (2 * math.pi * f_v), hi),
                  "vibration_Hz": f_v, "phase_rad": 0.0, "carrier": 0.0 if ctx.mode == "estimated" else 1.0}
        probed = _level_probe(ctx, "vibrating_clutter", params, r, col, float(ex[r, col]))
        if probed is not None:
            out.append(probed)
    return out


def _strongest_static(ctx: Context, first: int = 1) -> tuple[int, float]:
    """Range bin and power of the capture's strongest zero-Doppler return from bin ``first`` on."""
    zp = ctx.capture.stats.power.mean(dim=0)[:, ctx.capture.stats.power.shape[-1] // 2].clone()
    zp[: min(first, zp.numel() - 1)] = 0
    k = int(zp.argmax())
    return k, float(zp[k])


def _multipath() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        k, pk = _strongest_static(ctx)
        peak = _static_excess(ctx, slice(0, k + 1))
        if peak is None:
            return []
        r, _, p_r = peak
        lvl = 10 * math.log10(max(p_r, 1e-30) / max(pk, 1e-30))
        return [{"extra_range_m": ctx.range_m(r) - ctx.range_m(k), "level_dB": min(lvl, -0.5), "phase_rad": 0.0}]

    return Candidate("multipath", _range_level_specs("multipath", "extra_range_m"), starts, modes=("scene",))


def _chirp_nonlinearity() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        cfg = ctx.config
        k, pk = _strongest_static(ctx)
        peak = _static_excess(ctx, slice(0, 1), slice(max(k - 1, 0), k + 2))
        if peak is None:
            return []
        r, _, p_r = peak
        ratio = math.sqrt(max(p_r, 1e-30) / max(pk, 1e-30))
        tau = 2 * ctx.range_m(k) / SPEED_OF_LIGHT
        ripple = abs(r - k) * cfg.sample_rate_Hz / cfg.num_samples_per_chirp
        dev = ratio / (math.pi * max(tau, 1e-12))
        pr = _priors(ctx, "chirp_nonlinearity")
        dev = min(max(dev, pr["deviation_Hz"].lo), pr["deviation_Hz"].hi)
        return [{"deviation_Hz": dev, "ripple_Hz": max(ripple, pr["ripple_Hz"].lo), "phase_rad": 0.0}]

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        ripple = _priors(ctx, "chirp_nonlinearity")["ripple_Hz"]
        bin_hz = ctx.config.sample_rate_Hz / ctx.config.num_samples_per_chirp
        return [_narrow(ctx, "chirp_nonlinearity", start, "deviation_Hz", rel=0.6),
                ParamSpec("ripple_Hz", _around(start["ripple_Hz"], Prior(ripple.lo, ripple.hi, "lin"), half=bin_hz))]

    return Candidate("chirp_nonlinearity", specs, starts, modes=("scene",))


def _interference() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        m = ctx.measured.get("interference")
        if m:
            # The signature counted the bursts chirp by chirp: their share is the probability (kept),
            # their energy and length start the amplitude and duration.
            pr = _priors(ctx, "interference")
            a0 = min(max(float(m["amplitude_counts"]), pr["amplitude_counts"].lo), pr["amplitude_counts"].hi)
            d0 = min(max(float(m["duration_s"]), pr["duration_s"].lo), pr["duration_s"].hi)
            return [{"probability": float(m["probability"]), "amplitude_counts": a, "duration_s": d}
                    for a in (a0, a0 / 3) for d in (d0, 3 * d0)]
        # The share of chirps well above the median chirp power estimates the burst probability.
        p = ctx.capture.stats.burst_fraction - ctx.twin.stats.burst_fraction
        probs = (min(max(2 * p, 0.02), 0.9), 0.05, 0.25) if p > 0.005 else (0.05, 0.25)
        return [{"probability": q, "amplitude_counts": a, "duration_s": d}
                for q in probs for a in (30.0, 300.0) for d in (5e-6, 15e-6)]

    return Candidate("interference", _plain_specs("interference", "probability", "amplitude_counts", "duration_s",
                                                  kept=("probability",)), starts, joint=NOISE_BASE)


PHASE_NOISE_SEEN_DB = 30.0
"""Carrier over the per-chirp floor (dB) from which the views see an LO skirt in single cells; under it
the skirt shows only in the cross-RX signature, whose measurement the search then keeps."""
PHASE_NOISE_REL = 0.1
"""How far (log10) the search may move an LO noise its signature measured on a strong carrier (x/÷ 1.26)."""


def _phase_noise() -> Candidate:
    # Without a signature (or a phase-noise stage), the starts are those of the default 100 kHz RMS.
    plain = _noise_like("phase_noise", "freq_noise_rms_Hz", [100e3 * f for f in (0.3, 3.0, 10.0)], (0.3, 3.0, 10.0))

    def starts(ctx: Context) -> list[dict[str, Any]]:
        m = ctx.measured.get("phase_noise")
        if m and "freq_noise_rms_Hz" in m:
            return [{"freq_noise_rms_Hz": float(m["freq_noise_rms_Hz"])}]
        return plain.starts(ctx)

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        m = ctx.measured.get("phase_noise")
        if not m or "freq_noise_rms_Hz" not in m:
            return plain.specs(ctx, start)
        if float(m["carrier_snr_dB"]) < PHASE_NOISE_SEEN_DB:
            # The skirt is under every cell's floor: the views would trade it against the floor's level.
            return []
        return [_narrow(ctx, "phase_noise", start, "freq_noise_rms_Hz", rel=PHASE_NOISE_REL)]

    return Candidate("phase_noise", specs, starts)


def _frame_drift() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        m = ctx.measured.get("frame_drift")
        if m:
            # The signature measured the frame means' excess variance per RX (kept) and the common
            # gain's from the static returns (the start of its fit).
            return [{"gain_rms_dB": float(m["gain_rms_dB"]), "dc_rms_counts": float(m["dc_rms_mean_counts"])}]
        c, t = ctx.capture.stats, ctx.twin.stats
        if c.frame_noise is None or t.frame_noise is None:
            return []
        excess = (c.frame_noise**2 - c.chirp_noise**2) - (t.frame_noise**2 - t.chirp_noise**2)
        dc = math.sqrt(max(excess, 0.0)) if excess > 0 else 0.3
        sc, st = float(ctx.capture["frame_power"][1]), float(ctx.twin["frame_power"][1])
        g = math.sqrt(max(sc**2 - st**2, 0.0))
        return [{"gain_rms_dB": g, "dc_rms_counts": dc}, {"gain_rms_dB": 0.0, "dc_rms_counts": dc},
                {"gain_rms_dB": max(g, 0.3), "dc_rms_counts": 0.0}]

    plain = _plain_specs("frame_drift", "gain_rms_dB", "dc_rms_counts", kept=("dc_rms_counts",))

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        m = ctx.measured.get("frame_drift")
        g = float(m["gain_rms_dB"]) if m else 0.0  # the static returns' level spread over frames
        if g < DRIFT_GAIN_MIN_DB:
            return plain(ctx, start)
        return [ParamSpec("gain_rms_dB", _around(g, _priors(ctx, "frame_drift")["gain_rms_dB"], half=DRIFT_GAIN_REL * g))]

    return Candidate("frame_drift", specs, starts)


DRIFT_GAIN_MIN_DB = 0.15
"""A drift signature's gain reading (dB RMS) from which it bounds the search (the detector's own threshold)."""
DRIFT_GAIN_REL = 0.25
"""How far (a share of the reading) the search may move a drift gain its signature read off the static returns."""


MEASURED_GAIN_HALF_DB = 0.25
"""How far (dB) the search may move an RX gain the static returns measured (estimated mode)."""


def _gains_from_returns(ctx: Context) -> Mapping[str, float] | None:
    """The mismatch signature's reading when its static returns measured the gains in estimated mode.

    The estimated static scene copies the capture's returns, so the views see the mismatch only in the
    noise, whose thermal share the twin may not have.
    """
    m = ctx.measured.get("rx_gain_phase_mismatch")
    return m if ctx.mode == "estimated" and m and m.get("num_returns", 0) > 0 else None


def _rx_mismatch() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        R = ctx.config.num_rx
        if R < 2:
            return []
        # Static levels per RX where there is a static scene to compare, else the noise floors.
        part = slice(R, 2 * R) if ctx.mode == "scene" else slice(0, R)
        fc = ctx.capture["rx_balance"][part]
        ft = ctx.twin["rx_balance"][part]
        d = (fc - ft) - (fc - ft)[0]
        cur = find(ctx.chain, "rx_gain_phase_mismatch")
        params = cur["params"] if cur is not None else {"gain_dB": 0.0, "phase_rad": 0.0}
        g0, p0 = _as_list(params["gain_dB"], R), _as_list(params["phase_rad"], R)
        gains = [g0[i] + float(d[i]) for i in range(R)]
        m = _gains_from_returns(ctx)
        if m is not None:
            gains = [g0[0]] + [g0[0] + float(m[f"static_gain_dB_rx{i + 1}"]) for i in range(1, R)]
        phases = list(p0)
        if ctx.mode == "scene":
            k, _ = _strongest_static(ctx, first=3)
            pc = ctx.capture["rx_phase"][:, k] - ctx.capture["rx_phase"][0, k]
            pt = ctx.twin["rx_phase"][:, k] - ctx.twin["rx_phase"][0, k]
            phases = [p0[i] + float(torch.remainder(pc[i] - pt[i] + math.pi, 2 * math.pi) - math.pi) for i in range(R)]
        return [{"gain_dB": gains, "phase_rad": phases}]

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        R = ctx.config.num_rx
        pr = _priors(ctx, "rx_gain_phase_mismatch")
        half = MEASURED_GAIN_HALF_DB if _gains_from_returns(ctx) is not None else 2.0
        out = [ParamSpec("gain_dB", _around(start["gain_dB"][i], pr["gain_dB"], half=half), i) for i in range(1, R)]
        if ctx.mode == "scene":
            out += [ParamSpec("phase_rad", _around(start["phase_rad"][i], pr["phase_rad"], half=0.4), i)
                    for i in range(1, R)]
        return out

    return Candidate("rx_gain_phase_mismatch", specs, starts)


def _as_list(v: Any, n: int) -> list[float]:
    return [float(x) for x in v] if isinstance(v, list) else [float(v)] * n


def _leakage() -> Candidate:
    def starts(ctx: Context) -> list[dict[str, Any]]:
        cur = find(ctx.chain, "tx_rx_leakage")
        if cur is None:
            return [{"coupling_dB": -60.0, "range_m": 0.04, "phase_rad": 0.0}]
        R = ctx.config.num_rx
        M = ctx.capture.stats.power.shape[-1]
        pc = _db(ctx.capture.stats.power[:, 0:2, M // 2].mean(dim=1))
        pt = _db(ctx.twin.stats.power[:, 0:2, M // 2].mean(dim=1))
        c0 = _as_list(cur["params"]["coupling_dB"], R)
        return [{"coupling_dB": [c0[i] + float(pc[i] - pt[i]) for i in range(R)]}]

    def specs(ctx: Context, start: dict[str, Any]) -> list[ParamSpec]:
        R = ctx.config.num_rx
        pr = _priors(ctx, "tx_rx_leakage")
        c = _as_list(start.get("coupling_dB", -60.0), R)
        return [ParamSpec("coupling_dB", _around(c[i], pr["coupling_dB"], half=4.0), i) for i in range(R)]

    return Candidate("tx_rx_leakage", specs, starts, modes=("scene",))


def catalog() -> list[Candidate]:
    """Every candidate the loop tries after the base refit, in a fixed order (ties go to the first)."""
    return [
        _noise_like("adc_noise", "rms_counts", (0.5, 2.0, 8.0), joint=NOISE_BASE[:1] + NOISE_BASE[2:]),
        _frame_drift(),
        _spur(),
        _rx_mismatch(),
        _interference(),
        _vibrating(),
        _static_clutter(),
        _multipath(),
        _chirp_nonlinearity(),
        _leakage(),
        _phase_noise(),
    ]


CATALOG_NAMES = ("system_gain", "thermal_noise", "if_highpass", "anti_alias_lowpass", "dc_offset", "adc_quantization",
                 "adc_clipping", *(c.name for c in catalog()))
"""Every effect the loop fits: the base stages (refitted first; quantization and clipping are
always present and have nothing to fit) and the catalog candidates."""
