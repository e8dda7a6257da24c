"""What a calibrated floor changes in what the network sees: CDR against RT and RandomDR, world by world.

Issue 34 item 4 asks why CDR done the paper's way (a floor fitted on the empty-room capture) is last on
counting once the network's input is floor-relative. This script measures, on held-out worlds (the design
suite: validation, looked at as often as one likes), for each source of maps:

* ``capture``: the world's own test captures (empty, one, two people), through the recipes' RD chain;
* ``rt``: the recipes' noisy twin at the world's config, no DR;
* ``randomdr``: the same twin items through RandomDR;
* ``cdr_matched``: the CDR recipe (quiet twin, clamp matched to the calibration capture);
* ``cdr_normal``: the paper's clamp (``cdr_normal_floor``: quiet twin, Normal floor fitted on the capture),

two things, each per frame, cells off the blanked zero Doppler and outside the excised persistent cells:

* ``level_db``: the RX-combined map's median (the absolute floor, what CDR calibrates);
* ``peak_db``: the largest floor-relative cell (what a person adds over its row's floor: the network's cue).

From the per-frame values it records, per source and count, the median and 5/95th percentiles, and the
distance of the twin's empty-frame levels and peaks from the capture's (medians apart). It also records the
floor-relative noise texture: the spread (std) of the empty frames' floor-relative cells, against the closed
form for a complex-Gaussian floor averaged over the receivers (a chi-square law of 2 x RX degrees of freedom,
whose dB spread does not depend on the level).

    python scripts/cdr_floor_account.py --worlds 8 -o benchmarks/cdr_floor_account_cpu.json
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

import torch

from radaraug import recipes
from radaraug.files import atomic_write_json
from radaraug.io import open_capture
from radaraug.training.data import RadarDataModule
from radaraug.training.pipeline import floor_texture, noise_texture_db
from radaraug.training.reproduce import ReproduceSettings, _sized, run_recipe

SOURCES = {"rt": ("rt", None), "randomdr": ("randomdr", None), "cdr_matched": ("cdr", None),
           "cdr_normal": ("cdr", "cdr_normal_floor")}


def frame_stats(db_maps: torch.Tensor, dm: Any) -> dict[str, torch.Tensor]:
    """:func:`floor_texture` of maps with the run's excision and blanking."""
    return floor_texture(db_maps, dm.excise, dm.image_spec.blank_zero_doppler)


def _summary(v: torch.Tensor) -> dict[str, float] | None:
    if v.numel() == 0:
        return None
    q = torch.quantile(v.double(), torch.tensor([0.05, 0.5, 0.95], dtype=torch.float64))
    return {"p05": round(float(q[0]), 2), "median": round(float(q[1]), 2), "p95": round(float(q[2]), 2), "n": int(v.numel())}


def _auc(neg: torch.Tensor, pos: torch.Tensor) -> float | None:
    """P(a positive frame's value > a negative frame's): how far one number separates the two classes."""
    if not len(neg) or not len(pos):
        return None
    gt = (pos[:, None] > neg[None, :]).double().mean() + 0.5 * (pos[:, None] == neg[None, :]).double().mean()
    return round(float(gt), 3)


def world_record(world: Any, made: Any, out: Path, items: int, frames: int) -> dict[str, Any]:
    """Per-frame statistics of one world: its test captures by count, and each source's twin items by count."""
    settings = ReproduceSettings.quick()
    tests = [{"path": str(p), "count": int(c)} for p, c in made.tests]
    rec: dict[str, Any] = {"world": world.name, "sources": {}}
    capture_by_count: dict[int, torch.Tensor] = {}
    for name, (method, ablation) in SOURCES.items():
        recipe = _sized(run_recipe("counting", method, settings, ablation), settings)
        kw = recipes.merge(recipe["data"], {"task": "counting", "calibration": str(made.calibration), "test": tests,
                                            "cache_dir": str(out / "cache"),
                                            "twin": {"train_items": items, "val_items": 0, "progress": False}})
        dm = RadarDataModule.from_recipe(kw)
        dm.setup("fit")
        train = dm._train.base
        by_count = {}
        for c in (0, 1, 2):
            idx = (train.counts == c).nonzero().flatten().tolist()
            maps = train.maps(idx)
            if dm.dr is not None:  # RT has none
                with torch.no_grad():
                    maps = dm.dr.train()(maps.float())
            by_count[c] = frame_stats(maps, dm)
        rec["sources"][name] = by_count
        if name == "cdr_normal":
            rec["cdr_normal_fit_db"] = {"mean": round(dm.dr.mean_db, 2), "std": round(dm.dr.std_db, 2)}
        if not capture_by_count:  # the captures once, through the first source's chain and excision
            # the calibration's persistent cells the recipes excise from every map: their share of the map
            rec["excised_share"] = round(float(dm.excise.double().mean()), 4) if dm.excise is not None else 0.0
            for e in tests:
                with open_capture(e["path"]) as cap:
                    x = cap.read(0, min(frames, cap.num_frames))
                capture_by_count[e["count"]] = frame_stats(dm.rd_chain()(x), dm)
    rec["sources"] = {"capture": capture_by_count, **rec["sources"]}
    return rec


