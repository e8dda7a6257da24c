"""`radaraug reproduce`: the paper's experiment (Sec. 2.2-3) end to end, with a report.

2 tasks x the methods x N seeds per test set, plus ablations; writes ``OUT/report.md``, ``OUT/report.json``,
per-run metrics and the paper's figures (docs/training.md, "radaraug reproduce").
"""

from __future__ import annotations

import contextlib
import inspect
import json
import logging
import os
import platform
import statistics
import time
import warnings
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import asdict, dataclass, fields, replace
from pathlib import Path
from typing import Any

import torch

from radaraug import recipes
from radaraug._optional import lazy_import
from radaraug.errors import ConfigError
from radaraug.files import atomic_write_json, atomic_write_text
from radaraug.testsets.tasks import TASKS
from radaraug.training.classifier_file import classifier_record, save_checkpoint
from radaraug.training.methods import METHODS
from radaraug.training.pipeline import is_calibration_json
from radaraug.transforms.record_file import load_record
from radaraug.units import DB_CONVENTION

#: A :class:`ReproduceSettings` field left to the recipes (``radaraug.recipes``): the run takes the value
#: of its recipe (base + task + method [+ ablation]).
RECIPE = "recipe"
#: Each run's classifier file in its run folder (radaraug predict runs it; docs/predict.md).
CLASSIFIER_FILE = "classifier.pt"


@dataclass(frozen=True)
class ReproduceSettings:
    """Sizes of one reproduce run (``quick()`` for a 2-core CPU in minutes, ``full()`` for a GPU).

    The hyperparameters of the runs come from the recipes (:mod:`radaraug.recipes`): the fields of
    :data:`RECIPE_KEYS` are ``"recipe"`` (take the recipe's value) unless set to override it for
    every run of the experiment.
    """

    train_items: int = 6000
    val_items: int = 600
    epochs: int = 15
    image_size: tuple[int, int] = (128, 64)
    batch_size: int = 64
    lr: float | str = RECIPE
    proxy_frames_per_count: int = 300
    tracer_rays: int | None = None
    num_workers: int = 2
    sim_workers: int = 2
    #: twin randomization of the main runs: True (defaults), or a dict of TwinRandomization fields
    randomization: bool | dict[str, Any] | str = RECIPE
    #: calibration-capture frames that ``cdr_profile``'s diagnose reads (fits on half, scores on half)
    profile_max_frames: int = 100
    #: frames of causal context at test (``RDClassifier.context_frames``; 1: single frames, the paper's protocol)
    context_frames: int | str = RECIPE
    #: network input of the main runs (``RadarDataModule.representation``)
    representation: str = RECIPE
    #: how the map shrinks to ``image_size``: ``bilinear`` or ``max`` (``ImageSpec.resample``)
    resample: str = RECIPE
    #: Doppler bins blanked on each side of zero in floor-relative maps (``RadarDataModule.blank_zero_doppler``)
    blank_zero_doppler: int | str = RECIPE
    #: stop a run once simulated validation balanced accuracy has not risen for this many epochs and test
    #: the best epoch's weights (None: train ``epochs`` epochs and test the last)
    early_stopping_patience: int | None = None
    #: margin of the zero-Doppler change gate fused beside every run (:class:`radaraug.detection.StaticChangeDetector`,
    #: fitted on each test set's empty-room capture; None: no gate)
    static_gate_margin_db: float | None = 3.0
    #: write each run's classifier file (``runs/.../classifier.pt``, ~45 MB for a ResNet18; docs/predict.md)
    keep_classifiers: bool = True
    #: methods run unless ``reproduce(methods=...)`` names them
    methods: tuple[str, ...] = tuple(METHODS)
    #: generated test sets used when no test captures are given (:data:`DEFAULT_TEST_SETS`)
    test_sets: tuple[str, ...] = ("proxy", "independent")
    #: worlds per held-out suite (``design``/``report`` in ``test_sets``; None: ``radaraug.testsets.independent.worlds.DEFAULT_WORLDS``)
    worlds: int | None = None
    #: excise the calibration capture's persistent lines from floor-relative maps (``RadarDataModule.excise_persistent_db``)
    excise_persistent_db: float | None | str = RECIPE
    #: replace the chirps another radar's burst hit before the RD FFTs (``ImageSpec.excise_interference_db``)
    excise_interference_db: float | None | str = RECIPE
    #: fit the twin's noise figure to each calibration capture (``RadarDataModule.calibrate_noise``)
    calibrate_noise: bool | str = RECIPE
    #: counting's training labels: ``drawn`` or ``observable`` (``TwinSplits.count_labels``)
    count_labels: str = RECIPE
    #: CDR's twin noise below the others' (``RadarDataModule.cdr_twin_noise_offset_db``)
    cdr_twin_noise_offset_db: float | None | str = RECIPE
    #: CalibratedDR floor of the CDR methods (``RadarDataModule.cdr_floor``)
    cdr_floor: str | None = RECIPE
    #: ablation variants (``recipes/ablation/NAME.yaml``) run unless ``reproduce(ablation=False)``
    ablations: tuple[str, ...] = ("rt_paper_image", "randomdr_paper_image", "cdr_paper_image", "cdr_normal_floor",
                                  "cdr_empirical_floor", "rt_no_twin_randomization", "rt_noise_fit")

    @classmethod
    def full(cls) -> ReproduceSettings:
        """The default: sized for a GPU (hours on a 2-core CPU)."""
        return cls()

    @classmethod
    def quick(cls) -> ReproduceSettings:
        """Minutes on a 2-core CPU: fewer items and epochs, half-size images, a 40-frame ``cdr_profile`` diagnose."""
        return cls(train_items=800, val_items=90, epochs=4, image_size=(64, 32), batch_size=32,
                   proxy_frames_per_count=60, num_workers=0, sim_workers=2, profile_max_frames=40,
                   methods=("rt", "randomdr", "cdr"), ablations=(), test_sets=("independent",))


#: The settings fields that override a recipe key when set (those whose default is ``"recipe"``): field ->
#: the recipe key's path. A ``data.method.init_args`` key is set only where the run's method takes it.
RECIPE_KEYS: dict[str, tuple[str, ...]] = {
    "lr": ("model", "lr"), "context_frames": ("model", "context_frames"),
    "randomization": ("data", "twin", "randomization"), "calibrate_noise": ("data", "twin", "calibrate_noise"),
    "count_labels": ("data", "twin", "count_labels"),
    "representation": ("data", "image", "representation"), "resample": ("data", "image", "resample"),
    "blank_zero_doppler": ("data", "image", "blank_zero_doppler"),
    "excise_persistent_db": ("data", "image", "excise_persistent_db"),
    "excise_interference_db": ("data", "image", "excise_interference_db"),
    "cdr_twin_noise_offset_db": ("data", "method", "init_args", "twin_noise_offset_db"),
    "cdr_floor": ("data", "method", "init_args", "floor"),
}
assert set(RECIPE_KEYS) == {f.name for f in fields(ReproduceSettings) if f.default == RECIPE}
#: The settings fields that set a recipe key whatever the recipe says (sizes and workers): field -> path.
SIZE_KEYS: dict[str, tuple[str, ...]] = {
    "train_items": ("data", "twin", "train_items"), "val_items": ("data", "twin", "val_items"),
    "tracer_rays": ("data", "twin", "tracer_rays"), "sim_workers": ("data", "twin", "workers"),
    "image_size": ("data", "image", "size"), "batch_size": ("data", "batch_size"),
    "num_workers": ("data", "num_workers"), "profile_max_frames": ("data", "method", "init_args", "max_frames"),
}


