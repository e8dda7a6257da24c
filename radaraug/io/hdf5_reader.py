"""Reader of the radaraug HDF5 capture format (see :mod:`radaraug.io.hdf5_format`)."""

from __future__ import annotations

import json
import os
import warnings
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError
from radaraug.io import hdf5_format as fmt
from radaraug.io.base import CaptureReader, CaptureWarning, broadcast_label


def _plain(value: Any) -> Any:
    """HDF5 attribute value -> plain Python (str, int, float, bool, list)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()] if value.dtype.kind in "OS" else value.tolist()
    return value


def committed_frame_count(file: h5py.File, stored: int) -> int:
    """Frames of an open capture that were completely written: ``stored`` (the length of
    ``frames``) capped by the writer's ``frames_written`` count when the file has one (format 1.1).

    Raises:
        CaptureError: ``frames_written`` exists but is not one readable integer.
    """
    ds = file.get(fmt.FRAMES_WRITTEN)
    if ds is None:
        return stored
    try:
        if not isinstance(ds, h5py.Dataset) or ds.shape != (1,) or ds.dtype.kind not in "iu":
            raise ValueError(f"expected one integer, found {getattr(ds, 'dtype', type(ds).__name__)} "
                             f"{getattr(ds, 'shape', '')}")
        written = int(ds[0])
    except (OSError, RuntimeError, ValueError, TypeError) as e:
        raise CaptureError(f"{file.filename}: '{fmt.FRAMES_WRITTEN}' is unreadable ({e})") from None
    return max(0, min(stored, written))


class HDF5Capture(CaptureReader):
    """A radaraug HDF5 capture file, opened read-only (SWMR, so crashed recordings open).

    Metadata is read on construction; frames are read (and decompressed) on demand, one HDF5
    chunk per frame. Use :func:`radaraug.io.open_capture` rather than this class directly.

    Args:
        path: the ``.h5`` / ``.hdf5`` file.

    Raises:
        CaptureError: the file is missing, not HDF5, truncated or corrupt, not a radaraug
            capture, has an unsupported major version, a missing or invalid ``radar_config``
            (the :class:`~radaraug.errors.ConfigError` is chained), a ``frames`` dataset of the
            wrong dtype/rank/shape, no frames, or per-frame labels shorter than the frames.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        self._file: h5py.File | None = None
        if not self.path.exists():
            raise CaptureError(f"{self.path}: capture file does not exist")
        if not self.path.is_file():
            raise CaptureError(f"{self.path}: expected an HDF5 capture file, found a folder")
        if not fmt.looks_like_hdf5(self.path):
            raise CaptureError(f"{self.path}: not an HDF5 file (no HDF5 signature at its start)")
        missing = fmt.stored_eof_shortfall(self.path)
        if missing:
            raise CaptureError(
                f"{self.path}: HDF5 file is truncated ({missing} bytes missing from its end); "
                "it was cut short while copying or downloading"
            )
        self._file = self._open()
        try:
            self._load_metadata()
            # Decompress the first and last frame now, so a damaged file fails at open time
            # with a clear message rather than deep inside a DataLoader worker later.
            self._read_counts(0, 1)
            self._read_counts(self.num_frames - 1, self.num_frames)
        except BaseException:
            self.close()
            raise

    def _open(self) -> h5py.File:
        # SWMR read skips the "file is already open for write" consistency flag that a writer
        # killed while recording leaves behind (FIELD_NOTES: the frames flushed so far survive).
        # h5py raises OSError for most damage but RuntimeError for a corrupted superblock.
        try:
            return h5py.File(self.path, "r", swmr=True)
        except (OSError, RuntimeError) as swmr_error:
            try:
                return h5py.File(self.path, "r")
            except (OSError, RuntimeError) as e:
                hint = ""
                if "already open for write" in str(e):
                    hint = "; a writer was killed before switching to SWMR: `h5clear -s FILE` may recover it"
                raise CaptureError(f"{self.path}: cannot open HDF5 file ({e or swmr_error}){hint}") from None

    # ------------------------------------------------------------------ metadata
    def _fail(self, problem: str) -> CaptureError:
        return CaptureError(f"{self.path}: {problem}")

    def _load_metadata(self) -> None:
        f = self._file
        assert f is not None
        try:
            self.attrs = {k: _plain(v) for k, v in f.attrs.items()}
        except (OSError, RuntimeError) as e:
            raise self._fail(f"cannot read file attributes ({e})") from None
        name = self.attrs.get("format")
        if name != fmt.FORMAT_NAME:
            raise self._fail(
                f"not a radaraug capture: attribute 'format' is {name!r}, expected {fmt.FORMAT_NAME!r}"
            )
        version = str(self.attrs.get("format_version", ""))
        if version.split(".")[0] != fmt.FORMAT_VERSION.split(".")[0]:
            raise self._fail(
                f"unsupported format_version {version!r}; this radaraug reads {fmt.FORMAT_VERSION.split('.')[0]}.x"
            )
        self.config = self._load_config()
        self._frames = self._load_frames()
        # Frames past the writer's committed count may have no data on disk (a full disk or a
        # kill mid-append); they are never served.
        self.num_frames = committed_frame_count(f, int(self._frames.shape[0]))
        if self.num_frames == 0:
            raise self._fail(f"empty capture: '{fmt.FRAMES_WRITTEN}' says no frame was completely written")
        self.timestamps = self._load_timestamps()
        self.labels = self._load_labels()

    def _load_config(self) -> RadarConfig:
        text = self.attrs.get("radar_config")
        if text is None:
            raise self._fail("has no 'radar_config' attribute (the radar configuration of the frames)")
        try:
            data = json.loads(text)
            return RadarConfig.from_dict(data, source=str(self.path))
        except (TypeError, json.JSONDecodeError) as e:
            raise self._fail(f"attribute 'radar_config' is not valid JSON ({e})") from e
        except ConfigError as e:
            raise self._fail(f"attribute 'radar_config' is invalid: {e}") from e

    def _load_frames(self) -> h5py.Dataset:
        f = self._file
        assert f is not None
        frames = f.get(fmt.FRAMES)
        if not isinstance(frames, h5py.Dataset):
            raise self._fail(f"has no '{fmt.FRAMES}' dataset")
        if frames.dtype != np.uint16:
            raise self._fail(f"'{fmt.FRAMES}' has dtype {frames.dtype}, expected uint16 ADC counts")
        if frames.ndim != 4:
            raise self._fail(
                f"'{fmt.FRAMES}' has shape {frames.shape}, expected 4-D (frames, rx, chirps, samples)"
            )
        c = self.config
        for axis, name, want in (
            (1, "rx", c.num_rx),
            (2, "chirps", c.num_chirps_per_frame),
            (3, "samples", c.num_samples_per_chirp),
        ):
            if frames.shape[axis] != want:
                raise self._fail(
                    f"'{fmt.FRAMES}' has {frames.shape[axis]} {name} (shape {frames.shape}) but "
                    f"radar_config says {want}"
                )
        if frames.shape[0] == 0:
            raise self._fail("empty capture: 'frames' holds 0 frames")
        return frames

    def _load_timestamps(self) -> np.ndarray | None:
        f = self._file
        assert f is not None
        if fmt.TIMESTAMPS not in f:
            return None
        ds = f[fmt.TIMESTAMPS]
        # Timestamps are optional: unusable ones are dropped with a warning (the frames stay
        # readable), never returned as garbage (NaN durations, a 2-D array flattened).
        if not isinstance(ds, h5py.Dataset) or ds.ndim != 1 or ds.dtype.kind not in "iuf":
            what = "not a dataset" if not isinstance(ds, h5py.Dataset) else f"{ds.dtype} {ds.shape}"
            return self._drop_timestamps(f"'{fmt.TIMESTAMPS}' is {what}, expected float64 (frames,)")
        try:
            ts = np.asarray(ds[()], dtype=np.float64)
        except (OSError, RuntimeError) as e:
            return self._drop_timestamps(f"cannot read '{fmt.TIMESTAMPS}' ({e})")
        # The writer stores timestamps before the frame data of each append, so a writer killed
        # mid-append can leave timestamps ahead of the frames, never behind.
        if len(ts) < self.num_frames:
            return self._drop_timestamps(f"{len(ts)} timestamps for {self.num_frames} frames")
        ts = ts[: self.num_frames]
        if not np.isfinite(ts).all():
            return self._drop_timestamps("timestamps hold NaN or Inf")
        return ts

    def _drop_timestamps(self, problem: str) -> None:
        warnings.warn(f"{self.path}: {problem}; timestamps ignored", CaptureWarning, stacklevel=5)
        return None

    def _load_labels(self) -> dict[str, np.ndarray]:
        f = self._file
        assert f is not None
        n = self.num_frames
        labels: dict[str, np.ndarray] = {}
        # File-level labels first; per-frame datasets of the same name override them.
        text = self.attrs.get(fmt.FILE_LABELS_JSON)
        if text is not None:
            try:
                file_labels = json.loads(text)
            except (TypeError, json.JSONDecodeError) as e:
                raise self._fail(f"attribute 'labels' is not valid JSON ({e})") from e
            if not isinstance(file_labels, dict):
                raise self._fail("attribute 'labels' must be a JSON object of name -> value")
            for key, value in file_labels.items():
                labels[key] = broadcast_label(key, value, n, self.path)
        for key, value in self.attrs.items():
            if key.startswith(fmt.FILE_LABEL_PREFIX) and len(key) > len(fmt.FILE_LABEL_PREFIX):
                name = key[len(fmt.FILE_LABEL_PREFIX) :]
                labels[name] = broadcast_label(name, value, n, self.path)
        group = f.get(fmt.LABELS_GROUP)
        if group is None:
            return labels
        if not isinstance(group, h5py.Group):
            raise self._fail(f"'{fmt.LABELS_GROUP}' must be a group of per-frame datasets")
        for name, ds in group.items():
            if not isinstance(ds, h5py.Dataset) or ds.ndim != 1:
                raise self._fail(f"label '{fmt.LABELS_GROUP}/{name}' must be a 1-D per-frame dataset")
            values = ds[()]
            if len(values) < n:
                raise self._fail(f"label '{fmt.LABELS_GROUP}/{name}' has {len(values)} values for {n} frames")
            labels[name] = values[:n]
        return labels

    # ------------------------------------------------------------------ data
    def _read_counts(self, start: int, stop: int) -> np.ndarray:
        if self._file is None:
            raise CaptureError(f"{self.path}: capture is closed")
        try:
            return self._frames[start:stop]
        except (OSError, RuntimeError, ValueError) as e:
            raise CaptureError(
                f"{self.path}: cannot read frames {start}:{stop} ({e}); the file is corrupt or truncated"
            ) from None

    def close(self) -> None:
        """Close the HDF5 file (idempotent)."""
        if self._file is not None:
            try:
                self._file.close()
            finally:
                self._file = None

    def __reduce__(self) -> tuple[type, tuple[Path]]:
        # h5py handles cannot be pickled: a pickled reader reopens its file where it lands.
        return (type(self), (self.path,))
