"""Which simulated twin items carry labels the radar cannot observe (an analysis, not part of the library)?

Simulates items of the training twin exactly as ``radaraug reproduce --quick`` does for its RT /
RandomDR runs (the corridor scene, ``RadarConfig.bgt60tr13c()``, default ``TwinRandomization()``,
default receiver, twin seed (``data.twin.seed``) 0, one frame per item, ``rd_db_chain()``), and looks at each item's
floor-relative map as the network's level chain makes it (``level_chain("floor_relative", excise)``:
RX mean power, each range row minus its Doppler median, zero Doppler +-1 bin blanked, and the
persistent cells of the independent held-out set's empty-room capture excised, as the quick run does).

Per item the statistic is the *peak excess*: the largest cell of that map outside the blanked
zero-Doppler bins and outside the first ``--skip-range-bins`` range bins (TX/RX leakage), in dB above
its row's median. Each item is simulated

* ``on``: as the training set has it (the effect catalog on);
* ``off``: the same item with ``effects_probability=0`` (bit for bit the item without the catalog);
* ``self_excised``: ``on``, with the cells that persist over ``--mask-frames`` frames of the *item's
  own* empty room (same draw and catalog effects, no people) also excised: what a calibration
  capture recorded with the same spur / fan would let the excision remove;
* empty items only: with each catalog effect it carries alone (``only:NAME``) and left out
  (``without:NAME``), to attribute the empty items that look occupied.

Writes one JSON (settings, per-item records, summaries). Run with the repository's environment::

    python scripts/twin_observability.py --items 600 --seed 0 --out twin_observability.json
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import statistics
import tempfile
import time
from collections import Counter, defaultdict
from typing import Any

import torch
from tqdm import tqdm

from radaraug.config import RadarConfig
from radaraug.sim.catalog import BY_NAME as CATALOG_BY_NAME
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.randomization import ItemDraw, TwinRandomization
from radaraug.sim.seeding import Stream, item_generator
from radaraug.training.pipeline import level_chain, rd_db_chain
from radaraug.transforms import functional as F

SHORT = {"spur_tone": "spur", "interference": "interf", "vibrating_clutter": "vib", "rx_gain_phase_mismatch": "rxmm",
         "frame_drift": "drift", "wide_levels": "wide", "static_phase_noise": "spn"}
#: effects that can put energy off zero Doppler in an empty room (the others only change levels)
OFF_DOPPLER_EFFECTS = ("spur_tone", "interference", "vibrating_clutter")
PERSON_RANGE_WINDOW = 2  # range bins either side of a person's centre searched for their own excess
NULL_WINDOW_BINS = (8, 20, 35, 50, 65, 80)  # empty items: person windows at these range bins (1.4-13.8 m)


# ----------------------------------------------------------------------------- helpers
def quick_calibration_excise(threshold_db: float) -> tuple[torch.Tensor, dict[str, Any]]:
    """The quick run's excision mask: persistent cells of the independent set's empty-room capture."""
    from radaraug.diagnosis.record import persistent_cells_of
    from radaraug.testsets.independent import make_independent_set

    with tempfile.TemporaryDirectory() as tmp:
        # Same generator, seed (2024) and 40 calibration frames as reproduce's "independent" test set;
        # the calibration capture does not depend on the test files' counts or lengths.
        proxy = make_independent_set(tmp, frames_per_count=1, counts=(0,), progress=False)
        mask = persistent_cells_of(str(proxy.calibration), threshold_db, rd_db_chain())
    return mask, {"source": "independent held-out set, seed 2024, 40 frames", "threshold_db": threshold_db,
                  "cells": int(mask.sum())}


def with_fields(base: ItemDraw, source: ItemDraw, effects: list[str]) -> ItemDraw:
    """``base`` with the catalog draws of ``effects`` taken from ``source`` (the wide levels' offsets too)."""
    catalog = {n: v for n, v in base.catalog.items() if n not in effects}
    catalog.update({n: source.catalog[n] for n in effects if n in source.catalog})
    kw: dict[str, Any] = {"catalog": catalog}
    if "wide_levels" in effects:
        kw.update(system_gain_offset_dB=source.system_gain_offset_dB,
                  noise_figure_offset_dB=source.noise_figure_offset_dB)
    return dataclasses.replace(base, **kw)


def best_balanced_accuracy(neg: list[float], pos: list[float]) -> dict[str, float]:
    """Best ``value > t`` -> positive balanced accuracy over every threshold, and its threshold."""
    if not neg or not pos:
        return {"balanced_accuracy": float("nan"), "threshold_db": float("nan")}
    vals = sorted(set(neg + pos))
    cands = [vals[0] - 1.0] + [(a + b) / 2 for a, b in zip(vals, vals[1:])] + [vals[-1] + 1.0]
    best = (-1.0, 0.0)
    for t in cands:
        tnr = sum(v <= t for v in neg) / len(neg)
        tpr = sum(v > t for v in pos) / len(pos)
        best = max(best, ((tnr + tpr) / 2, t))
    return {"balanced_accuracy": round(best[0], 4), "threshold_db": round(best[1], 2)}


def quantiles(values: list[float]) -> dict[str, float]:
    """n, min, p10, median, p90, max (rounded)."""
    if not values:
        return {"n": 0}
    v = sorted(values)
    q = lambda p: v[min(len(v) - 1, max(0, round(p * (len(v) - 1))))]  # noqa: E731
    return {"n": len(v), "min": round(v[0], 2), "p10": round(q(0.1), 2), "median": round(q(0.5), 2),
            "p90": round(q(0.9), 2), "max": round(v[-1], 2)}


def frac(values: list[bool]) -> float | None:
    """Share of true values (None when empty)."""
    return round(sum(values) / len(values), 4) if values else None


class Analyzer:
    """The quick run's twin (catalog on and off) and the per-item measurements."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.config = RadarConfig.bgt60tr13c()
        n = args.start + args.items
        self.rz_on = TwinRandomization()
        self.rz_off = TwinRandomization(catalog={"scale": 0.0})
        self.ds_on = SimulatedRadarDataset("corridor", length=n, seed=args.seed, config=self.config, target="count",
                                           randomization=self.rz_on)
        self.ds_off = SimulatedRadarDataset("corridor", length=n, seed=args.seed, config=self.config, target="count",
                                            randomization=self.rz_off)
        self.chain = rd_db_chain()
        if args.no_calibration_excise:
            self.train_excise, self.excise_info = None, None
        else:
            self.train_excise, self.excise_info = quick_calibration_excise(args.excise_db)
        self.level = level_chain("floor_relative", self.train_excise)
        self.n_range, self.n_dopp = self.config.num_range_bins, self.config.num_chirps_per_frame
        self.centre = self.n_dopp // 2
        self.range_res = float(self.config.range_resolution_m)
        self.v_res = float(self.config.velocity_resolution_m_s)
        valid = torch.ones(self.n_range, self.n_dopp, dtype=torch.bool)
        valid[: args.skip_range_bins] = False
        valid[:, self.centre - 1: self.centre + 2] = False  # blanked by the level chain anyway
        self.valid = valid

    # -- simulation ---------------------------------------------------------------------
    def simulate(self, ds: SimulatedRadarDataset, index: int, draw: ItemDraw, people: list[Any] | None,
                 frames: int = 1, noise_stream: int | None = None) -> torch.Tensor:
        """Raw frames of item ``index`` under ``draw`` (its dataset's noise generator for one frame)."""
        twin = ds.variant_twin(draw.variant)
        times = twin.frame_times(range(frames))
        if noise_stream is None:
            gens: Any = item_generator(ds.seed, index, stream=Stream.ITEM_NOISE)
        else:  # per-frame generators of a side stream (the item's own empty-room "calibration")
            gens = [torch.Generator().manual_seed(((noise_stream * 1_000_003 + ds.seed) * 1_000_033 + index) * 97 + k)
                    for k in range(frames)]
        return twin.simulate(people or [], times, generators=gens, draw=draw)

    def level_map(self, raw: torch.Tensor, extra_excise: torch.Tensor | None = None) -> torch.Tensor:
        """``(rx, chirps, samples)`` raw frame -> floor-relative ``(range, doppler)`` map (the network's levels)."""
        fr = self.level(self.chain(raw)[None])[0, 0]
        if extra_excise is not None:
            fr = fr.masked_fill(extra_excise, 0.0)
        return fr

    def own_empty_mask(self, index: int, draw: ItemDraw) -> torch.Tensor:
        """Cells persistent over ``mask_frames`` frames of the item's own empty room (same catalog draw)."""
        empty = dataclasses.replace(draw, rcs_scale_dB=())
        raw = self.simulate(self.ds_on, index, empty, None, frames=self.args.mask_frames, noise_stream=7)
        db = F.combine_rx(self.chain(raw), db=True)[:, 0]  # (frames, range, doppler)
        return F.persistent_cells(db, self.args.excise_db)

    # -- statistics ---------------------------------------------------------------------
    def peak(self, fr: torch.Tensor) -> dict[str, Any]:
        """The peak excess of a floor-relative map, where it lies, its Doppler mirror and its spread."""
        m = fr.masked_fill(~self.valid, -math.inf)
        flat = int(torch.argmax(m))
        r, d = divmod(flat, self.n_dopp)
        mirror_d = 2 * self.centre - d
        mirror = float(fr[r, mirror_d]) if 0 <= mirror_d < self.n_dopp else None
        wide = m.clone()
        wide[:, self.centre - 2: self.centre + 3] = -math.inf  # zero Doppler +-2 bins left out
        return {"excess_db": round(float(m[r, d]), 2), "excess_blank2_db": round(float(wide.max()), 2),
                "range_bin": r, "range_m": round(r * self.range_res, 2),
                "doppler_offset_bins": d - self.centre, "velocity_m_s": round((d - self.centre) * self.v_res, 3),
                "mirror_excess_db": None if mirror is None else round(mirror, 2),
                "cells_over_10db": int((m > 10).sum()), "cells_over_17db": int((m > 17).sum())}

    def person_excess(self, fr: torch.Tensor, range_bin: int) -> float:
        """The peak excess within +-PERSON_RANGE_WINDOW range bins of ``range_bin``."""
        lo = max(self.args.skip_range_bins, range_bin - PERSON_RANGE_WINDOW)
        hi = min(self.n_range, range_bin + PERSON_RANGE_WINDOW + 1)
        if lo >= hi:
            return float("nan")
        m = fr.masked_fill(~self.valid, -math.inf)[lo:hi]
        return round(float(m.max()), 2)

    def geometry(self, index: int, scenario: Any, draw: ItemDraw) -> list[dict[str, Any]]:
        """Each person at the frame's start: slant range, radial velocity, angle off boresight."""
        radar = self.ds_on.variant_twin(draw.variant).scene.radar
        pos = radar.position.detach().to(torch.float64).cpu()
        bore = radar.rotation.detach().to(torch.float64).cpu()[:, 2]
        out = []
        t0 = torch.zeros(1, dtype=torch.float64)
        for person in scenario.people:
            e = person.ellipsoids(t0)
            c = e.centers.reshape(-1, 3).to(torch.float64).mean(0)
            v = e.velocities.reshape(-1, 3).to(torch.float64).mean(0)
            los = c - pos
            rng = float(los.norm())
            u = los / rng
            off = math.degrees(math.acos(max(-1.0, min(1.0, float(u @ bore)))))
            out.append({"slant_range_m": round(rng, 3), "range_bin": int(round(rng / self.range_res)),
                        "radial_velocity_m_s": round(float(v @ u), 3),
                        "doppler_bin": int(round(float(v @ u) / self.v_res)),
                        "off_boresight_deg": round(off, 1),
                        "two_way_pattern_dB": round(20 * math.log10(max(math.cos(math.radians(off)), 1e-3)), 1)})
        return out

    # -- one item -------------------------------------------------------------------------
    def item(self, index: int) -> dict[str, Any]:
        """Every measurement of item ``index`` (JSON-able)."""
        p = self.ds_on.item_params(index)
        scenario = self.ds_on.scenario(index)
        count = scenario.count
        draw_on = self.rz_on.item(self.ds_on.seed, index, count)
        draw_off = self.rz_off.item(self.ds_off.seed, index, count)
        effects = sorted(p["effects"])
        rec: dict[str, Any] = {
            "index": index, "count": count, "effects": effects,
            "effect_params": {k: v for k, v in p["effects"].items() if k != "rx_gain_phase_mismatch"},
            "system_gain_offset_dB": round(draw_on.system_gain_offset_dB, 2),
            "noise_figure_offset_dB": round(draw_on.noise_figure_offset_dB, 2),
            "phase_noise_rms_Hz": round(float(draw_on.phase_noise_rms_Hz or 0.0)),
            "static_scatterers": len(draw_on.scatterers),
            "room_length_m": round(p["room"]["length_m"], 2),
        }
        geo = self.geometry(index, scenario, draw_on)
        people = []
        for prm, g, rcs in zip(p["people"], geo, draw_on.rcs_scale_dB):
            people.append({"range_m": round(prm["range_m"], 3), "lateral_m": round(prm["lateral_m"], 3),
                           "speed_m_s": round(prm["speed_m_s"], 3), "toward": bool(prm["toward"]),
                           "rcs_scale_dB": round(rcs, 2), **g})
        rec["people"] = people

        fr_on = self.level_map(self.simulate(self.ds_on, index, draw_on, scenario.people)[0])
        fr_off = self.level_map(self.simulate(self.ds_off, index, draw_off, scenario.people)[0])
        own = self.own_empty_mask(index, draw_on) if any(e in effects for e in OFF_DOPPLER_EFFECTS) else None
        fr_self = fr_on if own is None else fr_on.masked_fill(own, 0.0)
        rec["on"], rec["off"], rec["self_excised"] = self.peak(fr_on), self.peak(fr_off), self.peak(fr_self)
        rec["self_excised"]["own_mask_cells"] = 0 if own is None else int(own.sum())
        for key, fr in (("on", fr_on), ("off", fr_off), ("self_excised", fr_self)):
            for person in people:
                person[f"excess_{key}_db"] = self.person_excess(fr, person["range_bin"])

        if count == 0:  # the person-window statistic of an empty room: its null distribution
            rec["window_null_off"] = [self.person_excess(fr_off, b) for b in NULL_WINDOW_BINS]
            rec["window_null_on"] = [self.person_excess(fr_on, b) for b in NULL_WINDOW_BINS]
        # attribution: each off-Doppler-capable catalog effect alone / left out (empty items only: cheap)
        if count == 0:
            only, only_blank2, without = {}, {}, {}
            for e in effects:
                d_only = with_fields(draw_off, draw_on, [e])
                d_wo = with_fields(draw_on, draw_off, [e])
                alone = self.peak(self.level_map(self.simulate(self.ds_on, index, d_only, None)[0]))
                only[e], only_blank2[e] = alone["excess_db"], alone["excess_blank2_db"]
                without[e] = self.peak(self.level_map(self.simulate(self.ds_on, index, d_wo, None)[0]))["excess_db"]
            rec["only"], rec["only_blank2"], rec["without"] = only, only_blank2, without
            spur, vib = draw_on.catalog.get("spur_tone"), draw_on.catalog.get("vibrating_clutter")
            rec["spur_range_bin"] = None if spur is None else int(round(spur["freq_nyquist"] * self.n_range))
            rec["vib_range_bin"] = None if vib is None else int(round(vib["range_m"] / self.range_res))
        return rec

    def check_reproduces(self, index: int) -> bool:
        """The script's simulation of item ``index`` equals the dataset's own item (bit for bit)."""
        scenario = self.ds_on.scenario(index)
        draw = self.rz_on.item(self.ds_on.seed, index, scenario.count)
        mine = self.simulate(self.ds_on, index, draw, scenario.people)[0]
        theirs, _ = self.ds_on[index]
        return bool(torch.equal(mine, theirs))


# ----------------------------------------------------------------------------- summaries
def effect_group(rec: dict[str, Any]) -> str:
    """The item's off-Doppler-capable catalog effects, e.g. ``vib+spur`` (``none``: none of them)."""
    on = [SHORT[e] for e in OFF_DOPPLER_EFFECTS if e in rec["effects"]]
    return "+".join(on) if on else "none"


def summarize(records: list[dict[str, Any]]) -> dict[str, Any]:
    """The numbers the findings quote, from the per-item records."""
    S: dict[str, Any] = {}
    empty = [r for r in records if r["count"] == 0]
    occ = [r for r in records if r["count"] > 0]
    S["counts"] = dict(sorted(Counter(r["count"] for r in records).items()))
    variants = ("on", "off", "self_excised")

    # ---- 1. empty items: distribution, by effect, attribution
    thr = {}
    for v in variants:
        ev = [r[v]["excess_db"] for r in empty]
        qs = quantiles(ev)
        thr[v] = {"empty_median_db": qs.get("median"), "empty_p90_db": qs.get("p90")}
        S[f"empty_peak_{v}"] = {**qs, "frac_over_17db": frac([x > 17 for x in ev]),
                                "frac_over_20db": frac([x > 20 for x in ev]),
                                "frac_over_17db_blank2": frac([r[v]["excess_blank2_db"] > 17 for r in empty])}
    S["thresholds_from_empty"] = thr
    groups: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in empty:
        groups[effect_group(r)].append(r)
    S["empty_by_effect_group"] = {
        g: {**quantiles([r["on"]["excess_db"] for r in rs]), "frac_over_17db": frac([r["on"]["excess_db"] > 17 for r in rs]),
            "off_median": quantiles([r["off"]["excess_db"] for r in rs]).get("median"),
            "self_excised_frac_over_17db": frac([r["self_excised"]["excess_db"] > 17 for r in rs])}
        for g, rs in sorted(groups.items(), key=lambda kv: -len(kv[1]))}
    per_effect = {}
    for e in CATALOG_BY_NAME:
        has = [r for r in empty if e in r["effects"]]
        only = [r["only"][e] for r in has]
        without = [r["without"][e] for r in has]
        per_effect[e] = {"n_with": len(has),
                         "frac_over_17db_with": frac([r["on"]["excess_db"] > 17 for r in has]),
                         "only_this_effect": {**quantiles(only), "frac_over_17db": frac([x > 17 for x in only])},
                         "all_but_this_effect": {**quantiles(without), "frac_over_17db": frac([x > 17 for x in without])}}
    S["empty_per_effect"] = per_effect
    loud = [r for r in empty if r["on"]["excess_db"] > 17]
    alone: Counter[str] = Counter()
    for r in loud:
        names = [SHORT[e] for e in r["effects"] if r["only"][e] > 17]
        alone["+".join(names) if names else "none alone (baseline or combination)"] += 1
    S["loud_empty_items"] = {
        "n": len(loud), "frac_of_empty": frac([r in loud for r in empty]),
        "effects_loud_alone": dict(alone.most_common()),
        "fixed_by_removing": dict(Counter("+".join(SHORT[e] for e in r["effects"] if r["without"][e] <= 17) or "nothing"
                                          for r in loud).most_common()),
        "abs_doppler_offset_bins": dict(sorted(Counter(abs(r["on"]["doppler_offset_bins"]) for r in loud).items())),
        "peak_at_vibrating_clutter_range_pm2": frac([r["vib_range_bin"] is not None
                                                     and abs(r["on"]["range_bin"] - r["vib_range_bin"]) <= 2 for r in loud]),
        "peak_at_spur_range_pm2": frac([r["spur_range_bin"] is not None
                                        and abs(r["on"]["range_bin"] - r["spur_range_bin"]) <= 2 for r in loud]),
        "self_excised_still_over_17db": frac([r["self_excised"]["excess_db"] > 17 for r in loud]),
        "blank2_still_over_17db": frac([r["on"]["excess_blank2_db"] > 17 for r in loud]),
    }
    for name, key in (("spur_tone", "spur_loud_alone"), ("vibrating_clutter", "vib_loud_alone")):
        sel = [r for r in loud if r["only"].get(name, 0) > 17]
        S["loud_empty_items"][key] = {
            "n": len(sel), "abs_doppler_offset_bins": quantiles([abs(r["on"]["doppler_offset_bins"]) for r in sel]),
            "peak_minus_mirror_db": quantiles([r["on"]["excess_db"] - r["on"]["mirror_excess_db"] for r in sel
                                               if r["on"]["mirror_excess_db"] is not None]),
            "cells_over_10db": quantiles([r["on"]["cells_over_10db"] for r in sel])}
    vib_all = [r for r in empty if "vibrating_clutter" in r["effects"]]
    vflag = lambda r: r["only"]["vibrating_clutter"] > 17  # noqa: E731
    vp = lambda r, k: r["effect_params"]["vibrating_clutter"][k]  # noqa: E731
    S["vibrating_clutter_empty"] = {
        "note": "frac = share of empty items whose peak with this effect alone exceeds 17 dB",
        "by_hz": _binned(vib_all, lambda r: vp(r, "vibration_Hz"), [5, 10, 20, 40, 60], vflag),
        "by_displacement_mm": _binned(vib_all, lambda r: 1e3 * vp(r, "displacement_m"), [0.1, 0.3, 1.0, 3.0], vflag),
        "by_doppler_extent_hz": _binned(vib_all, lambda r: _beta(r) * vp(r, "vibration_Hz"),
                                        [0, 10, 20, 40, 80, 400], vflag),
        "by_rcs_minus_40logR_db": _binned(vib_all, lambda r: vp(r, "rcs_dBsm") - 40 * math.log10(vp(r, "range_m")),
                                          [-60, -30, -20, -10, 0, 20], vflag),
        "gentle_draws": {
            "rule": "Doppler extent (4 pi d / lambda) f_v < 20 Hz and rcs_dBsm - 40 log10(range_m) < -30 dB",
            **_binned([r for r in vib_all if _vib_gentle(r)], lambda r: 0.0, [-1.0, 1.0], vflag)["[-1,1)"],
            "others": _binned([r for r in vib_all if not _vib_gentle(r)], lambda r: 0.0, [-1.0, 1.0], vflag)["[-1,1)"]},
        "alone_frac_over_17db": frac([vflag(r) for r in vib_all]),
        "alone_blank2_frac_over_17db": frac([r["only_blank2"]["vibrating_clutter"] > 17 for r in vib_all]),
        "self_excised_frac_over_17db": frac([r["self_excised"]["excess_db"] > 17 for r in vib_all]),
    }
    spur_all = [r for r in empty if "spur_tone" in r["effects"]]
    amp_db = [(20 * math.log10(r["effect_params"]["spur_tone"]["amplitude_counts"]), r["only"]["spur_tone"])
              for r in spur_all]
    slope, icpt = _line(amp_db)
    S["spur_tone_empty"] = {
        "alone_peak_fit": {"db_per_db": round(slope, 3), "peak_db_at_1_count": round(icpt, 2),
                           "amplitude_counts_for_17db": round(10 ** ((17 - icpt) / slope / 20), 3) if slope else None,
                           "amplitude_counts_for_empty_off_median": round(
                               10 ** ((thr["off"]["empty_median_db"] - icpt) / slope / 20), 3) if slope else None},
        "by_amplitude_counts": _binned(spur_all, lambda r: r["effect_params"]["spur_tone"]["amplitude_counts"],
                                       [0.3, 0.6, 1.2, 2.5, 5.0], lambda r: r["only"]["spur_tone"] > 17),
        "self_excised_frac_over_17db": frac([r["self_excised"]["excess_db"] > 17 for r in spur_all]),
    }

    # ---- 2. occupied items
    occ_out: dict[str, Any] = {}
    for v in variants:
        med, p90 = thr[v]["empty_median_db"], thr[v]["empty_p90_db"]
        occ_out[v] = {str(c): {"n": len(rs), "frac_under_empty_median": frac([r[v]["excess_db"] <= med for r in rs]),
                               "frac_under_empty_p90": frac([r[v]["excess_db"] <= p90 for r in rs]),
                               "peak": quantiles([r[v]["excess_db"] for r in rs])}
                      for c in (1, 2) for rs in [[r for r in occ if r["count"] == c]]}
    occ_out["note"] = "thresholds: the empty items' median / p90 of the same variant (on, off, self_excised)"
    S["occupied_under_empty_thresholds"] = occ_out
    # a person is visible when the max of their own +-2 range-bin window beats the same window in empty rooms
    null_off = [x for r in empty for x in r["window_null_off"]]
    vis_thr95 = sorted(null_off)[int(0.95 * (len(null_off) - 1))] if null_off else float("nan")
    S["person_window_null"] = {"off": quantiles(null_off), "off_p95": round(vis_thr95, 2),
                               "on": quantiles([x for r in empty for x in r["window_null_on"]])}
    persons = [p for r in occ for p in r["people"]]
    inv = lambda p: p["excess_off_db"] <= vis_thr95  # noqa: E731
    S["person_visibility"] = {
        "definition": "invisible: max of the person's +-2 range-bin window (catalog off) <= p95 of that window in empty "
                      "rooms (person_window_null.off_p95)",
        "threshold_db": round(vis_thr95, 2), "n_people": len(persons),
        "frac_invisible_off": frac([inv(p) for p in persons]),
        "frac_invisible_on": frac([p["excess_on_db"] <= vis_thr95 for p in persons]),
        "by_rcs_scale_dB": _binned(persons, lambda p: p["rcs_scale_dB"], [-20, -15, -10, -5, 0, 10.01], inv),
        "by_slant_range_m": _binned(persons, lambda p: p["slant_range_m"], [0, 2, 4, 6, 8, 10, 12, 16], inv),
        "by_abs_doppler_bin": _binned(persons, lambda p: abs(p["doppler_bin"]), [0, 2, 3, 5, 10, 40], inv),
        "by_off_boresight_deg": _binned(persons, lambda p: p["off_boresight_deg"], [0, 10, 20, 40, 90], inv),
        "by_strength_proxy_dB": _binned(persons, _strength, [-90, -60, -55, -50, -45, -40, -30, 10], inv),
        "strength_proxy": "rcs_scale_dB - 40 log10(slant range m) + 20 log10(cos(off boresight))",
        "strength_proxy_separation": best_balanced_accuracy([_strength(p) for p in persons if inv(p)],
                                                            [_strength(p) for p in persons if not inv(p)]),
        "share_of_invisible_with_rcs_scale_under_-10dB": frac([p["rcs_scale_dB"] < -10 for p in persons if inv(p)]),
        "frac_of_people_with_rcs_scale_under_-10dB": frac([p["rcs_scale_dB"] < -10 for p in persons]),
        "proxy_cutoffs": {str(c): {"flags_invisible": frac([_strength(p) < c for p in persons if inv(p)]),
                                   "flags_visible": frac([_strength(p) < c for p in persons if not inv(p)])}
                          for c in (-55, -50, -47, -44)},
    }
    # what the catalog does to people: their window excess on vs off
    drop = {}
    for e in CATALOG_BY_NAME:
        for has in (True, False):
            d = [p["excess_on_db"] - p["excess_off_db"] for r in occ if (e in r["effects"]) == has for p in r["people"]]
            drop[f"{e}:{'with' if has else 'without'}"] = {
                "n": len(d), "median_db": round(statistics.median(d), 2) if d else None,
                "frac_drop_over_6db": frac([x < -6 for x in d])}
    inter = [(r["effect_params"]["interference"], p["excess_on_db"] - p["excess_off_db"]) for r in occ
             if "interference" in r["effects"] for p in r["people"]]
    drop["interference_by_amplitude_counts"] = {
        f"[{lo:g},{hi:g})": {"n": len(s), "median_db": round(statistics.median(s), 2) if s else None,
                             "frac_drop_over_6db": frac([x < -6 for x in s])}
        for lo, hi in ((5, 30), (30, 150), (150, 1000.01))
        for s in [[x for q, x in inter if lo <= q["amplitude_counts"] < hi]]}
    S["person_excess_on_minus_off"] = drop

    # ---- 3. separability of occupancy by the one statistic
    S["occupancy_threshold_balanced_accuracy"] = {
        **{v: best_balanced_accuracy([r[v]["excess_db"] for r in empty], [r[v]["excess_db"] for r in occ])
           for v in variants},
        **{f"{v}_blank2": best_balanced_accuracy([r[v]["excess_blank2_db"] for r in empty],
                                                 [r[v]["excess_blank2_db"] for r in occ]) for v in variants}}

    # ---- 4. counting: when do 2 people look like 1
    pairs = []
    for r in (r for r in occ if r["count"] == 2):
        a, b = r["people"]
        dr_bins, dd_bins = abs(a["range_bin"] - b["range_bin"]), abs(a["doppler_bin"] - b["doppler_bin"])
        pairs.append({"one_invisible": inv(a) != inv(b), "both_invisible": inv(a) and inv(b),
                      "one_invisible_on": (a["excess_on_db"] <= vis_thr95) != (b["excess_on_db"] <= vis_thr95),
                      "same_range_pm2": dr_bins <= 2, "same_range_and_doppler_pm2": dr_bins <= 2 and dd_bins <= 2,
                      "strength_gap_db": abs(_strength(a) - _strength(b))})
    S["two_person_items"] = {
        "n": len(pairs),
        "frac_one_person_invisible_off": frac([p["one_invisible"] for p in pairs]),
        "frac_one_person_invisible_on": frac([p["one_invisible_on"] for p in pairs]),
        "frac_both_invisible_off": frac([p["both_invisible"] for p in pairs]),
        "frac_same_range_bins_pm2": frac([p["same_range_pm2"] for p in pairs]),
        "frac_same_range_and_doppler_pm2": frac([p["same_range_and_doppler_pm2"] for p in pairs]),
        "frac_strength_gap_over_20db": frac([p["strength_gap_db"] > 20 for p in pairs]),
        "frac_looks_like_at_most_one_off": frac([p["one_invisible"] or p["both_invisible"]
                                                 or p["same_range_and_doppler_pm2"] for p in pairs]),
    }
    one = [r for r in occ if r["count"] == 1]
    S["one_person_items"] = {"n": len(one), "frac_invisible_off": frac([inv(r["people"][0]) for r in one]),
                             "frac_invisible_on": frac([r["people"][0]["excess_on_db"] <= vis_thr95 for r in one])}
    S["observable_label_rule"] = {key: _label_rule(records, vis_thr95, key) for key in ("excess_off_db", "excess_on_db")}
    return S


def _beta(r: dict[str, Any]) -> float:
    """Vibration modulation index ``4 pi d / lambda`` (60 GHz)."""
    return 4 * math.pi * r["effect_params"]["vibrating_clutter"]["displacement_m"] / (3e8 / 60e9)


def _line(xy: list[tuple[float, float]]) -> tuple[float, float]:
    """Least-squares slope and intercept of ``y = a x + b`` (0, 0 with fewer than 2 points)."""
    if len(xy) < 2:
        return 0.0, 0.0
    mx = statistics.fmean(x for x, _ in xy)
    my = statistics.fmean(y for _, y in xy)
    sxx = sum((x - mx) ** 2 for x, _ in xy)
    a = sum((x - mx) * (y - my) for x, y in xy) / sxx if sxx else 0.0
    return a, my - a * mx


def _vib_gentle(r: dict[str, Any]) -> bool:
    """A vibrating-clutter draw whose Doppler extent is under half a bin and whose return is not strong."""
    p = r["effect_params"]["vibrating_clutter"]
    return _beta(r) * p["vibration_Hz"] < 20 and p["rcs_dBsm"] - 40 * math.log10(p["range_m"]) < -30


def _strength(p: dict[str, Any]) -> float:
    return p["rcs_scale_dB"] - 40 * math.log10(max(p["slant_range_m"], 0.3)) + p["two_way_pattern_dB"]


def _binned(items: list[Any], key: Any, edges: list[float], flag: Any) -> dict[str, Any]:
    out = {}
    for lo, hi in zip(edges, edges[1:]):
        sel = [x for x in items if lo <= key(x) < hi]
        out[f"[{lo:g},{hi:g})"] = {"n": len(sel), "frac": frac([bool(flag(x)) for x in sel])}
    return out


def _label_rule(records: list[dict[str, Any]], threshold: float, key: str) -> dict[str, Any]:
    """Labels that change if a person counts only when their window's ``key`` excess beats ``threshold``."""
    changed: Counter[str] = Counter()
    for r in records:
        visible = sum(p[key] > threshold for p in r["people"])
        if visible != r["count"]:
            changed[f"{r['count']}->{visible}"] += 1
    return {"visible_threshold_db": round(threshold, 2), "changed": dict(sorted(changed.items())),
            "frac_changed": round(sum(changed.values()) / max(1, len(records)), 4)}


# ----------------------------------------------------------------------------- main
def main() -> None:
    """Parse the arguments, measure every item, write the JSON."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--items", type=int, default=600, help="items to simulate (default 600)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the twin dataset (data.twin.seed; the quick run's: 0)")
    ap.add_argument("--start", type=int, default=0, help="first item index (default 0: the training items)")
    ap.add_argument("--out", required=True, help="JSON file to write")
    ap.add_argument("--skip-range-bins", type=int, default=3, help="first range bins left out (leakage)")
    ap.add_argument("--excise-db", type=float, default=3.0, help="persistent-cell threshold (the quick run's 3 dB)")
    ap.add_argument("--mask-frames", type=int, default=8, help="frames of the item's own empty room for self-excision")
    ap.add_argument("--no-calibration-excise", action="store_true",
                    help="leave out the quick run's calibration excision mask")
    args = ap.parse_args()
    torch.set_num_threads(1)

    t0 = time.time()
    an = Analyzer(args)
    an.ds_on.prepare()
    an.ds_off.prepare()
    reproduces = an.check_reproduces(args.start)
    records = []
    for i in tqdm(range(args.start, args.start + args.items), desc="items", unit="item"):
        records.append(an.item(i))
    summary = summarize(records)
    out = {
        "settings": {**{k: v for k, v in vars(args).items()}, "config": "RadarConfig.bgt60tr13c()", "scene": "corridor",
                     "randomization": "TwinRandomization() (defaults) vs TwinRandomization(catalog={'scale': 0})",
                     "receiver": "default (the quick run's rt / randomdr twin; cdr's quieter twin not simulated)",
                     "frames_per_item": 1, "chain": "rd_db_chain() -> level_chain('floor_relative', excise)",
                     "calibration_excise": an.excise_info, "statistic": (
                         "max of the floor-relative map (dB over the row's Doppler median) outside zero Doppler +-1 "
                         f"and the first {args.skip_range_bins} range bins"),
                     "person_excess": f"the same max within +-{PERSON_RANGE_WINDOW} range bins of the person's centre",
                     "script_reproduces_dataset_item": reproduces, "seconds": round(time.time() - t0, 1),
                     "torch": torch.__version__},
        "summary": summary,
        "items": records,
    }
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)
    s = summary
    print(json.dumps({k: s[k] for k in ("empty_peak_on", "empty_peak_off", "empty_peak_self_excised",
                                        "occupancy_threshold_balanced_accuracy")}, indent=1))
    print(f"wrote {args.out} ({time.time() - t0:.0f} s)")


if __name__ == "__main__":
    main()
