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

    An HDF5 file (``.h5``/``.hdf5`` or the HDF5 signature) gives an :class:`~radaraug.io.HDF5Capture`;
    an Infineon recording folder (or its ``RadarIfxAvian_00``, ``radar.npy``, ``config.json``) an
    :class:`~radaraug.io.InfineonRecording`.

    Raises:
        CaptureError: the path does not exist, is of no known kind or not a regular file or folder,
            or its reader refuses it.
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
