"""`RadarDataModule`: train on the twin, validate on held-out simulation, test on captures.

It takes built objects: a :mod:`method <radaraug.training.methods>`, the simulated splits' spec
(:class:`~radaraug.training.preparation.TwinSplits`), the image spec and the test captures;
:func:`~radaraug.training.preparation.prepare` turns the calibration capture into the DR, the excision
and the twin. The train and val items are simulated once into the map cache
(:mod:`radaraug.training.cache`) and get the run's DR on the device; captures never get DR (unless the
method's ``test_dr``). See docs/training.md.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence, Sized
from pathlib import Path
from typing import Any

import lightning as L
import torch
from torch.utils.data import ConcatDataset, DataLoader, Dataset, Subset

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.files import atomic_write_json
from radaraug.io import RadarCaptureDataset
from radaraug.testsets.checks import dataset_entries, parse_test_entry
from radaraug.testsets.tasks import check_task, label_of
from radaraug.training.cache import CachedMaps, build_map_caches, default_cache_dir
from radaraug.training.inputs import check_inputs
from radaraug.training.methods import Method, RandomDR, method_from
from radaraug.training.observable import observable_counts, person_range_bins
from radaraug.training.pipeline import estimate_clip_range, image_chain, is_calibration_json, rd_db_chain
from radaraug.training.preparation import NOISE_FIT_SKIPPED, ImageSpec, Prepared, TwinSplits, prepare
from radaraug.transforms import CalibratedDR, RadarCompose

#: Test frames per people count of the held-out proxy generated when a run names no test captures.
PROXY_FRAMES_PER_COUNT = 120


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
    """The paper's data side as a LightningDataModule (every argument is a recipe key; docs/training.md).

    Args:
        task: ``occupancy`` (2 classes) or ``counting`` (0/1/2 people).
        method: the noise-floor randomization and its twin (:mod:`radaraug.training.methods`; default
            :class:`~radaraug.training.methods.RandomDR`: it wins on held-out data).
        calibration: the empty-room capture recorded like the test captures: the twin simulates its radar
            config, its persistent lines are excised, CDR's floor (and ``CDRProfile``'s profile) is fitted on
            it. A calibration record (JSON) serves what it holds (a warning names what is left out). None with no
            ``test``:
            the held-out proxy's.
        test: test captures: ``"PATH:N"`` / ``{"path", "count": N}`` (N people in the whole file),
            ``"PATH"`` / ``{"path"}`` (the file's per-frame ``count`` labels), or a
            :class:`~radaraug.io.RadarCaptureDataset` labelled with people counts and without a transform
            (:func:`~radaraug.testsets.checks.dataset_entries`). None: the held-out proxy, generated once
            under ``cache_dir/proxy``. ``[]``: no test captures (fit only; the radar config is then the
            calibration's).
        twin: the simulated splits (:class:`~radaraug.training.preparation.TwinSplits`).
        image: the network input (:class:`~radaraug.training.preparation.ImageSpec`).
        cache_dir: folder of the simulate-once cache and the cached fits (None: the user's cache folder,
            :func:`radaraug.raytrace.cache.default_cache_dir`).
        batch_size: training batch size.
        num_workers: DataLoader workers for training and test reads.
        seed: seed of the DR draws and the shuffling (rank ``r`` draws with ``seed + 1000 r``).

    Raises:
        ConfigError: an unknown task or a malformed test entry.
    """

    def __init__(
        self,
        task: str = "occupancy",
        method: Method | None = None,
        calibration: str | None = None,
        test: list[RadarCaptureDataset | str | dict[str, Any]] | None = None,
        twin: TwinSplits | None = None,
        image: ImageSpec | None = None,
        cache_dir: str | None = None,
        batch_size: int = 32,
        num_workers: int = 0,
        seed: int = 0,
    ) -> None:
        super().__init__()
        self.class_names = check_task(task)
        self.task = task
        # specs given as plain values (a checkpoint's hparams, a recipe) are built here
        self.method = RandomDR() if method is None else method_from(method)
        self.twin = TwinSplits() if twin is None else TwinSplits(**twin) if isinstance(twin, dict) else twin
        self.image_spec = ImageSpec() if image is None else ImageSpec(**image) if isinstance(image, dict) else image
        # the specs as plain values: checkpoints and saved configs hold no objects
        self.save_hyperparameters(ignore=["method", "twin", "image", "test"])
        self.hparams.update(method=self.method.to_dict(), twin=self.twin.to_dict(), image=self.image_spec.to_dict())
        self.hparams["cache_dir"] = str(Path(cache_dir) if cache_dir is not None else default_cache_dir())
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
        clip = self.image_spec.clip_range
        self.clip: tuple[float, float] | None = None if clip is None else (float(clip[0]), float(clip[1]))
        self.dr: torch.nn.Module | None = None
        self.image: torch.nn.Module | None = None
        self.excise: torch.Tensor | None = None
        self.prepared: Prepared | None = None
        self._train: Dataset | None = None
        self._val: Dataset | None = None
        self._test: Dataset | None = None
        #: where each recording starts in the test order (set by setup; None under DDP: shards stride over frames)
        self.test_recording_starts: torch.Tensor | None = None
        self.train_class_counts: torch.Tensor | None = None
        #: with ``count_labels: observable``, training items whose counting label was lowered and the detection
        #: threshold (dB over the row's floor)
        self.observable_relabelled: dict[str, Any] | None = None

    @classmethod
    def from_recipe(cls, data: dict[str, Any]) -> RadarDataModule:
        """The data module of a recipe's ``data`` section, or of a checkpoint's hyperparameters (plain values).

        Raises:
            ConfigError: an unknown key or method.
        """
        try:
            return cls(**data)
        except TypeError as e:
            raise ConfigError(f"data: {e}") from None

    @property
    def config(self) -> RadarConfig | None:
        """The radar config :meth:`setup` read from the captures (None before)."""
        return None if self.prepared is None else self.prepared.config

    def _setup_config(self) -> RadarConfig:
        if self.prepared is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        return self.prepared.config

    # ------------------------------------------------------------------ resolving inputs
    def _proxy(self) -> Any:
        from radaraug.testsets.proxy import make_proxy

        return make_proxy(Path(self.hparams["cache_dir"]) / "proxy", frames_per_count=PROXY_FRAMES_PER_COUNT,
                          progress=self.twin.progress)

    def resolved_captures(self) -> tuple[str | None, list[dict[str, Any]]]:
        """``(calibration, test entries)``, the held-out proxy's where the config names none."""
        calibration, test = self.hparams["calibration"], self.hparams["test"]
        if test is None:
            proxy = self._proxy()
            test = [{"path": str(p), "count": int(c)} for p, c in proxy.tests]
            if calibration is None:
                calibration = str(proxy.calibration)
        elif calibration is None and self.method.needs_calibration:
            # The proxy's empty room says nothing about the user's captures: no silent stand-in.
            raise ConfigError(f"method {self.method.name!r} needs data.calibration: an empty-room capture (or "
                              "calibration record) recorded like the test captures")
        return calibration, [dict(e) for e in test]  # the config's entries were checked in __init__

    def prepare_data(self) -> None:
        """Generate the held-out proxy captures once per node when no test captures are given."""
        # Rank 0 of each node generates the proxy once; the other ranks reuse its files in setup().
        if self.hparams["test"] is None:
            self._proxy()

    def simulated_dataset(self, length: int | None = None, seed: int | None = None) -> Any:
        """The training twin's dataset in the test captures' radar config (after :meth:`setup`).

        Args:
            length: items (None: ``train_items + val_items``).
            seed: the set's seed (None: ``twin.seed``).
        """
        from radaraug.training.preparation import simulated_dataset

        if self.prepared is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        if length is None and seed is None and self.prepared.simulated is not None:
            return self.prepared.simulated
        return simulated_dataset(self.prepared, self.method, self.twin, length=length, seed=seed)

    # ------------------------------------------------------------------ Lightning hooks
    def setup(self, stage: str | None = None) -> None:
        """Resolve captures, DR and receiver; build the simulated splits (cached) and the image chain."""
        if self.image is not None and (stage != "test" or self._test is not None):
            return
        rank, world = _rank_world(self.trainer)
        calibration, test = self.resolved_captures()
        # Before any simulation: a test set that cannot score the task, or a calibration that cannot
        # serve the method, is refused (or warned about) now, not after training.
        check_inputs(test, self.task, calibration=calibration, method=self.method, profile=self.twin.profile,
                     calibrate_noise=self.twin.calibrate_noise, excise=self.image_spec.excises and self.excise is None)
        has_capture = calibration is not None and not is_calibration_json(calibration)
        source = calibration if calibration is not None and has_capture else test[0]["path"] if test else None
        n_train, n_val = self.twin.train_items, self.twin.val_items
        needs_sim = stage in (None, "fit", "validate") or self.clip is None
        self.prepared = p = prepare(self.method, calibration, source, self.twin, self.image_spec,
                                    self.hparams["cache_dir"], dr_seed=self.hparams["seed"] + 1000 * rank,
                                    simulate=needs_sim, fit_excision=self.excise is None and self.clip is None,
                                    broadcast=self._from_rank0, rank=rank)
        self.dr = p.dr
        if self.excise is None:
            self.excise = p.excise
        if needs_sim:
            # Equal shards: DDP all-reduces gradients every step, so a rank with one batch more than
            # the others would wait forever. The last n_train % world items are left out.
            # train and val simulated in one pass (the workers set each room variant up once)
            splits = {"train": range(rank, n_train - n_train % world, world),
                      "val": range(n_train + rank, n_train + n_val, world)}
            built = build_map_caches(p.simulated, splits, self.hparams["cache_dir"], num_workers=self.twin.workers,
                                     progress=self.twin.progress and rank == 0,
                                     interference_db=self.image_spec.excise_interference_db)
            train = CachedMaps(built["train"])
            if self.task == "counting" and self.twin.count_labels == "observable":
                self._observable_labels(train, p.simulated)
            self.train_class_counts = torch.bincount(label_of(train.counts, self.task),
                                                     minlength=len(self.class_names))
            self._train = _Labelled(train, self.task)
            if n_val > 0:
                self._val = _Labelled(CachedMaps(built["val"]), self.task)
            if self.method.floor == "matched" and isinstance(self.dr, CalibratedDR):
                self.dr = self._matched_dr(self.dr, train)
            if self.clip is None:
                self.clip = self._estimate_clip(train)
        assert self.clip is not None  # needs_sim whenever it was None
        self.image = self._image_chain()

        tests: list[RadarCaptureDataset] = []
        given_used: set[int] = set()
        for entry in test:
            count = entry.get("count")
            if "dataset" not in entry:
                tests.append(RadarCaptureDataset(entry["path"], label="count" if count is None else int(count),
                                                 transform=self.rd_chain()))
            elif entry["dataset"] not in given_used:
                given_used.add(entry["dataset"])
                # A copy with the module's RD chain: the user's dataset object keeps its own (no)
                # transform (the copy opens its own file handles: RadarCaptureDataset.__getstate__).
                given = copy.copy(self._given_tests[entry["dataset"]])
                given.transform = self.rd_chain()
                tests.append(given)
        for t in tests:
            if t.config != p.config:
                raise ConfigError(f"test capture {t.paths[0]} has another radar config ({t.config.describe()}) "
                                  f"than the training twin ({p.config.describe()}, from {source})")
        if tests:
            full: ConcatDataset[Any] = ConcatDataset(tests)  # items as RadarCaptureDataset gives them
            self._test = _Labelled(Subset(full, range(rank, len(full), world)), self.task)
        # Where each recording starts, in test order (frame context, RDClassifier.context_frames);
        # a DDP shard strides over the frames, so it has no order to give.
        self.test_recording_starts = _recording_starts(tests) if world == 1 else None
        if self.trainer is not None:
            folder = self.trainer.log_dir  # every rank asks: Lightning broadcasts it
            if self.trainer.global_rank == 0:
                self.write_run_files(folder)

    def _observable_labels(self, train: CachedMaps, dataset: Any) -> None:
        """Lower ``train``'s counts to the people each map shows apart (``count_labels: observable``)."""
        bins = [person_range_bins(dataset, int(i)) for i in train.indices]
        counts, threshold = observable_counts(train.maps(), train.counts, bins, excise=self.excise,
                                              blank_zero_doppler=self.image_spec.blank_zero_doppler)
        self.observable_relabelled = {"items": int((counts != train.counts).sum()), "threshold_db": threshold}
        train.counts = counts

    def rd_chain(self) -> RadarCompose:
        """Raw frames -> per-RX dB maps, as this module's simulated maps were made (captures and twin alike)."""
        return rd_db_chain(self.image_spec.excise_interference_db)

    def _image_chain(self) -> torch.nn.Module:
        assert self.clip is not None
        s = self.image_spec
        return image_chain(*self.clip, s.size, s.representation, self.excise, s.blank_zero_doppler, s.resample)

    def _matched_dr(self, dr: CalibratedDR, train: CachedMaps) -> CalibratedDR:
        """``dr`` with its floor quantiles matched to the twin's own empty-room floor (the ``matched`` floor)."""
        from radaraug.transforms.dsp_spec import doppler_window_of
        from radaraug.transforms.floor_fit import floor_values, matched_floor_quantiles

        empty = (train.counts == 0).nonzero().flatten()[:256].tolist()
        if not empty or dr.quantiles_db is None:
            raise ConfigError("CDR floor 'matched' needs empty items in the training split and a calibration with "
                              "recorded floor quantiles (fit it from the capture, not from an old JSON)")
        twin = floor_values(train.maps(empty).float(), doppler_window_of(dr.chain) or "hann")
        q = matched_floor_quantiles(dr.quantiles_db, twin)
        return dr.replace(floor="empirical", quantiles_db=self._from_rank0(q),
                          seed=self.hparams["seed"] + 1000 * _rank_world(self.trainer)[0])

    def _estimate_clip(self, train: CachedMaps) -> tuple[float, float]:
        s = self.image_spec
        vmin, vmax = estimate_clip_range(train.maps(slice(0, 256)), self.dr, percentiles=(s.clip_percentiles[0], s.clip_percentiles[1]),
                                         representation=s.representation, excise=self.excise,
                                         blank_zero_doppler=s.blank_zero_doppler)
        vmin, vmax = self._from_rank0((vmin, vmax))
        return float(vmin), float(vmax)

    def _from_rank0(self, value: Any) -> Any:
        """Under DDP, rank 0's ``value`` on every rank (``value`` itself on one process)."""
        if self.trainer is not None and self.trainer.world_size > 1:
            return self.trainer.strategy.broadcast(value, src=0)
        return value

    def write_run_files(self, folder: str | Path | None) -> None:
        """Write ``folder/clip_range.json``: the clip range, the twin's receiver and fits, the radar config."""
        if folder is None:
            return
        Path(folder).mkdir(parents=True, exist_ok=True)
        p = self.prepared
        info = {"clip_range_db": None if self.clip is None else list(self.clip), "task": self.task,
                "method": self.method.name, "twin_receiver": self.receiver_kind(),
                "twin_noise_fit": None if p is None else NOISE_FIT_SKIPPED
                if p.twin_profile is not None and self.twin.calibrate_noise else p.noise_fit,
                "twin_profile": None if p is None else p.profile_info,
                "catalog_priors": None if p is None else p.catalog_prior_info,
                "classes": list(self.class_names), "config": self._setup_config().to_dict(),
                "train_class_counts": None if self.train_class_counts is None else self.train_class_counts.tolist()}
        atomic_write_json(Path(folder) / "clip_range.json", info, newline=False, indent=2)

    def receiver_kind(self) -> str:
        """What the twin's receiver is: ``profile``, ``noise_fit`` or ``default`` (+ ``quiet`` for CDR's)."""
        if self.prepared is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        return self.prepared.receiver_kind(self.method)

    def state_dict(self) -> dict[str, Any]:
        """The clip range, the excised cells, the interference threshold and the resample, saved in checkpoints."""
        # Part of the model: a checkpoint tested later must clip and excise the same way.
        return {"clip_range": None if self.clip is None else list(self.clip),
                "excise": None if self.excise is None else self.excise.nonzero().tolist(),
                "excise_shape": None if self.excise is None else list(self.excise.shape),
                "interference_db": self.image_spec.excise_interference_db, "resample": self.image_spec.resample}

    def load_state_dict(self, state_dict: dict[str, Any]) -> None:
        """Restore the clip range, the excised cells (and the image chain) from a checkpoint.

        Raises:
            ConfigError: the checkpoint's network saw maps with another interference excision or resample than
                this module's ``image.excise_interference_db`` / ``image.resample`` (a checkpoint without the key:
                none / bilinear).
        """
        # absent from checkpoints of before the excision / the resample option: none / bilinear
        for key, saved in (("excise_interference_db", state_dict.get("interference_db")),
                           ("resample", state_dict.get("resample", "bilinear"))):
            if saved != getattr(self.image_spec, key):
                raise ConfigError(f"the checkpoint was trained with data.image.{key}: {saved}, this data module has "
                                  f"{getattr(self.image_spec, key)}: set it to {saved} to test it with the chain it "
                                  "was trained on")
        if state_dict.get("excise") is not None:
            mask = torch.zeros(*state_dict["excise_shape"], dtype=torch.bool)
            cells = torch.tensor(state_dict["excise"], dtype=torch.long).reshape(-1, 2)
            mask[cells[:, 0], cells[:, 1]] = True
            self.excise = mask
        if state_dict.get("clip_range") is not None:
            vmin, vmax = state_dict["clip_range"]
            self.clip = (vmin, vmax)
            self.image = self._image_chain()

    def _loader(self, ds: Dataset | None, *, shuffle: bool) -> DataLoader:
        if ds is None:
            raise ConfigError("this split is empty or setup() has not run")
        g = torch.Generator().manual_seed(self.hparams["seed"])
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
        """The test captures' loader.

        Raises:
            ConfigError: the module was given no test captures (``test=[]``).
        """
        if self._test is None and self.hparams["test"] == []:
            raise ConfigError("this data module was given no test captures (test=[]): nothing to test on")
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
                                                            or (trainer.testing and self.method.test_dr)):
            x = self.dr.to(x.device).train()(x)
        return self.image.to(x.device)(x), y

    def images(self, db_maps: torch.Tensor) -> torch.Tensor:
        """Network inputs from per-RX dB maps, without DR (this run's clip range): for figures."""
        if self.image is None:
            raise ConfigError("RadarDataModule.setup() has not run")
        return self.image(db_maps)
