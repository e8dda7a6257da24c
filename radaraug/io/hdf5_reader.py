"""Reader of the radaraug HDF5 capture format (see :mod:`radaraug.io.hdf5_format`)."""

from __future__ import annotations

import os
import warnings
from collections import Counter
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError, RadarAugError
from radaraug.files import parse_json, regular_file_size
from radaraug.io import hdf5_format as fmt
from radaraug.io.base import CaptureReader, CaptureWarning, broadcast_label, frames_problem, timestamp_problem
from radaraug.io.hdf5_open import open_hdf5_readonly

# What h5py raises for damaged or unexpected HDF5 content (RadarAugError is a ValueError too,
# and is re-raised untouched).
H5_ERRORS = (OSError, RuntimeError, KeyError, ValueError, TypeError, AttributeError, IndexError)


def _plain(value: Any) -> Any:
    """HDF5 attribute value -> plain Python (str, int, float, bool, list)."""
    if isinstance(value, h5py.Empty):
        return None
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()] if value.dtype.kind in "OS" else value.tolist()
    return value


def committed_frame_count(file: h5py.File, stored: int) -> int:
    """Frames of an open capture that were completely written.

    ``stored`` (the length of ``frames``) capped by the writer's ``frames_written`` count when the file
    has one (format 1.1).

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
    """A radaraug HDF5 capture file, opened read-only (a crashed recording opens too).

    Metadata is read on construction, frames on demand. Use :func:`radaraug.io.open_capture`.

    Args:
        path: the ``.h5`` / ``.hdf5`` file.

    Raises:
        CaptureError: the file is missing, not HDF5, damaged, not a radaraug capture (or another
            major version), has an invalid ``radar_config`` (``ConfigError`` chained) or ``frames``,
            no frames, or per-frame labels shorter than the frames.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        self._file: h5py.File | None = None
        if not os.path.lexists(self.path):
            raise CaptureError(f"{self.path}: capture file does not exist")
        if self.path.is_dir():
            raise CaptureError(f"{self.path}: expected an HDF5 capture file, found a folder")
        regular_file_size(self.path, error=CaptureError, what="capture file")
        self._file = open_hdf5_readonly(self.path)
        try:
            self._load_metadata(self._file)
            # Decompress the first and last frame now, so a damaged file fails at open time
            # with a clear message rather than deep inside a DataLoader worker later.
            self._read_counts(0, 1)
            self._read_counts(self.num_frames - 1, self.num_frames)
        except BaseException as e:
            self.close()
            if isinstance(e, H5_ERRORS) and not isinstance(e, RadarAugError):
                raise self._fail(
                    f"cannot read the HDF5 metadata ({type(e).__name__}: {e}); the file is damaged"
                ) from None
            raise

    # ------------------------------------------------------------------ metadata
    def _fail(self, problem: str) -> CaptureError:
        return CaptureError(f"{self.path}: {problem}")

    def _load_metadata(self, f: h5py.File) -> None:
        self.attrs = {}
        for key in list(f.attrs):
            try:
                self.attrs[key] = _plain(f.attrs[key])
            except H5_ERRORS as e:
                if key in fmt.RESERVED_ATTRS or key == fmt.FILE_LABELS_JSON or key.startswith(fmt.FILE_LABEL_PREFIX):
                    raise self._fail(f"cannot read attribute {key!r} ({type(e).__name__}: {e})") from None
                warnings.warn(f"{self.path}: unreadable attribute {key!r} ignored ({e})", CaptureWarning, stacklevel=4)
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
        self._frames = self._load_frames(f)
        # Frames past the writer's committed count may have no data on disk (a full disk or a
        # kill mid-append); they are never served. Within that count, a frame without stored data
        # (a file from another writer) is refused or cut off too (:meth:`_written_frames`).
        declared = int(self._frames.shape[0])
        committed = committed_frame_count(f, declared)
        if committed == 0:
            raise self._fail(f"empty capture: '{fmt.FRAMES_WRITTEN}' says no frame was completely written")
        if committed < declared:
            warnings.warn(
                f"{self.path}: frames {committed}..{declared - 1} were declared but never written (the "
                f"writer's '{fmt.FRAMES_WRITTEN}' count is {committed}: it stopped mid-append); reading "
                f"the {committed} written frames",
                CaptureWarning,
                stacklevel=3,
            )
        self.num_frames = self._written_frames(self._frames, committed)
        self.timestamps = self._load_timestamps(f)
        self.labels = self._load_labels(f)

    def _load_config(self) -> RadarConfig:
        text = self.attrs.get("radar_config")
        if text is None:
            raise self._fail("has no 'radar_config' attribute (the radar configuration of the frames)")
        data = parse_json(text, source=self.path, error=CaptureError, what="attribute 'radar_config'")
        try:
            return RadarConfig.from_dict(data, source=str(self.path))
        except ConfigError as e:
            raise self._fail(f"attribute 'radar_config' is invalid: {e}") from e

    def _dataset(self, group: h5py.Group, name: str, where: str) -> h5py.Dataset | h5py.Group | None:
        """``group[name]`` when it is an object stored in this file, None when absent.

        Soft and external links are refused before they are followed: a soft link can point at
        itself or nowhere, and an external link reads another file.
        """
        link = group.get(name, getlink=True)
        if link is None:
            return None
        if not isinstance(link, h5py.HardLink):
            kind = "an external link to another file" if isinstance(link, h5py.ExternalLink) else "a soft link"
            raise self._fail(f"'{where}' is {kind}; radaraug reads only objects stored in the capture itself")
        obj = group.get(name)
        if isinstance(obj, h5py.Dataset) and (obj.is_virtual or obj.external):
            raise self._fail(f"'{where}' keeps its data in other files (virtual or external storage); refused")
        return obj

    def _written_rows(self, ds: h5py.Dataset) -> tuple[int, int | None]:
        """``(w, gap_end)``: rows ``0..w-1`` of ``ds`` have stored data (unwritten rows read as fill values).

        ``gap_end``: None when no row from ``w`` on has stored data, else the first later row that has.
        One step per stored chunk, never per declared row.
        """
        n = int(ds.shape[0])
        if n == 0 or ds.size == 0:
            return n, None
        layout = ds.id.get_create_plist().get_layout()
        if layout == h5py.h5d.COMPACT:
            return n, None
        if layout == h5py.h5d.CONTIGUOUS:
            written = ds.id.get_storage_size() >= ds.size * ds.dtype.itemsize
            return (n, None) if written else (0, None)
        chunks = ds.chunks
        per_row = 1  # chunks that make up one row of chunks along axis 0
        for size, chunk in zip(ds.shape[1:], chunks[1:]):
            per_row *= -(-size // chunk)
        if ds.id.get_num_chunks() >= -(-n // chunks[0]) * per_row:
            return n, None
        rows: Counter[int] = Counter()

        def count(info: Any) -> None:
            rows[info.chunk_offset[0] // chunks[0]] += 1

        if hasattr(ds.id, "chunk_iter"):
            ds.id.chunk_iter(count)
        else:  # older HDF5: one lookup per stored chunk
            for i in range(ds.id.get_num_chunks()):
                count(ds.id.get_chunk_info(i))
        r = 0
        while rows.get(r, 0) >= per_row:
            r += 1
        w = min(n, r * chunks[0])
        later = [k for k in rows if k > r or (k == r and rows[k] > 0)]
        if not later:
            return w, None
        gap_end = min(later)
        return w, min(n, max(w + 1, gap_end * chunks[0]))

    def _written_frames(self, frames: h5py.Dataset, n: int) -> int:
        """Frames to serve: the first ``n`` (the committed count) rows of ``frames``.

        All of them must have stored data: a gap is a CaptureError; unwritten rows at the end are cut with
        a warning.
        """
        w, gap_end = self._written_rows(frames)
        w = min(w, n)
        # Written rows after the gap that lie past the committed count do not matter.
        if gap_end is not None and gap_end < n:
            raise self._fail(
                f"frames {w}..{gap_end - 1} of {n} were never written (no stored data: they would read "
                "as fill values), but later frames were"
            )
        if w == 0:
            raise self._fail(f"none of its {n} frames was ever written (no stored data)")
        if w < n:
            warnings.warn(
                f"{self.path}: frames {w}..{n - 1} were declared but never written (a writer stopped "
                f"mid-append); reading the {w} written frames",
                CaptureWarning,
                stacklevel=4,
            )
        return w

    def _load_frames(self, f: h5py.File) -> h5py.Dataset:
        frames = self._dataset(f, fmt.FRAMES, fmt.FRAMES)
        if not isinstance(frames, h5py.Dataset):
            raise self._fail(f"has no '{fmt.FRAMES}' dataset")
        if frames.dtype != np.uint16:
            raise self._fail(f"'{fmt.FRAMES}' has dtype {frames.dtype}, expected uint16 ADC counts")
        problem = frames_problem(frames.shape, self.config, "radar_config")
        if problem is not None:
            raise self._fail(f"'{fmt.FRAMES}' has {problem}")
        return frames

    def _load_timestamps(self, f: h5py.File) -> np.ndarray | None:
        ds = self._dataset(f, fmt.TIMESTAMPS, fmt.TIMESTAMPS)
        if ds is None:
            return None
        # Timestamps are optional: unusable ones are dropped with a warning (the frames stay
        # readable), never returned as garbage (NaN durations, a 2-D array flattened).
        n = self.num_frames
        ts = None
        if not isinstance(ds, h5py.Dataset) or ds.ndim != 1 or ds.dtype.kind not in "iuf":
            what = "not a dataset" if not isinstance(ds, h5py.Dataset) else f"{ds.dtype} {ds.shape}"
            problem: str | None = f"'{fmt.TIMESTAMPS}' is {what}, expected float64 (frames,)"
        elif ds.shape[0] < n:
            # The writer stores timestamps before the frame data of each append, so a writer killed
            # mid-append can leave timestamps ahead of the frames, never behind.
            problem = f"{ds.shape[0]} timestamps for {n} frames"
        elif (written := self._written_rows(ds)[0]) < n:
            problem = f"the timestamps of frames {written}.. were never written"
        else:
            try:
                ts = np.asarray(ds[:n], dtype=np.float64)  # only what the frames need
                problem = timestamp_problem(ts)
            except H5_ERRORS as e:
                problem = f"cannot read '{fmt.TIMESTAMPS}' ({e})"
        if problem is not None:
            warnings.warn(f"{self.path}: {problem}; timestamps ignored", CaptureWarning, stacklevel=4)
            return None
        return ts

    def _load_labels(self, f: h5py.File) -> dict[str, np.ndarray]:
        n = self.num_frames
        # File-level labels first (the JSON ``labels``, then ``label_<name>`` attributes); per-frame
        # datasets of the same name override them.
        text = self.attrs.get(fmt.FILE_LABELS_JSON)
        file_labels = {} if text is None else parse_json(text, source=self.path, error=CaptureError,
                                                         what="attribute 'labels'")
        if not isinstance(file_labels, dict):
            raise self._fail("attribute 'labels' must be a JSON object of name -> value")
        prefix = fmt.FILE_LABEL_PREFIX
        file_labels |= {key[len(prefix):]: value for key, value in self.attrs.items()
                        if key.startswith(prefix) and key != prefix}
        labels = {name: broadcast_label(name, value, n, self.path) for name, value in file_labels.items()}
        group = self._dataset(f, fmt.LABELS_GROUP, fmt.LABELS_GROUP)
        if group is None:
            return labels
        if not isinstance(group, h5py.Group):
            raise self._fail(f"'{fmt.LABELS_GROUP}' must be a group of per-frame datasets")
        for name in list(group):
            where = f"{fmt.LABELS_GROUP}/{name}"
            ds = self._dataset(group, name, where)
            if not isinstance(ds, h5py.Dataset) or ds.ndim != 1:
                raise self._fail(f"label '{where}' must be a 1-D per-frame dataset")
            if ds.dtype.kind not in "biuf":
                raise self._fail(f"label '{where}' has dtype {ds.dtype}; per-frame labels must be numbers or bools")
            if ds.shape[0] < n:
                raise self._fail(f"label '{where}' has {ds.shape[0]} values for {n} frames")
            written, _ = self._written_rows(ds)
            if written < n:
                raise self._fail(f"label '{where}' was never written for frames {written}..{n - 1}")
            labels[name] = ds[:n]  # only what the frames need, whatever length it declares
        return labels

    # ------------------------------------------------------------------ data
    def _read_counts(self, start: int, stop: int) -> np.ndarray:
        if self._file is None:
            raise CaptureError(f"{self.path}: capture is closed")
        try:
            return self._frames[start:stop]
        except H5_ERRORS as e:
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
