"""`RadarDataModule`: train on the twin, validate on held-out simulation, test on captures.

The train and val items are simulated once into the map cache (:mod:`radaraug.training.cache`) and get
the run's DR on the device; captures never get DR. Both go through the same image chain
(:mod:`radaraug.training.pipeline`). See docs/training.md.
"""

from __future__ import annotations

import copy
import warnings
from collections.abc import Sequence, Sized
from pathlib import Path
from typing import Any, Literal

import lightning as L
import torch
from torch.utils.data import ConcatDataset, DataLoader, Dataset, Subset

from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError
from radaraug.files import atomic_write_json
from radaraug.io import RadarCaptureDataset, open_capture
from radaraug.sensor.profile import PROFILE_VERSION, TwinProfile
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.training.cache import CachedMaps, build_map_caches, cache_key, content_digest, default_cache_dir
from radaraug.training.pipeline import (
    CDR_FLOORS,
    CDR_METHODS,
    PROFILE_METHODS,
    check_representation,
    check_task,
    estimate_clip_range,
    image_chain,
    is_calibration_json,
    label_of,
    make_dr,
    rd_db_chain,
)
from radaraug.training.testset import check_inputs, dataset_entries, parse_test_entry
from radaraug.transforms import CalibratedDR

PROFILE_FIT_FORMAT = "radaraug-profile-fit"
#: Where the twin randomization's effect catalog takes its priors (``catalog_priors``).
CATALOG_PRIORS = ("physics", "calibration")
#: Version of the cached ``cdr_profile`` fits (``cache_dir/profile-<key>.json``): part of their key,
#: bumped when what :func:`radaraug.calibration.diagnose` fits changes, so old fits are not reused.
PROFILE_FIT_VERSION = 1
NOISE_FIT_SKIPPED = "skipped: the twin's receiver comes from the twin profile (its fitted chain sets the floor)"


class _Labelled(Dataset):
    """``(x, count)`` items -> ``(x, class label of task)``."""

    def __init__(self, base: Dataset, task: str) -> None:
        self.base, self.task = base, task

    def __len__(self) -> int:
        return len(self.base)  # type: ignore[arg-type]  # torch's Dataset declares no __len__; ours are sized

    def __getitem__(self, i: int) -> tuple[torch.Tensor, int]:
        x, count = self.base[i]
        return x, int(label_of(int(count), self.task))


def _recording_starts(tests: Sequence[RadarCaptureDataset]) -> torch.Tensor:
    """``(frames,)`` bool over the concatenated test captures: True at each file's first frame."""
    flags = []
    for t in tests:
        for n in t.items_per_file:
            f = torch.zeros(n, dtype=torch.bool)
            if n:
                f[0] = True
            flags.append(f)
    return torch.cat(flags) if flags else torch.zeros(0, dtype=torch.bool)


def _rank_world(trainer: Any) -> tuple[int, int]:
    if trainer is None:
        return 0, 1
    return int(trainer.global_rank), int(trainer.world_size)


