"""Names and version of the radaraug HDF5 capture format (specified in ``docs/captures.md``).

Layout of a version 1.x file::

    /                   attrs: format, format_version, radar_config (JSON), sample_units,
                               float_convention, db_convention, created, source, description,
                               optional file-level labels (label_<name> or a JSON "labels")
    /frames             uint16 (F, rx, chirps, samples), one chunk per frame
    /timestamps         float64 (F,) Unix seconds                       (optional)
    /labels/<name>      (F,) per-frame label, e.g. labels/count int64    (optional)
    /frames_written     int64 (1,) frames completely written and flushed  (1.1, optional)

Since 1.1 the writer records in ``frames_written`` how many frames reached the file completely
(data, then flush, then the count, then a second flush). A reader serves no more frames than
that count: a writer stopped by a full disk or a kill mid-append may have extended ``frames``
over a frame whose data never reached the disk.

Readers accept any ``1.x`` version (minor versions only add optional content) and refuse
other major versions.
"""

from __future__ import annotations

import os
from pathlib import Path

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


def stored_eof_shortfall(path: str | os.PathLike) -> int:
    """Bytes missing from the end of an HDF5 file according to its superblock (0 if complete).

    HDF5 skips its own truncation check when a file is opened for SWMR reading, which is how
    radaraug opens captures (so a file left by a crashed writer still opens). This re-does the
    check for superblock versions 2 and 3, the ones ``libver="latest"`` (and SWMR) files have:
    signature, version, offset size, length size, flags, then base address, superblock
    extension address and end-of-file address, each ``offset size`` bytes, little endian.
    Older superblocks (never SWMR-written) return 0 here; HDF5 or the first read catches them.
    So does a file whose consistency flags are still set (a writer was killed): its stored
    end-of-file may legitimately run ahead of what reached the disk, and the frames flushed
    before the kill must stay readable.
    """
    with open(path, "rb") as fh:
        head = fh.read(48)
        size = os.fstat(fh.fileno()).st_size
    if len(head) < 12 or not head.startswith(HDF5_SIGNATURE) or head[8] not in (2, 3):
        return 0
    if head[11] != 0:  # file consistency flags: open for (SWMR) write when the writer died
        return 0
    so = head[9]
    if so not in (2, 4, 8) or len(head) < 12 + 3 * so:
        return 0
    base = int.from_bytes(head[12 : 12 + so], "little")
    eof = int.from_bytes(head[12 + 2 * so : 12 + 3 * so], "little")
    return max(0, base + eof - size)


def looks_like_hdf5(path: Path) -> bool:
    """True when the file starts with the HDF5 signature (no user block)."""
    try:
        with open(path, "rb") as fh:
            return fh.read(8) == HDF5_SIGNATURE
    except OSError:
        return False
