"""Recovering an HDF5 capture whose writer was killed, and knowing whether a writer is alive.

A killed writer leaves the superblock's consistency flags set; they are reset here as ``h5clear -s``
does, only under an exclusive ``flock`` that no live writer or reader holds. Superblock layout and
locking: ``docs/captures.md``, "Crash safety".
"""

from __future__ import annotations

import errno
import fcntl
import os
from pathlib import Path

from radaraug.errors import CaptureError
from radaraug.io import hdf5_format as fmt

BUSY = (  # the refusal when another process holds the file
    "another process has this file open (a writer, or a reader: HDF5 readers lock files too); "
    "wait for it to finish or close it"
)
_FLAGS_OFFSET = 11


def _superblock(head: bytes, file_size: int, path: Path) -> fmt.Superblock:
    """The version 2/3 superblock at the start of ``head``; CaptureError unless its flags can be reset."""
    sb = fmt.parse_superblock(head, file_size)
    if sb is None or len(head) < 12:
        raise CaptureError(f"{path}: not an HDF5 file (no HDF5 signature at its start)")
    if sb.version not in (2, 3):
        raise CaptureError(
            f"{path}: HDF5 superblock version {sb.version} (radaraug captures have version 2 or 3); "
            "cannot reset its consistency flags"
        )
    if sb.checksum_offset is None:
        raise CaptureError(f"{path}: damaged HDF5 superblock (size of offsets {head[9]})")
    if not sb.checksum_ok:
        raise CaptureError(f"{path}: damaged HDF5 superblock (checksum mismatch)")
    return sb


def status_flags(path: str | os.PathLike) -> int:
    """The file consistency flags of a version 2/3 superblock (0: closed cleanly).

    Raises:
        CaptureError: not HDF5, another superblock version, or a damaged superblock.
    """
    path = Path(path)
    with open(path, "rb") as fh:
        head = fh.read(fmt.SUPERBLOCK_HEAD_BYTES)
        size = os.fstat(fh.fileno()).st_size
    return _superblock(head, size, path).flags


def _flock(fd: int, how: int) -> None:
    """``flock(fd, how | LOCK_NB)``; no flock support (some network filesystems) counts as unlocked."""
    try:
        fcntl.flock(fd, how | fcntl.LOCK_NB)
    except BlockingIOError:
        raise
    except OSError as e:
        if e.errno not in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL):
            raise


def writer_is_alive(path: str | os.PathLike) -> bool:
    """True when another process holds a lock on ``path`` (radaraug's writer lock, or HDF5's, readers included)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as e:
        raise CaptureError(f"{path}: cannot open ({e.strerror})") from None
    try:
        _flock(fd, fcntl.LOCK_EX)
    except BlockingIOError:
        return True
    finally:
        os.close(fd)  # closing releases the lock when it was taken
    return False


def _reset_flags(fd: int, path: Path) -> bool:
    """Reset the flags through ``fd`` (the caller holds the exclusive lock); True when they were set."""
    sb = _superblock(os.pread(fd, fmt.SUPERBLOCK_HEAD_BYTES, 0), os.fstat(fd).st_size, path)
    if sb.flags == 0:
        return False
    assert sb.checksum_offset is not None and sb.eof is not None
    fixed = bytearray(os.pread(fd, sb.checksum_offset, 0))
    fixed[_FLAGS_OFFSET] = 0
    try:
        # A writer stopped by a full disk may have recorded an end of file that its last (failed)
        # write never reached; HDF5 refuses such a file as truncated. Nothing committed lives
        # there (readers serve only frames_written), so the gap is filled with (sparse) zeros.
        if os.fstat(fd).st_size < sb.eof:
            os.ftruncate(fd, sb.eof)
        os.pwrite(fd, bytes(fixed) + fmt.lookup3(bytes(fixed)).to_bytes(4, "little"), 0)
        os.fsync(fd)
    except OSError as e:
        raise CaptureError(f"{path}: cannot rewrite the HDF5 superblock ({e.strerror})") from None
    return True


def _open_exclusive(path: Path, flags: int) -> int:
    try:
        fd = os.open(path, flags | os.O_NONBLOCK)
    except OSError as e:
        raise CaptureError(f"{path}: cannot open for writing ({e.strerror})") from None
    try:
        _lock_or_busy(fd, fcntl.LOCK_EX, path)
    except BaseException:
        os.close(fd)
        raise
    return fd


def _lock_or_busy(fd: int, how: int, path: Path) -> None:
    """:func:`_flock`, with the one documented refusal when another process holds the file."""
    try:
        _flock(fd, how)
    except BlockingIOError:
        raise CaptureError(f"{path}: {BUSY}") from None


def clear_status_flags(path: str | os.PathLike) -> bool:
    """Reset the consistency flags left by a killed writer, like ``h5clear -s`` (superblock v2/v3).

    Returns:
        True when flags were set and reset, False when the file was already clean.

    Raises:
        CaptureError: a live process holds the file, or it is not HDF5 with a v2/v3 superblock, or
            its superblock is damaged or cannot be written.
    """
    path = Path(path)
    fd = _open_exclusive(path, os.O_RDWR)
    try:
        return _reset_flags(fd, path)
    finally:
        os.close(fd)


def hold_writer_lock(path: str | os.PathLike, *, reset_flags: bool = False) -> int:
    """Take the writer lock of ``path``: a shared ``flock`` on the file itself, held until released.

    Exclusive first (a second writer is refused), then shared, so that HDF5 readers can open the file.

    Args:
        path: the capture file.
        reset_flags: reset stale consistency flags under the exclusive lock (a resume).

    Returns:
        The file descriptor holding the lock; :func:`release_writer_lock` closes it.

    Raises:
        CaptureError: the file cannot be opened, another process holds it, or its flags cannot be reset.
    """
    path = Path(path)
    fd = _open_exclusive(path, os.O_RDWR)
    try:
        if reset_flags:
            _reset_flags(fd, path)
        _lock_or_busy(fd, fcntl.LOCK_SH, path)
    except BaseException:
        os.close(fd)
        raise
    return fd


def release_writer_lock(fd: int | None) -> None:
    """Release a lock taken by :func:`hold_writer_lock` (None: nothing to do)."""
    if fd is not None:
        try:
            os.close(fd)
        except OSError:
            pass
