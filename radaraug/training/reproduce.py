"""`radaraug reproduce`: the paper's experiment (Sec. 2.2-3) end to end, with a report.

2 tasks (occupancy, counting) x 4 methods (RT, RandomDR, CDR, and CDR on the twin profile fitted on
the calibration capture: ``cdr_profile``) x N seeds, tested on the same captures. RT, RandomDR and
CDR train on one simulated set (simulated once, :mod:`radaraug.training.cache`); ``cdr_profile``
on a second one, simulated with the profile's receiver. Plus an ablation (CDR without twin
randomization). Writes ``OUT/report.md``, ``OUT/report.json``
(``results[task][method]["balanced_accuracy"] = {"mean", "std", "per_seed"}``), per-run metrics
under ``OUT/runs/`` and the paper's figures under ``OUT/figures/``.

Seeds change the network initialization, the DR draws and the batch order, not the simulated
set: the spread reported is that of training, for a fixed twin sample.
"""

from __future__ import annotations

import logging
import os
import platform
import statistics
import time
import warnings
from collections.abc import Sequence
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import torch

from radaraug._optional import lazy_import
from radaraug.errors import ConfigError
from radaraug.io.atomic import atomic_write_json, atomic_write_text
from radaraug.training.chain import METHODS, PROFILE_METHODS, TASKS, is_calibration_json
from radaraug.units import DB_CONVENTION


@dataclass(frozen=True)
class ReproduceSettings:
    """Sizes of one reproduce run (``quick()`` for a 2-core CPU in minutes, ``full()`` for a GPU)."""

    train_items: int = 6000
    val_items: int = 600
    epochs: int = 15
    image_size: tuple[int, int] = (128, 64)
    batch_size: int = 64
    lr: float = 1e-3
    proxy_frames_per_count: int = 300
    tracer_rays: int | None = None
    num_workers: int = 2
    sim_workers: int = 2
    #: twin randomization of the main runs: True (defaults), or a dict of TwinRandomization fields
    randomization: bool | dict[str, Any] = True
    #: calibration-capture frames that ``cdr_profile``'s diagnose reads (fits on half, scores on half)
    profile_max_frames: int = 100

    @classmethod
    def full(cls) -> ReproduceSettings:
        """The default: sized for a GPU (hours on a 2-core CPU)."""
        return cls()

    @classmethod
    def quick(cls) -> ReproduceSettings:
        """Minutes on a 2-core CPU: fewer items and epochs, half-size images.

        And a 40-frame diagnose for ``cdr_profile`` (the room: the twin's default image-method trace,
        faster than a coarse SBR trace and converged).
        """
        return cls(train_items=360, val_items=90, epochs=4, image_size=(64, 32), batch_size=32,
                   proxy_frames_per_count=60, num_workers=0, sim_workers=0, profile_max_frames=40)


def parse_test_arg(text: str) -> dict[str, Any]:
    """``PATH`` or ``PATH:COUNT`` -> a test entry (``count`` None: per-frame labels in the file)."""
    path, sep, count = text.rpartition(":")
    if sep and count.isdigit() and path:
        return {"path": path, "count": int(count)}
    return {"path": text}


def _summary(values: Sequence[float]) -> dict[str, Any]:
    vals = [float(v) for v in values]
    return {"mean": statistics.fmean(vals), "std": statistics.pstdev(vals) if len(vals) > 1 else 0.0,
            "per_seed": vals}


def _cdr_floor_of(keep: dict[tuple[str, str], tuple[Any, Any]]) -> str | None:
    """The floor distribution the CDR runs drew from (None when no CDR method ran)."""
    from radaraug.transforms import CalibratedDR

    floors = {dm.dr.floor for _, dm in keep.values() if isinstance(dm.dr, CalibratedDR)}
    return floors.pop() if len(floors) == 1 else None


