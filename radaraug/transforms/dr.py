"""Noise-floor domain randomization: the paper's per-cell clamp ``S~ = max(S, N)`` in dB.

Both transforms take dB RD maps ``(..., rx, range, doppler)`` (``radaraug.units.DB_CONVENTION``)
and raise every cell below a random floor ``N`` to it; cells above the floor are returned
exactly unchanged. ``N`` is i.i.d. Gaussian per cell, per RX and per frame (sample).

* :class:`RandomDR`: per frame, ``m ~ U(mean_db)``, ``s ~ U(std_db)``, ``N ~ Normal(m, s**2)``.
* :class:`CalibratedDR`: fixed ``(m_t, s_t)``, the mean and standard deviation of all RD dB
  values of an empty-room capture processed by the same chain (fitted by
  :mod:`radaraug.transforms.floor_fit`; :meth:`CalibratedDR.fit` delegates to it).

Replayable parameters (``last_params``): ``apply`` (bool per sample), ``noise_db`` (the floor
map ``N``, broadcastable to the input), and for RandomDR ``mean_db``/``std_db`` per sample.

Default RandomDR range: the paper draws ``m`` from [-130, -100] dB in its simulator's units.
radaraug keeps the 30 dB width and centres it on the RD noise floor of a real BGT60TR13C with
``RadarConfig.bgt60tr13c()`` and the default chain (``RangeDoppler() -> ToDecibels()``),
about -105 dBFS at 33 dB IF gain: ``mean_db=(-120, -90)``. See docs/transforms.md for the
measurement and how the floor moves with IF gain, samples and chirps.
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError, RadarAugError
from radaraug.files import safe_repr
from radaraug.transforms import functional as F
from radaraug.transforms._motion import DEFAULT_THRESHOLD_DB
from radaraug.transforms.base import Params, RandomRadarTransform
from radaraug.transforms.dsp_spec import canonical_chain, describe_chain

if TYPE_CHECKING:
    from radaraug.transforms.record_file import CalibrationRecord

DEFAULT_RANDOM_DR_MEAN_DB = (-120.0, -90.0)
DEFAULT_RANDOM_DR_STD_DB = (1.0, 4.0)
#: CalibratedDR's floor distributions: the paper's normal in dB, or the measured one.
FLOORS = ("normal", "empirical")


_MISSING_FLOOR = (
    "CalibratedDR needs its fitted floor, got no {missing}. radaraug ships no default noise floor (it depends "
    "on your sensor, IF gain, DSP chain and room): fit one on ~10 s of your empty room with "
    "CalibratedDR.fit(EMPTY_ROOM) (a capture path, reader or tensor; `radaraug fit-cdr EMPTY_ROOM -o cdr.json` "
    "on the command line), load a saved one with CalibratedDR.load('cdr.json'), or pass the numbers: "
    "CalibratedDR(mean_db, std_db, ...)"
)
"""The :class:`ConfigError` of ``CalibratedDR()`` without ``mean_db``/``std_db``."""


def _range_arg(name: str, value: Any, cls: str) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise RadarAugError(f"{cls}: {name} must be a (low, high) pair, got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo > hi:
        raise RadarAugError(f"{cls}: {name} must be finite with low <= high, got {value!r}")
    return lo, hi


def _ends_in_db(prefix: list[dict[str, Any]]) -> bool:
    for spec in reversed(prefix):
        if not (spec["name"] == "CombineRx" and spec.get("db", False)):  # CombineRx(db=True) keeps dB
            return spec["name"] == "ToDecibels"
    return False


class _DRClamp(RandomRadarTransform):
    """Shared clamp: ``max(S, noise_db)``."""

    input_layout = "a dB RD map (..., rx, range, doppler)"

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        return F.dr_clamp(x, params["noise_db"])

    def check_preceding_chain(self, before: list[dict[str, Any]], where: str) -> None:
        """Raise :class:`CalibrationError` if the steps ``before`` this one do not make dB maps.

        The steps are given by their chain specs. Called by
        :class:`~radaraug.transforms.compose.RadarCompose`.

        Args:
            before: chain specs of the preceding steps (empty: maps made elsewhere, not checked).
            where: the step's place, e.g. ``"RadarCompose: RandomDR at position 2"``.
        """
        if canonical_chain(before) and not _ends_in_db(canonical_chain(before)):
            raise CalibrationError(
                f"{where} clamps dB maps, but the steps before it ({describe_chain(before)}) do not end in ToDecibels"
            )


class RandomDR(_DRClamp):
    """Random noise-floor clamp with per-frame ``(m, s)`` drawn from ranges.

    Args:
        mean_db: range of the floor mean ``m`` (dB), drawn uniformly per frame.
        std_db: range of the floor standard deviation ``s`` (dB), drawn uniformly per frame.
        p, same_on_batch, generator, seed, reseed_in_workers: see
            :class:`~radaraug.transforms.base.RandomRadarTransform`.
    """

    def __init__(
        self,
        mean_db: tuple[float, float] = DEFAULT_RANDOM_DR_MEAN_DB,
        std_db: tuple[float, float] = DEFAULT_RANDOM_DR_STD_DB,
        p: float = 1.0,
        same_on_batch: bool = False,
        generator: torch.Generator | None = None,
        **rng: Any,
    ) -> None:
        super().__init__(p=p, same_on_batch=same_on_batch, generator=generator, **rng)
        self.mean_db = _range_arg("mean_db", mean_db, "RandomDR")
        self.std_db = _range_arg("std_db", std_db, "RandomDR")
        if self.std_db[0] < 0:
            raise RadarAugError(f"RandomDR: std_db must be >= 0, got {std_db!r}")

    def sample_params(
        self, x: torch.Tensor, shape: tuple[int, ...], generator: torch.Generator | None
    ) -> Params:
        """Per-frame ``mean_db``/``std_db`` drawn from the ranges and the floor ``noise_db`` they give."""
        (m_lo, m_hi), (s_lo, s_hi) = self.mean_db, self.std_db
        mean = m_lo + (m_hi - m_lo) * self.draw("rand", shape, x, generator)
        std = s_lo + (s_hi - s_lo) * self.draw("rand", shape, x, generator)
        noise = self.draw("normal", shape + tuple(x.shape[-self.event_ndim :]), x, generator)
        return {"mean_db": mean, "std_db": std, "noise_db": F.random_floor(shape, mean, std, noise)}

    def extra_spec(self) -> dict[str, Any]:
        """The mean and std ranges, ``p`` and ``same_on_batch``."""
        return {"mean_db": list(self.mean_db), "std_db": list(self.std_db), **super().extra_spec()}


def _valid_chain(chain: Any) -> list[dict[str, Any]]:
    """A recorded DSP chain, checked: a list of step objects, each with a string ``name``.

    As ``chain_spec()`` makes them. Checked when a calibration is made or loaded, so a malformed one fails
    there with :class:`CalibrationError`, not later where the chain is compared.
    """
    if not isinstance(chain, (list, tuple)):
        raise CalibrationError(f"CalibratedDR: chain must be a list of step objects, got {safe_repr(chain)}")
    steps = []
    for step in chain:
        if not isinstance(step, Mapping) or not isinstance(step.get("name"), str):
            raise CalibrationError(
                f"CalibratedDR: each chain step must be an object with a string 'name', got {safe_repr(step)}"
            )
        steps.append(dict(step))
    return steps


class CalibratedDR(_DRClamp):
    """Calibrated noise-floor clamp ``max(S, N)``, ``N`` drawn per cell from the measured floor.

    ``floor="normal"`` (the paper's CDR, the default): ``N ~ Normal(mean_db, std_db**2)``, the mean
    and std of all RD dB values of the empty-room capture. ``floor="empirical"``: ``N`` follows the
    capture's own distribution of dB values off zero Doppler (``quantiles_db``, inverse-transform
    sampling), so its upper tail is the real floor's: a receiver's noise in dB is the log of an
    exponential, whose upper tail is far lighter than a normal's with the same std (on the proxy's
    empty room, 99.9th percentile -89.4 dB measured vs -81.2 dB for the normal; docs/transforms.md).

    Made by :meth:`fit` (from an empty-room capture), :meth:`load` (from a calibration file) or
    :meth:`from_record` (from a :class:`~radaraug.transforms.record_file.CalibrationRecord`); these
    classmethods delegate to :mod:`~radaraug.transforms.floor_fit` and :mod:`~radaraug.transforms.record_file`.
    They record the DSP chain, radar config and map shape the floor was measured with; a
    :class:`~radaraug.transforms.compose.RadarCompose` then refuses a different chain, and a map
    of another shape is refused at call time. The constructor itself only takes fitted numbers:
    it never reads a file or the environment and never fits anything.

    Args:
        mean_db: floor mean ``m_t`` in dB (dBFS with radaraug's chain). Required.
        std_db: floor standard deviation ``s_t`` in dB. Required.
        chain: chain spec list the maps were made with (None: not checked).
        config: ``RadarConfig`` (or its dict) of the calibration capture (None: not checked).
        map_shape: ``(rx, range, doppler)`` of the fitted maps (None: not checked).
        p, same_on_batch, generator, seed, reseed_in_workers: see
            :class:`~radaraug.transforms.base.RandomRadarTransform`.
        source: name of the calibration capture (recorded only).
        num_frames: frames the statistics came from (recorded only).
        motion: the motion statistic of the fit (recorded only; see :mod:`._motion`).
        floor: ``"normal"`` (default) or ``"empirical"`` (needs ``quantiles_db``).
        quantiles_db: quantiles of the floor's dB values at equally spaced probabilities from 0 to
            1 (non-decreasing, >= 2 values; :meth:`fit` records 1025, off zero Doppler).

    radaraug ships no default floor: the floor depends on the sensor, its IF gain, the chain and
    the room, and no empty-room recording at the paper's configuration is available to fit one
    from (docs/transforms.md). So ``CalibratedDR()`` without ``mean_db``/``std_db`` is a
    :class:`~radaraug.errors.ConfigError` that says what to call instead:
    ``CalibratedDR.fit(empty_room_capture)`` or ``CalibratedDR.load("cdr.json")``.
    :attr:`provenance` says where the numbers came from.

    Raises:
        ConfigError: ``mean_db`` or ``std_db`` not given (use :meth:`fit` or :meth:`load`).
        CalibrationError: invalid fitted values: non-finite ``mean_db``/``std_db`` or a negative
            ``std_db``, a malformed ``chain``/``config``/``map_shape``, an unknown ``floor``,
            ``floor="empirical"`` without valid ``quantiles_db``.
    """

    spec_fields = ("mean_db", "std_db", "floor", "p", "same_on_batch")
    provenance: dict[str, Any]
    """Where ``(mean_db, std_db)`` came from: ``{"from": "arguments" | "file" | "record", "path": ...,
    "source": capture name, "num_frames": ...}`` (``path`` for a loaded file only)."""

    def __init__(
        self,
        mean_db: float | None = None,
        std_db: float | None = None,
        *,
        chain: list[dict[str, Any]] | None = None,
        config: RadarConfig | dict[str, Any] | None = None,
        map_shape: tuple[int, int, int] | None = None,
        p: float = 1.0,
        same_on_batch: bool = False,
        generator: torch.Generator | None = None,
        source: str | None = None,
        num_frames: int | None = None,
        motion: float | None = None,
        floor: str | None = None,
        quantiles_db: Any = None,
        **rng: Any,
    ) -> None:
        super().__init__(p=p, same_on_batch=same_on_batch, generator=generator, **rng)
        if mean_db is None or std_db is None:
            raise ConfigError(_MISSING_FLOOR.format(
                missing=" and ".join(n for n, v in (("mean_db", mean_db), ("std_db", std_db)) if v is None)))
        self.mean_db, self.std_db = float(mean_db), float(std_db)
        if not (math.isfinite(self.mean_db) and math.isfinite(self.std_db)) or self.std_db < 0:
            raise CalibrationError(
                f"CalibratedDR: need finite mean_db and std_db >= 0, got {mean_db}, {std_db}"
            )
        self.chain = None if chain is None else _valid_chain(chain)
        if isinstance(config, dict):
            try:
                config = RadarConfig.from_dict(config)
            except ConfigError as e:
                raise CalibrationError(f"CalibratedDR: bad radar config: {e}") from None
        elif config is not None and not isinstance(config, RadarConfig):
            raise CalibrationError(
                f"CalibratedDR: config must be a RadarConfig or its dict, got {type(config).__name__}"
            )
        self.config = config
        if map_shape is not None and not (
            isinstance(map_shape, (list, tuple))
            and len(map_shape) == 3
            and all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) and 0 < v <= 2**20 for v in map_shape)
        ):
            raise CalibrationError(
                f"CalibratedDR: map_shape must be (rx, range, doppler) positive integers, got {safe_repr(map_shape)}"
            )
        self.map_shape: tuple[int, int, int] | None = (
            None if map_shape is None else (int(map_shape[0]), int(map_shape[1]), int(map_shape[2])))
        checks = (
            ("source", source, isinstance(source, str)),
            ("num_frames", num_frames,
             isinstance(num_frames, (int, np.integer)) and not isinstance(num_frames, bool) and num_frames >= 0),
            ("motion", motion,
             isinstance(motion, (int, float)) and not isinstance(motion, bool) and math.isfinite(motion)),
        )
        for name, value, ok in checks:
            if value is not None and not ok:
                raise CalibrationError(f"CalibratedDR: {name} has an invalid value {safe_repr(value)}")
        self.source = source
        # the calibration file it was loaded from, if any (named by the errors raised when it is used)
        self.file: str | None = None
        self.provenance = {"from": "arguments", "source": source, "num_frames": num_frames}
        self.num_frames = num_frames
        self.motion = motion
        self.floor = "normal" if floor is None else floor
        if self.floor not in FLOORS:
            raise CalibrationError(f"CalibratedDR: floor must be one of {FLOORS}, got {safe_repr(self.floor)}")
        self.quantiles_db: torch.Tensor | None = None if quantiles_db is None else _valid_quantiles(quantiles_db)
        if self.floor == "empirical" and self.quantiles_db is None:
            raise CalibrationError(
                "CalibratedDR: floor='empirical' needs the floor's quantiles (quantiles_db), which CalibratedDR.fit "
                "records; a calibration saved by an older radaraug has none: refit it"
            )

    # ------------------------------------------------------------------ the transform
    def check_input(self, x: Any) -> torch.Tensor:
        """As :meth:`RadarTransform.check_input`; maps of another shape raise CalibrationError."""
        x = super().check_input(x)
        if self.map_shape is not None and tuple(x.shape[-3:]) != self.map_shape:
            raise CalibrationError(
                f"CalibratedDR{f' ({self.file})' if self.file else ''} fitted on maps of shape "
                f"(rx, range, doppler) = {self.map_shape}"
                f"{f' from {self.source}' if self.source else ''}, got {tuple(x.shape[-3:])}"
            )
        return x

    def sample_params(
        self, x: torch.Tensor, shape: tuple[int, ...], generator: torch.Generator | None
    ) -> Params:
        """The floor ``noise_db`` drawn per cell from the fitted statistics (``floor``'s distribution)."""
        event = tuple(x.shape[-self.event_ndim :])
        if self.floor == "empirical":
            assert self.quantiles_db is not None  # checked in __init__
            return {"noise_db": F.empirical_floor(shape + event, self.quantiles_db, like=x, generator=generator)}
        return {"noise_db": F.calibrated_floor(shape + event, self.mean_db, self.std_db, like=x, generator=generator)}

    def check_config(self, config: RadarConfig | dict[str, Any]) -> None:
        """Raise :class:`CalibrationError` if ``config`` differs from the calibration's config.

        Warns (``UserWarning``) when the calibration recorded no config.
        """
        if isinstance(config, dict):
            config = RadarConfig.from_dict(config)
        if self.config is None:
            warnings.warn(
                "CalibratedDR has no recorded radar config; cannot check it", UserWarning, stacklevel=2
            )
            return
        if config != self.config:
            a, b = self.config.to_dict(), config.to_dict()
            diff = {k: (a[k], b.get(k)) for k in a if a[k] != b.get(k)}
            raise CalibrationError(
                f"CalibratedDR was fitted with another radar config; (fitted, given): {diff}"
            )

    def check_preceding_chain(self, before: list[dict[str, Any]], where: str) -> None:
        """Also refuse a chain other than the one the floor was fitted with (when recorded)."""
        super().check_preceding_chain(before, where)
        prefix = canonical_chain(before)
        if prefix and self.chain is not None and prefix != canonical_chain(self.chain):
            loaded = f" (loaded from {self.file})" if self.file else ""
            raise CalibrationError(
                f"{where}{loaded} was fitted on maps made by {describe_chain(self.chain)}, "
                f"but here it follows {describe_chain(before)}"
            )

    # ------------------------------------------------------------------ fitting
    @classmethod
    def fit(
        cls,
        source: Any,
        *,
        pipeline: Any = None,
        config: RadarConfig | None = None,
        max_frames: int | None = None,
        input: str = "raw",
        batch_size: int = 32,
        motion_threshold_db: float = DEFAULT_THRESHOLD_DB,
        progress: bool = False,
        **kwargs: Any,
    ) -> CalibratedDR:
        """Fit ``(m_t, s_t)`` = mean and std of all RD dB values of an empty-room capture.

        Also records the quantiles of the dB values off the zero-Doppler main lobe, which
        ``floor="empirical"`` draws from (pass ``floor=`` here or when loading).

        Args:
            source: a capture path (radaraug ``.h5`` or Infineon recording folder, opened with
                ``radaraug.io.open_capture``), an open capture reader, a tensor of frames
                ``(frames, rx, chirps, samples)`` (raw) or ``(frames, rx, range, doppler)`` (dB),
                or a ``Dataset`` / iterable yielding frames or ``(frame, label)`` samples.
            pipeline: raw cube -> dB map chain (default ``RangeDoppler() -> ToDecibels()``). With
                ``input="db"`` it is not run, only recorded as the chain that made the maps.
            config: the radar config (taken from the capture when the source is one; an
                explicit config that differs from the capture's is an error).
            max_frames: use at most this many frames.
            input: ``"raw"`` (raw cubes, default) or ``"db"`` (already dB RD maps).
            batch_size: frames processed at once.
            motion_threshold_db: threshold of the motion check (see :mod:`._motion`).
            progress: show a progress bar (tqdm, on stderr) over the batches.
            **kwargs: passed to the constructor (``floor``, ``p``, ``generator``, ``seed``...).

        Raises:
            CalibrationError: ``max_frames``/``batch_size`` not a positive integer, a source with
                no frames, NaN/Inf maps, or a config that differs from the capture's.

        Warns:
            MotionWarning: (a ``UserWarning``) when the capture shows motion (it should be empty).

        The standard deviation is the population one (``correction=0``); statistics are
        accumulated in float64.
        """
        # Imported here: floor_fit builds its chain from the transforms' submodules.
        from radaraug.transforms.floor_fit import floor_statistics

        stats = floor_statistics(
            source, pipeline=pipeline, config=config, max_frames=max_frames, input=input,
            batch_size=batch_size, motion_threshold_db=motion_threshold_db, progress=progress,
        )
        return cls(**stats, **kwargs)

    # ------------------------------------------------------------------ persistence
    def to_dict(self) -> dict[str, Any]:
        """The calibration record :meth:`save` writes (``radaraug fit-cdr --json`` prints it)."""
        from radaraug.transforms.record_file import CalibrationRecord

        return CalibrationRecord.from_cdr(self).to_dict()

    def save(self, path: str | os.PathLike) -> None:
        """Write the calibration as a :class:`~radaraug.transforms.record_file.CalibrationRecord`, atomically.

        A full disk or a crash leaves the previous file, or none, never a partial one.

        Raises:
            CalibrationError: the file cannot be written (the message names it).
        """
        from radaraug.transforms.record_file import CalibrationRecord

        CalibrationRecord.from_cdr(self).save(path)

    def replace(self, **changes: Any) -> CalibratedDR:
        """A copy with ``changes`` to its constructor arguments (e.g. ``floor=``, ``quantiles_db=``, ``seed=``).

        The fitted numbers, chain, config and map shape are kept unless changed, and so are the
        provenance and the file it was loaded from (named by the errors raised when it is used).

        Raises:
            CalibrationError: a changed value the constructor refuses.
        """
        kept = {"mean_db": self.mean_db, "std_db": self.std_db, "chain": self.chain, "config": self.config,
                "map_shape": self.map_shape, "source": self.source, "num_frames": self.num_frames,
                "motion": self.motion, "floor": self.floor, "quantiles_db": self.quantiles_db}
        made = type(self)(**(kept | changes))
        made.file, made.provenance = self.file, dict(self.provenance)
        return made

    @classmethod
    def load(cls, path: str | os.PathLike, **kwargs: Any) -> CalibratedDR:
        """Read a calibration record (or an older CalibratedDR JSON); ``kwargs`` go to the constructor.

        ``CalibratedDR.from_record(load_record(path), **kwargs)``
        (:func:`radaraug.transforms.record_file.load_record`).

        Raises:
            CalibrationError: missing, unreadable or malformed file, another format or version, another
                ``db_convention``, or a record without a floor (the message names the file).
        """
        from radaraug.transforms.record_file import load_record  # the one reader of calibration files

        return cls.from_record(load_record(path), **kwargs)

    @classmethod
    def from_record(cls, record: CalibrationRecord, **kwargs: Any) -> CalibratedDR:
        """The clamp of a :class:`~radaraug.transforms.record_file.CalibrationRecord`'s floor.

        Nothing is fitted or read: the record's numbers go to the constructor, ``kwargs`` after them
        (e.g. ``seed=``, or ``floor=`` to override the record's).

        Raises:
            CalibrationError: the record holds no floor, or a value the constructor refuses (the message
                names the record's file).
        """
        try:
            made = cls(**(record.cdr_arguments() | kwargs))
        except CalibrationError as e:
            msg, file = str(e), record.file
            raise CalibrationError(msg if not file or file in msg else f"calibration file {file}: {msg}") from None
        made.file = record.file  # named by the errors raised when it is used
        made.provenance.update({"from": "file", "path": record.file} if record.file else {"from": "record"})
        return made


def _valid_quantiles(values: Any) -> torch.Tensor:
    """``quantiles_db`` as a float64 tensor, checked: 1-D, >= 2 finite non-decreasing values."""
    try:
        q = torch.as_tensor(values, dtype=torch.float64)  # lists and tensors alike
    except (TypeError, ValueError, RuntimeError, OverflowError):
        raise CalibrationError(f"CalibratedDR: quantiles_db must be a list of numbers, got {safe_repr(values)}") from None
    if q.ndim != 1 or q.numel() < 2 or not bool(torch.isfinite(q).all()) or bool((q.diff() < 0).any()):
        raise CalibrationError(
            f"CalibratedDR: quantiles_db must be >= 2 finite, non-decreasing values, got {safe_repr(values)}"
        )
    return q.clone()