class RadarDataModule(L.LightningDataModule):
    """The paper's data side as a LightningDataModule (every argument is a YAML key; docs/training.md).

    Args:
        task: ``occupancy`` (2 classes) or ``counting`` (0/1/2 people).
        method: ``rt``, ``randomdr`` (default: it wins on held-out data), ``cdr``, or ``cdr_profile``
            (``cdr``'s DR on a twin whose receiver is the twin profile fitted on the calibration capture).
        scene: training scene: built-in name or scene file.
        calibration: the empty-room capture recorded like the test captures: the twin simulates its radar
            config, its persistent lines are excised, CDR's floor (and ``cdr_profile``'s profile) is fitted on
            it. A CalibratedDR JSON serves CDR only (a warning names what is left out). None with no ``test``:
            the held-out proxy's.
        test: test captures: ``"PATH:N"`` / ``{"path", "count": N}`` (N people in the whole file),
            ``"PATH"`` / ``{"path"}`` (the file's per-frame ``count`` labels), or a
            :class:`~radaraug.io.RadarCaptureDataset` labelled with people counts and without a transform
            (:func:`~radaraug.training.testset.dataset_entries`). None: the held-out proxy.
        proxy_dir: where the held-out proxy is generated and reused (None: ``cache_dir/proxy``).
        proxy_frames_per_count: test frames per people count of a generated proxy.
        train_items, val_items: simulated items for training and validation.
        sim_seed: seed of the simulated set (item ``i`` is a function of ``(sim_seed, i)``).
        randomization: twin randomization: True (defaults), False/None (off), or a dict of
            :class:`~radaraug.sim.randomization.TwinRandomization` fields.
        catalog_priors: ``"physics"`` (the effect catalog's own ranges) or ``"calibration"`` (centred on the
            effects ``diagnose`` adds on the calibration capture: :mod:`radaraug.calibration.priors`).
        calibrate_noise: fit the twin's noise figure to the calibration capture's empty-room floor
            (:mod:`radaraug.calibration.noise_fit`); skipped when the receiver is a profile.
        profile: a twin profile JSON (``radaraug diagnose`` writes one) the twin's receiver is built from,
            any method; for ``cdr_profile`` it replaces the fitted one.
        profile_max_frames: frames of the calibration capture that ``cdr_profile``'s diagnose reads.
        tracer_rays: trace the room with SBR at this many rays per axis (None: the image method).
        cache_dir: folder of the simulate-once cache and the cached fits (None: the user's cache folder,
            :func:`radaraug.raytrace.cache.default_cache_dir`).
        image_size: network input ``[H, W]`` (None: the RD map's own size).
        representation: ``"floor_relative"`` (default: :class:`~radaraug.transforms.FloorRelative`) or
            ``"paper"`` (the RX-combined dBFS map, clipped).
        blank_zero_doppler: with ``floor_relative``: Doppler bins blanked on each side of zero.
        excise_persistent_db: with ``floor_relative``: cells whose median over the calibration capture
            stands this many dB above their row's floor are set to the floor in every map (None: none).
        clip_percentiles: percentiles of simulated (post-DR) maps that give ``[vmin, vmax]``.
        clip_range: a fixed ``[vmin, vmax]`` instead of the estimate.
        randomdr_mean_db, randomdr_std_db: RandomDR ranges (None: radaraug's defaults).
        cdr_floor: CalibratedDR's floor: ``"normal"`` (the paper's), ``"empirical"`` (the capture's
            distribution), ``"matched"`` (so that ``max(S, N)`` on the twin has the capture's
            distribution; needs empty training items), or None (the calibration's own).
        cdr_twin_noise_offset_db: ``cdr`` only: lower the twin's noise by this many dB so that the clamp
            supplies the floor, as in the paper (None: ``cdr`` shares the other methods' twin).
        test_dr: also pass the test captures through the run's DR (not the paper's protocol).
        simulated: the training twin's dataset, used as given instead of the built one (the fitted-receiver
            options are then not applied; a warning names them). It needs the test captures' radar
            config, target ``count`` and at least ``train_items + val_items`` items.
        dr: the run's DR as a module on per-RX dB maps ``(B, rx, range, doppler)``, instead of the one
            ``method`` builds (``method`` still picks the twin). None: ``method``'s.
        dr_seed: seed of the DR draws (rank ``r`` uses ``dr_seed + 1000 r``).
        batch_size: training batch size.
        num_workers: DataLoader workers for training and test reads.
        sim_workers: DataLoader workers that simulate while the cache is built.
        progress: progress bars while simulating.
        out_dir: where the run's ``clip_range.json`` is written (default: the trainer's log dir).
    """

    def __init__(
        self,
        task: str = "occupancy",
        method: str = "randomdr",
        scene: str = "corridor",
        calibration: str | None = None,
        test: list[RadarCaptureDataset | str | dict[str, Any]] | None = None,
        proxy_dir: str | None = None,
        proxy_frames_per_count: int = 120,
        train_items: int = 1200,
        val_items: int = 240,
        sim_seed: int = 0,
        randomization: bool | dict[str, Any] | None = True,
        catalog_priors: Literal["physics", "calibration"] = "physics",
        calibrate_noise: bool = True,
        profile: str | None = None,
        profile_max_frames: int = 100,
        tracer_rays: int | None = None,
        cache_dir: str | None = None,
        image_size: list[int] | None = None,
        representation: Literal["paper", "floor_relative"] = "floor_relative",
        blank_zero_doppler: int = 1,
        excise_persistent_db: float | None = 3.0,
        clip_percentiles: tuple[float, float] = (1.0, 99.9),
        clip_range: list[float] | None = None,
        randomdr_mean_db: list[float] | None = None,
        randomdr_std_db: list[float] | None = None,
        cdr_floor: Literal["normal", "empirical", "matched"] | None = None,
        cdr_twin_noise_offset_db: float | None = None,
        test_dr: bool = False,
        dr: torch.nn.Module | None = None,
        simulated: SimulatedRadarDataset | None = None,
        dr_seed: int = 0,
        batch_size: int = 32,
        num_workers: int = 0,
        sim_workers: int = 0,
        progress: bool = True,
        out_dir: str | None = None,
    ) -> None:
        super().__init__()
        self.class_names = check_task(task)
        if train_items < 1 or val_items < 0:
            raise ConfigError(f"train_items must be >= 1 and val_items >= 0, got {train_items}, {val_items}")
        if catalog_priors not in CATALOG_PRIORS:
            raise ConfigError(f"catalog_priors must be one of {CATALOG_PRIORS}, got {catalog_priors!r}")
        if cdr_floor is not None and cdr_floor not in CDR_FLOORS:
            raise ConfigError(f"cdr_floor must be one of {CDR_FLOORS} or null, got {cdr_floor!r}")
        check_representation(representation)
        # dr is an object: the saved config (LightningCLI's config.yaml) names it, hparams cannot
        self.save_hyperparameters(ignore=["dr", "simulated", "test"])
        cache = Path(cache_dir) if cache_dir is not None else default_cache_dir()
        self.hparams["cache_dir"] = str(cache)
        self.hparams["proxy_dir"] = str(proxy_dir) if proxy_dir is not None else str(cache / "proxy")
        # Test datasets given as objects are used as they are; hparams keeps their files (entries
        # with the dataset's index), so the checks and the saved config see every test file.
        self._given_tests = [e for e in test or [] if isinstance(e, RadarCaptureDataset)]
        entries: list[dict[str, Any]] = []
        for i, e in enumerate(test or []):
            if isinstance(e, RadarCaptureDataset):
                k = self._given_tests.index(e)
                entries += [{**d, "dataset": k} for d in dataset_entries(e, f"test[{i}]")]
            else:
                entries.append(parse_test_entry(e, f"test[{i}]"))
        self.hparams["test"] = None if test is None else entries
        self.task, self.method = task, method
        self._given_dr, self._given_simulated = dr, simulated
        if clip_range is not None and len(clip_range) != 2:
            raise ConfigError(f"clip_range must be [vmin, vmax], got {clip_range!r}")
        self.clip: tuple[float, float] | None = None if clip_range is None else (clip_range[0], clip_range[1])
        self.dr: torch.nn.Module | None = None
        self.image: torch.nn.Module | None = None
        self.config: RadarConfig | None = None
        self.excise: torch.Tensor | None = None
        self._train: Dataset | None = None
        self._val: Dataset | None = None
        self._test: Dataset | None = None
        #: where each recording starts in the test order (set by setup; None under DDP: shards stride over frames)
        self.test_recording_starts: torch.Tensor | None = None
        self.train_class_counts: torch.Tensor | None = None
        self.noise_fit: dict[str, Any] | None = None
        self.twin_profile: TwinProfile | None = None
        self.profile_info: dict[str, Any] | None = None
        self.catalog_prior_info: dict[str, Any] | None = None
        self._calibration_profile: TwinProfile | None = None

    def _setup_config(self) -> RadarConfig:
        """The radar config that :meth:`setup` read from the captures."""
        if self.config is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        return self.config

    # ------------------------------------------------------------------ resolving inputs
    def _proxy(self) -> Any:
        from radaraug.sim.proxy import make_proxy

        return make_proxy(self.hparams["proxy_dir"], frames_per_count=self.hparams["proxy_frames_per_count"],
                          progress=self.hparams["progress"])

    def resolved_captures(self) -> tuple[str | None, list[dict[str, Any]]]:
        """``(calibration, test entries)``, the held-out proxy's where the config names none."""
        calibration, test = self.hparams["calibration"], self.hparams["test"]
        if test is None:
            proxy = self._proxy()
            test = [{"path": str(p), "count": int(c)} for p, c in proxy.tests]
            if calibration is None:
                calibration = str(proxy.calibration)
        elif calibration is None and self.method in CDR_METHODS:
            # The proxy's empty room says nothing about the user's captures: no silent stand-in.
            raise ConfigError(f"method {self.method!r} needs data.calibration: an empty-room capture (or CalibratedDR "
                              "JSON) recorded like the test captures")
        return calibration, [dict(e) for e in test]  # the config's entries were checked in __init__

    def prepare_data(self) -> None:
        """Generate the held-out proxy captures once per node when no test captures are given."""
        # Rank 0 of each node generates the proxy once; the other ranks reuse its files in setup().
        if self.hparams["test"] is None:
            self._proxy()

    def simulated_dataset(self, length: int | None = None, seed: int | None = None) -> SimulatedRadarDataset:
        """The training twin's dataset in the test captures' radar config.

        Args:
            length: items (None: ``train_items + val_items``).
            seed: the set's seed (None: ``sim_seed``).
        """
        if self._given_simulated is not None:
            return self._checked_given_simulated()
        r = self.hparams["randomization"]
        randomization = None
        if r:
            from radaraug.sim.randomization import TwinRandomization

            randomization = TwinRandomization() if r is True else TwinRandomization.from_dict(dict(r))
            if self._calibration_profile is not None:
                from radaraug.calibration.priors import calibration_priors

                randomization, record = calibration_priors(self._calibration_profile, randomization,
                                                           self._setup_config())
                self.catalog_prior_info = {"source": "diagnose on data.calibration", **record}
        twin_options: dict[str, Any] = {}
        if self.hparams["tracer_rays"] is not None:
            twin_options["tracer_options"] = {"method": "sbr", "rays": int(self.hparams["tracer_rays"])}
        extra: dict[str, Any] = {} if randomization is None else {"randomization": randomization}
        if self.twin_profile is not None:
            extra["profile"] = self.twin_profile
        elif self.noise_fit is not None or self._quiet_twin_db() is not None:
            from radaraug.calibration.noise_fit import noise_fit_receiver
            from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS, DEFAULT_NOISE_FIGURE_DB

            fit = self.noise_fit or {"noise_figure_dB": DEFAULT_NOISE_FIGURE_DB, "adc_noise_rms_counts": ADC_NOISE_RMS_COUNTS}
            quiet = self._quiet_twin_db()
            if quiet is not None:
                # CDR's twin: both noise sources lowered, so that the clamp supplies the floor (as in the paper)
                fit = {"noise_figure_dB": float(fit["noise_figure_dB"]) + quiet,
                       "adc_noise_rms_counts": float(fit["adc_noise_rms_counts"]) * 10 ** (quiet / 20)}
            # Both noise sources moved by the fitted offset (noise figure and ADC-side noise).
            twin_options["receiver"] = noise_fit_receiver(self._setup_config(), fit)
        return SimulatedRadarDataset(
            self.hparams["scene"], length=self.hparams["train_items"] + self.hparams["val_items"] if length is None
            else int(length), seed=self.hparams["sim_seed"] if seed is None else int(seed), config=self.config,
            target="count", twin_options=twin_options, **extra,
        )

    def _checked_given_simulated(self) -> SimulatedRadarDataset:
        """``simulated`` as given, after the checks its docstring names."""
        ds = self._given_simulated
        assert ds is not None
        if ds.config != self._setup_config():
            raise ConfigError(f"data.simulated has another radar config ({ds.config.describe()}) than the test "
                              f"captures ({self._setup_config().describe()})")
        n = self.hparams["train_items"] + self.hparams["val_items"]
        if len(ds) < n or ds.target != "count":
            raise ConfigError(f"data.simulated must give people counts (target='count') for at least "
                              f"train_items + val_items = {n} items; it has {len(ds)} items, target {ds.target!r}")
        h = self.hparams
        unused = [k for k, on in (("calibrate_noise", h["calibrate_noise"]), ("profile", h["profile"]),
                                  ("catalog_priors", h["catalog_priors"] != "physics"),
                                  ("cdr_twin_noise_offset_db", self._quiet_twin_db() is not None),
                                  ("method cdr_profile", self.method in PROFILE_METHODS)) if on]
        if unused:
            warnings.warn(f"data.simulated is used as given: {', '.join(unused)} not applied to it", stacklevel=3)
        return ds

    # ------------------------------------------------------------------ Lightning hooks
    def setup(self, stage: str | None = None) -> None:
        """Resolve captures, DR and receiver; build the simulated splits (cached) and the image chain."""
        if self.image is not None and (stage != "test" or self._test is not None):
            return
        rank, world = _rank_world(self.trainer)
        calibration, test = self.resolved_captures()
        # Before any simulation: a test set that cannot score the task, or a calibration that cannot
        # serve the method, is refused (or warned about) now, not after training.
        excise = self.hparams["representation"] == "floor_relative" and self.hparams["excise_persistent_db"] is not None
        check_inputs(test, self.task, calibration=calibration, method=self.method, profile=self.hparams["profile"],
                     calibrate_noise=self.hparams["calibrate_noise"], excise=excise and self.excise is None,
                     cdr_floor=self.hparams["cdr_floor"])
        has_capture = calibration is not None and not is_calibration_json(calibration)
        source = calibration if calibration is not None and has_capture else test[0]["path"]
        with open_capture(source) as cap:
            self.config = config = cap.config
        self.dr = dr = self._given_dr if self._given_dr is not None else make_dr(
            self.method, calibration=calibration, seed=self.hparams["dr_seed"] + 1000 * rank,
            randomdr_mean_db=self.hparams["randomdr_mean_db"], randomdr_std_db=self.hparams["randomdr_std_db"],
            cdr_floor=self.hparams["cdr_floor"])
        if isinstance(dr, CalibratedDR):  # the CDR methods
            dr.check_config(config)

        if (self.excise is None and self.clip is None and self.hparams["representation"] == "floor_relative"
                and self.hparams["excise_persistent_db"] is not None and has_capture and calibration is not None):
            self.excise = self._persistent_cells(calibration)
        n_train, n_val = self.hparams["train_items"], self.hparams["val_items"]
        needs_sim = stage in (None, "fit", "validate") or self.clip is None
        if needs_sim and self._given_simulated is None:  # a given dataset brings its own receiver
            self._resolve_receiver(calibration, has_capture, rank)
            if self.hparams["catalog_priors"] == "calibration" and self.hparams["randomization"]:
                if not has_capture or calibration is None:
                    raise ConfigError("catalog_priors: calibration fits the effect catalog's priors on the empty-room "
                                      f"capture in data.calibration, but {calibration!r} is not a capture")
                self._calibration_profile = self._shared_profile_fit(calibration, rank)[0]
            if self.twin_profile is None and self.hparams["calibrate_noise"] and has_capture and calibration is not None:
                self.noise_fit = self._fit_noise(calibration)
        if needs_sim:
            sim = self.simulated_dataset()
            # Equal shards: DDP all-reduces gradients every step, so a rank with one batch more than
            # the others would wait forever. The last n_train % world items are left out.
            # train and val simulated in one pass (the workers set each room variant up once)
            splits = {"train": range(rank, n_train - n_train % world, world),
                      "val": range(n_train + rank, n_train + n_val, world)}
            built = build_map_caches(sim, splits, self.hparams["cache_dir"],
                                     num_workers=self.hparams["sim_workers"],
                                     progress=self.hparams["progress"] and rank == 0)
            train = CachedMaps(built["train"])
            self.train_class_counts = torch.bincount(label_of(train.counts, self.task),
                                                     minlength=len(self.class_names))
            self._train = _Labelled(train, self.task)
            if n_val > 0:
                self._val = _Labelled(CachedMaps(built["val"]), self.task)
            if self.hparams["cdr_floor"] == "matched" and isinstance(self.dr, CalibratedDR):
                self.dr = self._matched_dr(self.dr, train)
            if self.clip is None:
                self.clip = self._estimate_clip(train)
        assert self.clip is not None  # needs_sim whenever it was None
        self.image = image_chain(*self.clip, self.hparams["image_size"], self.hparams["representation"], self.excise,
                                 self._blank)

        tests: list[RadarCaptureDataset] = []
        given_used: set[int] = set()
        for entry in test:
            count = entry.get("count")
            if "dataset" not in entry:
                tests.append(RadarCaptureDataset(entry["path"], label="count" if count is None else int(count),
                                                 transform=rd_db_chain()))
            elif entry["dataset"] not in given_used:
                given_used.add(entry["dataset"])
                # A copy with the module's RD chain: the user's dataset object keeps its own (no)
                # transform (the copy opens its own file handles: RadarCaptureDataset.__getstate__).
                given = copy.copy(self._given_tests[entry["dataset"]])
                given.transform = rd_db_chain()
                tests.append(given)
        for t in tests:
            if t.config != self.config:
                raise ConfigError(f"test capture {t.paths[0]} has another radar config ({t.config.describe()}) "
                                  f"than the training twin ({config.describe()}, from {source})")
        full: ConcatDataset[Any] = ConcatDataset(tests)  # items as RadarCaptureDataset gives them
        self._test = _Labelled(Subset(full, range(rank, len(full), world)), self.task)
        # Where each recording starts, in test order (frame context, RDClassifier.context_frames);
        # a DDP shard strides over the frames, so it has no order to give.
        self.test_recording_starts = _recording_starts(tests) if world == 1 else None
        self._write_run_files()

    def _resolve_receiver(self, calibration: str | None, has_capture: bool, rank: int) -> None:
        """Set :attr:`twin_profile` and :attr:`profile_info`: ``data.profile``, ``cdr_profile``'s fit, or None."""
        self.twin_profile, self.profile_info = None, None
        if self.hparams["profile"] is not None:
            path = str(self.hparams["profile"])
            prof = TwinProfile.load(path)
            info: dict[str, Any] = {"source": "data.profile", "path": path}
        elif self.method in PROFILE_METHODS:
            if not has_capture or calibration is None:
                raise ConfigError(
                    f"method {self.method!r} fits a twin profile on the empty-room capture in data.calibration, but "
                    f"{calibration!r} is a CalibratedDR JSON: give the capture itself, or a fitted profile as "
                    "data.profile (radaraug diagnose CAPTURE -o DIR writes DIR/profile.json)")
            prof, path = self._shared_profile_fit(calibration, rank)
            info = {"source": "fitted on data.calibration", "path": path, "calibration": str(calibration),
                    "max_frames": int(self.hparams["profile_max_frames"])}
        else:
            return
        fitted_on = prof.fitted_on
        if "config" in fitted_on:
            try:
                same = RadarConfig.from_dict(fitted_on["config"]) == self.config
            except (ConfigError, TypeError, ValueError):
                same = False
            if not same:
                warnings.warn(f"twin profile {info['path']} was fitted on a capture with another radar config than "
                              f"the training twin's ({self._setup_config().describe()}); its sensor effects are applied as "
                              "fitted", stacklevel=2)
        info |= {
            "capture": fitted_on.get("capture"),
            "mode": fitted_on.get("mode"),
            "effects": prof.effect_names,
            "effects_added": list(fitted_on.get("effects_added") or []),
            "error_before_dB": fitted_on.get("error_before_dB"),
            "error_after_dB": fitted_on.get("error_after_dB"),
        }
        if self.hparams["calibrate_noise"]:
            info["calibrate_noise"] = NOISE_FIT_SKIPPED
        self.twin_profile, self.profile_info = prof, info

    def _shared_profile_fit(self, calibration: str, rank: int) -> tuple[TwinProfile, str]:
        """The profile fitted on ``calibration`` (cached), fitted on rank 0 and broadcast to the others."""
        data: dict[str, Any] | None = None
        path_fitted: str | None = None
        if rank == 0:  # one diagnose per run; the other DDP ranks get its result
            fitted, cached = self._fit_profile(calibration)
            data, path_fitted = fitted.to_dict(), str(cached)
        data, path_fitted = self._from_rank0((data, path_fitted))
        if data is None or path_fitted is None:
            raise CalibrationError(f"rank {rank} did not receive the twin profile fitted on rank 0")
        return TwinProfile.from_dict(data, source=path_fitted), path_fitted

    def profile_cache_path(self, calibration: str) -> Path:
        """``cache_dir/profile-<key>.json`` of ``calibration`` (keyed by its bytes, frames read, fit version)."""
        key = cache_key({"format": PROFILE_FIT_FORMAT, "version": PROFILE_FIT_VERSION,
                         "profile_version": PROFILE_VERSION, "capture_sha256": content_digest(calibration),
                         "scene": None, "max_frames": int(self.hparams["profile_max_frames"])})
        return Path(self.hparams["cache_dir"]) / f"profile-{key}.json"

    def _fit_profile(self, calibration: str) -> tuple[TwinProfile, Path]:
        """The twin profile fitted on the calibration capture (empty room, no scene), cached."""
        from radaraug.calibration.record import cached_profile_fit

        path = self.profile_cache_path(calibration)
        return cached_profile_fit(calibration, path, max_frames=int(self.hparams["profile_max_frames"]),
                                  progress=bool(self.hparams["progress"])), path

    def _fit_noise(self, calibration: str) -> dict[str, Any]:
        """The twin's noise figure fitted to the calibration capture's floor (cached in cache_dir)."""
        from radaraug.calibration.record import cached_noise_fit

        return cached_noise_fit(calibration, scene=str(self.hparams["scene"]), config=self._setup_config(),
                                cache_dir=self.hparams["cache_dir"], tracer_rays=self.hparams["tracer_rays"])

    def _persistent_cells(self, calibration: str) -> torch.Tensor:
        """The calibration capture's persistent lines (``excise_persistent_db``), as an RD-map mask."""
        from radaraug.calibration.record import persistent_cells_of

        return persistent_cells_of(calibration, float(self.hparams["excise_persistent_db"]), rd_db_chain())

    def _matched_dr(self, dr: CalibratedDR, train: CachedMaps) -> CalibratedDR:
        """``dr`` with its floor quantiles matched to the twin's own empty-room floor (``cdr_floor="matched"``)."""
        from radaraug.transforms.dsp_spec import doppler_window_of
        from radaraug.transforms.floor_fit import floor_values, matched_floor_quantiles

        empty = (train.counts == 0).nonzero().flatten()[:256].tolist()
        if not empty or dr.quantiles_db is None:
            raise ConfigError("cdr_floor='matched' needs empty items in the training split and a calibration with "
                              "recorded floor quantiles (fit it from the capture, not from an old JSON)")
        twin = floor_values(train.maps(empty).float(), doppler_window_of(dr.chain) or "hann")
        q = matched_floor_quantiles(dr.quantiles_db, twin)
        return dr.replace(floor="empirical", quantiles_db=self._from_rank0(q),
                          seed=self.hparams["dr_seed"] + 1000 * _rank_world(self.trainer)[0])

    @property
    def _blank(self) -> int:
        """Doppler bins blanked on each side of zero (hparams of older checkpoints lack the key: 1)."""
        return int(self.hparams.get("blank_zero_doppler", 1))

    def _estimate_clip(self, train: CachedMaps) -> tuple[float, float]:
        maps = train.maps(slice(0, 256))
        vmin, vmax = estimate_clip_range(maps, self.dr, percentiles=tuple(self.hparams["clip_percentiles"]),
                                         representation=self.hparams["representation"], excise=self.excise,
                                         blank_zero_doppler=self._blank)
        vmin, vmax = self._from_rank0((vmin, vmax))
        return float(vmin), float(vmax)

    def _from_rank0(self, value: Any) -> Any:
        """Under DDP, rank 0's ``value`` on every rank (``value`` itself on one process)."""
        if self.trainer is not None and self.trainer.world_size > 1:
            return self.trainer.strategy.broadcast(value, src=0)
        return value

    def _write_run_files(self) -> None:
        out = self.hparams["out_dir"]
        if out is None and self.trainer is not None:
            out = self.trainer.log_dir
        if out is None or (self.trainer is not None and self.trainer.global_rank != 0):
            return
        Path(out).mkdir(parents=True, exist_ok=True)
        info = {"clip_range_db": None if self.clip is None else list(self.clip), "task": self.task, "method": self.method,
                "twin_receiver": self.receiver_kind(),
                "twin_noise_fit": NOISE_FIT_SKIPPED if self.twin_profile is not None and self.hparams["calibrate_noise"]
                else self.noise_fit,
                "twin_profile": self.profile_info,
                "catalog_priors": self.catalog_prior_info,
                "classes": list(self.class_names), "config": self._setup_config().to_dict(),
                "train_class_counts": None if self.train_class_counts is None else self.train_class_counts.tolist()}
        atomic_write_json(Path(out) / "clip_range.json", info, newline=False, indent=2)

    def _quiet_twin_db(self) -> float | None:
        """The CDR twin's noise offset (``cdr_twin_noise_offset_db``), for the ``cdr`` method only."""
        off = self.hparams["cdr_twin_noise_offset_db"]
        return None if off is None or self.method != "cdr" else float(off)

    def receiver_kind(self) -> str:
        """What the twin's receiver is: ``profile``, ``noise_fit`` or ``default`` (+ ``quiet`` for CDR's)."""
        if self.twin_profile is not None:
            return "profile"
        kind = "noise_fit" if self.noise_fit is not None else "default"
        quiet = self._quiet_twin_db()
        return kind if quiet is None else f"{kind}, noise {quiet:+g} dB (cdr_twin_noise_offset_db)"

    def state_dict(self) -> dict[str, Any]:
        """The clip range and the excised cells, saved in checkpoints (they are part of the model)."""
        # Part of the model: a checkpoint tested later must clip and excise the same way.
        return {"clip_range": None if self.clip is None else list(self.clip),
                "excise": None if self.excise is None else self.excise.nonzero().tolist(),
                "excise_shape": None if self.excise is None else list(self.excise.shape)}

    def load_state_dict(self, state_dict: dict[str, Any]) -> None:
        """Restore the clip range, the excised cells (and the image chain) from a checkpoint."""
        if state_dict.get("excise") is not None:
            mask = torch.zeros(*state_dict["excise_shape"], dtype=torch.bool)
            cells = torch.tensor(state_dict["excise"], dtype=torch.long).reshape(-1, 2)
            mask[cells[:, 0], cells[:, 1]] = True
            self.excise = mask
        if state_dict.get("clip_range") is not None:
            vmin, vmax = state_dict["clip_range"]
            self.clip = (vmin, vmax)
            self.image = image_chain(*self.clip, self.hparams["image_size"], self.hparams["representation"],
                                     self.excise, self._blank)

    def _loader(self, ds: Dataset | None, *, shuffle: bool) -> DataLoader:
        if ds is None:
            raise ConfigError("this split is empty or setup() has not run")
        g = torch.Generator().manual_seed(self.hparams["dr_seed"])
        bs = self.hparams["batch_size"]
        # Training drops a last partial batch: one of a single item breaks BatchNorm (and a short
        # one skews its statistics), unless the whole split is smaller than a batch.
        return DataLoader(ds, batch_size=bs, shuffle=shuffle, generator=g if shuffle else None,
                          drop_last=shuffle and isinstance(ds, Sized) and len(ds) > bs,
                          num_workers=self.hparams["num_workers"], persistent_workers=self.hparams["num_workers"] > 0)

    def train_dataloader(self) -> DataLoader:
        """The training split's loader (shuffled)."""
        return self._loader(self._train, shuffle=True)

    def val_dataloader(self) -> DataLoader | list:
        """The validation split's loader (an empty list when there is none)."""
        return self._loader(self._val, shuffle=False) if self._val is not None else []

    def test_dataloader(self) -> DataLoader:
        """The test captures' loader."""
        return self._loader(self._test, shuffle=False)

    def on_after_batch_transfer(self, batch: Any, dataloader_idx: int) -> Any:
        """Apply the DR (simulated splits only) and the image chain on the batch's device."""
        x, y = batch
        if self.image is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        trainer = self.trainer
        # Simulated splits (train and held-out val) go through the run's DR; captures only with test_dr.
        if self.dr is not None and trainer is not None and (trainer.training or trainer.validating
                                                            or trainer.sanity_checking
                                                            or (trainer.testing and self.hparams["test_dr"])):
            x = self.dr.to(x.device).train()(x)
        return self.image.to(x.device)(x), y

    def images(self, db_maps: torch.Tensor) -> torch.Tensor:
        """Network inputs from per-RX dB maps, without DR (this run's clip range): for figures."""
        if self.image is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        return self.image(db_maps)
