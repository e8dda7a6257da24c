"""Writing radaraug HDF5 captures: a crash-safe frame-by-frame recorder and a one-shot helper.

How crash safety works (SWMR, flushes, ``frames_written``, hidden temporaries, the writer lock,
resume and full disks) is described in ``docs/captures.md``, "Crash safety".
"""

from __future__ import annotations

import json
import os
import re
import resource
import shutil
from collections.abc import Mapping
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError
from radaraug.files import (
    PARTIAL_SUFFIX,
    fsync_folder,
    parse_json,
    remove_stale_temporaries,
    temporaries_of,
    temporary_name,
)
from radaraug.io import hdf5_format as fmt
from radaraug.io.counts import as_counts, as_timestamps
from radaraug.io.hdf5_reader import committed_frame_count
from radaraug.io.hdf5_recovery import BUSY, hold_writer_lock, release_writer_lock, writer_is_alive
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

_COMPRESSION = {
    None: {},
    "gzip": {"compression": "gzip", "compression_opts": 4, "shuffle": True},
    "lzf": {"compression": "lzf", "shuffle": True},
}
_AUX_CHUNK = 1024  # timestamps / labels: small values, many per chunk
SPACE_MARGIN_BYTES = 1 << 20
"""Head room of the free-space check, on top of the frames' uncompressed size (metadata)."""
_FRAME_OVERHEAD_BYTES = 256  # per frame: chunk index entry, timestamp, labels (generous)


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



STALE_PARTIAL_S = 60.0
"""Age (s since the last write) after which an unlocked ``.<name>.*.partial`` counts as a killed writer's."""


def _remove_stale_partials(path: Path) -> list[Path]:
    """Remove the temporaries ``.<name>.*.partial`` that killed writers of ``path`` left; the removed paths.

    One is stale when no process holds a lock on it and it was last written more than
    :data:`STALE_PARTIAL_S` ago (so a writer between creating and locking its file is never hit).
    """
    return remove_stale_temporaries(path.parent, temporaries_of(path, PARTIAL_SUFFIX),
                                    older_than_s=STALE_PARTIAL_S, in_use=writer_is_alive)


