"""One preparation step: from the calibration capture and a run's specs to the objects a run trains with.

:func:`prepare` reads the radar config, builds the method's DR, the excision mask and the twin's receiver
(a twin profile, the noise fit, or the default; CDR's quiet twin), and the simulated dataset.
:class:`~radaraug.training.RadarDataModule` calls it in ``setup``; :func:`~radaraug.training.training_chains`
too. docs/training.md, "Objects, not strings".
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any, Literal

import torch
from torch import nn

from radaraug.config import RadarConfig
from radaraug.diagnosis.record import INTERFERENCE_THRESHOLD_DB, PERSISTENT_THRESHOLD_DB
from radaraug.errors import CalibrationError, ConfigError
from radaraug.sensor.profile import PROFILE_VERSION, TwinProfile
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.training.methods import CDR, Method
from radaraug.training.pipeline import check_representation, check_resample, is_calibration_json
from radaraug.transforms.record_file import CalibrationRecord, load_record

#: Where the twin randomization's effect catalog takes its priors (``TwinSplits.catalog_priors``).
CATALOG_PRIORS = ("physics", "calibration")
COUNT_LABELS = ("drawn", "observable")
PROFILE_FIT_FORMAT = "radaraug-profile-fit"
#: Version of the cached ``cdr_profile`` fits (``cache_dir/profile-<key>.json``): part of their key,
#: bumped when what :func:`radaraug.diagnosis.diagnose` fits changes, so old fits are not reused.
PROFILE_FIT_VERSION = 1
NOISE_FIT_SKIPPED = "skipped: the twin's receiver comes from the twin profile (its fitted chain sets the floor)"


@dataclasses.dataclass
class TwinSplits:
    """The simulated training and validation splits (a recipe's ``data.twin``).

    Args:
        scene: training scene: built-in name or scene file.
        train_items, val_items: simulated items for training and validation.
        seed: seed of the simulated set (item ``i`` is a function of ``(seed, i)``).
        randomization: twin randomization: True (defaults), False/None (off), or a mapping of its sections
            (:class:`~radaraug.sim.randomization.TwinRandomization`).
        catalog_priors: ``"physics"`` (the effect catalog's own ranges) or ``"calibration"`` (centred on the
            effects ``diagnose`` adds on the calibration capture: :mod:`radaraug.diagnosis.priors`).
        calibrate_noise: fit the twin's noise figure to the calibration capture's floor (skipped when the
            receiver is a profile).
        profile: a twin profile JSON (``radaraug diagnose`` writes one) the twin's receiver is built from, any
            method; for ``CDRProfile`` it replaces the fitted one.
        tracer_rays: trace the room with SBR at this many rays per axis (None: the image method).
        workers: DataLoader workers that simulate while the cache is built.
        progress: progress bars while simulating and fitting.
        count_labels: counting's training labels: ``"drawn"`` (the people drawn) or ``"observable"`` (no more
            than the map shows apart: :func:`~radaraug.training.observable.observable_counts`).
        dataset: a :class:`~radaraug.sim.SimulatedRadarDataset` used as given instead of the one built from
            the fields above (the fitted-receiver options are then not applied; a warning names them). It
            needs the test captures' radar config, target ``count`` and ``train_items + val_items`` items.

    Raises:
        ConfigError: sizes, ``catalog_priors`` or ``count_labels`` out of range.
    """

    scene: str = "corridor"
    train_items: int = 1200
    val_items: int = 240
    seed: int = 0
    randomization: bool | dict[str, Any] | None = True
    catalog_priors: Literal["physics", "calibration"] = "physics"
    calibrate_noise: bool = False
    profile: str | None = None
    tracer_rays: int | None = None
    workers: int = 0
    progress: bool = True
    count_labels: Literal["drawn", "observable"] = "drawn"
    dataset: SimulatedRadarDataset | None = None

    def __post_init__(self) -> None:
        if self.train_items < 1 or self.val_items < 0:
            raise ConfigError(f"train_items must be >= 1 and val_items >= 0, got {self.train_items}, {self.val_items}")
        if self.catalog_priors not in CATALOG_PRIORS:
            raise ConfigError(f"catalog_priors must be one of {CATALOG_PRIORS}, got {self.catalog_priors!r}")
        if self.count_labels not in COUNT_LABELS:
            raise ConfigError(f"count_labels must be one of {COUNT_LABELS}, got {self.count_labels!r}")

    def to_dict(self) -> dict[str, Any]:
        """The fields as plain values (``dataset`` left out)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.name != "dataset"}


