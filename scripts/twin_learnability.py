"""How far can the quick run's classifiers learn the twin itself, and what do they miss (an analysis)?

Issue 34 asks for simulated validation >= 0.97 occupancy / 0.85 counting at the demo's size, or a
measured account of the frames no classifier can get right. This script trains the demo's RandomDR
runs (the recipes, ``ReproduceSettings.quick()``'s image, batch and workers; the independent set's
calibration capture for the excision, as ``make demo``) with more training items and epochs, and scores
every run on one fixed *account set* of twin items (indices from ``--account-start``, never trained on;
through the run's DR and image chain, as validation does). Per account item it records what the frame
holds (``twin_observability.py``'s measurements, on the recipes' twin): each person's peak excess in
their own +-2 range-bin window with the catalog off (visible when it beats the 95th percentile of the
same window in the account set's empty rooms), their range and Doppler bins, and the item's peak
excess with the catalog on. From these, the balanced accuracy on the frames whose every person is
visible, and against labels that count only visible people.

    python scripts/twin_learnability.py --work WORK --out twin_learnability.json

Writes the summary JSON (``--out``) and, in WORK, the full one (``<its stem>_full.json``: every run's
scores and the per-item account, which ``--rescore`` reads again); the runs' folders stay in WORK.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import platform
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import torch
from torch.utils.data import DataLoader
from tqdm import tqdm

sys.path.insert(0, str(Path(__file__).resolve().parent))
import twin_observability as obs  # noqa: E402  (the per-item measurements, one file beside this one)

from radaraug.sim.dataset import SimulatedRadarDataset  # noqa: E402
from radaraug.sim.randomization import TwinRandomization  # noqa: E402
from radaraug.testsets.tasks import TASKS, label_of  # noqa: E402
from radaraug.training import reproduce as rp  # noqa: E402
from radaraug.training.cache import CachedMaps, build_map_caches  # noqa: E402
from radaraug.training.metrics import balanced_accuracy, confusion_matrix  # noqa: E402


def bacc(probs: torch.Tensor, labels: torch.Tensor, classes: int) -> float:
    """Balanced accuracy of the argmax of ``probs``."""
    return balanced_accuracy(confusion_matrix(probs.argmax(1), labels, classes))


def account(dm: Any, start: int, n: int) -> tuple[list[dict[str, Any]], float]:
    """What each account item holds, and the detection threshold its people are judged by.

    Per item: each person's geometry and the peak of their own +-2 range-bin window in the catalog-off
    map (the physics, without the effect catalog), and the item's whole-map peak with the catalog on
    (what training sees). The threshold is the 95th percentile of the empty items' whole-map peak
    (catalog off): a person under it is weaker than what one empty room in twenty shows somewhere. A
    person is *resolved* when their window's peak beats the threshold in a connected region (8-neighbour
    cells over it) that no other person's peak shares; ``observable_count`` counts them.
    """
    from scipy import ndimage

    ds = dm.simulated_dataset(length=start + n)
    args = argparse.Namespace(start=start, items=n, seed=ds.seed, skip_range_bins=3, excise_db=3.0, mask_frames=8,
                              no_calibration_excise=True)
    an = obs.Analyzer(args)
    # the recipes' twin (catalog without spur and fan), not the analyzer's default one
    an.ds_on, an.rz_on = ds, ds.randomization
    an.rz_off = TwinRandomization.from_dict({**ds.randomization.to_dict(), "catalog": {"scale": 0.0}})
    an.ds_off = SimulatedRadarDataset(ds.scene, length=ds.length, seed=ds.seed, config=ds.config, target=ds.target,
                                      twin_options=ds.twin_options, randomization=an.rz_off)
    an.level = obs.level_chain("floor_relative", dm.excise)  # the run's excision mask
    an.chain = dm.rd_chain()
    records, maps_off = [], []
    for i in tqdm(range(start, start + n), desc="account items"):
        scenario = ds.scenario(i)
        d_on, d_off = an.rz_on.item(ds.seed, i, scenario.count), an.rz_off.item(ds.seed, i, scenario.count)
        if tuple(d_on.rcs_scale_dB) != tuple(d_off.rcs_scale_dB):
            raise RuntimeError(f"item {i}: the catalog-off draw has other people's RCS")
        fr_on = an.level_map(an.simulate(ds, i, d_on, scenario.people)[0])
        fr_off = an.level_map(an.simulate(an.ds_off, i, d_off, scenario.people)[0])
        maps_off.append(fr_off.masked_fill(~an.valid, float("-inf")))
        people = [{**g, "rcs_scale_dB": round(r, 2), "excess_off_db": an.person_excess(fr_off, g["range_bin"])}
                  for g, r in zip(an.geometry(i, scenario, d_on), d_on.rcs_scale_dB)]
        records.append({"index": i, "count": scenario.count, "effects": sorted(ds.item_params(i)["effects"]),
                        "peak_on_db": an.peak(fr_on)["excess_db"], "peak_off_db": an.peak(fr_off)["excess_db"],
                        "people": people})
    empty = sorted(r["peak_off_db"] for r in records if r["count"] == 0)
    threshold = empty[int(0.95 * (len(empty) - 1))]
    w = obs.PERSON_RANGE_WINDOW
    for rec, m in zip(records, maps_off):
        labels, _ = ndimage.label((m > threshold).numpy(), structure=[[1, 1, 1]] * 3)
        seen = set()
        for p in rec["people"]:
            lo, hi = max(0, p["range_bin"] - w), min(m.shape[0], p["range_bin"] + w + 1)
            win = m[lo:hi]
            if lo >= hi or not bool((win > threshold).any()):
                p["region"] = None
                continue
            r, d = divmod(int(torch.argmax(win)), m.shape[1])
            p["region"] = int(labels[lo + r, d])
            seen.add(p["region"])
        rec["observable_count"] = len(seen)
    return records, threshold


def summarize(task: str, probs: list[torch.Tensor], records: list[dict[str, Any]]) -> dict[str, Any]:
    """Balanced accuracy on all items, on the items whose people are all resolved, and against resolved labels."""
    k = len(TASKS[task])
    counts = torch.tensor([r["count"] for r in records])
    labels = label_of(counts, task)
    seen = torch.tensor([r["observable_count"] for r in records])
    seen_labels = label_of(seen, task)
    all_visible = seen == counts
    out: dict[str, Any] = {}
    for name, f in (("all items", lambda p: bacc(p, labels, k)),
                    ("items whose people are all resolved", lambda p: bacc(p[all_visible], labels[all_visible], k)),
                    ("labels counting resolved people only", lambda p: bacc(p, seen_labels, k))):
        v = [f(p) for p in probs]
        out[name] = {"per_seed": [round(x, 4) for x in v], "mean": round(statistics.fmean(v), 4),
                     "std": round(statistics.stdev(v), 4) if len(v) > 1 else None}
    ens = torch.stack(probs).mean(0)
    out["seed ensemble, all items"] = round(bacc(ens, labels, k), 4)
    for name, m in (("confusion_summed_over_seeds", torch.ones_like(all_visible)),
                    ("confusion_summed_over_seeds, items whose people are all resolved", all_visible)):
        conf = torch.zeros(k, k, dtype=torch.long)
        for p in probs:
            conf += torch.bincount(labels[m] * k + p[m].argmax(1), minlength=k * k).reshape(k, k)
        out[name] = conf.tolist()
    # where the errors lie (summed over seeds)
    kinds = {"empty, catalog peak > 17 dB": (counts == 0) & torch.tensor([r["peak_on_db"] > 17 for r in records]),
             "a person not resolved": ~all_visible,
             "two people, one region over the threshold": (counts == 2) & (seen == 1)}
    wrong = torch.stack([p.argmax(1) != labels for p in probs])  # (seeds, items)
    out["errors"] = {"total": int(wrong.sum()), "items": len(records) * len(probs)}
    for name, m in kinds.items():
        out["errors"][name] = {"items": int(m.sum()), "errors": int(wrong[:, m].sum())}
    return out


def main() -> None:
    """Train the grid (or read earlier runs), score the account set, write the record."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--work", required=True, help="folder for the test set, caches and runs")
    ap.add_argument("--out", required=True, help="JSON file to write")
    ap.add_argument("--grid", default="800x4,3200x4,800x16,12800x4",
                    help="training items x epochs, comma-separated (default: %(default)s)")
    ap.add_argument("--tasks", default="occupancy,counting")
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--account-start", type=int, default=20000)
    ap.add_argument("--account-items", type=int, default=600)
    ap.add_argument("--resample", choices=("bilinear", "max"), default="bilinear",
                    help="how the map shrinks to the image size (data.image.resample): the recipes' bilinear resize "
                         "of the colour image, or the max of each pixel's cells before the colour map")
    ap.add_argument("--account-from", nargs="+", metavar="RECORD",
                    help="take the account of the same items from an earlier full record instead of redoing it")
    ap.add_argument("--note", default=None, help="a note to keep in the record (e.g. what else ran on the machine)")
    ap.add_argument("--rescore", nargs="+", metavar="RECORD",
                    help="train nothing: take the runs of these records (same account set) and redo the account")
    args = ap.parse_args()
    work = Path(args.work)
    t0 = time.perf_counter()
    quick = rp.ReproduceSettings.quick()
    (ts,) = rp._test_sets(work, quick, None, None, ["independent"], progress=True)
    data_kw = {"calibration": ts.calibration, "test": ts.tests, "cache_dir": str(work / "cache")}

    def recipe_of(task: str, items: int, epochs: int) -> tuple[Any, dict[str, Any], dict[str, Any]]:
        settings = dataclasses.replace(quick, train_items=items, val_items=0, epochs=epochs, keep_classifiers=False,
                                       resample=args.resample)
        recipe = rp._sized(rp.run_recipe(task, "randomdr", settings), settings)
        return settings, recipe.get("data", {}) | data_kw, recipe.get("model", {})

    runs: list[dict[str, Any]] = []
    records: list[dict[str, Any]] | None = None
    threshold = None
    if args.rescore:
        for path in args.rescore:
            old = json.loads(Path(path).read_text())
            runs += [r | {"resample": r.get("resample", "max" if "--resample max" in old["command"] else "bilinear")}
                     for r in old["runs"]]
        records, threshold = _earlier_account(args.rescore, args.account_start, args.account_items)
        if records is None:
            from radaraug.training.data import RadarDataModule

            dm = RadarDataModule.from_recipe(recipe_of("counting", 800, 4)[1] | {"task": "counting"})
            dm.setup("fit")
            records, threshold = account(dm, args.account_start, args.account_items)
    else:
        maps = None
        for task in args.tasks.split(","):
            for g in args.grid.split(","):
                items, epochs = (int(v) for v in g.split("x"))
                settings, kw, model_kw = recipe_of(task, items, epochs)
                for seed in range(args.seeds):
                    run_dir = work / "runs" / f"{task}_{items}x{epochs}_{args.resample}_seed{seed}"
                    model, dm, _, fit_s, _ = rp._fit(task, seed, settings=settings, data_kw=kw, model_kw=model_kw,
                                                     run_dir=run_dir, accelerator="cpu", progress=True)
                    if maps is None:
                        ds = dm.simulated_dataset(length=args.account_start + args.account_items)
                        idx = range(args.account_start, args.account_start + args.account_items)
                        built = build_map_caches(ds, {"account": idx}, work / "cache", num_workers=2,
                                                 interference_db=dm.image_spec.excise_interference_db)
                        maps = CachedMaps(built["account"])
                        records, threshold = _earlier_account(args.account_from or [], args.account_start,
                                                              args.account_items)
                        if records is None:
                            records, threshold = account(dm, args.account_start, args.account_items)
                        if [r["count"] for r in records] != maps.counts.tolist():
                            raise RuntimeError("the account's items and the cached maps disagree")
                    # through the run's DR (train mode) and image chain, as validation
                    p = rp._scores(model, dm, DataLoader(maps, batch_size=64), with_dr=True, limit=len(maps))[0]
                    runs.append({"task": task, "train_items": items, "epochs": epochs, "resample": args.resample,
                                 "seed": seed, "fit_seconds": round(fit_s, 1),
                                 "probs": [[round(float(v), 4) for v in row] for row in p]})
                    print(f"{task} {items}x{epochs} seed {seed}: account balanced accuracy "
                          f"{bacc(p, label_of(maps.counts, task), len(TASKS[task])):.3f} ({fit_s:.0f} s)", flush=True)
                _write(args, runs, records, threshold, t0)
    _write(args, runs, records, threshold, t0)


