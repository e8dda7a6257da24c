"""Writing radaraug HDF5 captures: a crash-safe frame-by-frame recorder and a one-shot helper.

Crash safety follows what was measured with h5py (FIELD_NOTES): every attribute and dataset is
created first, then the file switches to SWMR mode, and each :meth:`CaptureWriter.append`
ends with a flush. A process killed (even SIGKILL) while recording leaves a file that opens
with every frame flushed before the kill; without SWMR such a file is unreadable.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError
from radaraug.io import hdf5_format as fmt
from radaraug.io.counts import as_counts
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

_COMPRESSION = {
    None: {},
    "gzip": {"compression": "gzip", "compression_opts": 4, "shuffle": True},
    "lzf": {"compression": "lzf", "shuffle": True},
}
_AUX_CHUNK = 1024  # timestamps / labels: small values, many per chunk


def _attr_value(key: str, value: Any, where: str) -> Any:
    """A user attribute as something HDF5 stores: containers become JSON text."""
    if isinstance(value, (Mapping, list, tuple)):
        try:
            return json.dumps(value, sort_keys=True)
        except TypeError as e:
            raise CaptureError(f"{where}: attribute {key!r} is not JSON-serialisable ({e})") from None
    if isinstance(value, np.generic):
        return value.item()
    if value is None or not isinstance(value, (str, int, float, bool)):
        raise CaptureError(
            f"{where}: attribute {key!r} must be str, number, bool, list or dict, got {value!r}"
        )
    return value


class CaptureWriter:
    """Record frames into a new radaraug HDF5 capture, one flushed append at a time.

    Example:
        >>> with CaptureWriter("run.h5", config, labels_schema={"count": "int64"}) as w:  # doctest: +SKIP
        ...     for counts in sensor:          # uint16 (rx, chirps, samples)
        ...         w.append(counts, timestamp=time.time(), labels={"count": 1})

    Args:
        path: file to create (overwritten if it exists).
        config: radar configuration of every frame (stored as JSON in ``radar_config``).
        labels_schema: per-frame label name -> numeric numpy dtype (e.g. ``{"count": "int64"}``),
            stored under ``labels/<name>``. ``None``: taken from the first ``append``'s labels.
        compression: ``"gzip"`` (level 4 + shuffle, readable by any HDF5), ``"lzf"`` (fast,
            h5py only) or ``None``.
        attrs: extra file attributes (``source``, ``description``, file-level labels such as
            ``label_count=2`` or ``labels={"count": 2}``); dicts and lists are stored as JSON.

    Timestamps: pass one with every append or with none; the choice made by the first append
    holds for the file (SWMR files cannot gain datasets later).

    Raises:
        CaptureError: the file cannot be created, an attribute is reserved or not storable, an
            append breaks the file's timestamp/label layout, or the writer is closed.
        radaraug.errors.InputTensorError: frames of the wrong dtype, shape or value range
            (see :func:`radaraug.io.counts.as_counts`).
    """

    def __init__(
        self,
        path: str | os.PathLike,
        config: RadarConfig,
        *,
        labels_schema: Mapping[str, Any] | None = None,
        compression: str | None = "gzip",
        attrs: Mapping[str, Any] | None = None,
    ) -> None:
        self.path = Path(path)
        if not isinstance(config, RadarConfig):
            raise ConfigError(f"{self.path}: config must be a RadarConfig, got {type(config).__name__}")
        if compression not in _COMPRESSION:
            raise CaptureError(f"{self.path}: compression must be 'gzip', 'lzf' or None, got {compression!r}")
        self.config = config
        self._n = 0
        self._started = False
        self._has_timestamps = False
        self._schema = self._check_schema(labels_schema) if labels_schema is not None else None
        file_attrs = self._file_attrs(attrs or {})
        try:
            self._file: h5py.File | None = h5py.File(self.path, "w", libver="latest")
        except OSError as e:
            raise CaptureError(f"{self.path}: cannot create capture file ({e})") from None
        try:
            self._file.attrs.update(file_attrs)
            c = config
            shape = (c.num_rx, c.num_chirps_per_frame, c.num_samples_per_chirp)
            self._frames = self._file.create_dataset(
                fmt.FRAMES,
                shape=(0, *shape),
                maxshape=(None, *shape),
                chunks=(1, *shape),  # one chunk per frame: a random frame costs one decompression
                dtype=np.uint16,
                **_COMPRESSION[compression],
            )
            self._file.flush()
        except BaseException:
            self._file.close()
            self._file = None
            raise

    # ------------------------------------------------------------------ setup
    def _check_schema(self, schema: Mapping[str, Any]) -> dict[str, np.dtype]:
        out: dict[str, np.dtype] = {}
        for name, dtype in schema.items():
            try:
                dt = np.dtype(dtype)
            except TypeError as e:
                raise CaptureError(
                    f"{self.path}: label {name!r} has an invalid dtype {dtype!r} ({e})"
                ) from None
            if dt.kind not in "biuf" or not name or "/" in name:
                raise CaptureError(
                    f"{self.path}: per-frame label {name!r} must have a plain name and a numeric or bool "
                    f"dtype, got {dt}"
                )
            out[str(name)] = dt
        return out

    def _file_attrs(self, attrs: Mapping[str, Any]) -> dict[str, Any]:
        reserved = fmt.RESERVED_ATTRS.intersection(attrs)
        if reserved:
            raise CaptureError(f"{self.path}: attributes {sorted(reserved)} are set by the writer")
        out: dict[str, Any] = {
            "format": fmt.FORMAT_NAME,
            "format_version": fmt.FORMAT_VERSION,
            "radar_config": json.dumps(self.config.to_dict(), sort_keys=True),
            "sample_units": fmt.SAMPLE_UNITS,
            "float_convention": FLOAT_CONVENTION,
            "db_convention": DB_CONVENTION,
            "created": datetime.now(timezone.utc).isoformat(timespec="seconds"),
            "source": "unspecified",
            "description": "",
        }
        for key, value in attrs.items():
            out[str(key)] = _attr_value(str(key), value, str(self.path))
        return out

    def _start(self, with_timestamps: bool, labels: Mapping[str, Any] | None) -> None:
        """Create the optional datasets, then switch to SWMR (no datasets can be added after)."""
        f = self._file
        assert f is not None
        if self._schema is None:
            self._schema = self._check_schema({k: np.asarray(v).dtype for k, v in (labels or {}).items()})
        aux = {"shape": (0,), "maxshape": (None,), "chunks": (_AUX_CHUNK,)}
        if with_timestamps:
            f.create_dataset(fmt.TIMESTAMPS, dtype=np.float64, **aux)
        if self._schema:
            group = f.create_group(fmt.LABELS_GROUP)
            for name, dt in self._schema.items():
                group.create_dataset(name, dtype=dt, **aux)
        self._has_timestamps = with_timestamps
        f.swmr_mode = True
        self._started = True

    # ------------------------------------------------------------------ recording
    @classmethod
    def resume(cls, path: str | os.PathLike, config: RadarConfig) -> CaptureWriter:
        """Reopen a capture written by a :class:`CaptureWriter` to append more frames.

        Frames, timestamps and labels already flushed (also by a writer that was killed) are
        kept; ``num_frames`` starts at their count. Where a kill left timestamps or labels
        ahead of the frames, they are cut back to the frame count.

        Raises:
            CaptureError: the file is missing, not a radaraug capture, or was made with another
                radar config.
        """
        self = cls.__new__(cls)
        self.path = Path(path)
        self.config = config
        try:
            f = h5py.File(self.path, "a", libver="latest")
        except (OSError, RuntimeError) as e:
            raise CaptureError(f"{self.path}: cannot reopen capture for appending ({e})") from None
        try:
            if f.attrs.get("format") != fmt.FORMAT_NAME or fmt.FRAMES not in f:
                raise CaptureError(f"{self.path}: not a radaraug capture; cannot resume it")
            stored = json.loads(f.attrs["radar_config"])
            if RadarConfig.from_dict(stored) != config:
                raise CaptureError(f"{self.path}: was recorded with another radar config; cannot resume it")
            self._file = f
            self._frames = f[fmt.FRAMES]
            self._n = int(self._frames.shape[0])
            self._has_timestamps = fmt.TIMESTAMPS in f
            group = f.get(fmt.LABELS_GROUP)
            self._schema = {name: group[name].dtype for name in group} if group is not None else {}
            started = self._has_timestamps or group is not None
            for ds in ([f[fmt.TIMESTAMPS]] if self._has_timestamps else []) + (
                [group[name] for name in group] if group is not None else []
            ):
                if ds.shape[0] > self._n:
                    ds.resize((self._n,))
            if started:
                f.swmr_mode = True
            self._started = started
            f.flush()
        except BaseException:
            f.close()
            raise
        return self

    @property
    def num_frames(self) -> int:
        """Frames written (and flushed) so far."""
        return self._n

    def append(
        self,
        frame_counts: np.ndarray | torch.Tensor,
        timestamp: float | np.ndarray | None = None,
        labels: Mapping[str, Any] | None = None,
    ) -> None:
        """Append one frame ``(rx, chirps, samples)`` or a block ``(k, rx, chirps, samples)``.

        Args:
            frame_counts: integer ADC counts matching the config (uint16 is stored).
            timestamp: Unix time in seconds: a number for one frame, ``(k,)`` for a block.
            labels: per-frame label name -> value (scalar, repeated over a block, or ``(k,)``).
        """
        if self._file is None:
            raise CaptureError(f"{self.path}: writer is closed")
        where = str(self.path)
        counts = as_counts(frame_counts, self.config, where)
        k = len(counts)
        if not self._started:
            self._start(timestamp is not None, labels)
        ts = self._check_timestamps(timestamp, k)
        lab = self._check_labels(labels, k)

        f = self._file
        n0, n1 = self._n, self._n + k
        # Timestamps and labels before the frames: a kill between the two leaves them ahead
        # of the frames (the reader trims), never behind.
        if ts is not None:
            f[fmt.TIMESTAMPS].resize((n1,))
            f[fmt.TIMESTAMPS][n0:n1] = ts
        for name, values in lab.items():
            ds = f[fmt.LABELS_GROUP][name]
            ds.resize((n1,))
            ds[n0:n1] = values
        self._frames.resize((n1, *counts.shape[1:]))
        self._frames[n0:n1] = counts
        f.flush()
        self._n = n1

    def _check_timestamps(self, timestamp: Any, k: int) -> np.ndarray | None:
        if not self._has_timestamps:
            if timestamp is not None:
                raise CaptureError(
                    f"{self.path}: the first append had no timestamp, so this capture stores none"
                )
            return None
        if timestamp is None:
            raise CaptureError(f"{self.path}: this capture stores timestamps; append() needs one per frame")
        ts = np.asarray(timestamp, dtype=np.float64).reshape(-1)
        if ts.shape != (k,) or not np.all(np.isfinite(ts)):
            raise CaptureError(
                f"{self.path}: need {k} finite timestamp(s) for {k} frame(s), got {timestamp!r}"
            )
        return ts

    def _check_labels(self, labels: Mapping[str, Any] | None, k: int) -> dict[str, np.ndarray]:
        schema = self._schema or {}
        given = dict(labels or {})
        if set(given) != set(schema):
            raise CaptureError(
                f"{self.path}: append() labels {sorted(given)} do not match the capture's per-frame "
                f"labels {sorted(schema)}"
            )
        out = {}
        for name, dt in schema.items():
            arr = np.asarray(given[name])
            if arr.ndim == 0:
                arr = np.full(k, arr)
            if arr.shape != (k,) or arr.dtype.kind not in "biuf":
                raise CaptureError(
                    f"{self.path}: label {name!r} needs a number or ({k},) numbers, got {given[name]!r}"
                )
            if not np.can_cast(arr.dtype, dt, casting="same_kind"):
                raise CaptureError(f"{self.path}: label {name!r} of dtype {arr.dtype} does not fit {dt}")
            out[name] = arr.astype(dt)
        return out

    # ------------------------------------------------------------------ closing
    def close(self) -> None:
        """Flush and close the file (idempotent)."""
        if self._file is not None:
            try:
                self._file.flush()
                self._file.close()
            finally:
                self._file = None

    def __enter__(self) -> CaptureWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if self._file is None else "open"
        return f"CaptureWriter({str(self.path)!r}, {self._n} frames, {state})"


def write_capture(
    path: str | os.PathLike,
    counts: np.ndarray | torch.Tensor,
    config: RadarConfig,
    timestamps: np.ndarray | None = None,
    labels: Mapping[str, Any] | None = None,
    attrs: Mapping[str, Any] | None = None,
    *,
    compression: str | None = "gzip",
) -> Path:
    """Write a whole capture ``(F, rx, chirps, samples)`` of ADC counts in one go.

    Args:
        path: file to create (overwritten).
        counts: integer ADC counts.
        config: their radar configuration.
        timestamps: optional ``(F,)`` Unix seconds.
        labels: name -> value. A scalar becomes a file-level label (attribute ``label_<name>``,
            read back broadcast to every frame); an ``(F,)`` array becomes ``labels/<name>``.
        attrs: extra file attributes (see :class:`CaptureWriter`).
        compression: ``"gzip"``, ``"lzf"`` or ``None``.

    Returns:
        The path written.
    """
    file_labels: dict[str, Any] = {}
    frame_labels: dict[str, Any] = {}
    for name, value in (labels or {}).items():
        if np.ndim(value) == 0:
            file_labels[f"{fmt.FILE_LABEL_PREFIX}{name}"] = value
        else:
            frame_labels[name] = value
    all_attrs = {**(attrs or {}), **file_labels}
    with CaptureWriter(path, config, compression=compression, attrs=all_attrs) as writer:
        writer.append(counts, timestamp=timestamps, labels=frame_labels or None)
    return Path(path)