class CaptureWriter:
    """Record frames into a new radaraug HDF5 capture, one flushed append at a time.

    Crash-safe: a process killed while recording (even by SIGKILL) leaves a file that opens with every
    frame flushed before; a failed write (full disk) closes the file with the frames completed before.
    Timestamps are given with every append or with none (the first append decides).

    Args:
        path: file to create (replaced if it exists).
        config: radar configuration of every frame (stored as JSON in ``radar_config``).
        labels_schema: per-frame label name -> numeric numpy dtype (e.g. ``{"count": "int64"}``);
            ``None``: taken from the first ``append``'s labels.
        compression: ``"gzip"`` (level 4 + shuffle), ``"lzf"`` (fast, h5py only) or ``None``.
        attrs: extra file attributes (e.g. ``source``, ``label_count=2``); dicts and lists are stored as JSON.
        expected_frames: frames this run will write, when known: checked against the free space
            (:func:`check_free_space`) before anything is written.
        publish: when the file gets its name: ``"first_append"`` (a recording, readable while it
            grows and after a kill) or ``"close"`` (a generated file that appears only complete).

    Raises:
        CaptureError: the file cannot be created (bad folder, another writer, not enough space),
            a reserved or unstorable attribute, an append that breaks the timestamp/label layout,
            a failed write or flush, or a closed writer.
        radaraug.errors.InputTensorError: frames of the wrong dtype, shape or value range.
    """

    # The state of a writer with no file yet (__init__ and resume set what they open).
    _file: h5py.File | None = None
    _n = 0
    _started = False
    _has_timestamps = False
    _lock_fd: int | None = None
    _tmp: Path | None = None  # the file's name until it is published under self.path
    _failed: str | None = None
    _publish_on_close = False

    def __init__(
        self,
        path: str | os.PathLike,
        config: RadarConfig,
        *,
        labels_schema: Mapping[str, Any] | None = None,
        compression: str | None = "gzip",
        attrs: Mapping[str, Any] | None = None,
        expected_frames: int | None = None,
        publish: str = "first_append",
    ) -> None:
        self.path = Path(path)
        if publish not in ("first_append", "close"):
            raise ConfigError(f"{self.path}: publish must be 'first_append' or 'close', got {publish!r}")
        if not isinstance(config, RadarConfig):
            raise ConfigError(f"{self.path}: config must be a RadarConfig, got {type(config).__name__}")
        if compression not in _COMPRESSION:
            raise CaptureError(f"{self.path}: compression must be 'gzip', 'lzf' or None, got {compression!r}")
        self.config = config
        self._publish_on_close = publish == "close"
        self._schema = self._check_schema(labels_schema) if labels_schema is not None else None
        file_attrs = self._file_attrs(attrs or {})
        if expected_frames is not None:
            check_free_space(self.path, config, expected_frames)
        if self.path.is_dir():
            raise CaptureError(f"{self.path}: is a folder; cannot create a capture file there")
        # With publish="close", an existing file is only ever replaced whole, by a rename.
        if not self._publish_on_close and self.path.exists() and writer_is_alive(self.path):
            raise CaptureError(f"{self.path}: {BUSY}")
        _remove_stale_partials(self.path)
        tmp = temporary_name(self.path, PARTIAL_SUFFIX)
        try:
            # O_EXCL: a fresh name; mode 0o666 minus the umask, as for any file the user creates.
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
        except OSError as e:
            raise CaptureError(f"{self.path}: cannot create capture file ({e.strerror or e})") from None
        self._tmp = tmp
        try:
            self._lock_fd = hold_writer_lock(self._tmp)
            try:
                # HDF5's own lock is off: it drops it in SWMR mode anyway; radaraug's lock is held
                # for the writer's whole life instead (radaraug.io.hdf5_recovery).
                self._file = h5py.File(self._tmp, "w", libver="latest", locking=False)
            except OSError as e:
                raise CaptureError(f"{self.path}: cannot create capture file ({e})") from None
            self._file.attrs.update(file_attrs)
            c = config
            shape = c.frame_shape
            self._frames = self._file.create_dataset(
                fmt.FRAMES,
                shape=(0, *shape),
                maxshape=(None, *shape),
                chunks=(1, *shape),  # one chunk per frame: a random frame costs one decompression
                dtype=np.uint16,
                **_COMPRESSION[compression],
            )
            self._written = self._file.create_dataset(fmt.FRAMES_WRITTEN, data=np.zeros(1, np.int64))
            self._file.flush()
        except BaseException as e:
            self._setup_failed(e, "create capture file", (OSError, RuntimeError))
            raise

    def _setup_failed(self, err: BaseException, doing: str, wrapped: tuple[type[Exception], ...]) -> None:
        """Close after ``__init__`` or :meth:`resume` failed; re-raise ``wrapped`` kinds as CaptureError."""
        if isinstance(err, (OSError, RuntimeError)):
            self._failed = _short_reason(err)  # e.g. a full disk: drop what HDF5 cannot write
        self._abort()
        if isinstance(err, wrapped) and not isinstance(err, CaptureError):
            raise CaptureError(f"{self.path}: cannot {doing} ({_short_reason(err)})") from None

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
        f.flush()
        if not self._publish_on_close:
            self._publish()

    def _publish(self) -> None:
        """Give the temporary file its real name (it opens from now on)."""
        if self._tmp is None:
            return
        os.replace(self._tmp, self.path)
        self._tmp = None
        fsync_folder(self.path.parent)  # make the rename itself durable

    def _abort(self) -> None:
        """Close after a failure without raising: the file keeps what was flushed before."""
        f, self._file = self._file, None
        if f is not None:
            if self._failed is not None:
                _discard_pending_writes(f)
            try:
                f.close()
            except Exception:  # noqa: BLE001 - a broken file (full disk) may fail to close; h5py drops the id
                pass
        self._release()

    def _release(self) -> None:
        """Remove a temporary never published (no frame, or ``publish="close"`` not complete); unlock."""
        if self._tmp is not None:
            self._tmp.unlink(missing_ok=True)
            self._tmp = None
        release_writer_lock(self._lock_fd)
        self._lock_fd = None

    # ------------------------------------------------------------------ recording
    @classmethod
    def resume(
        cls, path: str | os.PathLike, config: RadarConfig, *, expected_frames: int | None = None
    ) -> CaptureWriter:
        """Reopen a capture written by a :class:`CaptureWriter` (also a killed one) to append more frames.

        Completed frames are kept and anything past them is cut off; the consistency flags a killed
        writer left are reset (as ``h5clear -s`` does) when no live process holds the file.

        Args:
            path: the capture.
            config: the radar config of the frames to append (must equal the file's).
            expected_frames: frames still to write, for the free-space check.

        Raises:
            CaptureError: the file is missing, held by another process, not a radaraug capture,
                recorded with another config, or there is not enough space.
        """
        self = cls.__new__(cls)
        self.path = Path(path)
        self.config = config
        if not self.path.is_file():
            raise CaptureError(f"{self.path}: no capture file to resume")
        self._lock_fd = hold_writer_lock(self.path, reset_flags=True)
        try:
            if expected_frames is not None:
                check_free_space(self.path, config, expected_frames, existing=self.path.stat().st_size)
            try:
                f = h5py.File(self.path, "a", libver="latest", locking=False)
            except (OSError, RuntimeError) as e:
                raise CaptureError(f"{self.path}: cannot reopen capture for appending ({e})") from None
            self._file = f
            if f.attrs.get("format") != fmt.FORMAT_NAME or fmt.FRAMES not in f:
                raise CaptureError(f"{self.path}: not a radaraug capture; cannot resume it")
            stored = parse_json(f.attrs["radar_config"], source=self.path, error=CaptureError,
                                what="attribute 'radar_config'")
            if RadarConfig.from_dict(stored) != config:
                raise CaptureError(f"{self.path}: was recorded with another radar config; cannot resume it")
            self._frames = f[fmt.FRAMES]
            self._n = committed_frame_count(f, int(self._frames.shape[0]))
            self._has_timestamps = fmt.TIMESTAMPS in f
            group = f.get(fmt.LABELS_GROUP)
            labels = dict(group.items()) if group is not None else {}
            self._schema = {name: ds.dtype for name, ds in labels.items()}
            # Frames first: a kill in between leaves timestamps and labels ahead of them (the reader trims).
            timestamps = [f[fmt.TIMESTAMPS]] if self._has_timestamps else []
            for ds in [self._frames, *timestamps, *labels.values()]:
                if ds.shape[0] > self._n:
                    ds.resize(self._n, axis=0)
            if fmt.FRAMES_WRITTEN not in f:  # files of format 1.0 get the count now (SWMR cannot add it later)
                f.create_dataset(fmt.FRAMES_WRITTEN, data=np.zeros(1, np.int64))
            self._written = f[fmt.FRAMES_WRITTEN]
            self._written[0] = self._n
            if self._has_timestamps or group is not None:
                f.swmr_mode = True
                self._started = True
            f.flush()
        except BaseException as e:
            self._setup_failed(e, "resume this capture", (OSError, RuntimeError, KeyError, ValueError))
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
        if self._failed is not None:
            raise CaptureError(f"{self.path}: recording stopped after an error ({self._failed})")
        if self._file is None:
            raise CaptureError(f"{self.path}: writer is closed")
        where = str(self.path)
        counts = as_counts(frame_counts, self.config, where)
        k = len(counts)
        if not self._started:
            try:
                self._start(timestamp is not None, labels)
            except (OSError, RuntimeError) as e:
                self._fail(e, 0, k)
        ts = self._check_timestamps(timestamp, k)
        lab = self._check_labels(labels, k)

        f = self._file
        n0, n1 = self._n, self._n + k
        try:
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
            # Only now are the frames on disk: claim them (a second flush, so the count never
            # reaches the file before the data it counts).
            self._written[0] = n1
            f.flush()
        except (OSError, RuntimeError) as e:
            self._fail(e, n0, n1)
        self._n = n1

    def _fail(self, err: BaseException, n0: int, n1: int) -> None:
        """Stop recording after a failed write or flush: close the file, raise CaptureError."""
        reason = _short_reason(err)
        self._failed = reason
        self._abort()
        raise CaptureError(
            f"{self.path}: cannot write frames {n0}:{n1} ({reason}); recording stopped and the file was "
            f"closed with the {n0} frames completed before (run again with more space to resume)"
        ) from None

    def _check_timestamps(self, timestamp: Any, k: int) -> np.ndarray | None:
        if not self._has_timestamps:
            if timestamp is not None:
                raise CaptureError(
                    f"{self.path}: the first append had no timestamp, so this capture stores none"
                )
            return None
        if timestamp is None:
            raise CaptureError(f"{self.path}: this capture stores timestamps; append() needs one per frame")
        return as_timestamps(timestamp, k, str(self.path))

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
        """Flush and close the file (idempotent); a file never appended to is published now.

        Raises:
            CaptureError: the final flush or close failed (the writer is closed, earlier frames kept).
        """
        f = self._file
        if f is None:
            self._release()
            return
        try:
            f.flush()
            f.close()
        except (OSError, RuntimeError) as e:
            self._failed = str(e)
            self._abort()
            raise CaptureError(f"{self.path}: cannot close the capture ({e}); it keeps {self._n} frames") from None
        self._file = None
        try:
            self._publish()
        except OSError as e:
            raise CaptureError(f"{self.path}: cannot give the capture its name ({e.strerror or e})") from None
        finally:
            self._release()

    def discard(self) -> None:
        """Close without leaving a file if no frame was appended; else as :meth:`close`."""
        if self._started or self._file is None:
            self.close()
            return
        self._abort()

    def __enter__(self) -> CaptureWriter:
        return self

    def __exit__(self, exc_type: object, *exc: object) -> None:
        if exc_type is not None and self._publish_on_close:
            self._abort()  # the file was to appear only complete: drop the temporary
            return
        self.close()

    def __del__(self) -> None:
        # A writer dropped without close(): close the file here, not at interpreter exit, where
        # h5py closing a file in a broken state (full disk) has crashed the process.
        try:
            # publish="close": a writer never closed did not complete its file.
            self._abort() if self._failed or self._publish_on_close else self.close()
        except Exception:  # noqa: BLE001 - nothing to report to at garbage collection
            pass

    def __repr__(self) -> str:
        state = "closed" if self._file is None else "open"
        return f"CaptureWriter({str(self.path)!r}, {self._n} frames, {state})"