def _run_one(task: str, method: str, seed: int, *, settings: ReproduceSettings, data_kw: dict[str, Any],
             run_dir: Path, accelerator: str, progress: bool) -> tuple[dict[str, Any], Any, Any]:
    import lightning as L

    from radaraug.training.data import RadarDataModule
    from radaraug.training.module import RDClassifier

    L.seed_everything(seed, workers=True, verbose=False)
    dm = RadarDataModule(task=task, method=method, dr_seed=seed, out_dir=str(run_dir),
                         train_items=settings.train_items, val_items=settings.val_items,
                         image_size=list(settings.image_size), batch_size=settings.batch_size,
                         num_workers=settings.num_workers, sim_workers=settings.sim_workers,
                         tracer_rays=settings.tracer_rays, proxy_frames_per_count=settings.proxy_frames_per_count,
                         profile_max_frames=settings.profile_max_frames, progress=progress, **({"randomization": settings.randomization} | data_kw))
    model = RDClassifier(task=task, lr=settings.lr, out_dir=str(run_dir))
    trainer = L.Trainer(max_epochs=settings.epochs, accelerator=accelerator, devices=1, logger=False,
                        enable_checkpointing=False, enable_model_summary=False, num_sanity_val_steps=0,
                        enable_progress_bar=False, default_root_dir=str(run_dir))
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*does not have many workers.*")
        warnings.filterwarnings("ignore", message=".*isinstance\\(treespec, LeafSpec\\).*")  # Lightning-internal
        trainer.fit(model, datamodule=dm)
        fit_s = time.perf_counter() - t0
        val_bacc = trainer.callback_metrics.get("val/balanced_accuracy")  # test() resets the metrics
        trainer.test(model, datamodule=dm, verbose=False)
    report = dict(model.last_test_report or {})
    report.update({"task": task, "method": method, "seed": seed, "fit_seconds": fit_s,
                   "clip_range_db": None if dm.clip is None else list(dm.clip), "val_balanced_accuracy": None if val_bacc is None else float(val_bacc)})
    atomic_write_json(run_dir / "run.json", report, newline=False, indent=2)
    return report, model, dm