def summarize(rec: dict[str, Any]) -> dict[str, Any]:
    """Percentiles per source and count, the twin's gaps to the capture, and the peak's AUC between counts."""
    src = rec["sources"]
    cap = src["capture"]
    out: dict[str, Any] = {"world": rec["world"], "cdr_normal_fit_db": rec.get("cdr_normal_fit_db"),
                           "excised_share": rec.get("excised_share"), "by_source": {}}
    for name, by_count in src.items():
        row: dict[str, Any] = {}
        for c, s in by_count.items():
            row[str(c)] = {k: _summary(v) for k, v in s.items()}
        row["auc_peak_0_vs_1"] = _auc(by_count[0]["peak_db"], by_count[1]["peak_db"])
        row["auc_peak_1_vs_2"] = _auc(by_count[1]["peak_db"], by_count[2]["peak_db"])
        if name != "capture":
            row["empty_level_gap_db"] = round(float(by_count[0]["level_db"].median() - cap[0]["level_db"].median()), 2)
            row["empty_peak_gap_db"] = round(float(by_count[0]["peak_db"].median() - cap[0]["peak_db"].median()), 2)
            row["one_peak_gap_db"] = round(float(by_count[1]["peak_db"].median() - cap[1]["peak_db"].median()), 2)
            row["texture_gap_db"] = round(float(by_count[0]["texture_std_db"].median()
                                                - cap[0]["texture_std_db"].median()), 2)
        out["by_source"][name] = row
    return out


def main() -> None:
    """Measure every world of the suite and write the record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--suite", default="design")
    ap.add_argument("--worlds", type=int, default=8)
    ap.add_argument("--items", type=int, default=150, help="twin items per source and world")
    ap.add_argument("--frames", type=int, default=60, help="capture frames per test file")
    ap.add_argument("--work", type=Path, default=Path("cdr_floor_work"), help="worlds and caches")
    ap.add_argument("-o", "--out", type=Path, required=True)
    args = ap.parse_args()
    from radaraug.testsets.independent.worlds import make_suite

    t0 = time.perf_counter()
    worlds = []
    for world, made in make_suite(args.work / "worlds", args.suite, worlds=args.worlds, frames_per_count=60,
                                  progress=False):
        rec = world_record(world, made, args.work, args.items, args.frames)
        s = summarize(rec)
        worlds.append(s)
        b = s["by_source"]
        print(world.name, {k: (v.get("empty_level_gap_db"), v.get("empty_peak_gap_db"), v.get("one_peak_gap_db"),
                               v["auc_peak_0_vs_1"], v["auc_peak_1_vs_2"]) for k, v in b.items()}, flush=True)
    rx = 3
    record = {
        "benchmark": "cdr_floor_account", "suite": args.suite,
        "note": ("validation: the design suite is looked at. Per world and source: per-frame RX-combined median "
                 "level and largest floor-relative cell (off zero Doppler, outside the excised cells), their "
                 "5/50/95th percentiles, the gaps of the twin's medians to the capture's, and the AUC of the "
                 "largest cell between counts. No training."),
        "command": f"python scripts/cdr_floor_account.py --suite {args.suite} --worlds {args.worlds} --items {args.items} "
                   f"--frames {args.frames} -o {args.out}",
        "closed_form_texture_std_db": {"1 rx": round(noise_texture_db(1), 2), f"{rx} rx": round(noise_texture_db(rx), 2)},
        "wall_seconds": round(time.perf_counter() - t0, 1), "worlds": worlds,
    }
    atomic_write_json(args.out, record)
    print(args.out, record["wall_seconds"], "s")


if __name__ == "__main__":
    main()