@dataclasses.dataclass
class ImageSpec:
    """What the network sees (a recipe's ``data.image``; docs/training.md, "Representations").

    Args:
        size: network input ``[H, W]`` (None: the RD map's own size).
        representation: ``"floor_relative"`` (:class:`~radaraug.transforms.FloorRelative`) or ``"paper"``
            (the RX-combined dBFS map, clipped).
        blank_zero_doppler: with ``floor_relative``: Doppler bins blanked on each side of zero.
        excise_persistent_db: with ``floor_relative``: cells whose median over the calibration capture stands
            this many dB above their row's floor are set to the floor in every map (None: none).
        excise_interference_db: replace each frame's chirps whose moving power stands this many dB over the
            frame's median chirp (another radar's burst; :class:`~radaraug.transforms.InterferenceExcision`),
            before the RD FFTs, in training and test alike (6; None: none).
        resample: how the map shrinks to ``size``: ``"bilinear"`` (the colour image resized, the paper's) or
            ``"max"`` (each pixel the max of the levels it covers, before the colour map).
        clip_percentiles: percentiles of simulated (post-DR) maps that give ``[vmin, vmax]``.
        clip_range: a fixed ``[vmin, vmax]`` instead of the estimate.

    Raises:
        ConfigError: an unknown representation or resample, or a malformed clip range.
    """

    size: list[int] | None = None
    representation: Literal["paper", "floor_relative"] = "floor_relative"
    blank_zero_doppler: int = 1
    excise_persistent_db: float | None = PERSISTENT_THRESHOLD_DB
    excise_interference_db: float | None = INTERFERENCE_THRESHOLD_DB  # chosen on the design suite (docs/training.md)
    resample: Literal["bilinear", "max"] = "bilinear"
    clip_percentiles: tuple[float, float] = (1.0, 99.9)
    clip_range: list[float] | None = None

    def __post_init__(self) -> None:
        check_representation(self.representation)
        check_resample(self.resample)
        lo, hi = self.clip_percentiles  # a YAML list or a tuple: one value
        self.clip_percentiles = (float(lo), float(hi))
        if self.clip_range is not None and len(self.clip_range) != 2:
            raise ConfigError(f"clip_range must be [vmin, vmax], got {self.clip_range!r}")
        if self.excise_interference_db is not None and not float(self.excise_interference_db) > 0:
            raise ConfigError(f"excise_interference_db must be > 0 dB or null, got {self.excise_interference_db!r}")

    @property
    def excises(self) -> bool:
        """Whether the calibration capture's persistent lines are excised."""
        return self.representation == "floor_relative" and self.excise_persistent_db is not None

    def to_dict(self) -> dict[str, Any]:
        """The fields as plain values."""
        return dataclasses.asdict(self) | {"clip_percentiles": list(self.clip_percentiles)}


@dataclasses.dataclass
class Prepared:
    """What :func:`prepare` builds (see there)."""

    config: RadarConfig
    dr: nn.Module | None
    excise: torch.Tensor | None
    simulated: Any = None
    twin_profile: TwinProfile | None = None
    profile_info: dict[str, Any] | None = None
    noise_fit: dict[str, Any] | None = None
    catalog_prior_info: dict[str, Any] | None = None

    def receiver_kind(self, method: Method) -> str:
        """What the twin's receiver is: ``profile``, ``noise_fit`` or ``default`` (+ ``quiet`` for CDR's)."""
        if self.twin_profile is not None:
            return "profile"
        kind = "noise_fit" if self.noise_fit is not None else "default"
        quiet = method.twin_noise_offset_db
        return kind if quiet is None else f"{kind}, noise {quiet:+g} dB (twin_noise_offset_db)"


def _same_process(value: Any) -> Any:
    return value


