"""Safe opening of ``.npy`` files: the header is parsed and checked before any data is touched.

numpy's loader trusts the header (a hostile shape ends in a bare error or a terabyte allocation);
here a plain numeric dtype, a valid shape and the exact file size are required first.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Literal

import numpy as np

from radaraug.errors import CaptureError
from radaraug.files import open_regular

MAX_HEADER_BYTES = 10_000
"""Largest .npy header accepted (numpy writes 128 bytes for any array radaraug stores)."""


def read_npy_header(path: Path) -> tuple[tuple[int, ...], bool, np.dtype, int, int]:
    """``(shape, fortran_order, dtype, data_offset, file_size)`` of a .npy file, validated.

    Raises:
        CaptureError: not a regular .npy file, an unparsable header, a non-plain dtype, an invalid
            shape, or a file size other than the header plus the declared data.
    """
    fd = open_regular(path, error=CaptureError, what=".npy file")
    with os.fdopen(fd, "rb") as fh:
        size = os.fstat(fh.fileno()).st_size
        try:
            version = np.lib.format.read_magic(fh)
            if version == (1, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_1_0(fh, max_header_size=MAX_HEADER_BYTES)
            elif version == (2, 0):
                shape, fortran, dtype = np.lib.format.read_array_header_2_0(fh, max_header_size=MAX_HEADER_BYTES)
            else:  # 3.0 only adds UTF-8 field names, which radar data never has
                raise ValueError(f"unknown .npy format version {version}")
            offset = fh.tell()
        except Exception as e:  # noqa: BLE001 - any failure to parse hostile bytes is "not a .npy"
            # numpy's messages may tell users to trust the file with allow_pickle=True: never pass that on.
            reason = str(e).split("\n")[0]
            if "allow_pickle" in reason or "pickle" in reason or len(reason) > 200:
                reason = "its header is invalid or too large"
            raise CaptureError(f"{path}: not a readable .npy file ({type(e).__name__}: {reason})") from None
    if not isinstance(dtype, np.dtype) or dtype.hasobject or dtype.fields is not None or dtype.subdtype is not None:
        raise CaptureError(f"{path}: .npy dtype {dtype} is not a plain numeric type")
    if not isinstance(shape, tuple) or any(isinstance(n, bool) or not isinstance(n, int) or n < 0 for n in shape):
        raise CaptureError(f"{path}: .npy header declares an invalid shape {str(shape)[:80]}")
    need = offset + math.prod(shape) * dtype.itemsize  # Python ints: no overflow, whatever the header claims
    if need != size:
        what = "truncated .npy file" if size < need else ".npy file longer than its header says"
        raise CaptureError(
            f"{path}: {what} ({size} bytes, its header {str(shape)[:80]} {dtype} needs {need})"
        )
    return shape, bool(fortran), dtype, offset, size


def open_npy(path: Path, *, kinds: str = "iuf", mmap: bool = True) -> np.ndarray:
    """A validated .npy file as a read-only memory map (or an array read whole, ``mmap=False``).

    Args:
        path: the .npy file.
        kinds: the dtype kinds accepted (numpy ``dtype.kind`` letters).
        mmap: memory-map instead of reading.

    Raises:
        CaptureError: see :func:`read_npy_header`, or a dtype of another kind.
    """
    shape, fortran, dtype, offset, _ = read_npy_header(path)
    if dtype.kind not in kinds:
        raise CaptureError(f"{path}: .npy dtype {dtype} is not one of the accepted kinds ({kinds})")
    order: Literal["C", "F"] = "F" if fortran else "C"
    if 0 in shape:
        return np.empty(shape, dtype, order=order)
    try:
        if mmap:
            return np.memmap(path, dtype=dtype, mode="r", offset=offset, shape=shape, order=order)
        fd = open_regular(path, error=CaptureError, what=".npy file")
        with os.fdopen(fd, "rb") as fh:
            fh.seek(offset)
            count = int(np.prod(shape, dtype=np.int64))
            flat = np.fromfile(fh, dtype=dtype, count=count)
        if flat.size != count:
            raise CaptureError(f"{path}: .npy file shrank while being read")
        return flat.reshape(shape, order=order)
    except (OSError, ValueError, MemoryError) as e:
        if isinstance(e, CaptureError):
            raise
        raise CaptureError(f"{path}: cannot read .npy data ({type(e).__name__}: {e})") from None