def reproduce(
    out: str | os.PathLike,
    *,
    quick: bool = False,
    seeds: int = 3,
    calibration: str | None = None,
    test: Sequence[dict[str, Any]] | None = None,
    tasks: Sequence[str] = tuple(TASKS),
    methods: Sequence[str] = METHODS,
    ablation: bool = True,
    accelerator: str = "auto",
    progress: bool = True,
    settings: ReproduceSettings | None = None,
    cdr_floor: str | None = None,
    test_dr: bool = False,
) -> dict[str, Any]:
    """Run the experiment and write the report; return the ``report.json`` content.

    Args:
        out: output folder.
        quick: the quick settings (:meth:`ReproduceSettings.quick`) instead of the full ones.
        seeds: seeds per task x method (0 .. seeds-1).
        calibration: empty-room capture for CDR and for ``cdr_profile``'s twin profile (None: the
            held-out proxy's). A CalibratedDR JSON serves CDR but not ``cdr_profile``.
        test: test entries ``{"path", "count"?}`` (None: the held-out proxy).
        tasks: subset of ``occupancy``/``counting``.
        methods: subset of ``rt``/``randomdr``/``cdr``/``cdr_profile``.
        ablation: also train CDR without twin randomization.
        accelerator: Lightning accelerator (``auto`` uses a GPU when there is one).
        progress: progress bars.
        settings: explicit sizes (overrides ``quick``).
        cdr_floor: CalibratedDR's floor for the CDR methods: ``"normal"`` (the paper's; what None
            means for a capture) or ``"empirical"`` (the capture's measured distribution).
        test_dr: pass the test captures through each run's DR too (not the paper's protocol; see
            :class:`~radaraug.training.data.RadarDataModule`).
    """
    if seeds < 1:
        raise ConfigError(f"seeds must be >= 1, got {seeds}")
    for t in tasks:
        if t not in TASKS:
            raise ConfigError(f"unknown task {t!r}; choose from {sorted(TASKS)}")
    for m in methods:
        if m not in METHODS:
            raise ConfigError(f"unknown method {m!r}; choose from {METHODS}")
    if calibration is not None and is_calibration_json(calibration) and any(m in PROFILE_METHODS for m in methods):
        raise ConfigError(f"method 'cdr_profile' fits a twin profile on an empty-room capture, but the calibration "
                          f"{calibration!r} is a CalibratedDR JSON: give the capture, or leave cdr_profile out")
    settings = settings or (ReproduceSettings.quick() if quick else ReproduceSettings.full())
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    proxy_info = None
    if test is None or calibration is None:
        from radaraug.sim.proxy import make_proxy

        proxy = make_proxy(out / "proxy", frames_per_count=settings.proxy_frames_per_count, progress=progress)
        proxy_info = proxy.to_dict()
        if test is None:
            test = [{"path": str(p), "count": int(c)} for p, c in proxy.tests]
        if calibration is None:
            calibration = str(proxy.calibration)
    data_kw = {"calibration": calibration, "test": [dict(e) for e in test], "cache_dir": str(out / "cache"),
               "proxy_dir": str(out / "proxy"), "cdr_floor": cdr_floor, "test_dr": test_dr}

    variants: list[tuple[str, str, dict[str, Any]]] = [(m, m, {}) for m in methods]
    if ablation and "cdr" in methods:
        variants.append(("cdr_no_twin_randomization", "cdr", {"randomization": False}))
    results: dict[str, dict[str, Any]] = {}
    runs: list[dict[str, Any]] = []
    cms: dict[str, dict[str, torch.Tensor]] = {}
    keep: dict[tuple[str, str], tuple[Any, Any]] = {}
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

    # Lightning logs its hardware summary at every Trainer: 24 times is noise next to the run bar.
    for name in ("lightning.pytorch", "lightning.fabric"):
        logging.getLogger(name).setLevel(logging.WARNING)
    bar = tqdm(total=len(tasks) * len(variants) * seeds, desc="reproduce runs", disable=not progress)
    for task in tasks:
        results[task] = {}
        cms[task] = {}
        for name, method, extra in variants:
            per_seed: list[float] = []
            cm_sum: torch.Tensor | None = None
            for seed in range(seeds):
                run_dir = out / "runs" / f"{task}_{name}_seed{seed}"
                bar.set_postfix_str(f"{task} {name} seed {seed}")
                rep, model, dm = _run_one(task, method, seed, settings=settings, data_kw={**data_kw, **extra},
                                          run_dir=run_dir, accelerator=accelerator, progress=progress)
                bar.update(1)
                bar.write(f"{task:9s} {name:26s} seed {seed}: balanced accuracy {rep['balanced_accuracy']:.3f} "
                          f"(simulated val {rep['val_balanced_accuracy'] or float('nan'):.3f})")
                runs.append({k: rep[k] for k in ("task", "method", "seed", "balanced_accuracy", "accuracy",
                                                 "fit_seconds", "clip_range_db", "val_balanced_accuracy")}
                            | {"variant": name})
                per_seed.append(rep["balanced_accuracy"])
                cm = torch.tensor(rep["confusion_matrix"])
                cm_sum = cm if cm_sum is None else cm_sum + cm
                if seed == 0:
                    keep[(task, name)] = (model, dm)
            assert cm_sum is not None  # seeds >= 1 (checked above)
            results[task][name] = {
                "balanced_accuracy": _summary(per_seed),
                "accuracy": _summary([r["accuracy"] for r in runs if r["task"] == task and r["variant"] == name]),
                "confusion_matrix_sum_over_seeds": cm_sum.tolist(),
            }
            cms[task][name] = cm_sum
    bar.close()
    floors: dict[str, float] = {}
    figures = _figures(out / "figures", keep, cms, results, calibration, test, settings, floors)
    wall = time.perf_counter() - t_start
    report = {
        "kind": "sim-to-proxy" if proxy_info is not None else "sim-to-capture",
        "results": results,
        "runs": runs,
        "settings": asdict(settings) | {"seeds": seeds, "quick": quick, "tasks": list(tasks), "methods": list(methods),
                                        "cdr_floor": _cdr_floor_of(keep), "test_dr": test_dr},
        "test": [dict(e) for e in test],
        "calibration": calibration,
        "proxy": proxy_info,
        "figures": {k: str(Path(v).relative_to(out)) for k, v in figures.items()},
        "empty_room_median_db": floors,
        "twin_noise_fit": _noise_fit_of(keep),
        "twin_profile": _profile_of(keep, out),
        "wall_seconds": wall,
        "machine": {"platform": platform.platform(), "torch": torch.__version__,
                    "device": "cuda" if torch.cuda.is_available() and accelerator != "cpu" else "cpu",
                    "threads": torch.get_num_threads()},
        "db_convention": DB_CONVENTION,
    }
    atomic_write_json(out / "report.json", report, newline=False, indent=2)
    atomic_write_text(out / "report.md", _markdown(report))
    return report