def _set_key(cfg: dict[str, Any], path: tuple[str, ...], value: Any) -> None:
    """``cfg[path] = value``; a method argument only where the recipe's method takes it."""
    if path[:3] == ("data", "method", "init_args"):
        name = recipes.method_of(cfg.get("data", {}).get("method"))
        if name is None or path[3] not in inspect.signature(METHODS[name]).parameters:
            return
    *parents, key = path
    node = cfg
    for p in parents:
        node = node.setdefault(p, {})
    node[key] = value


def _get_key(cfg: dict[str, Any], path: tuple[str, ...]) -> Any:
    for p in path:
        cfg = cfg.get(p, {}) if isinstance(cfg, dict) else {}
    return None if cfg == {} else cfg


def parse_test_arg(text: str) -> dict[str, Any]:
    """``PATH`` or ``PATH:COUNT`` -> a test entry (:func:`radaraug.testsets.checks.parse_test_entry`)."""
    from radaraug.testsets.checks import parse_test_entry

    return parse_test_entry(text, "--test")


def _check_known(kind: str, names: Sequence[str], known: Sequence[str]) -> None:
    """ConfigError for the first of ``names`` that is not in ``known`` (the message lists them)."""
    for name in names:
        if name not in known:
            raise ConfigError(f"unknown {kind} {name!r}; choose from {known}")


def _summary(values: Sequence[float]) -> dict[str, Any]:
    vals = [float(v) for v in values]
    return {"mean": statistics.fmean(vals), "std": statistics.pstdev(vals), "per_seed": vals}


def _cdr_floor_of(keep: dict[tuple[str, str, str], tuple[Any, Any]], settings: ReproduceSettings) -> str | None:
    """The floor the main CDR runs drew from (None when no CDR method ran)."""
    from radaraug.transforms import CalibratedDR

    if not any(isinstance(dm.dr, CalibratedDR) for _, dm in keep.values()):
        return None
    floors = {dm.method.floor or dm.dr.floor for (_, _, n), (_, dm) in keep.items()
              if n in METHODS and dm.method.needs_calibration and isinstance(dm.dr, CalibratedDR)}
    return floors.pop() if len(floors) == 1 else effective_settings(settings)["cdr_floor"]


#: The held-out test sets ``reproduce`` generates when no test captures are given: the twin in
#: another room (:mod:`radaraug.testsets.proxy`) and a NumPy generator that shares no simulation code
#: with the twin (:mod:`radaraug.testsets.independent`). Each comes with its own empty-room capture.
DEFAULT_TEST_SETS = ("proxy", "independent")
#: The held-out suites of test worlds (:mod:`radaraug.testsets.independent.worlds`): ``design`` (look at it freely;
#: its numbers are validation numbers), ``report`` (run only to report) and the spent report suites
#: (``report-1`` … ``report-3``: rerun their records; validation numbers now). Each world is a test set.
SUITE_TEST_SETS = ("design", "report", "report-1", "report-2", "report-3")
#: Every generated test set ``--test-sets`` may name: the defaults, ``standing`` (the independent
#: generator with standing (breathing, swaying) people in 30 % of the drawn people, another seed) and
#: the suites of :data:`SUITE_TEST_SETS`.
GENERATED_TEST_SETS = (*DEFAULT_TEST_SETS, "standing", *SUITE_TEST_SETS)
#: Seed and standing probability of the ``standing`` set.
STANDING_SEED, STANDING_PROBABILITY = 2025, 0.3

#: Ablation variants: name -> (the method whose run it changes, the data keys it changes). Each is a
#: recipe override (``recipes/ablation/NAME.yaml``) that changes one thing of the method's
#: run, so its row of the report measures it.
ABLATIONS: dict[str, tuple[str, dict[str, Any]]] = {name: recipes.ablation(name) for name in recipes.ablations()}


def run_recipe(task: str, method: str, settings: ReproduceSettings, ablation: str | None = None) -> dict[str, Any]:
    """The recipe of one run: base + task + method (+ the ablation), with ``settings``' overrides."""
    cfg = recipes.compose(f"{task}_{method}")
    for field, path in RECIPE_KEYS.items():
        value = getattr(settings, field)
        if not (isinstance(value, str) and value == RECIPE):
            _set_key(cfg, path, value)
    if ablation is not None:  # last: an ablation's one change wins over the experiment's settings
        cfg = recipes.merge(cfg, recipes.compose(f"ablation/{ablation}"))
    return cfg


def effective_settings(settings: ReproduceSettings) -> dict[str, Any]:
    """``settings`` as a mapping with every ``"recipe"`` field replaced by the recipes' value.

    The data keys of the CDR methods (``cdr_floor``, ``cdr_twin_noise_offset_db``) are read from the
    ``cdr`` method's recipe; the others from the base recipe.
    """
    cfg = run_recipe("occupancy", "cdr", settings)
    return asdict(settings) | {field: _get_key(cfg, path) for field, path in RECIPE_KEYS.items()}


@dataclass
class TestSet:
    """One test side: labelled captures and the empty-room capture that calibrates for them."""

    name: str
    calibration: str | None
    tests: list[dict[str, Any]]
    info: dict[str, Any] | None = None
    suite: str | None = None


def _test_sets(out: Path, settings: ReproduceSettings, calibration: str | None,
               test: Sequence[dict[str, Any]] | None, names: Sequence[str], progress: bool) -> list[TestSet]:
    """The user's captures, or the generated held-out sets named in ``names``."""
    if test is not None:
        if not test:
            raise ConfigError("reproduce: the test set is empty; give labelled test captures (--test PATH[:COUNT])")
        if calibration is None:
            raise ConfigError("reproduce --test needs --calibration: an empty-room capture recorded like the test "
                              "captures (CDR and the twin's noise fit calibrate on it; without one they would "
                              "calibrate on a generated room that has nothing to do with yours)")
        return [TestSet("captures", calibration, [dict(e) for e in test])]
    if calibration is not None:
        raise ConfigError("reproduce --calibration without --test: the generated test sets bring their own "
                          "empty-room captures; give the test captures recorded with your calibration")
    _check_known("test set", names, GENERATED_TEST_SETS)
    if not names:
        raise ConfigError(f"no test set: name at least one of {GENERATED_TEST_SETS}, or give --test captures")
    sets = []
    for name in names:
        if name in SUITE_TEST_SETS:
            from radaraug.testsets.independent.worlds import make_suite

            for world, made in make_suite(out / "worlds", name, worlds=settings.worlds,
                                          frames_per_count=settings.proxy_frames_per_count, progress=progress):
                sets.append(TestSet(world.name, str(made.calibration),
                                    [{"path": str(p), "count": int(c)} for p, c in made.tests],
                                    made.to_dict() | {"world": world.to_dict()}, suite=name))
            continue
        if name == "proxy":
            from radaraug.testsets.proxy import make_proxy

            proxy: Any = make_proxy(out / "proxy", frames_per_count=settings.proxy_frames_per_count, progress=progress)
        else:  # "independent" or "standing"
            from radaraug.testsets.independent import make_independent_set

            standing: dict[str, Any] = {"seed": STANDING_SEED, "standing_probability": STANDING_PROBABILITY}
            proxy = make_independent_set(out / name, frames_per_count=settings.proxy_frames_per_count,
                                           progress=progress, **(standing if name == "standing" else {}))
        sets.append(TestSet(name, str(proxy.calibration),
                            [{"path": str(p), "count": int(c)} for p, c in proxy.tests], proxy.to_dict()))
    return sets


def _shared_across_test_sets(data: dict[str, Any]) -> bool:
    """True when a run does not depend on the calibration capture (train once, test on every set)."""
    from radaraug.training.methods import method_from
    from radaraug.training.preparation import ImageSpec, TwinSplits

    twin, image = TwinSplits(**data.get("twin", {})), ImageSpec(**data.get("image", {}))
    # the excision mask of floor_relative maps comes from the calibration capture too
    return (not method_from(data["method"]).needs_calibration and not twin.calibrate_noise and twin.profile is None
            and not image.excises and twin.catalog_priors == "physics")


