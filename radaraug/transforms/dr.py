"""Noise-floor domain randomization: the paper's per-cell clamp ``S~ = max(S, N)`` on dB RD maps.

Floors, defaults, fitting and measurements: docs/transforms.md, "Noise-floor domain randomization".
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
        """Raise :class:`CalibrationError` if the steps before this one do not make dB maps.

        Called by :class:`~radaraug.transforms.compose.RadarCompose`.

        Args:
            before: chain specs of the preceding steps (empty: maps made elsewhere, not checked).
            where: the step's place, e.g. ``"RadarCompose: RandomDR at position 2"``.
        """
        if canonical_chain(before) and not _ends_in_db(canonical_chain(before)):
            raise CalibrationError(
                f"{where} clamps dB maps, but the steps before it ({describe_chain(before)}) do not end in ToDecibels"
            )


class RandomDR(_DRClamp):
    """Random noise-floor clamp: per frame ``m ~ U(mean_db)``, ``s ~ U(std_db)``, ``N ~ Normal(m, s**2)``.

    Parameters in ``last_params``: ``apply``, ``mean_db``, ``std_db`` (per frame) and the floor ``noise_db``.

    Args:
        mean_db: range of the floor mean ``m`` (dB).
        std_db: range of the floor standard deviation ``s`` (dB).
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
        """Per-frame ``mean_db``/``std_db`` and the floor ``noise_db`` they give."""
        (m_lo, m_hi), (s_lo, s_hi) = self.mean_db, self.std_db
        mean = m_lo + (m_hi - m_lo) * self.draw("rand", shape, x, generator)
        std = s_lo + (s_hi - s_lo) * self.draw("rand", shape, x, generator)
        noise = self.draw("normal", shape + tuple(x.shape[-self.event_ndim :]), x, generator)
        return {"mean_db": mean, "std_db": std, "noise_db": F.random_floor(shape, mean, std, noise)}

    def extra_spec(self) -> dict[str, Any]:
        """The mean and std ranges, ``p`` and ``same_on_batch``."""
        return {"mean_db": list(self.mean_db), "std_db": list(self.std_db), **super().extra_spec()}


def _valid_chain(chain: Any) -> list[dict[str, Any]]:
    """A recorded chain, checked at load: a list of step objects with a string ``name`` (else CalibrationError)."""
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
    """Calibrated noise-floor clamp ``max(S, N)``, ``N`` drawn per cell from an empty room's floor.

    ``floor="normal"`` (the paper's): ``N ~ Normal(mean_db, std_db**2)``; ``floor="empirical"``: the
    capture's own dB values off zero Doppler (``quantiles_db``), with the real floor's lighter upper tail.
    radaraug ships no default floor: get one with :meth:`fit`, :meth:`load` or :meth:`from_record`. The
    recorded chain and map shape are enforced by :class:`~radaraug.transforms.compose.RadarCompose` and at
    call time.

    Args:
        mean_db: floor mean ``m_t`` in dB. Required.
        std_db: floor standard deviation ``s_t`` in dB. Required.
        chain, config, map_shape: the chain specs, ``RadarConfig`` (or dict) and ``(rx, range, doppler)``
            shape the floor was fitted with (None: not checked).
        p, same_on_batch, generator, seed, reseed_in_workers: as for
            :class:`~radaraug.transforms.base.RandomRadarTransform`.
        source, num_frames, motion: the capture's name, frame count and motion statistic (recorded only).
        floor: ``"normal"`` (default) or ``"empirical"`` (needs ``quantiles_db``).
        quantiles_db: non-decreasing floor quantiles in dB at probabilities ``0, ..., 1`` (>= 2 values).

    Raises:
        ConfigError: ``mean_db`` or ``std_db`` not given (use :meth:`fit` or :meth:`load`).
        CalibrationError: an invalid fitted value, ``chain``, ``config``, ``map_shape`` or ``floor``, or
            ``floor="empirical"`` without ``quantiles_db``.
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
        """The floor ``noise_db`` drawn per cell from ``floor``'s distribution."""
        event = tuple(x.shape[-self.event_ndim :])
        if self.floor == "empirical":
            assert self.quantiles_db is not None  # checked in __init__
            return {"noise_db": F.empirical_floor(shape + event, self.quantiles_db, like=x, generator=generator)}
        return {"noise_db": F.calibrated_floor(shape + event, self.mean_db, self.std_db, like=x, generator=generator)}

    def check_config(self, config: RadarConfig | dict[str, Any]) -> None:
        """Raise :class:`CalibrationError` if ``config`` differs from the calibration's (warn if none recorded)."""
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
        """Fit ``(m_t, s_t)``, the mean and population std of all RD dB values of an empty-room capture.

        Also records the floor's quantiles off the zero-Doppler main lobe, for ``floor="empirical"``.

        Args:
            source: a capture path or open reader, a tensor of frames, or a Dataset / iterable of frames
                or ``(frame, label)`` samples.
            pipeline: raw cube -> dB map chain (default ``RangeDoppler() -> ToDecibels()``); with
                ``input="db"`` only recorded.
            config: the radar config (a capture's own by default; a different one is an error).
            max_frames: use at most this many frames.
            input: ``"raw"`` cubes (default) or ``"db"`` RD maps.
            batch_size: frames processed at once.
            motion_threshold_db: threshold of the motion check.
            progress: show a tqdm progress bar on stderr.
            **kwargs: passed to the constructor (``floor``, ``p``, ``seed``, ...).

        Raises:
            CalibrationError: a bad ``max_frames``/``batch_size``, no frames, NaN/Inf maps, or a config that
                differs from the capture's.

        Warns:
            MotionWarning: the capture shows motion (it should be empty).
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
        """Write the calibration record atomically (a crash leaves the old file or none).

        Raises:
            CalibrationError: the file cannot be written (the message names it).
        """
        from radaraug.transforms.record_file import CalibrationRecord

        CalibrationRecord.from_cdr(self).save(path)

    def replace(self, **changes: Any) -> CalibratedDR:
        """A copy with ``changes`` to its constructor arguments (``floor=``, ``seed=``, ...), provenance kept.

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

        Raises:
            CalibrationError: missing, unreadable or malformed file, another format, version or ``db_convention``,
                or a record without a floor (the message names the file).
        """
        from radaraug.transforms.record_file import load_record  # the one reader of calibration files

        return cls.from_record(load_record(path), **kwargs)

    @classmethod
    def from_record(cls, record: CalibrationRecord, **kwargs: Any) -> CalibratedDR:
        """The clamp of a :class:`~radaraug.transforms.record_file.CalibrationRecord`'s floor; ``kwargs`` override.

        Raises:
            CalibrationError: the record holds no floor, or a value the constructor refuses.
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

