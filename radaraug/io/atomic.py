"""Whole-file outputs written atomically: a temporary file in the same folder, fsync, rename.

Every file radaraug writes in one piece (calibration and profile JSON, reports, figures, caches,
Infineon recording files) goes through :func:`atomic_open`. A reader, a crash or a full disk then
sees either the old file (or none) or the complete new one, never a half-written or 0-byte file:
the data is written under a hidden temporary name (``.<name>.<pid>.<random>.tmp``) in the target's
folder, flushed to disk, and only then renamed over the target (``os.replace``, atomic on one
filesystem). If anything fails, the temporary file is removed and the error propagates (an
``OSError`` such as ``ENOSPC``; callers turn it into their :class:`~radaraug.errors.RadarAugError`
where the file is a documented output). A process killed mid-write leaves its temporary file.
"""

from __future__ import annotations

import json
import os
import secrets
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any


def temporary_name(path: str | os.PathLike) -> Path:
    """A fresh hidden name beside ``path`` for its temporary file."""
    p = Path(path)
    return p.with_name(f".{p.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp")


def _fsync_folder(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass  # some filesystems cannot fsync a folder; the rename itself was still atomic
    finally:
        os.close(fd)


@contextmanager
def atomic_open(path: str | os.PathLike, mode: str = "w", *, encoding: str | None = "utf-8") -> Iterator[IO[Any]]:
    """Open a temporary file for writing that replaces ``path`` when the block ends without error.

    Args:
        path: the file to (re)place.
        mode: ``"w"`` (text) or ``"wb"`` (binary).
        encoding: text encoding (ignored for ``"wb"``).

    Yields:
        The open temporary file.

    Raises:
        OSError: the folder is missing or read-only, the disk is full...; ``path`` is unchanged.
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"atomic_open writes whole files: mode must be 'w' or 'wb', got {mode!r}")
    target = Path(path)
    tmp = temporary_name(target)
    # O_EXCL: never reuse a name; 0o666 minus the umask, the mode of any new file of the user.
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, mode, encoding=None if "b" in mode else encoding) as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _fsync_folder(target.parent)


def atomic_write_text(path: str | os.PathLike, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_open(path, "w", encoding=encoding) as fh:
        fh.write(text)
    return Path(path)


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; returns the path."""
    with atomic_open(path, "wb") as fh:
        fh.write(data)
    return Path(path)


def atomic_write_json(path: str | os.PathLike, obj: Any, *, newline: bool = True, **dumps: Any) -> Path:
    """Write ``json.dumps(obj, **dumps)`` to ``path`` atomically and return the path.

    The object is serialised before the file is created, so an object that is not JSON leaves nothing
    behind.
    """
    text = json.dumps(obj, **dumps) + ("\n" if newline else "")
    return atomic_write_text(path, text)


def atomic_save(path: str | os.PathLike, save: Callable[[IO[bytes]], Any]) -> Path:
    """Call ``save(file)`` on a binary temporary file that then replaces ``path``.

    Example:
        >>> atomic_save("maps.pt", lambda f: torch.save(maps, f))  # doctest: +SKIP
        >>> atomic_save("radar.npy", lambda f: np.save(f, counts))  # doctest: +SKIP
    """
    with atomic_open(path, "wb") as fh:
        save(fh)
    return Path(path)


def atomic_savefig(fig: Any, path: str | os.PathLike, **kwargs: Any) -> Path:
    """``fig.savefig`` (matplotlib) to ``path`` atomically; the format comes from the suffix."""
    fmt = kwargs.pop("format", None) or (Path(path).suffix.lstrip(".").lower() or "png")
    return atomic_save(path, lambda fh: fig.savefig(fh, format=fmt, **kwargs))
