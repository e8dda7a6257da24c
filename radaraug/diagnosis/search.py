"""The search: refit the base chain, then add catalog effects while they beat it on held-out frames.

The capture is split in two contiguous halves: parameters are fitted on the first and every
decision is scored on the second, by the overall view error (dB). Twin noise uses fixed seeds, so
candidates are compared on the same noise and the objective is smooth. Parameters move by SciPy's
bounded Nelder-Mead in their prior ranges from starts the catalog reads off the residual. An effect
with a detector is a candidate only when its signature is present beyond the declared chain.
Decision rule and margins: ``docs/diagnosis.md``, "The effect catalog and the search".
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import torch

from radaraug.diagnosis.base_bounds import bounded
from radaraug.diagnosis.catalog import (
    BASE_STAGES,
    Candidate,
    Chain,
    Context,
    ParamSpec,
    _as_list,
    catalog,
    find,
    get_param,
    require,
    set_params,
    with_effect,
)
from radaraug.diagnosis.room import ROOM_PRIORS, ROOM_STAGE, Room
from radaraug.diagnosis.twin_source import TwinSource
from radaraug.diagnosis.views import ADC_QUANTILES, Views, compute_views, overall_error, view_errors
from radaraug.sensor.effects import EFFECTS
from radaraug.sensor.effects.base import Prior
from radaraug.sensor.effects.filters import section_cutoff

HP_REFIT_SPAN = 1.2
"""A high-pass refitted from its signature keeps its cutoff within this factor of the measured one."""


@dataclass
class SearchSettings:
    """Knobs of the search (defaults are what the tests and benchmarks use).

    Attributes:
        sim_frames: twin frames per evaluation (at most the capture half's frame count).
        evals_per_param: Nelder-Mead evaluations per searched parameter (plus 4).
        screen_top: candidates refined after screening their starts.
        max_steps: most effects added.
        min_gain_rel: relative held-out improvement an effect must bring without its signature (5 %).
        min_gain_db: absolute held-out improvement it must bring (dB).
        per_param_db: held-out improvement each fitted parameter must pay for (dB); candidates are
            ranked by held-out error plus this times their parameter count.
        ambiguity_db: alternatives whose penalized held-out error is within this of the chosen one's
            are listed as ambiguous (dB; at least ``ambiguity_rel`` of the step's gain).
        ambiguity_rel: relative part of the ambiguity band.
        use_signatures: read the capture's signatures first (False: every candidate competes on the
            error alone).
        seed: seed of the twin's noise.
    """

    sim_frames: int = 24
    evals_per_param: int = 10
    screen_top: int = 4
    max_steps: int = 5
    min_gain_rel: float = 0.05
    min_gain_db: float = 0.02
    per_param_db: float = 0.005
    ambiguity_db: float = 0.03
    ambiguity_rel: float = 0.15
    use_signatures: bool = True
    seed: int = 0


@dataclass
class Score:
    """Overall error (dB), per-view errors and the twin's views."""

    overall: float
    views: dict[str, float]
    twin: Views

    def as_dict(self) -> dict[str, Any]:
        """The overall and per-view errors rounded to 4 decimals, JSON-able (the twin's views left out)."""
        return {"overall": round(self.overall, 4), "views": _rounded(self.views)}


@dataclass
class SearchResult:
    """What the search found.

    ``room_*``: the room parameters with each chain; empty when the source has none to fit.
    """

    chain_before: Chain
    chain_base: Chain
    chain_after: Chain
    before: Score
    base: Score
    after: Score
    steps: list[dict[str, Any]] = field(default_factory=list)
    tried: list[dict[str, Any]] = field(default_factory=list)
    evaluations: int = 0
    room_before: Room = field(default_factory=dict)
    room_base: Room = field(default_factory=dict)
    room_after: Room = field(default_factory=dict)


Progress = Callable[[str], None]


class Search:
    """Fit a receiver chain to a capture through a :class:`TwinSource`.

    Args:
        source: simulates frames of the capture's scene for a chain.
        fit_frames: capture frames for fitting ``(F1, rx, chirps, samples)`` SDK floats.
        held_frames: capture frames for scoring.
        settings: search knobs.
        progress: called with one line per decision (e.g. a progress bar's ``write``).
    """

    def __init__(self, source: TwinSource, fit_frames: torch.Tensor, held_frames: torch.Tensor,
                 settings: SearchSettings | None = None, progress: Progress | None = None) -> None:
        self.source = source
        self.config = source.config
        self.settings = settings or SearchSettings()
        self.cap_fit = compute_views(fit_frames, self.config)
        self.cap_held = compute_views(held_frames, self.config)
        self.n_fit = max(2, min(self.settings.sim_frames, fit_frames.shape[0]))
        self.n_held = max(2, min(self.settings.sim_frames, held_frames.shape[0]))
        self.first_held = int(fit_frames.shape[0])
        self.progress = progress or (lambda s: None)
        self.evaluations = 0
        self._measured: dict[str, dict[str, float]] = {}  # present signatures' measurements (run() sets them)

    # ------------------------------------------------------------------ scoring
    def _score(self, twin_frames: torch.Tensor, cap: Views) -> Score:
        self.evaluations += 1
        tv = compute_views(twin_frames, self.config)
        errs = view_errors(tv, cap)
        return Score(overall_error(errs), errs, tv)

    def fit_score(self, chain: Chain, room: Room | None = None) -> Score:
        """Error of ``chain`` (with room parameters ``room``, default: as traced) against the fitting half."""
        x = self.source.frames(chain, self.n_fit, seed=self.settings.seed * 7919 + 1, room=room)
        return self._score(x, self.cap_fit)

    def held_score(self, chain: Chain, room: Room | None = None) -> Score:
        """Error of ``chain`` (with room parameters ``room``) against the held-out half."""
        x = self.source.frames(chain, self.n_held, seed=self.settings.seed * 7919 + 2, first_frame=self.first_held,
                               room=room)
        return self._score(x, self.cap_held)

    # ------------------------------------------------------------------ optimizer
    def optimize(self, chain: Chain, specs: Sequence[tuple[str, ParamSpec]],
                 room: Room | None = None) -> tuple[Chain, Room, Score]:
        """Nelder-Mead over ``specs`` from their current values, in each prior's scale.

        ``specs`` are ``(stage, spec)``: an effect of ``chain``, or
        :data:`~radaraug.diagnosis.room.ROOM_STAGE` for a room parameter of ``room``. Returns the best
        chain and room evaluated and the fit score.
        """
        R = self.config.num_rx
        room = self.source.check_room(room)

        def build(us: list[float]) -> tuple[Chain, Room]:
            ch, rm = chain, dict(room)
            for (eff, sp), u in zip(specs, us):
                if eff == ROOM_STAGE:
                    rm[sp.name] = _from_unit(u, sp.prior)
                else:
                    ch = set_params(ch, eff, [sp], [_from_unit(u, sp.prior)], R)
            return ch, rm

        us = [_to_unit(room[sp.name] if eff == ROOM_STAGE else get_param(chain, eff, sp), sp.prior) for eff, sp in specs]
        lo = [_to_unit(sp.prior.lo, sp.prior) for _, sp in specs]
        hi = [_to_unit(sp.prior.hi, sp.prior) for _, sp in specs]
        cache: dict[tuple[float, ...], tuple[Score, Chain, Room]] = {}

        def f(u: list[float]) -> float:
            u = [min(max(v, a), b) for v, a, b in zip(u, lo, hi)]
            key = tuple(round(v, 9) for v in u)
            if key not in cache:
                ch, rm = build(u)
                cache[key] = (self.fit_score(ch, rm), ch, rm)
            return cache[key][0].overall

        nelder_mead(f, us, [(b - a) / 4 for a, b in zip(lo, hi)], lo, hi,
                    max_evals=self.settings.evals_per_param * len(specs) + 4)
        best, best_chain, best_room = min(cache.values(), key=lambda t: t[0].overall)
        return best_chain, best_room, best

    # ------------------------------------------------------------------ closed forms
    def dc_closed_form(self, chain: Chain, iterations: int = 2, room: Room | None = None) -> Chain:
        """Move each RX's DC level by the capture-minus-twin median ADC code."""
        if find(chain, "dc_offset") is None:
            return chain
        mid = ADC_QUANTILES.index(0.5)
        R = self.config.num_rx
        for _ in range(iterations):
            tv = self.fit_score(chain, room).twin
            d = (self.cap_fit["adc_histogram"][:, mid] - tv["adc_histogram"][:, mid]).tolist()
            cur = _as_list(require(chain, "dc_offset")["params"]["level_counts"], R)
            new = [min(max(c + di, 0.0), float(self.config.adc_full_scale_counts)) for c, di in zip(cur, d)]
            chain = with_effect(chain, "dc_offset", {"level_counts": new})
        return chain

    def base_specs(self, chain: Chain) -> list[tuple[str, ParamSpec]]:
        """The base parameters present in ``chain`` that the search refits, then the room's (stage ``ROOM_STAGE``)."""
        names = [("thermal_noise", "noise_figure_dB"), ("adc_noise", "rms_counts"), ("anti_alias_lowpass", "cutoff_Hz")]
        if self.source.mode == "scene":
            # With an estimated static scene the high-pass only shapes the thermal noise (weak at
            # low IF gain): left at the config's cutoff rather than bent to imitate something else.
            names += [("if_highpass", "cutoff_Hz"), ("system_gain", "gain_dB")]
        specs = []
        for eff, p in names:
            e = find(chain, eff)
            if e is None or e["params"].get(p) is None:
                continue
            prior = bounded(eff, p, EFFECTS[eff].priors(self.config)[p])  # what a radar engineer would sign
            if p == "cutoff_Hz":
                # A filter's cutoff is a config setting, known to a factor of 2 at worst; a wider
                # range lets the base bend its shape to imitate a local feature (a line, a bump).
                nominal = (self.config.effective_hp_cutoff_Hz if eff == "if_highpass"
                           else self.config.effective_aaf_cutoff_Hz)
                prior = Prior(max(nominal / 2, prior.lo), min(nominal * 2, prior.hi), "log")
            specs.append((eff, ParamSpec(p, prior)))
        specs += [(ROOM_STAGE, ParamSpec(p, ROOM_PRIORS[p])) for p in self.source.room_params]
        return specs

    def refit_base(self, chain: Chain, extra: Sequence[tuple[str, ParamSpec]] = (),
                   room: Room | None = None) -> tuple[Chain, Room]:
        """Refit the base stages present in ``chain``, the room and the DC offsets, with ``extra``.

        The base is the noise figure, anti-alias cutoff and ADC-side noise (plus high-pass cutoff and system
        gain in scene mode); ``extra`` are the just-added effect's parameters, which the base had imitated.
        """
        chain = self.dc_closed_form(chain, room=room)
        chain, room, _ = self.optimize(chain, self.base_specs(chain) + list(extra), room)
        chain = self.dc_closed_form(chain, iterations=1, room=room)
        return chain, room

    def uncertainty(self, chain: Chain, specs: Sequence[tuple[str, ParamSpec]], room: Room | None,
                    noise_db: float) -> dict[str, list[float] | None]:
        """A +-1 sigma interval per fitted parameter from the fit objective's curvature (two evaluations each).

        The objective's noise is the gap between the fitting and held-out errors (at least 0.01 dB); sigma is
        ``sqrt(2 noise / curvature)`` from a parabola through the optimum and two probes 2 % of the prior range
        away (a factor for log parameters). None where the views do not constrain the parameter.
        """
        R = self.config.num_rx
        f0 = self.fit_score(chain, room).overall
        delta = max(float(noise_db), 0.01)
        out: dict[str, list[float] | None] = {}
        for eff, sp in specs:
            lo, hi = _to_unit(sp.prior.lo, sp.prior), _to_unit(sp.prior.hi, sp.prior)
            # The fitted value lies inside the prior (the optimizer keeps it there).
            u = _to_unit(get_param(chain, eff, sp), sp.prior)
            h = 0.02 * (hi - lo)

            def at(uu: float, eff: str = eff, sp: ParamSpec = sp) -> float:
                return self.fit_score(set_params(chain, eff, [sp], [_from_unit(uu, sp.prior)], R), room).overall

            curv = (at(u + h) + at(u - h) - 2 * f0) / h**2
            label = sp.name if sp.index is None else f"{sp.name}[{sp.index}]"
            if not curv > 0:
                out[label] = None
                continue
            sig = math.sqrt(2 * delta / curv)
            a, b = max(u - sig, lo), min(u + sig, hi)
            out[label] = [_from_unit(a, sp.prior), _from_unit(b, sp.prior)]
        return out

    # ------------------------------------------------------------------ signature-led steps
    def _signature_steps(self, chain: Chain, room: Room, held: Score, ev: Mapping[str, Any],
                         steps: list[dict[str, Any]], added: set[str]) -> tuple[Chain, Room, Score]:
        """Effects the chain already holds whose signature departs from the declaration.

        ``if_highpass`` takes the detected cutoff and order and the base is refitted (kept unless the
        held-out error rises by more than ``min_gain_db``); ``adc_clipping`` is reported from its
        signature, in estimated mode with the gain before the ADC refitted (:meth:`_clipping_gain`);
        in estimated mode ``tx_rx_leakage`` is reported from its signature.
        """
        hp = ev.get("if_highpass")
        if hp is not None and hp.present and find(chain, "if_highpass") is not None:
            p = hp.capture.params
            order = int(round(float(p["order"])))
            # The signature's cutoff is the -3 dB point of a Butterworth fit; the twin's stage is
            # ``order`` cascaded first-order sections, each with its own (lower) cutoff.
            declared = require(chain, "if_highpass")["params"]
            start = {**declared, "cutoff_Hz": section_cutoff(float(p["cutoff_Hz"]), order), "order": order}
            cand = with_effect(chain, "if_highpass", start)
            prior = EFFECTS["if_highpass"].priors(self.config)["cutoff_Hz"]
            # The floor's shape measures the cutoff to a few per cent (closed-form tests: 5 %); the
            # nine views would trade it for the noise figure and gain, so it moves +-20 % at most.
            lo, hi = max(prior.lo, start["cutoff_Hz"] / HP_REFIT_SPAN), min(prior.hi, start["cutoff_Hz"] * HP_REFIT_SPAN)
            extra = [("if_highpass", ParamSpec("cutoff_Hz", Prior(min(lo, hi * 0.99), hi, "log")))]
            fitted, fitted_room = self.refit_base(cand, extra, room=room)
            new_held = self.held_score(fitted, fitted_room)
            keep = new_held.overall <= held.overall + self.settings.min_gain_db
            # A declared stage at other parameters: the report gives them before and after (the
            # signature's reading where the views could not tell the refit apart: not in the profile).
            steps.append(_step("if_highpass", True, require(fitted, "if_highpass")["params"] if keep else start, held,
                               new_held if keep else held, "clear" if keep else "signature only", hp.reason,
                               source="signature", params_before=dict(declared)))
            self.progress(f"refit if_highpass from its signature ({hp.reason}): held-out {held.overall:.3f} -> "
                          f"{new_held.overall:.3f} dB{'' if keep else ' (not kept)'}")
            added.add("if_highpass")
            if keep:
                chain, room, held = fitted, fitted_room, new_held
        clip = ev.get("adc_clipping")
        if clip is not None and clip.present and self.source.mode == "estimated" \
                and find(chain, "system_gain") is not None:
            chain, room, held = self._clipping_gain(chain, room, held, clip, steps)
            added.add("adc_clipping")
        reported = [("adc_clipping", "always in the chain: the capture's ADC sits at its rails"),
                    ("tx_rx_leakage", "estimated mode: the static scene copies the capture's leakage")]
        for name, why in reported:
            e = ev.get(name)
            if e is None or not e.present or name in added:
                continue
            if name == "tx_rx_leakage" and self.source.mode != "estimated":
                continue  # scene mode: the catalog's leakage candidate fits it
            steps.append(_step(name, True, dict(e.capture.params), held, held, "signature only", e.reason,
                               source="signature", note=why))
            self.progress(f"{name}: {e.reason} ({why})")
            added.add(name)
        return chain, room, held

    def _clipping_gain(self, chain: Chain, room: Room, held: Score, clip: Any,
                       steps: list[dict[str, Any]]) -> tuple[Chain, Room, Score]:
        """A clipping capture: refit the gain before the ADC with the base, kept if the held-out error falls.

        Too much gain (or too small an ADC range) lifts the thermal noise over the ADC's own noise and
        drives the strong part into the rails. In estimated mode the static scene follows the capture
        whatever the gain, so the gain moves only the noise's share: the base refit alone cannot reach
        it within its physical bounds. A rail hit by a strong near return instead leaves the gain where
        it is (the step stays a report of the signature).
        """
        declared = float(require(chain, "system_gain")["params"]["gain_dB"])
        prior = EFFECTS["system_gain"].priors(self.config)["gain_dB"]
        fitted, fitted_room = self.refit_base(chain, [("system_gain", ParamSpec("gain_dB", prior))], room=room)
        new_held = self.held_score(fitted, fitted_room)
        gain = float(require(fitted, "system_gain")["params"]["gain_dB"])
        keep = new_held.overall < held.overall - self.settings.min_gain_db
        at_bound = min(gain - prior.lo, prior.hi - gain) <= 0.02 * (prior.hi - prior.lo)
        why = (f"gain before the ADC {gain - declared:+.1f} dB over the declared chain: noise and returns reach "
               "the rails" + (" (at the prior's bound: the capture asks for more)" if at_bound else "")
               if keep else "always in the chain: the capture's ADC sits at its rails")
        moved = {"params_before": {"gain_dB": declared}} if keep else {}
        steps.append(_step("adc_clipping", True, {**clip.capture.params, "gain_dB": gain if keep else declared},
                           held, new_held if keep else held, "clear" if keep else "signature only", clip.reason,
                           source="signature", note=why, **moved))
        self.progress(f"adc_clipping: {clip.reason}; {why}: held-out {held.overall:.3f} -> "
                      f"{(new_held if keep else held).overall:.3f} dB")
        return (fitted, fitted_room, new_held) if keep else (chain, room, held)

    # ------------------------------------------------------------------ the loop
    def _context(self, chain: Chain, twin_views: Views, room: Room | None = None) -> Context:
        return Context(self.config, self.source.mode, chain, self.cap_fit, twin_views,
                       probe=lambda ch: self.fit_score(ch, room).twin, measured=self._measured)

    def run(self, chain: Chain, room: Room | None = None, evidence: Mapping[str, Any] | None = None) -> SearchResult:
        """Refit the base, then add effects while they improve the held-out error.

        Args:
            chain: the declared chain to start from.
            room: the room parameters to start from (default: as the source traced them).
            evidence: :func:`radaraug.diagnosis.evidence.assess` of the capture (None: every
                candidate may be added, by the error alone).
        """
        st = self.settings
        room_before = self.source.check_room(room)
        before = self.held_score(chain, room_before)
        self.progress(f"twin as given: held-out error {before.overall:.3f} dB")
        base_chain, base_room = self.refit_base(chain, room=room_before)
        base = self.held_score(base_chain, base_room)
        fitted_room = "".join(f", {k} {v:.2f}" for k, v in base_room.items())
        self.progress(f"base chain refitted: held-out error {base.overall:.3f} dB{fitted_room}")
        current, cur_room, cur_held = base_chain, base_room, base
        steps: list[dict[str, Any]] = []
        tried: list[dict[str, Any]] = []
        added: set[str] = set()
        own_specs: dict[str, list[tuple[str, ParamSpec]]] = {}  # each search step's own parameters
        ev = dict(evidence or {})
        self._measured = {k: dict(e.capture.params) for k, e in ev.items() if e.present}
        if ev:
            current, cur_room, cur_held = self._signature_steps(current, cur_room, cur_held, ev, steps, added)

        def signature(name: str) -> bool | None:
            """Whether ``name``'s signature is present (None: ``name`` has no detector)."""
            return bool(ev[name].present) if name in ev else None

        for _ in range(st.max_steps):
            fit_now = self.fit_score(current, cur_room)
            ctx = self._context(current, fit_now.twin, cur_room)
            screened = []
            for cand in catalog():
                if self.source.mode not in cand.modes or cand.name in added or signature(cand.name) is False:
                    continue
                if ev and cand.name in BASE_STAGES and find(current, cand.name) is not None:
                    # A base stage the chain holds is refitted with the base, not named as an effect.
                    continue
                # Screen the candidate's starts with the room fixed; the first of equal scores wins.
                starts = [with_effect(current, cand.name, start) for start in cand.starts(ctx)]
                best = min(((self.fit_score(ch, cur_room).overall, ch) for ch in starts), key=lambda t: t[0],
                           default=None)
                if best is not None and best[0] < fit_now.overall:
                    screened.append((best[0], cand, best[1]))
            screened.sort(key=lambda t: t[0])
            results = []
            for _, cand, ch in screened[: st.screen_top]:
                start = require(ch, cand.name)["params"]
                specs = [(cand.name, sp) for sp in cand.specs(ctx, start)]
                joint = set(cand.joint)
                if signature(cand.name):
                    # Its signature says it is there: the base noise, bent to imitate it by the base
                    # refit, is fitted jointly with it (not instead of it).
                    joint |= {("thermal_noise", "noise_figure_dB"), ("adc_noise", "rms_counts")}
                specs += [(e, sp) for e, sp in self.base_specs(ch) if (e, sp.name) in joint]
                fitted, _, fit_sc = self.optimize(ch, specs, cur_room)
                fitted = self.dc_closed_form(fitted, iterations=1, room=cur_room)
                held = self.held_score(fitted, cur_room)
                # The candidate's own parameters (the joint base ones are refitted anyway).
                results.append((held, cand, fitted, fit_sc, [(e, sp) for e, sp in specs if e == cand.name]))
                tried.append({"step": len(steps) + 1, "effect": cand.name, "fit_error": round(fit_sc.overall, 4),
                              "held_out_error": round(held.overall, 4)})
            if not results:
                break

            def penalized(r: tuple[Score, Candidate, Chain, Score, list[tuple[str, ParamSpec]]]) -> float:
                return r[0].overall + st.per_param_db * len(r[4])

            results.sort(key=penalized)
            held, cand, fitted, fit_sc, own = results[0]
            gain = cur_held.overall - held.overall
            k = len(own)
            backed = bool(signature(cand.name))
            need = (st.min_gain_db if backed else max(st.min_gain_db, st.min_gain_rel * cur_held.overall)) \
                + st.per_param_db * k
            if gain < need:
                self.progress(f"best candidate {cand.name} gains {gain:.3f} dB < {need:.3f} dB: stop")
                break
            band = max(st.ambiguity_db, st.ambiguity_rel * gain)
            alternatives = [{"effect": r[1].name, "held_out_error": round(r[0].overall, 4),
                             "penalized_error": round(penalized(r), 4), "params_fitted": len(r[4]),
                             "signature": signature(r[1].name)}
                            for r in results[1:]]
            best_pen = penalized(results[0])
            close = [r[1].name for r in results[1:] if penalized(r) - best_pen <= band]
            refit = find(current, cand.name) is not None
            steps.append(_step(
                cand.name, refit, require(fitted, cand.name)["params"], cur_held, held,
                "ambiguous" if close else "clear", None if cand.name not in ev else ev[cand.name].reason,
                ambiguous_with=close, alternatives=alternatives, params_fitted=k,
                uncertainty=self.uncertainty(fitted, own, cur_room, abs(held.overall - fit_sc.overall)),
                # The detector's own estimate beside the fit: two independent readings of one effect.
                signature_params=None if cand.name not in ev else {
                    k: round(float(v), 6) for k, v in ev[cand.name].capture.params.items()}))
            self.progress(f"{'refit' if refit else 'add'} {cand.name}: held-out {cur_held.overall:.3f} -> "
                          f"{held.overall:.3f} dB")
            added.add(cand.name)
            current, cur_held = fitted, held
            # The base was bent to imitate the new stage before it existed (a higher floor, a lower
            # anti-alias cutoff...): refit the base together with the new stage's parameters. So were
            # the effects added before it (phase noise raising the floor that bursts raise): then a
            # second refit adds the earlier steps' parameters. Each is kept only when the held-out
            # error does not get worse.
            earlier = [spec for specs_of in own_specs.values() for spec in specs_of]
            own_specs[cand.name] = own
            for extra in (own, own + earlier) if earlier else (own,):
                rebased, rebased_room = self.refit_base(current, extra, room=cur_room)
                rebased_held = self.held_score(rebased, rebased_room)
                if rebased_held.overall <= cur_held.overall:
                    current, cur_room, cur_held = rebased, rebased_room, rebased_held
                    steps[-1]["error_after_base_refit"] = round(rebased_held.overall, 4)
                    steps[-1]["params"] = require(current, cand.name)["params"]
                    for prev in own_specs:  # the earlier steps' parameters as the joint refit left them
                        first = next(step for step in steps if step["effect"] == prev)
                        first["params"] = require(current, prev)["params"]
                    if cur_room:
                        steps[-1]["room_after_base_refit"] = dict(cur_room)
        for name, e in ev.items():
            if e.present and name not in added:
                # Named by its signature even though no fit beat the margin: the report says both.
                steps.append(_step(
                    name, find(current, name) is not None, dict(e.capture.params), cur_held, cur_held,
                    "signature only", e.reason, source="signature",
                    note="its signature is present, but fitting it did not lower the held-out error by the margin"))
                self.progress(f"{name}: signature present ({e.reason}); no fit beat the margin")
        return SearchResult(chain, base_chain, current, before, base, cur_held, steps, tried, self.evaluations,
                            room_before, base_room, cur_room)


def _to_unit(v: float, prior: Prior) -> float:
    """``v``, clipped to ``prior``, on the scale the search moves it on (log10 for a log prior)."""
    v = min(max(v, prior.lo), prior.hi)
    return math.log10(v) if prior.scale == "log" else v


def _from_unit(u: float, prior: Prior) -> float:
    """The inverse of :func:`_to_unit`."""
    return 10**u if prior.scale == "log" else u


def _rounded(views: dict[str, float]) -> dict[str, float]:
    return {k: round(v, 4) for k, v in views.items()}


def _step(name: str, refit: bool, params: dict[str, Any], before: Score, after: Score, verdict: str,
          signature: str | None, **extra: Any) -> dict[str, Any]:
    """One step of the report: an effect added, refitted or named (``extra``: the keys only some steps have).

    An effect named from its signature has ``source="signature"`` and no alternatives.
    """
    return {"effect": name, "refit": refit, "params": params, "signature": signature, "verdict": verdict,
            "ambiguous_with": [], "alternatives": [], **extra,
            "error_before": round(before.overall, 4), "error_after": round(after.overall, 4),
            "views_before": _rounded(before.views), "views_after": _rounded(after.views)}


def nelder_mead(f: Callable[[list[float]], float], x0: Sequence[float], step: Sequence[float],
                lo: Sequence[float], hi: Sequence[float], max_evals: int) -> tuple[list[float], float]:
    """Minimize ``f`` from ``x0`` with SciPy's bounded Nelder-Mead simplex in ``[lo, hi]``.

    The first simplex is ``x0`` plus one ``step`` along each axis (away from a bound it would cross);
    at most ``max_evals`` evaluations.
    """
    import numpy as np
    from scipy.optimize import minimize

    x = np.clip(np.asarray(x0, dtype=float), lo, hi)
    simplex = [x.copy()]
    for i in range(len(x)):
        p = x.copy()
        p[i] = p[i] + step[i] if p[i] + step[i] <= hi[i] else p[i] - step[i]
        simplex.append(np.clip(p, lo, hi))
    res = minimize(lambda u: f([float(v) for v in u]), x, method="Nelder-Mead", bounds=list(zip(lo, hi)),
                   options={"initial_simplex": np.stack(simplex), "maxfev": int(max_evals), "xatol": 1e-9,
                            "fatol": 1e-9})
    return [float(v) for v in res.x], float(res.fun)