@torch.no_grad()
def _scores(model: Any, dm: Any, loader: Any, *, with_dr: bool, limit: int = 512) -> tuple[torch.Tensor, torch.Tensor]:
    """Class probabilities and labels of up to ``limit`` items of ``loader`` (simulated splits with the DR)."""
    model.eval()
    probs, labels = [], []
    n = 0
    for x, y in loader:
        x = x.to(model.device)
        if with_dr and dm.dr is not None:
            x = dm.dr.to(x.device).train()(x)
        probs.append(torch.softmax(model(dm.image.to(x.device)(x)).float(), dim=1).cpu())
        labels.append(torch.as_tensor(y).cpu())
        n += len(y)
        if n >= limit:
            break
    return torch.cat(probs)[:limit], torch.cat(labels)[:limit]


def _fit(task: str, seed: int, *, settings: ReproduceSettings, data_kw: dict[str, Any],
         model_kw: dict[str, Any], run_dir: Path, accelerator: str,
         progress: bool) -> tuple[Any, Any, Any, float, float | None]:
    """Train one run: ``data_kw`` / ``model_kw`` are its recipe's sections with this experiment's inputs."""
    import lightning as L

    from radaraug.training.data import RadarDataModule
    from radaraug.training.module import RDClassifier

    L.seed_everything(seed, workers=True, verbose=False)
    dm = RadarDataModule.from_recipe(recipes.merge(data_kw, {"task": task, "seed": seed, "twin": {"progress": progress}}))
    model = RDClassifier(**(model_kw | {"task": task, "out_dir": str(run_dir)}))
    trainer = _trainer(settings, accelerator, run_dir, fitting=True)
    t0 = time.perf_counter()
    with _quiet():
        trainer.fit(model, datamodule=dm)
    val_bacc = trainer.callback_metrics.get("val/balanced_accuracy")  # test() resets the metrics
    best = trainer.checkpoint_callback  # None unless early stopping set one up (_trainer)
    if best is not None and best.best_model_path:
        # the best epoch's weights, and its validation score (not the last epoch's)
        model.load_state_dict(torch.load(best.best_model_path, map_location="cpu", weights_only=False)["state_dict"])
        val_bacc = best.best_model_score
    return model, dm, trainer, time.perf_counter() - t0, None if val_bacc is None else float(val_bacc)


def _sized(recipe: dict[str, Any], settings: ReproduceSettings) -> dict[str, Any]:
    """``recipe`` with the keys ``reproduce`` sets from its settings (:data:`SIZE_KEYS`), whatever it says."""
    out = recipes.merge(recipe, {})
    for field, path in SIZE_KEYS.items():
        value = getattr(settings, field)
        _set_key(out, path, list(value) if field == "image_size" else value)
    return out


def _trainer(settings: ReproduceSettings, accelerator: str, run_dir: Path, *, fitting: bool = False) -> Any:
    import lightning as L

    callbacks: list[Any] = []
    patience = settings.early_stopping_patience
    if fitting and patience is not None:
        from lightning.pytorch.callbacks import EarlyStopping, ModelCheckpoint

        metric = "val/balanced_accuracy"
        callbacks = [EarlyStopping(monitor=metric, mode="max", patience=patience),
                     ModelCheckpoint(dirpath=run_dir / "best", filename="best", monitor=metric, mode="max", save_top_k=1)]
    return L.Trainer(max_epochs=settings.epochs, accelerator=accelerator, devices=1, logger=False,
                     enable_checkpointing=bool(callbacks), callbacks=callbacks, enable_model_summary=False,
                     num_sanity_val_steps=0, enable_progress_bar=False, default_root_dir=str(run_dir))


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Silence Lightning's warnings that say nothing about the run (few workers, a pytree internal)."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*does not have many workers.*")
        warnings.filterwarnings("ignore", message=".*isinstance\\(treespec, LeafSpec\\).*")  # Lightning-internal
        yield


def _test(model: Any, dm: Any, trainer: Any, run_dir: Path) -> dict[str, Any]:
    """Test ``model`` on ``dm``'s test captures (no DR unless ``test_dr``); the classification report."""
    model.hparams["out_dir"] = str(run_dir)
    with _quiet():
        trainer.test(model, datamodule=dm, verbose=False)
    return dict(model.last_test_report or {})


def _test_dm(trained: Any, ts: TestSet, data_kw: dict[str, Any], run_dir: Path) -> Any:
    """A data module for testing a model trained with ``trained`` (its clip range) on test set ``ts``."""
    from radaraug.training.data import RadarDataModule

    dm = RadarDataModule.from_recipe(dict(trained.hparams) | {"calibration": ts.calibration, "test": ts.tests})
    dm.clip, dm.excise = trained.clip, trained.excise
    return dm