def check_free_space(path: str | os.PathLike, config: RadarConfig, frames: int, *, existing: int = 0) -> None:
    """Refuse, before anything is written, a run whose frames cannot fit next to ``path``.

    The frames' uncompressed size plus :data:`SPACE_MARGIN_BYTES` must fit the folder's free space and
    the file-size limit (``ulimit -f``, less the ``existing`` bytes of a resumed file).

    Raises:
        CaptureError: not enough space, or the folder cannot be examined.
    """
    path = Path(path)
    c = config
    per_frame = 2 * c.num_rx * c.num_chirps_per_frame * c.num_samples_per_chirp + _FRAME_OVERHEAD_BYTES
    need = int(frames) * per_frame + SPACE_MARGIN_BYTES
    folder = path.parent
    while not folder.exists() and folder != folder.parent:  # a folder the run will create
        folder = folder.parent
    try:
        free = shutil.disk_usage(folder).free
    except OSError as e:
        raise CaptureError(f"{path}: cannot write in {folder} ({e.strerror or e})") from None
    where, room = f"free in {folder}", free
    soft = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
    if soft != resource.RLIM_INFINITY and soft - existing < room:
        where, room = "left under this process's file-size limit (ulimit -f)", max(0, soft - existing)
    if need > room:
        raise CaptureError(
            f"{path}: not enough space: {frames} frames need about {need / 2**20:.1f} MiB "
            f"(uncompressed, with margin), only {room / 2**20:.1f} MiB {where}; nothing was written"
        )