def _check_record_chain(record: CalibrationRecord, path: str, run_chain: list[dict[str, Any]]) -> None:
    """Warn when a calibration record was fitted on maps made otherwise than the run makes them."""
    from radaraug.training.inputs import CalibrationWarning
    from radaraug.transforms.dsp_spec import canonical_chain, describe_chain

    fitted = (record.cdr or {}).get("chain")
    if fitted is not None and canonical_chain(fitted) != canonical_chain(run_chain):
        warnings.warn(f"calibration record {path} was fitted on maps made by {describe_chain(fitted)}, but this run "
                      f"makes {describe_chain(run_chain)}: its floor and persistent cells may not match the run's maps; "
                      "refit it with `radaraug fit-cdr` (it fits on the recipes' chain)", CalibrationWarning,
                      stacklevel=3)


def prepare(method: Method, calibration: str | None, source: str | None, twin: TwinSplits, image: ImageSpec,
            cache_dir: str | Path, *, dr_seed: int, simulate: bool = True, fit_excision: bool = True,
            broadcast: Callable[[Any], Any] = _same_process, rank: int = 0) -> Prepared:
    """The radar config, DR, excision mask, receiver and simulated dataset of one run.

    Args:
        method: the run's method.
        calibration: the empty-room capture, a calibration record (JSON: what it holds is used), or None.
        source: the capture whose radar config the twin simulates (the calibration capture, else a test file;
            None: the calibration's, capture or record).
        twin: the simulated splits' spec.
        image: the network input's spec (whether to excise).
        cache_dir: where the fits are cached.
        dr_seed: the DR's seed on this process.
        simulate: also resolve the receiver and build the simulated dataset (not needed to test a model
            whose clip range is known).
        fit_excision: fit the excision mask (False: the caller already has one, a checkpoint's).
        broadcast: under DDP, rank 0's value on every rank (the profile fit is made on rank 0 only).
        rank: this process's rank.

    Raises:
        ConfigError: a method that needs what the calibration cannot give, or no config (no ``source`` and
            no calibration record holding one).
        CalibrationError: the profile fit did not reach this rank.
    """
    from radaraug.io import open_capture
    from radaraug.training.pipeline import rd_db_chain
    from radaraug.transforms import CalibratedDR

    has_capture = calibration is not None and not is_calibration_json(calibration)
    record = None if calibration is None or has_capture else load_record(calibration)
    config_from = source if source is not None else calibration if has_capture else None
    if config_from is not None:
        with open_capture(config_from) as cap:
            config = cap.config
    elif record is not None and record.config is not None:
        config = record.config
    else:
        raise ConfigError(f"no radar config: no capture to read it from, and the calibration {calibration!r} is "
                          "not a calibration record that holds one")
    maps = rd_db_chain(image.excise_interference_db)  # raw frames -> dB maps, as this run makes them
    if record is not None and record.cdr is not None:
        _check_record_chain(record, str(calibration), maps.chain_spec())
    # CDR's floor from the capture's maps as the run makes them (without the bursts the excision removes)
    dr_source: Any = CalibratedDR.fit(calibration, pipeline=maps, progress=False) \
        if isinstance(method, CDR) and has_capture else calibration
    dr = method.dr(dr_source, dr_seed)
    if isinstance(dr, CalibratedDR):
        dr.check_config(config)
    excise = None
    if fit_excision and image.excises and has_capture and calibration is not None:
        from radaraug.diagnosis.record import persistent_cells_of

        excise = persistent_cells_of(calibration, float(image.excise_persistent_db or 0.0), maps)
    elif fit_excision and image.excises and record is not None:
        excise = record.persistent_mask()  # at the record's threshold (radaraug fit-cdr records the recipes')
        shape = (config.num_range_bins, config.num_chirps_per_frame)
        if excise is not None and tuple(excise.shape) != shape:
            raise ConfigError(f"calibration record {calibration}: its persistent cells are of a {tuple(excise.shape)} "
                              f"map, the captures' maps are {shape} (another radar config)")
    out = Prepared(config, dr, excise)
    if not simulate:
        return out
    if twin.dataset is not None:
        out.simulated = _checked_given(twin, config, method)
        return out
    _resolve_receiver(out, method, calibration if has_capture else None, cache_dir, twin, broadcast, rank, record)
    if twin.catalog_priors == "calibration" and twin.randomization:
        if not has_capture or calibration is None:
            raise ConfigError("catalog_priors: calibration fits the effect catalog's priors on the empty-room "
                              f"capture in data.calibration, but {calibration!r} is not a capture")
        calibration_profile = _shared_profile_fit(calibration, cache_dir, twin, method, broadcast, rank)[0]
    else:
        calibration_profile = None
    if out.twin_profile is None and twin.calibrate_noise and has_capture and calibration is not None:
        from radaraug.diagnosis.record import cached_noise_fit

        out.noise_fit = cached_noise_fit(calibration, scene=str(twin.scene), config=config, cache_dir=cache_dir,
                                         tracer_rays=twin.tracer_rays)
    elif out.twin_profile is None and twin.calibrate_noise and record is not None:
        out.noise_fit = record.noise_fit
    out.simulated = simulated_dataset(out, method, twin, calibration_profile)
    return out


