"""Opening an HDF5 capture read-only so that a damaged file fails in seconds, never hangs.

SWMR (needed for a file a writer left open) is used only when the superblock says so, with fewer
metadata retries; see ``docs/captures.md``, "Reading".
"""

from __future__ import annotations

import ctypes
import functools
import os
import re
from pathlib import Path

import h5py

from radaraug.errors import CaptureError
from radaraug.io import hdf5_format as fmt

SWMR_READ_ATTEMPTS = 20
"""Metadata read attempts of an SWMR reader (HDF5's default is 100, with a doubling sleep:
20 attempts sleep about 2 ms in all; 100 would sleep for ages)."""

@functools.lru_cache(maxsize=1)
def _hdf5_library() -> ctypes.CDLL | None:
    """The HDF5 C library h5py uses (already loaded in this process), or None if not found."""
    try:
        with open("/proc/self/maps") as fh:
            paths = {line.split()[-1] for line in fh if ".so" in line}
        for path in sorted(paths):
            if re.search(r"/libhdf5(-[0-9a-f]+)?\.so", path):
                lib = ctypes.CDLL(path)
                if hasattr(lib, "H5Pset_metadata_read_attempts"):
                    return lib
    except OSError:  # not Linux, or the library cannot be mapped: plain SWMR below
        pass
    return None


def _swmr_open(path: Path) -> h5py.File:
    fapl = h5py.h5p.create(h5py.h5p.FILE_ACCESS)
    fapl.set_fclose_degree(h5py.h5f.CLOSE_STRONG)
    lib = _hdf5_library()
    if lib is not None:
        lib.H5Pset_metadata_read_attempts.argtypes = [ctypes.c_int64, ctypes.c_uint]
        if lib.H5Pset_metadata_read_attempts(fapl.id, SWMR_READ_ATTEMPTS) < 0:
            lib = None
    if lib is None:
        # Without the C call a damaged file may block in HDF5's retry loop; only files a writer
        # left open get here, and their superblock was checked above.
        return h5py.File(path, "r", swmr=True)
    fid = h5py.h5f.open(os.fsencode(path), h5py.h5f.ACC_RDONLY | h5py.h5f.ACC_SWMR_READ, fapl=fapl)
    return h5py.File(fid)


def open_hdf5_readonly(path: Path) -> h5py.File:
    """Open a radaraug HDF5 capture for reading: superblock checked first, SWMR only when needed.

    Raises:
        CaptureError: not a regular file, no HDF5 signature, a damaged superblock, a truncated
            file, or HDF5 cannot open it (the message names the file and says why).
    """
    sb = fmt.read_superblock(path)
    if sb is None:
        raise CaptureError(f"{path}: not an HDF5 file (no HDF5 signature at its start)")
    if sb.checksum_ok is False:
        raise CaptureError(f"{path}: HDF5 superblock is damaged (its checksum does not match)")
    if sb.eof is not None and not sb.open_for_write and sb.eof != sb.file_size:
        if sb.eof > sb.file_size:
            raise CaptureError(
                f"{path}: HDF5 file is truncated ({sb.eof - sb.file_size} bytes missing from its end); "
                "it was cut short while copying or downloading"
            )
        raise CaptureError(
            f"{path}: HDF5 file is damaged: its superblock says it ends at byte {sb.eof}, but it holds "
            f"{sb.file_size} bytes"
        )
    try:
        if sb.open_for_write:
            return _swmr_open(path)
        return h5py.File(path, "r")
    except (OSError, RuntimeError, ValueError, KeyError, TypeError) as e:
        hint = ""
        if "already open for write" in str(e):
            hint = "; a writer was killed before switching to SWMR: `h5clear -s FILE` may recover it"
        raise CaptureError(f"{path}: cannot open HDF5 file ({e}){hint}") from None