def _short_reason(err: BaseException) -> str:
    """One line for a failed HDF5 write: the OS error when HDF5 names one (full disk...)."""
    text = str(err)
    m = re.search(r"errno = (\d+), error message = '([^']*)'", text)
    if m:
        code = int(m.group(1))
        hint = {28: "the disk is full", 27: "the file-size limit (ulimit -f) is reached",
                122: "the disk quota is exceeded"}.get(code, "a write failed")
        return f"{hint}: {m.group(2)} [errno {code}]"
    return " ".join(text.split()) or type(err).__name__


def _discard_pending_writes(f: h5py.File) -> None:
    """Point HDF5's file descriptor at /dev/null so that closing a file whose writes fail succeeds.

    What HDF5 still caches is dropped (else it retries at shutdown and crashes the process); the file
    stays as it was at the failure.
    """
    try:
        handle = f.id.get_vfd_handle()
        null = os.open(os.devnull, os.O_RDWR)
        try:
            os.dup2(null, handle)
        finally:
            os.close(null)
    except (OSError, RuntimeError, ValueError, TypeError):
        pass  # not the default (sec2) driver: close as it is


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
        labels: name -> a scalar (file-level ``label_<name>``) or an ``(F,)`` array (``labels/<name>``).
        attrs: extra file attributes (see :class:`CaptureWriter`).
        compression: ``"gzip"``, ``"lzf"`` or ``None``.

    Returns:
        The path written.
    """
    labels = labels or {}
    file_labels = {f"{fmt.FILE_LABEL_PREFIX}{k}": v for k, v in labels.items() if np.ndim(v) == 0}
    frame_labels = {k: v for k, v in labels.items() if np.ndim(v) != 0}
    all_attrs = {**(attrs or {}), **file_labels}
    with CaptureWriter(path, config, compression=compression, attrs=all_attrs) as writer:
        writer.append(counts, timestamp=timestamps, labels=frame_labels or None)
    return Path(path)
