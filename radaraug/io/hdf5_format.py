"""Names and version of the radaraug HDF5 capture format, and its superblock checks.

The format (``/frames``, ``/timestamps``, ``/labels/<name>``, ``/frames_written`` and the file
attributes) is specified in ``docs/captures.md``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from radaraug.errors import CaptureError
from radaraug.files import open_regular

FORMAT_NAME = "radaraug-capture"
FORMAT_VERSION = "1.1"
SAMPLE_UNITS = "adc_counts"

FRAMES = "frames"
TIMESTAMPS = "timestamps"
LABELS_GROUP = "labels"
FRAMES_WRITTEN = "frames_written"
FILE_LABEL_PREFIX = "label_"
FILE_LABELS_JSON = "labels"

HDF5_SUFFIXES = (".h5", ".hdf5")
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"

# Attributes the writer owns; user attrs may not override them.
RESERVED_ATTRS = frozenset(
    {
        "format",
        "format_version",
        "radar_config",
        "sample_units",
        "float_convention",
        "db_convention",
        "created",
    }
)


MASK32 = 0xFFFFFFFF


def _rot(x: int, k: int) -> int:
    return ((x << k) | (x >> (32 - k))) & MASK32


def lookup3(data: bytes, initval: int = 0) -> int:
    """Bob Jenkins' lookup3 ``hashlittle``: the checksum HDF5 stores after its v2/v3 superblocks."""
    length = len(data)
    a = b = c = (0xDEADBEEF + length + initval) & MASK32
    if length == 0:
        return c
    pos = 0
    while length - pos > 12:
        a = (a + int.from_bytes(data[pos : pos + 4], "little")) & MASK32
        b = (b + int.from_bytes(data[pos + 4 : pos + 8], "little")) & MASK32
        c = (c + int.from_bytes(data[pos + 8 : pos + 12], "little")) & MASK32
        # mix(a, b, c)
        a = (a - c) & MASK32; a ^= _rot(c, 4); c = (c + b) & MASK32  # noqa: E702
        b = (b - a) & MASK32; b ^= _rot(a, 6); a = (a + c) & MASK32  # noqa: E702
        c = (c - b) & MASK32; c ^= _rot(b, 8); b = (b + a) & MASK32  # noqa: E702
        a = (a - c) & MASK32; a ^= _rot(c, 16); c = (c + b) & MASK32  # noqa: E702
        b = (b - a) & MASK32; b ^= _rot(a, 19); a = (a + c) & MASK32  # noqa: E702
        c = (c - b) & MASK32; c ^= _rot(b, 4); b = (b + a) & MASK32  # noqa: E702
        pos += 12
    tail = data[pos:] + bytes(12 - (length - pos))  # the last 1..12 bytes, zero padded
    a = (a + int.from_bytes(tail[0:4], "little")) & MASK32
    b = (b + int.from_bytes(tail[4:8], "little")) & MASK32
    c = (c + int.from_bytes(tail[8:12], "little")) & MASK32
    # final(a, b, c)
    c ^= b; c = (c - _rot(b, 14)) & MASK32  # noqa: E702
    a ^= c; a = (a - _rot(c, 11)) & MASK32  # noqa: E702
    b ^= a; b = (b - _rot(a, 25)) & MASK32  # noqa: E702
    c ^= b; c = (c - _rot(b, 16)) & MASK32  # noqa: E702
    a ^= c; a = (a - _rot(c, 4)) & MASK32  # noqa: E702
    b ^= a; b = (b - _rot(a, 14)) & MASK32  # noqa: E702
    c ^= b; c = (c - _rot(b, 24)) & MASK32  # noqa: E702
    return c


@dataclass(frozen=True)
class Superblock:
    """What radaraug checks in an HDF5 superblock before handing the file to HDF5.

    Attributes:
        version: superblock version (0..3; SWMR and ``libver="latest"`` files have 2 or 3).
        file_size: size of the file in bytes.
        flags: consistency flags (v2/v3; non-zero while a writer has the file open or was killed).
        eof: stored end-of-file address plus base address (v2/v3), else None.
        checksum_ok: the stored lookup3 checksum matches (v2/v3), else None.
        checksum_offset: where the checksum is stored (= length of the checksummed bytes), else None.
    """

    version: int
    file_size: int
    flags: int
    eof: int | None
    checksum_ok: bool | None
    checksum_offset: int | None = None

    @property
    def open_for_write(self) -> bool:
        """A writer had the file open and did not close it (or still has it open)."""
        return self.flags != 0


def read_superblock(path: str | os.PathLike) -> Superblock | None:
    """The superblock fields of an HDF5 file (no user block), or None without the HDF5 signature.

    Raises:
        CaptureError: the path is not a readable regular file.
    """
    fd = open_regular(path, error=CaptureError, what="HDF5 file")
    with os.fdopen(fd, "rb") as fh:
        head = fh.read(SUPERBLOCK_HEAD_BYTES)
        size = os.fstat(fh.fileno()).st_size
    return parse_superblock(head, size)


SUPERBLOCK_HEAD_BYTES = 64
"""Bytes at the start of a file that hold any v2/v3 superblock (48 at most, with 8-byte offsets)."""


def parse_superblock(head: bytes, file_size: int) -> Superblock | None:
    """:func:`read_superblock` of bytes already read from the start of a file."""
    if len(head) < 9 or not head.startswith(HDF5_SIGNATURE):
        return None
    version = head[8]
    if version not in (2, 3):
        return Superblock(version, file_size, 0, None, None)
    so = head[9] if len(head) > 9 else 0
    end = 12 + 4 * so
    if so not in (2, 4, 8) or len(head) < end + 4:
        return Superblock(version, file_size, head[11] if len(head) > 11 else 0, None, False)
    base = int.from_bytes(head[12 : 12 + so], "little")
    eof = int.from_bytes(head[12 + 2 * so : 12 + 3 * so], "little")
    stored = int.from_bytes(head[end : end + 4], "little")
    return Superblock(version, file_size, head[11], base + eof, lookup3(head[:end]) == stored, end)


def stored_eof_shortfall(path: str | os.PathLike) -> int:
    """Bytes missing from the end of an HDF5 file according to its v2/v3 superblock (0 if complete).

    HDF5 skips this check for SWMR reads. 0 for older superblocks and for files a writer left open
    (their stored end of file may run ahead of the disk).
    """
    try:
        sb = read_superblock(path)
    except CaptureError:
        return 0
    if sb is None or sb.eof is None or sb.open_for_write:
        return 0
    return max(0, sb.eof - sb.file_size)


def looks_like_hdf5(path: Path) -> bool:
    """True when ``path`` is a regular file that starts with the HDF5 signature (no user block)."""
    try:
        return read_superblock(path) is not None
    except CaptureError:
        return False