def simulated_dataset(prepared: Prepared, method: Method, twin: TwinSplits, calibration_profile: TwinProfile | None = None,
                      length: int | None = None, seed: int | None = None) -> Any:
    """The training twin's dataset in ``prepared``'s radar config, with its receiver.

    Args:
        prepared: the run's prepared parts (config, profile, noise fit).
        method: the run's method (CDR's quiet twin).
        twin: the splits' spec.
        calibration_profile: the profile the effect catalog's priors are centred on (``catalog_priors``).
        length: items (None: ``train_items + val_items``).
        seed: the set's seed (None: ``twin.seed``).
    """
    if twin.dataset is not None:
        return twin.dataset
    randomization = None
    if twin.randomization:
        from radaraug.sim.randomization import TwinRandomization

        r = twin.randomization
        randomization = TwinRandomization() if r is True else TwinRandomization.from_dict(dict(r))
        if calibration_profile is not None:
            from radaraug.diagnosis.priors import calibration_priors

            randomization, record = calibration_priors(calibration_profile, randomization, prepared.config)
            prepared.catalog_prior_info = {"source": "diagnose on data.calibration", **record}
    twin_options: dict[str, Any] = {}
    if twin.tracer_rays is not None:
        twin_options["tracer_options"] = {"method": "sbr", "rays": int(twin.tracer_rays)}
    extra: dict[str, Any] = {} if randomization is None else {"randomization": randomization}
    quiet = method.twin_noise_offset_db
    if prepared.twin_profile is not None:
        extra["profile"] = prepared.twin_profile
    elif prepared.noise_fit is not None or quiet is not None:
        from radaraug.diagnosis.noise_fit import noise_fit_receiver
        from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS, DEFAULT_NOISE_FIGURE_DB

        fit = prepared.noise_fit or {"noise_figure_dB": DEFAULT_NOISE_FIGURE_DB,
                                     "adc_noise_rms_counts": ADC_NOISE_RMS_COUNTS}
        if quiet is not None:
            # CDR's twin: both noise sources lowered, so that the clamp supplies the floor (as in the paper)
            fit = {"noise_figure_dB": float(fit["noise_figure_dB"]) + quiet,
                   "adc_noise_rms_counts": float(fit["adc_noise_rms_counts"]) * 10 ** (quiet / 20)}
        # Both noise sources moved by the fitted offset (noise figure and ADC-side noise).
        twin_options["receiver"] = noise_fit_receiver(prepared.config, fit)
    return SimulatedRadarDataset(
        twin.scene, length=twin.train_items + twin.val_items if length is None else int(length),
        seed=twin.seed if seed is None else int(seed), config=prepared.config, target="count",
        twin_options=twin_options, **extra,
    )


def _checked_given(twin: TwinSplits, config: RadarConfig, method: Method) -> SimulatedRadarDataset:
    """``twin.dataset`` as given, after the checks :class:`TwinSplits` names."""
    ds = twin.dataset
    assert ds is not None
    if ds.config != config:
        raise ConfigError(f"data.twin.dataset has another radar config ({ds.config.describe()}) than the test "
                          f"captures ({config.describe()})")
    n = twin.train_items + twin.val_items
    if len(ds) < n or ds.target != "count":
        raise ConfigError(f"data.twin.dataset must give people counts (target='count') for at least "
                          f"train_items + val_items = {n} items; it has {len(ds)} items, target {ds.target!r}")
    unused = [k for k, on in (("calibrate_noise", twin.calibrate_noise), ("profile", twin.profile is not None),
                              ("catalog_priors", twin.catalog_priors != "physics"),
                              ("the method's quiet twin", method.twin_noise_offset_db is not None),
                              (f"method {method.name}'s profile", method.fits_profile)) if on]
    if unused:
        warnings.warn(f"data.twin.dataset is used as given: {', '.join(unused)} not applied to it", stacklevel=4)
    return ds