def _noise_fit_of(keep: dict) -> dict[str, Any] | None:
    """The twin's noise-figure fit of the runs (they share it), if any."""
    for _model, dm in keep.values():
        if getattr(dm, "noise_fit", None) is not None:
            return dm.noise_fit
    return None


def _profile_of(keep: dict, out: Path) -> dict[str, Any] | None:
    """The twin profile of the ``cdr_profile`` runs (they share it).

    Where it came from, the effects the fit added and the diagnose error before / after
    (``profile.fitted_on``).
    """
    for _model, dm in keep.values():
        info = getattr(dm, "profile_info", None)
        if info is not None:
            info = dict(info)
            try:
                info["path"] = str(Path(info["path"]).resolve().relative_to(out.resolve()))
            except (KeyError, TypeError, ValueError):
                pass
            return info
    return None


def _maps_of(cache_dm: Any, count: int, n: int) -> torch.Tensor:
    ds = cache_dm._train.base  # CachedMaps of the run
    idx = (ds.counts == count).nonzero().flatten()[:n]
    return ds.maps(idx.tolist()) if len(idx) else torch.empty(0, *ds.map_shape)


def _capture_maps(path: str, n: int) -> torch.Tensor:
    from radaraug.io import open_capture
    from radaraug.training.chain import rd_db_chain

    with open_capture(path) as cap:
        x = cap.read(0, min(n, cap.num_frames))
    return rd_db_chain()(x)