def _earlier_account(paths: list[str], start: int, n: int) -> tuple[Any, Any]:
    """The account of items ``start .. start + n`` from the first full record in ``paths`` that has it."""
    for path in paths:
        old = json.loads(Path(path).read_text())
        acc = old.get("account") or []
        if acc and "observable_count" in acc[0] and [r["index"] for r in acc] == list(range(start, start + n)):
            return acc, old.get("account_set", {}).get("detection_threshold_db", old.get("detection_threshold_db"))
    return None, None


def _write(args: argparse.Namespace, runs: list[dict[str, Any]], records: Any, threshold: Any, t0: float) -> None:
    """Write the summary (``--out``) and the full record (WORK/<the summary's stem>_full.json).

    The summary: settings and a summary per (task, items x epochs, resample); the full record adds the
    per-item account and every run's scores (what ``--rescore`` reads).
    """
    groups: dict[str, list[dict[str, Any]]] = {}
    for r in runs:
        groups.setdefault(f"{r['task']} {r['train_items']}x{r['epochs']} {r['resample']}", []).append(r)
    summaries = {k: summarize(rs[0]["task"], [torch.tensor(r["probs"]) for r in rs], records)
                 | {"fit_seconds_median": statistics.median(r["fit_seconds"] for r in rs)} for k, rs in groups.items()}
    counts = [r["count"] for r in records]
    resolved = [r["observable_count"] for r in records]
    rec = {"benchmark": "twin_learnability", "kind": "simulated (the twin's own items; no test set involved)",
           "command": "python scripts/twin_learnability.py --work WORK --out OUT " + " ".join(
               f"--{k.replace('_', '-')} {v}" for k, v in vars(args).items()
               if k in (("account_start", "account_items") if args.rescore else ("grid", "tasks", "seeds", "account_start",
                                                                                  "account_items", "resample")))
           + ("" if not args.rescore else " --rescore " + " ".join(Path(r).name for r in args.rescore)),
           "machine": {"cpu_threads": torch.get_num_threads(), "python": platform.python_version(),
                       "torch": torch.__version__},
           "wall_seconds": round(time.perf_counter() - t0, 1), "note": args.note,
           "account_set": {"twin_indices": [args.account_start, args.account_start + args.account_items],
                           "items_per_count": {str(c): counts.count(c) for c in sorted(set(counts))},
                           "detection_threshold_db": threshold,
                           "items_with_a_person_not_resolved": sum(a != b for a, b in zip(counts, resolved)),
                           "resolved_count_by_count": {str(c): {str(k): sum(1 for a, b in zip(counts, resolved)
                                                                             if a == c and b == k)
                                                                for k in range(c + 1)} for c in sorted(set(counts))}},
           "summaries": summaries}
    Path(args.out).write_text(json.dumps(rec, indent=1) + "\n")
    full = rec | {"account": records, "runs": runs}
    (Path(args.work) / f"{Path(args.out).stem}_full.json").write_text(json.dumps(full) + "\n")


if __name__ == "__main__":
    main()