def _resolve_receiver(out: Prepared, method: Method, capture: str | None, cache_dir: str | Path, twin: TwinSplits,
                      broadcast: Callable[[Any], Any], rank: int, record: CalibrationRecord | None) -> None:
    """Set the twin profile and its info: ``twin.profile``, the method's fit (the record's, or on the capture)."""
    if twin.profile is not None:
        prof = TwinProfile.load(str(twin.profile))
        info: dict[str, Any] = {"source": "data.twin.profile", "path": str(twin.profile)}
    elif not method.fits_profile:
        return
    elif record is not None and record.profile is not None:
        prof = record.profile
        info = {"source": f"the calibration record {record.file}", "path": record.file}
    else:
        if capture is None:
            raise ConfigError(
                f"method {method.name!r} fits a twin profile on the empty-room capture in data.calibration, but "
                "there is none: give the capture itself, or a fitted profile as "
                "data.twin.profile (radaraug diagnose CAPTURE -o DIR writes DIR/profile.json)")
        prof, path = _shared_profile_fit(capture, cache_dir, twin, method, broadcast, rank)
        info = {"source": "fitted on data.calibration", "path": path, "calibration": str(capture),
                "max_frames": _max_frames(method)}
    fitted_on = prof.fitted_on
    if "config" in fitted_on:
        try:
            same = RadarConfig.from_dict(fitted_on["config"]) == out.config
        except (ConfigError, TypeError, ValueError):
            same = False
        if not same:
            warnings.warn(f"twin profile {info['path']} was fitted on a capture with another radar config than "
                          f"the training twin's ({out.config.describe()}); its sensor effects are applied as "
                          "fitted", stacklevel=3)
    info |= {
        "capture": fitted_on.get("capture"),
        "mode": fitted_on.get("mode"),
        "effects": prof.effect_names,
        "effects_added": list(fitted_on.get("effects_added") or []),
        "error_before_dB": fitted_on.get("error_before_dB"),
        "error_after_dB": fitted_on.get("error_after_dB"),
    }
    if twin.calibrate_noise:
        info["calibrate_noise"] = NOISE_FIT_SKIPPED
    out.twin_profile, out.profile_info = prof, info


def _max_frames(method: Method) -> int:
    """Calibration frames a profile fit reads (``CDRProfile.max_frames``; 100 for the catalog priors' fit)."""
    return int(getattr(method, "max_frames", 100))


def profile_cache_path(calibration: str, cache_dir: str | Path, max_frames: int) -> Path:
    """``cache_dir/profile-<key>.json`` of ``calibration`` (keyed by its bytes, frames read, fit version)."""
    from radaraug.training.cache import cache_key, content_digest

    key = cache_key({"format": PROFILE_FIT_FORMAT, "version": PROFILE_FIT_VERSION,
                     "profile_version": PROFILE_VERSION, "capture_sha256": content_digest(calibration),
                     "scene": None, "max_frames": int(max_frames)})
    return Path(cache_dir) / f"profile-{key}.json"


def _shared_profile_fit(calibration: str, cache_dir: str | Path, twin: TwinSplits, method: Method,
                        broadcast: Callable[[Any], Any], rank: int) -> tuple[TwinProfile, str]:
    """The profile fitted on ``calibration`` (cached), fitted on rank 0 and broadcast to the others."""
    data: dict[str, Any] | None = None
    path_fitted: str | None = None
    if rank == 0:  # one diagnose per run; the other DDP ranks get its result
        from radaraug.diagnosis.record import cached_profile_fit

        path = profile_cache_path(calibration, cache_dir, _max_frames(method))
        fitted = cached_profile_fit(calibration, path, max_frames=_max_frames(method), progress=twin.progress)
        data, path_fitted = fitted.to_dict(), str(path)
    data, path_fitted = broadcast((data, path_fitted))
    if data is None or path_fitted is None:
        raise CalibrationError(f"rank {rank} did not receive the twin profile fitted on rank 0")
    return TwinProfile.from_dict(data, source=path_fitted), path_fitted