def reproduce(
    out: str | os.PathLike,
    *,
    quick: bool = False,
    seeds: int = 3,
    calibration: str | None = None,
    test: Sequence[dict[str, Any]] | None = None,
    tasks: Sequence[str] = tuple(TASKS),
    methods: Sequence[str] | None = None,
    ablation: bool = True,
    ablations: Sequence[str] | None = None,
    test_sets: Sequence[str] | None = None,
    accelerator: str = "auto",
    progress: bool = True,
    settings: ReproduceSettings | None = None,
    cdr_floor: str | None = None,
    test_dr: bool = False,
    worlds: int | None = None,
) -> dict[str, Any]:
    """Run the experiment and write the report; return the ``report.json`` content.

    Args:
        out: output folder.
        quick: the quick settings (:meth:`ReproduceSettings.quick`) instead of the full ones.
        seeds: seeds per task x method (0 .. seeds-1).
        calibration: empty-room capture of the test captures (CDR, noise fit, ``cdr_profile``'s profile);
            required with ``test``, refused without it. A calibration record (JSON) serves what it holds.
        test: test entries ``{"path", "count"?}`` (None: the generated ``test_sets``).
        tasks: subset of ``occupancy``/``counting``.
        methods: subset of ``rt``/``randomdr``/``cdr``/``cdr_profile`` (None: the settings').
        ablation: run the ablation variants (``ablations``, default: the settings' list).
        ablations: names from :data:`ABLATIONS` (None: ``settings.ablations``).
        test_sets: the generated test sets used when ``test`` is None (None: the settings'; names from
            :data:`GENERATED_TEST_SETS`; ``design``/``report`` add one test set per world of the suite).
        accelerator: Lightning accelerator (``auto`` uses a GPU when there is one).
        progress: progress bars.
        settings: explicit sizes (overrides ``quick``).
        cdr_floor: CalibratedDR's floor for the CDR methods, ``"matched"``, ``"normal"`` or ``"empirical"``
            (None: the settings'; :class:`~radaraug.training.data.RadarDataModule`).
        test_dr: pass the test captures through each run's DR too (not the paper's protocol).
        worlds: worlds per held-out suite (``design``/``report`` in ``test_sets``; None: the settings').
    """
    if seeds < 1:
        raise ConfigError(f"seeds must be >= 1, got {seeds}")
    _check_known("task", tasks, sorted(TASKS))
    mode = "custom" if settings is not None else "quick" if quick else "full"
    settings = settings or (ReproduceSettings.quick() if quick else ReproduceSettings.full())
    if cdr_floor is not None:
        settings = replace(settings, cdr_floor=cdr_floor)
    if worlds is not None:
        settings = replace(settings, worlds=worlds)
    methods = tuple(settings.methods if methods is None else methods)
    test_sets = tuple(settings.test_sets if test_sets is None else test_sets)
    _check_known("method", methods, list(METHODS))
    if (calibration is not None and is_calibration_json(calibration) and any(METHODS[m].fits_profile for m in methods)
            and load_record(calibration).profile is None):
        raise ConfigError(f"method 'cdr_profile' fits a twin profile on an empty-room capture, but the calibration "
                          f"{calibration!r} is a calibration record without one: give the capture, or leave "
                          "cdr_profile out")

    names = list(settings.ablations if ablations is None else ablations) if ablation else []
    _check_known("ablation", names, sorted(ABLATIONS))
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    sets = _test_sets(out, settings, calibration, test, test_sets, progress)
    from radaraug.testsets.checks import check_test_set
    from radaraug.training.inputs import CalibrationWarning

    for ts in sets:
        for task in tasks:
            check_test_set(ts.tests, task)

    gates = {ts.name: _static_gate(ts, settings.static_gate_margin_db) for ts in sets}
    for ts in sets:
        if settings.static_gate_margin_db is not None and gates[ts.name] is None:
            what = "no calibration" if ts.calibration is None else f"calibration {ts.calibration} is a calibration record (no frames)"
            warnings.warn(f"test set {ts.name}: {what}, so no static-change gate is fitted: the report has no "
                          "gated accuracies (+ static gate) and its classifier files no gate; give the empty-room "
                          "capture itself", CalibrationWarning, stacklevel=2)
    # (row name, method, ablation override or None): every run is its recipe (+ the ablation)
    variants: list[tuple[str, str, str | None]] = [(m, m, None) for m in methods]
    variants += [(n, ABLATIONS[n][0], n) for n in names if ABLATIONS[n][0] in methods]
    results: dict[str, dict[str, dict[str, Any]]] = {ts.name: {} for ts in sets}
    runs: list[dict[str, Any]] = []
    keep: dict[tuple[str, str, str], tuple[Any, Any]] = {}
    scores: dict[str, dict[str, dict[str, dict[str, tuple[torch.Tensor, torch.Tensor]]]]] = {ts.name: {} for ts in sets}
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

    # Lightning logs its hardware summary at every Trainer: dozens of times is noise next to the run bar.
    for name in ("lightning.pytorch", "lightning.fabric"):
        logging.getLogger(name).setLevel(logging.WARNING)
    bar = tqdm(total=len(sets) * len(tasks) * len(variants) * seeds, desc="reproduce runs", disable=not progress)
    shared: dict[tuple[str, str, int, str], tuple[Any, Any, float, float | None]] = {}  # model, data module, fit s, val
    for ts in sets:
        data_kw = {"calibration": ts.calibration, "test": ts.tests, "cache_dir": str(out / "cache")}
        for task in tasks:
            results[ts.name][task], scores[ts.name][task] = {}, {}
            for name, method, ablation_name in variants:
                seed_reps: list[dict[str, Any]] = []
                seed_scores: list[tuple[Any, Any, Any]] = []
                recipe = _sized(run_recipe(task, method, settings, ablation_name), settings)
                if test_dr:
                    _set_key(recipe, ("data", "method", "init_args", "test_dr"), True)
                context_frames = int(recipe.get("model", {}).get("context_frames", 1))
                kw = recipe.get("data", {}) | data_kw
                is_shared = _shared_across_test_sets(kw)
                for seed in range(seeds):
                    run_dir = out / "runs" / ts.name / f"{task}_{name}_seed{seed}"
                    bar.set_postfix_str(f"{ts.name} {task} {name} seed {seed}")
                    # a shared run serves only test sets of its radar config (the twin simulates in it)
                    key = (task, name, seed, json.dumps((ts.info or {}).get("config"), sort_keys=True))
                    if is_shared and key in shared:
                        model, trained_dm, fit_s, val_bacc = shared[key]
                        dm = _test_dm(trained_dm, ts, kw, run_dir)
                        trainer = _trainer(settings, accelerator, run_dir)
                        trained_on = trained_dm.hparams["calibration"]
                    else:
                        model, dm, trainer, fit_s, val_bacc = _fit(task, seed, settings=settings, data_kw=kw,
                                                                   model_kw=recipe.get("model", {}), run_dir=run_dir, accelerator=accelerator,
                                                                   progress=progress)
                        trained_on = None
                        if is_shared:
                            shared[key] = (model, dm, fit_s, val_bacc)
                    rep = _headline(_test(model, dm, trainer, run_dir))
                    seed_scores.append(_save_scores(run_dir, model, dm,
                                                    _calibration_scores(model, dm, ts, kw, run_dir, test_dr)))
                    gated = _gated(seed_scores[-1], gates[ts.name], context_frames, TASKS[task])
                    if gated is not None:
                        rep["static_gate"] = gated
                    rep.update({"task": task, "method": method, "seed": seed, "fit_seconds": fit_s,
                                "clip_range_db": None if dm.clip is None else list(dm.clip),
                                "val_balanced_accuracy": val_bacc, "test_set": ts.name,
                                "trained_for": trained_on or ts.calibration})
                    if settings.keep_classifiers:  # with the gate of the room it was tested in (docs/predict.md)
                        _keep_classifier(out, run_dir, rep, classifier_record(
                        model, dm, gate=(gates[ts.name] or {}).get("detector"),
                            provenance={"variant": name, "seed": seed, "test_set": ts.name,
                                        "val_balanced_accuracy": val_bacc,
                                        "calibration": Path(ts.calibration).name if ts.calibration else None}))
                    atomic_write_json(run_dir / "run.json", rep, newline=False, indent=2)
                    bar.update(1)
                    bar.write(f"{ts.name:11s} {task:9s} {name:26s} seed {seed}: balanced accuracy "
                              f"{rep['balanced_accuracy']:.3f} (simulated val {val_bacc or float('nan'):.3f})")
                    runs.append({k: rep[k] for k in ("task", "method", "seed", "balanced_accuracy", "accuracy",
                                                     "fit_seconds", "clip_range_db", "val_balanced_accuracy",
                                                     "protocol")}
                                | {"classifier": rep.get("classifier")}
                                | {"variant": name, "test_set": ts.name, "shared_training": trained_on is not None})
                    seed_reps.append(rep)
                    if seed == 0:
                        keep[(ts.name, task, name)] = (model, dm)
                        if dm._val is not None or trained_on is not None:
                            src = shared[key][1] if trained_on is not None else dm  # the trained run's val split
                            scores[ts.name][task][name] = {
                                "simulated val": _scores(model, src, src.val_dataloader(), with_dr=True),
                                "test": _scores(model, dm, dm.test_dataloader(), with_dr=test_dr)}
                cm_sum = torch.tensor([r["confusion_matrix"] for r in seed_reps]).sum(dim=0)
                results[ts.name][task][name] = {k: _summary([r[k] for r in seed_reps])
                                                for k in ("balanced_accuracy", "accuracy")}
                vals = [r["val_balanced_accuracy"] for r in seed_reps if r["val_balanced_accuracy"] is not None]
                if vals:
                    results[ts.name][task][name]["val_balanced_accuracy"] = _summary(vals)
                if "single_frame" in seed_reps[0]:  # the paper's protocol beside the context's
                    results[ts.name][task][name]["single_frame_balanced_accuracy"] = _summary(
                        [r["single_frame"]["balanced_accuracy"] for r in seed_reps])
                if all("static_gate" in r for r in seed_reps):
                    results[ts.name][task][name]["static_gate_balanced_accuracy"] = _summary(
                        [r["static_gate"]["balanced_accuracy"] for r in seed_reps])
                ens = _ensemble(seed_scores, context_frames, TASKS[task])
                if ens is not None:
                    results[ts.name][task][name]["ensemble"] = ens
                results[ts.name][task][name]["confusion_matrix_sum_over_seeds"] = cm_sum.tolist()
    bar.close()
    from radaraug.training import figures as F

    figures: dict[str, Path] = {}
    floors: dict[str, dict[str, float]] = {ts.name: {} for ts in sets}
    textures: dict[str, dict[str, Any]] = {ts.name: {} for ts in sets}
    for ts in sets:
        fig_dir = out / "figures" / ts.name
        sub = {(t, n): v for (s, t, n), v in keep.items() if s == ts.name}
        figs = _figures(fig_dir, sub, results[ts.name], ts.calibration, ts.tests, floors[ts.name], textures[ts.name])
        for task, by in scores[ts.name].items():
            if by:
                figs[f"scores_{task}"] = F.score_histograms(
                    by, TASKS[task], fig_dir / f"scores_{task}.png",
                    f"{task}: score per true class, simulated validation (filled) vs test (lines), seed 0")
        figures |= {f"{ts.name}/{k}": v for k, v in figs.items()}
    wall = time.perf_counter() - t_start
    primary = sets[0]
    report = {
        "kind": "sim-to-capture" if primary.info is None else "sim-to-generated",
        "results": results[primary.name],
        "test_sets": {ts.name: {"calibration": ts.calibration, "test": ts.tests, "generator": ts.info,
                                "results": results[ts.name], "empty_room_median_db": floors[ts.name],
                                "empty_room_floor_relative": textures[ts.name] or None,
                                "static_gate": (gates[ts.name] or {}).get("info"),
                                "ablation_table": _ablation_table(results[ts.name])} for ts in sets},
        "suites": _suite_summary(sets, results),
        "classifiers": _best_classifiers(runs, results[primary.name], primary.name, methods),
        "runs": runs,
        "settings": effective_settings(settings) | {"seeds": seeds, "quick": quick, "mode": mode, "tasks": list(tasks), "methods": list(methods),
                                        "ablations": names, "cdr_floor": _cdr_floor_of(keep, settings),
                                        "test_dr": test_dr, "test_sets": [ts.name for ts in sets]},
        "test": primary.tests,
        "calibration": primary.calibration,
        "proxy": primary.info,
        "figures": {k: str(Path(v).relative_to(out)) for k, v in figures.items()},
        "empty_room_median_db": floors[primary.name],
        "twin_noise_fit": _shared_info(keep, "noise_fit"),
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


def _keep_classifier(out: Path, run_dir: Path, rep: dict[str, Any], record: dict[str, Any]) -> None:
    """Write a run's classifier file and name it (relative to ``out``) in the run's report ``rep``."""
    save_checkpoint(record, run_dir / CLASSIFIER_FILE)
    rep["classifier"] = str((run_dir / CLASSIFIER_FILE).relative_to(out))


def _best_classifiers(runs: Sequence[dict[str, Any]], results: dict[str, dict[str, Any]], test_set: str,
                      methods: Sequence[str]) -> dict[str, dict[str, Any]]:
    """Per task, the classifier file a user runs: the best method's (mean test score), its seed by simulated val.

    The seed is chosen on simulated validation, not on the test set, so the test score stays a test score
    for the method; the method itself is the report's best row, as the tables show it.
    """
    out: dict[str, dict[str, Any]] = {}
    for task, by in results.items():
        rows = [m for m in methods if m in by]
        if not rows or not any(r.get("classifier") for r in runs):
            continue
        best = max(rows, key=lambda m: by[m]["balanced_accuracy"]["mean"])
        cand = [r for r in runs if r["task"] == task and r["variant"] == best and r["test_set"] == test_set]
        run = max(cand, key=lambda r: (r["val_balanced_accuracy"] if r["val_balanced_accuracy"] is not None else -1.0,
                                       -r["seed"]))
        out[task] = {"method": best, "seed": run["seed"], "path": run["classifier"],
                     "balanced_accuracy": run["balanced_accuracy"], "val_balanced_accuracy": run["val_balanced_accuracy"],
                     "method_balanced_accuracy": by[best]["balanced_accuracy"]}
    return out


def _headline(rep: dict[str, Any]) -> dict[str, Any]:
    """A run's test report with the context's figures as its headline, the single frame's under ``single_frame``."""
    ctx = rep.get("context")
    keys = ("balanced_accuracy", "accuracy", "recall", "support", "confusion_matrix")
    if not ctx:
        return rep | {"protocol": "single frame"}
    return rep | {"single_frame": {k: rep[k] for k in keys}, "protocol": f"context of {ctx['frames']} frames"} | {
        k: ctx[k] for k in keys}


def _save_scores(run_dir: Path, model: Any, dm: Any,
                 calibration_probs: torch.Tensor | None = None) -> tuple[Any, Any, Any]:
    """The test's per-frame probabilities, labels and recording starts, also written to ``run_dir/test_scores.pt``.

    ``calibration_probs``: the same network's probabilities on the empty-room capture (saved beside them).
    """
    scores = (model.last_test_probs, model.last_test_labels, dm.test_recording_starts)
    if scores[0] is not None:
        torch.save(dict(zip(("probs", "labels", "recording_starts"), scores))
                   | {"calibration_probs": calibration_probs}, run_dir / "test_scores.pt")
    return scores


def _calibration_scores(model: Any, test_dm: Any, ts: TestSet, data_kw: dict[str, Any], run_dir: Path,
                        test_dr: bool, limit: int = 4096) -> torch.Tensor | None:
    """The network's class probabilities on the test set's empty-room capture (test chain), in frame order, or None."""
    if ts.calibration is None or is_calibration_json(ts.calibration):
        return None
    cal = replace(ts, tests=[{"path": ts.calibration, "count": 0}])
    dm = _test_dm(test_dm, cal, data_kw, run_dir)
    from radaraug.testsets.checks import TestSetWarning

    with _quiet(), warnings.catch_warnings():
        warnings.simplefilter("ignore", TestSetWarning)  # an empty-room capture holds one class by design
        dm.setup("test")
    return _scores(model, dm, dm.test_dataloader(), with_dr=test_dr, limit=limit)[0]


def _static_gate(ts: TestSet, margin_db: float | None) -> dict[str, Any] | None:
    """The zero-Doppler change gate of test set ``ts``, or None (no margin, or a JSON calibration).

    Fitted on the set's empty-room capture and run on its test frames in test order:
    ``{"detections": (N,) bool, "info": ...}``.
    """
    if margin_db is None or ts.calibration is None or is_calibration_json(ts.calibration):
        return None
    from radaraug.detection import StaticChangeDetector

    det = StaticChangeDetector.from_capture(ts.calibration, margin_db=margin_db)
    detections = torch.cat([det.detect_capture(e["path"]) for e in ts.tests])
    return {"detections": detections, "detector": det,
            "info": {"threshold_db": det.threshold_db, "margin_db": det.margin_db,
                     "calibration_frames": len(det.calibration_scores_db),
                     "calibration_max_db": float(det.calibration_scores_db.max()),
                     "first_range_bin": det.first_bin, "test_frames_fired": float(detections.double().mean())}}


def _gated(scores: tuple[Any, Any, Any], gate: dict[str, Any] | None, context_frames: int,
           classes: Sequence[str]) -> dict[str, Any] | None:
    """A run's test balanced accuracy with the static-change gate fused in (:func:`metrics.gated_predictions`)."""
    from radaraug.training.metrics import (
        balanced_accuracy,
        confusion_matrix,
        context_predictions,
        gated_predictions,
    )

    probs, labels, starts = scores
    if gate is None or probs is None or len(gate["detections"]) != len(probs):
        return None
    preds = gated_predictions(context_predictions(probs, starts, context_frames), gate["detections"], starts,
                              context_frames)
    cm = confusion_matrix(preds, labels, len(classes))
    return {"balanced_accuracy": balanced_accuracy(cm), "confusion_matrix": cm.tolist()}


def _ensemble(scores: Sequence[tuple[Any, Any, Any]], context_frames: int,
              classes: Sequence[str]) -> dict[str, Any] | None:
    """Balanced accuracy of the seeds' mean probabilities (with and without frame context), or None."""
    from radaraug.training.metrics import balanced_accuracy, confusion_matrix, context_predictions

    if len(scores) < 2 or any(p is None for p, _, _ in scores):
        return None
    probs = torch.stack([p for p, _, _ in scores]).mean(dim=0)
    labels, starts = scores[0][1], scores[0][2]

    def bacc(frames: int) -> float:
        return balanced_accuracy(confusion_matrix(context_predictions(probs, starts, frames), labels, len(classes)))

    return {"seeds": len(scores), "balanced_accuracy": bacc(context_frames),
            "single_frame_balanced_accuracy": bacc(1)}


def _suite_summary(sets: Sequence[TestSet], results: dict[str, dict[str, dict[str, Any]]]) -> dict[str, Any]:
    """Per held-out suite, task and variant: the mean over worlds and the worst world (seed-averaged values)."""
    out: dict[str, Any] = {}
    for suite in SUITE_TEST_SETS:
        worlds = [ts.name for ts in sets if ts.suite == suite]
        if not worlds:
            continue
        by_task: dict[str, Any] = {}
        for task in results[worlds[0]]:
            by_task[task] = {}
            for variant in results[worlds[0]][task]:
                per_world = {w: results[w][task][variant]["balanced_accuracy"]["mean"] for w in worlds}
                val = [results[w][task][variant].get("val_balanced_accuracy", {}).get("mean") for w in worlds]
                worst = min(per_world, key=lambda w: per_world[w])
                by_task[task][variant] = {
                    "mean": statistics.fmean(per_world.values()), "worst": per_world[worst], "worst_world": worst,
                    "per_world": per_world,
                    "val_mean": statistics.fmean(v for v in val if v is not None) if any(v is not None for v in val)
                    else None}
                rows = [results[w][task][variant] for w in worlds]
                if all("single_frame_balanced_accuracy" in r for r in rows):
                    by_task[task][variant]["single_frame_mean"] = statistics.fmean(
                        r["single_frame_balanced_accuracy"]["mean"] for r in rows)
                if all("static_gate_balanced_accuracy" in r for r in rows):
                    gated = [r["static_gate_balanced_accuracy"]["mean"] for r in rows]
                    by_task[task][variant]["gated_mean"] = statistics.fmean(gated)
                    by_task[task][variant]["gated_worst"] = min(gated)
                if all("ensemble" in r for r in rows):
                    ens = [r["ensemble"]["balanced_accuracy"] for r in rows]
                    by_task[task][variant]["ensemble_mean"] = statistics.fmean(ens)
                    by_task[task][variant]["ensemble_worst"] = min(ens)
        out[suite] = {"worlds": worlds, "results": by_task,
                      "role": ("report suite: run only to report a decision already made" if suite == "report" else
                               "design suite: looked at; its numbers are validation numbers" if suite == "design" else
                               "spent report suite: looked at before; its numbers are validation numbers now")}
    return out


def _ablation_table(results: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    """Each ablation against the main run it changes: balanced accuracy with and without, per task."""
    rows = []
    for task, by in results.items():
        for name, (method, change) in ABLATIONS.items():
            if name in by and method in by:
                main, abl = by[method]["balanced_accuracy"], by[name]["balanced_accuracy"]
                rows.append({"task": task, "ablation": name, "changes": change, "main": method,
                             "main_mean": main["mean"], "main_std": main["std"],
                             "ablation_mean": abl["mean"], "ablation_std": abl["std"],
                             "delta": abl["mean"] - main["mean"]})
    return rows


def _shared_info(keep: dict, attr: str) -> dict[str, Any] | None:
    """The data modules' ``attr`` (``noise_fit``, ``profile_info``: the runs share it), if any run has one."""
    return next((getattr(dm.prepared, attr) for _, dm in keep.values()
                 if getattr(dm.prepared, attr, None) is not None), None)


def _profile_of(keep: dict, out: Path) -> dict[str, Any] | None:
    """The twin profile of the ``cdr_profile`` runs (they share it): source, added effects, errors."""
    info = _shared_info(keep, "profile_info")
    if info is None:
        return None
    info = dict(info)
    with contextlib.suppress(KeyError, TypeError, ValueError):
        info["path"] = str(Path(info["path"]).resolve().relative_to(out.resolve()))
    return info


def _maps_of(cache_dm: Any, count: int, n: int) -> torch.Tensor:
    ds = cache_dm._train.base  # CachedMaps of the run
    idx = (ds.counts == count).nonzero().flatten()[:n]
    return ds.maps(idx.tolist()) if len(idx) else torch.empty(0, *ds.map_shape)


def _with_dr(dm: Any) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
    """Up to 64 empty-room and one-person maps of a run's simulated set, then both through its DR."""
    empty, one = _maps_of(dm, 0, 64), _maps_of(dm, 1, 64)
    with torch.no_grad():
        return empty, one, dm.dr.train()(empty), dm.dr.train()(one)


def _capture_maps(path: str, n: int, dm: Any) -> torch.Tensor:
    from radaraug.io import open_capture

    with open_capture(path) as cap:
        x = cap.read(0, min(n, cap.num_frames))
    return dm.rd_chain()(x)  # as the run's own maps were made


def _empty_textures(keep: dict, task: str, dm: Any, real_empty: torch.Tensor) -> dict[str, Any]:
    """The empty room once floor-referenced: each run's training maps (after its DR) and the calibration capture.

    Per source the medians over frames of :func:`~radaraug.training.pipeline.floor_texture`'s spread and
    largest cell, and the spread of noise alone (closed form): what is left of a calibrated floor in the
    network's input (docs/training.md, "CDR's floor once the map is floor-relative").
    """
    from radaraug.training.pipeline import floor_texture, noise_texture_db

    def medians(maps: torch.Tensor, run_dm: Any) -> dict[str, float]:
        t = floor_texture(maps, run_dm.excise, run_dm.image_spec.blank_zero_doppler)
        return {"texture_std_db": round(float(t["texture_std_db"].median()), 2),
                "peak_db": round(float(t["peak_db"].median()), 2), "frames": len(maps)}

    out: dict[str, Any] = {"noise_alone_texture_std_db": round(noise_texture_db(real_empty.shape[-3]), 2),
                           "capture": medians(real_empty, dm)}
    for (t, name), (_, run_dm) in keep.items():
        train = getattr(run_dm, "_train", None)
        if t != task or train is None:  # a run trained for another test set keeps no simulated split here
            continue
        empty = _maps_of(run_dm, 0, 64).float()
        if len(empty):
            with torch.no_grad():
                out[name] = medians(empty if run_dm.dr is None else run_dm.dr.train()(empty), run_dm)
    return out


def _figures(fig_dir: Path, keep: dict, results: dict, calibration: str | None,
             test: Sequence[dict[str, Any]], floors: dict[str, float], textures: dict[str, Any]) -> dict[str, Path]:
    """Write the figures; fill ``floors`` with the median empty-room RD level (dB) of each source.

    The sources: simulation, simulation + CDR, the calibration capture and, with ``cdr_profile`` runs, the
    profile twin with and without CDR (Fig. 4's data). ``textures`` gets :func:`_empty_textures`.
    """
    from radaraug.training import figures as F

    figs: dict[str, Path] = {}
    for task, by_method in results.items():
        cms = {m: r["confusion_matrix_sum_over_seeds"] for m, r in by_method.items()}
        n = "fig8" if task == "occupancy" else "fig9"
        figs[f"{n}_confusion_{task}"] = F.confusion_grid(cms, TASKS[task], fig_dir / f"{n}_confusion_{task}.png",
                                                          f"{task}: confusion matrices (summed over seeds)")
    figs["results"] = F.results_bars(results, fig_dir / "balanced_accuracy.png")
    task = next(iter(results))
    cdr_run, rt_run, prof_run = (keep.get((task, m)) for m in ("cdr", "rt", "cdr_profile"))
    if cdr_run is None or calibration is None or is_calibration_json(calibration):
        return figs
    dm = cdr_run[1]
    sim_empty, sim_one, cdr_empty, cdr_one = _with_dr(dm)
    real_empty = _capture_maps(calibration, 64, dm)
    one = [e for e in test if e.get("count") == 1]
    real_one = _capture_maps(one[0]["path"], 64, dm) if one else None
    # Fig. 4's sources (legend, key in ``floors``, maps) and Fig. 5's simulated columns (title,
    # empty-room maps, one-person maps), in their order
    sources = [("simulation", "simulation", sim_empty), ("simulation + CDR", "simulation_cdr", cdr_empty)]
    columns = [("sim", sim_empty, sim_one), ("sim + CDR", cdr_empty, cdr_one)]
    if prof_run is not None:
        prof_empty, _, prof_cdr_empty, prof_cdr_one = _with_dr(prof_run[1])
        sources += [("profile twin", "simulation_profile", prof_empty),
                    ("profile twin + CDR", "simulation_profile_cdr", prof_cdr_empty)]
        columns.append(("profile sim + CDR", prof_cdr_empty, prof_cdr_one))
    sources.append(("empty-room capture", "capture", real_empty))
    for _, key, maps in sources:
        v = maps.float().flatten()
        floors[key] = round(float(v[torch.isfinite(v) & (v > -250)].median()), 2)
    textures.update(_empty_textures(keep, task, dm, real_empty))
    figs["fig4_noise_floor"] = F.noise_floor_histograms({name: maps for name, _, maps in sources},
                                                        fig_dir / "fig4_noise_floor_histograms.png")
    vmin, vmax = dm.clip
    cfg = dm.config
    rows = {"empty": ([(name, empty[0]) for name, empty, _ in columns if len(empty)]
                      + [("capture", real_empty[0])])}
    if real_one is not None and len(sim_one):
        rows["one person"] = ([(name, person[0]) for name, _, person in columns if len(person)]
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


def _fmt(s: dict[str, Any], prefix: str = "") -> str:
    """``mean ± std`` of a summary, or of its ``PREFIXmean`` / ``PREFIXstd`` keys (an ablation-table row)."""
    return f"{s[prefix + 'mean']:.3f} ± {s[prefix + 'std']:.3f}"


TEST_SET_TEXT = {
    "proxy": ("**proxy**: radaraug's own twin in another room (other clutter, motion source, receiver effects; "
              "docs/proxy.md). It shares the twin's simulation code."),
    "independent": ("**independent**: a NumPy generator that shares no simulation code with the twin (its own "
                    "receiver, room and walkers; docs/proxy.md). Its settings were fixed before any training result "
                    "was seen."),
    "standing": ("**standing**: the independent generator (another seed) with 30 % of its people standing "
                 "(breathing, swaying) instead of walking; they count."),
}

SUITE_TEXT = {
    "design": ("**design suite** (`radaraug.testsets.independent.worlds`): test worlds drawn from wide priors (room, mounting, "
               "radar config, people, disturbances), each with its own empty-room capture. It may be looked at as "
               "often as one likes, so numbers on it are **validation** numbers."),
    "report": ("**report suite**: worlds from the same priors and other seeds, run only to report a decision "
               "already made, never to make one."),
    "report-1": ("**report-1**: the first report suite, run once and then looked at: spent, so its numbers are "
                 "**validation** numbers now."),
    "report-2": ("**report-2**: the second report suite, run once and then looked at: spent, so its numbers are "
                 "**validation** numbers now."),
    "report-3": ("**report-3**: the third report suite, run once and then published world by world: spent, so its "
                 "numbers are **validation** numbers now."),
}

QUICK_TRADES = ("Quick mode trades, against full mode (6000 items, 15 epochs, 128 x 64, every ablation): fewer "
                "simulated items and epochs, 64 x 32 images, and only the ablations listed in its settings; the "
                "network is still the paper's ResNet18. Full mode is for a GPU.")


#: Notes on the first test set that compare a row with ``cdr``'s: row -> text ({row}, {cdr}: their means)
CDR_NOTES = {"cdr_profile": "CDR on the profile twin {row:.3f} vs CDR on the noise-fitted twin {cdr:.3f}.",
             "cdr_no_twin_randomization": ("twin randomization ablation: CDR {cdr:.3f} with vs {row:.3f} "
                                           "without.")}


def _md_table(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> list[str]:
    """A Markdown table: the header line, the separator and one line per row (cells as ``str``)."""
    return ["| " + " | ".join(header) + " |", "|" + "---|" * len(header),
            *("| " + " | ".join(map(str, row)) + " |" for row in rows)]


def _results_table(results: dict[str, dict[str, Any]]) -> list[str]:
    cols = list(next(iter(results.values())).keys())

    def cell_of(r: dict[str, Any]) -> str:
        val, one, ens = r.get("val_balanced_accuracy"), r.get("single_frame_balanced_accuracy"), r.get("ensemble")
        gated = r.get("static_gate_balanced_accuracy")
        return (_fmt(r["balanced_accuracy"]) + ("" if val is None else f" (sim val {val['mean']:.3f})")
                + ("" if one is None else f"; 1 frame {one['mean']:.3f}")
                + ("" if ens is None else f"; seed ensemble {ens['balanced_accuracy']:.3f}")
                + ("" if gated is None else f"; + static gate {gated['mean']:.3f}"))

    cell = {task: {c: cell_of(by[c]) for c in by} for task, by in results.items()}
    return _md_table(["task", *cols], ([task, *(cell[task].get(c, "") for c in cols)] for task in results))


def _orderings(results: dict[str, dict[str, Any]]) -> list[str]:
    order = []
    for task, by in results.items():
        m = {k: v["balanced_accuracy"]["mean"] for k, v in by.items()}
        if all(k in m for k in ("rt", "randomdr", "cdr")):
            holds = m["rt"] < m["randomdr"] < m["cdr"]
            order.append(f"- {task}: paper's ordering RT < RandomDR < CDR {'holds' if holds else 'does NOT hold'} "
                         f"({m['rt']:.3f} / {m['randomdr']:.3f} / {m['cdr']:.3f}).")
        best = max(m, key=lambda k: m[k])
        order.append(f"- {task}: best {best} {m[best]:.3f}.")
    return order


def _markdown(rep: dict[str, Any]) -> str:
    lines = ["# radaraug reproduce: train on the twin, test on captures", ""]
    st = rep["settings"]
    sets_text = ("; `cdr_profile` trains on its own set of that size, simulated with the twin profile's receiver"
                 if "cdr_profile" in st["methods"] else "")
    lines += [f"Seeds: {st['seeds']} (network init, DR draws, batch order; simulated sets of {st['train_items']} "
              f"training + {st['val_items']} validation items{sets_text}). Epochs {st['epochs']}, image "
              f"{st['image_size'][0]}x{st['image_size'][1]}, representation `{st['representation']}`, "
              f"{st['mode']} mode. Wall time {rep['wall_seconds'] / 60:.1f} min on "
              f"{rep['machine']['device']}."
              + (f" CalibratedDR floor of the CDR methods: `{st['cdr_floor']}`." if st.get("cdr_floor") else "")
              + (" **Test captures went through each run's DR too (`test_dr`), not the paper's protocol.**"
                 if st.get("test_dr") else ""), ""]
    if st["mode"] == "quick":
        lines += [QUICK_TRADES, ""]
    if rep.get("classifiers"):
        lines += ["**Classifiers to use** (the best method's, its seed chosen on simulated validation): "
                  + "; ".join(f"{task}: `{c['path']}` ({c['method']}, seed {c['seed']}, balanced accuracy "
                              f"{c['balanced_accuracy']:.3f})" for task, c in rep["classifiers"].items())
                  + ". Run one with `radaraug predict CLASSIFIER CAPTURE` (docs/predict.md).", ""]
    if rep["kind"] == "sim-to-generated":
        lines += ["**These are sim-to-generated numbers, not sim-to-real.** The test captures come from generators "
                  "that training was not made with, each with its own empty-room capture (CDR and the twin's noise "
                  "fit see only that):", ""]
        generic = [name for name in rep["test_sets"] if not (rep["test_sets"][name].get("generator") or {}).get("world")]
        lines += [f"- {TEST_SET_TEXT.get(name, name)}" for name in generic]
        lines += [f"- {SUITE_TEXT[suite]}" for suite in rep.get("suites") or {}]
        lines += [""]
    for suite, summ in (rep.get("suites") or {}).items():
        lines += [f"## Suite `{suite}`: mean over {len(summ['worlds'])} worlds and the worst world", "",
                  f"{SUITE_TEXT[suite]} Each world's value is its balanced accuracy averaged over seeds.", ""]
        header = ["task", "variant", "mean over worlds", "worst world", "simulated val (mean)", "single frame (mean)",
                  "seed ensemble (mean / worst)", "+ static gate (mean / worst)", "per world"]

        def opt(v: dict[str, Any], key: str) -> str:
            return f"{v[key]:.3f}" if v.get(key) is not None else "n/a"

        rows = [[task, variant, f"{v['mean']:.3f}", f"{v['worst']:.3f} ({v['worst_world']})", opt(v, "val_mean"),
                 opt(v, "single_frame_mean"),
                 f"{v['ensemble_mean']:.3f} / {v['ensemble_worst']:.3f}" if "ensemble_mean" in v else "n/a",
                 f"{v['gated_mean']:.3f} / {v['gated_worst']:.3f}" if "gated_mean" in v else "n/a",
                 ", ".join(f"{w.split('-')[-1]} {a:.3f}" for w, a in v["per_world"].items())]
                for task, by in summ["results"].items() for variant, v in by.items()]
        lines += [*_md_table(header, rows), ""]
    for name, ts in rep["test_sets"].items():
        lines += [f"## Test set `{name}`: balanced accuracy (mean ± std over seeds)", ""]
        world = (ts.get("generator") or {}).get("world")
        if world:
            c = world["config"]
            lines += [f"World `{name}`: {c['num_samples_per_chirp']} samples x {c['num_chirps_per_frame']} chirps, "
                      f"{c['sample_rate_Hz'] / 1e6:g} MHz, IF gain {c['if_gain_dB']} dB, room "
                      f"{' x '.join(f'{v:.1f}' for v in world['room']['size_m'])} m, radar at "
                      f"{world['room']['radar_position_m'][2]:.2f} m tilted {world['room']['radar_tilt_down_deg']:.0f} deg, "
                      f"people RCS {world['people']['rcs_dBsm'][0]:.1f}..{world['people']['rcs_dBsm'][1]:.1f} dBsm, "
                      f"disturbances: {', '.join(world['disturbances']) or 'none'}.", ""]
        if ts["generator"] is None:
            lines += ["Test captures: " + ", ".join(
                f"`{e['path']}`" + (f" (count {e['count']})" if e.get("count") is not None else " (per-frame labels)")
                for e in ts["test"]) + f"; calibration `{ts['calibration']}`.", ""]
        lines += [*_results_table(ts["results"]), "", *_orderings(ts["results"]), ""]
        gate = ts.get("static_gate")
        if gate:
            lines += [f"Static-change gate (`radaraug.detection.StaticChangeDetector`, docs/static_change.md): fitted "
                      f"on the {gate['calibration_frames']} empty-room frames, threshold {gate['threshold_db']:.1f} dB "
                      f"(their largest leave-one-out score {gate['calibration_max_db']:.1f} dB + {gate['margin_db']:g} "
                      f"dB); it fired on {100 * gate['test_frames_fired']:.0f} % of the test frames. \"+ static gate\" "
                      "raises a run's 'nobody' to one person where it fires (with the run's frame context).", ""]
        tex = ts.get("empty_room_floor_relative")
        if tex:
            srcs = [k for k in tex if k != "noise_alone_texture_std_db"]
            lines += ["Empty room once floor-referenced (the network's input: cells off zero Doppler, medians over "
                      "frames; docs/training.md, \"CDR's floor once the map is floor-relative\"): spread "
                      + ", ".join(f"{k} {tex[k]['texture_std_db']:.2f} dB" for k in srcs)
                      + f" (noise alone, any level: {tex['noise_alone_texture_std_db']:.2f} dB); largest cell "
                      + ", ".join(f"{k} {tex[k]['peak_db']:.1f} dB" for k in srcs)
                      + ". The level a calibrated floor sets cancels in this map; its spread is what is left.", ""]
        if ts["ablation_table"]:
            header = ["task", "ablation", "changes", "main run", "with", "without (ablation)", "delta"]
            rows = [[r["task"], r["ablation"], f"`{json.dumps(r['changes'])}`", r["main"], _fmt(r, "main_"),
                     _fmt(r, "ablation_"), f"{r['delta']:+.3f}"] for r in ts["ablation_table"]]
            lines += [*_md_table(header, rows), ""]
    lines += ["Paper (real corridor): occupancy 97 % CDR, ~83 % RandomDR, ~50 % RT; counting 72 % / ~61 % / ~33 %.", ""]
    order: list[str] = []
    for task, by in rep["results"].items():
        m = {k: v["balanced_accuracy"]["mean"] for k, v in by.items()}
        order += [f"- {task}: " + note.format(row=m[row], cdr=m["cdr"]) for row, note in CDR_NOTES.items()
                  if row in m and "cdr" in m]
    floors = rep.get("empty_room_median_db") or {}
    if floors and "simulation_cdr" in floors and floors["simulation_cdr"] > floors["capture"] + 1.0:
        fit = rep.get("twin_noise_fit")
        why = (f"The twin's noise figure was fitted to the calibration capture ({fit['noise_figure_dB']:.1f} dB), "
               "so" if fit else "So")
        order.append(
            f"- CDR raises the simulated empty-room floor above the capture's: median {floors['simulation']:.1f} dB "
            f"(simulation) -> {floors['simulation_cdr']:.1f} dB (simulation + CDR) against {floors['capture']:.1f} dB "
            f"(capture). {why} the simulated floor already sits near the capture's and the clamp "
            "max(S, N) adds a second floor on top (docs/training.md, 'What the numbers show').")
    lines += ["## Notes on the first test set", "", *order, ""] if order else []
    prof = rep.get("twin_profile")
    if prof:
        def db(v: Any) -> str:
            return "n/a" if v is None else f"{v:.3f} dB"

        added = ", ".join(f"`{e}`" for e in prof.get("effects_added") or []) or "none"
        how = ("fitted by `radaraug diagnose` on the calibration capture"
               if str(prof.get("source", "")).startswith("fitted") else "given as `data.twin.profile`")
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
    lines += ["## Figures", "", "Score histograms (`scores_*`): the network's score per true class on simulated "
              "validation (filled) and on the test captures (lines), seed 0; a collapse to one class shows every test "
              "class piled at one end.", ""]
    lines += [f"![{key}]({rel})" for key, rel in rep["figures"].items()]
    header = ["test set", "task", "variant", "seed", "balanced acc.", "accuracy", "val bal. acc. (sim)",
              "clip range dB", "fit s"]
    rows = [[r["test_set"], r["task"], r["variant"], r["seed"], f"{r['balanced_accuracy']:.3f}",
             f"{r['accuracy']:.3f}",
             "n/a" if r["val_balanced_accuracy"] is None else f"{r['val_balanced_accuracy']:.3f}",
             f"{r['clip_range_db'][0]:.1f} .. {r['clip_range_db'][1]:.1f}", f"{r['fit_seconds']:.0f}"]
            for r in rep["runs"]]
    lines += ["", "## Runs", "", *_md_table(header, rows)]
    lines += ["", f"dB convention: {rep['db_convention']}.", ""]
    return "\n".join(lines)

