"""`open_capture`: one entry point for every capture radaraug reads."""

from __future__ import annotations

import os
from pathlib import Path

from radaraug.errors import CaptureError
from radaraug.files import regular_file_size
from radaraug.io import hdf5_format as fmt
from radaraug.io.base import CaptureReader
from radaraug.io.hdf5_reader import HDF5Capture
from radaraug.io.infineon import InfineonRecording


def open_capture(path: str | os.PathLike) -> CaptureReader:
    """Open a capture for reading, choosing the reader from what ``path`` is.

    * a ``.h5`` / ``.hdf5`` file (or any file starting with the HDF5 signature) -> radaraug
      HDF5 capture (:class:`~radaraug.io.hdf5_reader.HDF5Capture`);
    * a folder holding ``RadarIfxAvian_00/``, that folder itself, or its ``radar.npy`` /
      ``config.json`` -> Infineon recording (:class:`~radaraug.io.InfineonRecording`).

    Example:
        >>> with open_capture(sample_recording_path()) as cap:  # doctest: +SKIP
        ...     x = cap.read(0, 10)          # float32 (10, rx, chirps, samples)

    Raises:
        CaptureError: the path does not exist, is of no known kind, is not a regular file or
            folder (a FIFO, a device), or its reader refuses it.
    """
    p = Path(path)
    if not os.path.lexists(p):
        raise CaptureError(f"{p}: capture does not exist")
    if p.is_dir() or p.name in ("radar.npy", "config.json"):
        return InfineonRecording(p)
    # A FIFO would block the signature check's open(); /dev/zero would pass any size check.
    regular_file_size(p, error=CaptureError, what="capture")
    if p.suffix.lower() in fmt.HDF5_SUFFIXES or fmt.looks_like_hdf5(p):
        return HDF5Capture(p)
    raise CaptureError(
        f"{p}: unknown capture type (expected a .h5/.hdf5 radaraug capture or an Infineon recording folder)"
    )