def _figures(fig_dir: Path, keep: dict, cms: dict, results: dict, calibration: str | None,
             test: Sequence[dict[str, Any]], settings: ReproduceSettings, floors: dict[str, float]) -> dict[str, Path]:
    """Write the figures; fill ``floors`` with the median empty-room RD level (dB) of each source.

    The sources: simulation, simulation + CDR, the calibration capture and, with ``cdr_profile`` runs, the
    profile twin with and without CDR (Fig. 4's data).
    """
    from radaraug.training import figures as F

    figs: dict[str, Path] = {}
    for task, by_method in cms.items():
        names = TASKS[task]
        n = "fig8" if task == "occupancy" else "fig9"
        figs[f"{n}_confusion_{task}"] = F.confusion_grid(by_method, names, fig_dir / f"{n}_confusion_{task}.png",
                                                          f"{task}: confusion matrices (summed over seeds)")
    figs["results"] = F.results_bars(results, fig_dir / "balanced_accuracy.png")
    task = next(iter(cms))
    cdr_run = keep.get((task, "cdr"))
    rt_run = keep.get((task, "rt"))
    prof_run = keep.get((task, "cdr_profile"))
    if cdr_run is None or calibration is None or is_calibration_json(calibration):
        return figs
    dm = cdr_run[1]
    sim_empty = _maps_of(dm, 0, 64)
    sim_one = _maps_of(dm, 1, 64)
    real_empty = _capture_maps(calibration, 64)
    one = [e for e in test if e.get("count") == 1]
    real_one = _capture_maps(one[0]["path"], 64) if one else None
    with torch.no_grad():
        cdr_empty, cdr_one = dm.dr.train()(sim_empty), dm.dr.train()(sim_one)
    groups = {"simulation": sim_empty, "simulation + CDR": cdr_empty}
    median_of = {"simulation": sim_empty, "simulation_cdr": cdr_empty}
    prof_empty = prof_one = None
    if prof_run is not None:
        pdm = prof_run[1]
        prof_empty, prof_one = _maps_of(pdm, 0, 64), _maps_of(pdm, 1, 64)
        with torch.no_grad():
            prof_cdr_empty = pdm.dr.train()(prof_empty)
            prof_one = pdm.dr.train()(prof_one)
        groups |= {"profile twin": prof_empty, "profile twin + CDR": prof_cdr_empty}
        median_of |= {"simulation_profile": prof_empty, "simulation_profile_cdr": prof_cdr_empty}
        prof_empty = prof_cdr_empty
    groups["empty-room capture"] = real_empty
    median_of["capture"] = real_empty
    for key, maps in median_of.items():
        v = maps.float().flatten()
        floors[key] = round(float(v[torch.isfinite(v) & (v > -250)].median()), 2)
    figs["fig4_noise_floor"] = F.noise_floor_histograms(groups, fig_dir / "fig4_noise_floor_histograms.png")
    vmin, vmax = dm.clip
    cfg = dm.config
    rows = {"empty": [("sim", sim_empty[0]), ("sim + CDR", cdr_empty[0])]
            + ([("profile sim + CDR", prof_empty[0])] if prof_empty is not None and len(prof_empty) else [])
            + [("capture", real_empty[0])]}
    if real_one is not None and len(sim_one):
        rows["one person"] = ([("sim", sim_one[0]), ("sim + CDR", cdr_one[0])]
                              + ([("profile sim + CDR", prof_one[0])] if prof_one is not None and len(prof_one) else [])
                              + [("capture", real_one[len(real_one) // 2])])
    figs["fig5_rd_triplets"] = F.rd_triplets(rows, fig_dir / "fig5_rd_triplets.png", vmin=vmin, vmax=vmax,
                                             range_max_m=float(cfg.max_range_m), v_max_m_s=float(cfg.max_velocity_m_s))
    energy = {"simulation": torch.cat([sim_empty, sim_one]), "simulation + CDR": torch.cat([cdr_empty, cdr_one]),
              "empty-room capture": real_empty}
    if real_one is not None:
        energy["1-person capture"] = real_one
    figs["fig6_static_energy"] = F.static_energy_plot(energy, fig_dir / "fig6_static_to_total_energy.png")
    if rt_run is not None and real_one is not None and len(sim_one):
        inputs = {"simulated": dm.images(sim_one[:1])[0], "capture": dm.images(real_one[len(real_one) // 2:][:1])[0]}
        models = {"RT": rt_run[0].net, "CDR": cdr_run[0].net}
        if prof_run is not None:
            models["CDR-profile"] = prof_run[0].net
        figs["fig7_feature_maps"] = F.feature_maps(models, inputs, fig_dir / "fig7_feature_maps.png")
    return figs


def _fmt(s: dict[str, Any]) -> str:
    return f"{s['mean']:.3f} ± {s['std']:.3f}"


def _markdown(rep: dict[str, Any]) -> str:
    lines = ["# radaraug reproduce: train on the twin, test on captures", ""]
    if rep["kind"] == "sim-to-proxy":
        lines += ["**These are sim-to-proxy numbers, not sim-to-real.** The test captures are the held-out proxy "
                  "that radaraug generates from a deliberately different twin configuration (another room with "
                  "clutter, another motion source, other sensor effects; docs/proxy.md). They show that training "
                  "survives a twin it was not made with; they are not a measurement on a real sensor.", ""]
    else:
        lines += ["Test captures: " + ", ".join(f"`{e['path']}`" + (f" (count {e['count']})" if e.get('count') is not None else " (per-frame labels)") for e in rep["test"]), ""]
    st = rep["settings"]
    sets = ("; `cdr_profile` trains on a second set of that size, simulated with the twin profile's receiver"
            if "cdr_profile" in st.get("methods", []) else "")
    lines += [f"Seeds: {st['seeds']} (network init, DR draws, batch order; one shared simulated set of "
              f"{st['train_items']} training + {st['val_items']} validation items{sets}). Epochs {st['epochs']}, image "
              f"{st['image_size'][0]}x{st['image_size'][1]}, {'quick' if st['quick'] else 'full'} mode. "
              f"Wall time {rep['wall_seconds'] / 60:.1f} min on {rep['machine']['device']}."
              + (f" CalibratedDR floor: {st['cdr_floor']}"
                 f"{' (the paper’s normal in dB)' if st['cdr_floor'] == 'normal' else ' (the capture’s measured distribution)'}."
                 if st.get("cdr_floor") else "")
              + (" **Test captures went through each run's DR too (`test_dr`), not the paper's protocol.**"
                 if st.get("test_dr") else ""), "",
              "## Balanced accuracy (mean ± std over seeds)", "",
              "| task | " + " | ".join(next(iter(rep["results"].values())).keys()) + " |",
              "|---|" + "---|" * len(next(iter(rep["results"].values()))), ]
    for task, by in rep["results"].items():
        lines.append(f"| {task} | " + " | ".join(_fmt(v["balanced_accuracy"]) for v in by.values()) + " |")
    lines += ["", "Paper (real corridor): occupancy 97 % CDR, ~83 % RandomDR, ~50 % RT; counting 72 % / ~61 % / ~33 %.", ""]
    order = []
    for task, by in rep["results"].items():
        m = {k: v["balanced_accuracy"]["mean"] for k, v in by.items()}
        if all(k in m for k in ("rt", "randomdr", "cdr")):
            holds = m["rt"] < m["randomdr"] < m["cdr"]
            order.append(f"- {task}: paper's ordering RT < RandomDR < CDR {'holds' if holds else 'does NOT hold'} "
                         f"({m['rt']:.3f} / {m['randomdr']:.3f} / {m['cdr']:.3f}).")
        if "cdr_profile" in m and "cdr" in m:
            order.append(f"- {task}: CDR on the profile twin {m['cdr_profile']:.3f} vs CDR on the noise-fitted twin "
                         f"{m['cdr']:.3f}.")
        if "cdr_no_twin_randomization" in m and "cdr" in m:
            order.append(f"- {task}: twin randomization ablation: CDR {m['cdr']:.3f} with vs "
                         f"{m['cdr_no_twin_randomization']:.3f} without.")
    floors = rep.get("empty_room_median_db") or {}
    if floors and "simulation_cdr" in floors and floors["simulation_cdr"] > floors["capture"] + 1.0:
        fit = rep.get("twin_noise_fit")
        why = (f"The twin's noise figure was fitted to the calibration capture ({fit['noise_figure_dB']:.1f} dB), "
               "so" if fit else "So")
        order.append(
            f"- CDR raises the simulated empty-room floor above the capture's: median {floors['simulation']:.1f} dB "
            f"(simulation) -> {floors['simulation_cdr']:.1f} dB (simulation + CDR) against {floors['capture']:.1f} dB "
            f"(capture). {why} the simulated floor already sits near the capture's and the clamp "
            "max(S, N) adds a second, i.i.d. floor on top: training sees a higher, rougher floor than the test "
            "captures have, which penalises CDR against RT (see docs/training.md, 'What the numbers show').")
    lines += ["## Ordering and ablation", "", *order, ""]
    prof = rep.get("twin_profile")
    if prof:
        def db(v: Any) -> str:
            return "n/a" if v is None else f"{v:.3f} dB"

        added = ", ".join(f"`{e}`" for e in prof.get("effects_added") or []) or "none"
        how = ("fitted by `radaraug diagnose` on the calibration capture"
               if str(prof.get("source", "")).startswith("fitted") else "given as `data.profile`")
        frames = f", {prof['max_frames']} frames read" if prof.get("max_frames") else ""
        lines += ["## Twin profile (`cdr_profile`)", "",
                  f"The `cdr_profile` runs simulate with the twin profile {how} (`{prof.get('path')}`; capture "
                  f"`{prof.get('capture')}`, {prof.get('mode')} scene{frames}) instead of the noise-figure fit.", "",
                  f"- effects added by the fit: {added}",
                  f"- diagnose error (held-out frames): {db(prof.get('error_before_dB'))} before -> "
                  f"{db(prof.get('error_after_dB'))} after",
                  "- chain: " + " -> ".join(prof.get("effects") or []), ""]
        if "simulation_profile" in floors:
            lines += [f"Empty-room median RD level: profile twin {floors['simulation_profile']:.1f} dB, "
                      f"+ CDR {floors['simulation_profile_cdr']:.1f} dB, capture {floors['capture']:.1f} dB "
                      f"(noise-fitted twin {floors['simulation']:.1f} dB, + CDR {floors['simulation_cdr']:.1f} dB).",
                      ""]
    lines += ["## Figures", ""]
    for key, rel in rep["figures"].items():
        lines.append(f"![{key}]({rel})")
    lines += ["", "## Runs", "", "| task | variant | seed | balanced acc. | accuracy | val bal. acc. (sim) | clip range dB | fit s |",
              "|---|---|---|---|---|---|---|---|"]
    for r in rep["runs"]:
        val = "n/a" if r["val_balanced_accuracy"] is None else f"{r['val_balanced_accuracy']:.3f}"
        lines.append(f"| {r['task']} | {r['variant']} | {r['seed']} | {r['balanced_accuracy']:.3f} | "
                     f"{r['accuracy']:.3f} | {val} | {r['clip_range_db'][0]:.1f} .. {r['clip_range_db'][1]:.1f} | "
                     f"{r['fit_seconds']:.0f} |")
    lines += ["", f"dB convention: {rep['db_convention']}.", ""]
    return "\n".join(lines)

