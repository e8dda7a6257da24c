"""Whole-file outputs written atomically, and the one naming convention of temporary files.

Every file radaraug writes in one piece (calibration and profile JSON, reports, figures, caches,
Infineon recording files) goes through :func:`atomic_open`. A reader, a crash or a full disk then
sees either the old file (or none) or the complete new one, never a half-written or 0-byte file:
the data is written under a hidden temporary name (``.<name>.<pid>.<random>.tmp``) in the target's
folder, flushed to disk, and only then renamed over the target (``os.replace``, atomic on one
filesystem). If anything fails, the temporary file is removed and the error propagates (an
``OSError`` such as ``ENOSPC``; callers turn it into their :class:`~radaraug.errors.RadarAugError`
where the file is a documented output). A process killed mid-write leaves its temporary file.

Temporary files, one convention (:func:`temporary_name`): ``.<name>.<pid>.<random>.<suffix>`` in
the target's folder -- hidden, unique per writer, never mistaken for the target, and found again
by the target's name (:func:`temporaries_of`), so that the next writer of the same target removes
what a killed writer left (:func:`remove_stale_temporaries`). The suffix says what the file is:

* ``tmp`` (:data:`TMP_SUFFIX`): a whole-file output in the making (:func:`atomic_open`). It is
  only ever renamed over the target once complete.
* ``partial`` (:data:`PARTIAL_SUFFIX`): a radaraug HDF5 capture in the making
  (:class:`radaraug.io.CaptureWriter`). It differs from ``tmp`` in one way that is needed: a
  recording is SWMR and must stay readable (and keep its flushed frames after a kill) *while* it
  grows, so the writer renames it to the target at its first frame, not at the end; only a
  capture with no frame yet (or one written with ``publish="close"``, such as the held-out
  proxy's files, which appear under their name only once complete) is ever left under this name.
  Its writer holds a lock on it, so a stale one is told from a live one by the lock, not only by
  its age.

One temporary name is outside this convention: the map cache of :mod:`radaraug.training.cache`
(``<stem>.partial-<pid>.h5``, removed by the next build when its pid is dead) -- left as it is
for now; moving it here changes nothing in its crash safety.
"""

from __future__ import annotations

import glob
import json
import os
import secrets
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from radaraug.errors import RadarAugError

TMP_SUFFIX = "tmp"
"""Suffix of a whole-file output's temporary (:func:`atomic_open`)."""
PARTIAL_SUFFIX = "partial"
"""Suffix of an HDF5 capture's temporary (:class:`radaraug.io.CaptureWriter`)."""


def temporary_name(path: str | os.PathLike, suffix: str = TMP_SUFFIX) -> Path:
    """A fresh hidden name beside ``path`` for its temporary file: ``.<name>.<pid>.<random>.<suffix>``."""
    p = Path(path)
    return p.with_name(f".{p.name}.{os.getpid()}.{secrets.token_hex(4)}.{suffix}")


def temporaries_of(path: str | os.PathLike, suffix: str = TMP_SUFFIX) -> str:
    """The glob pattern (relative to ``path``'s folder) of every :func:`temporary_name` of ``path``."""
    return f".{glob.escape(Path(path).name)}.*.{suffix}"


def remove_stale_temporaries(
    folder: str | os.PathLike,
    pattern: str,
    *,
    older_than_s: float,
    in_use: Callable[[Path], bool] | None = None,
) -> list[Path]:
    """Remove the temporaries matching ``pattern`` in ``folder`` that killed writers left; the removed paths.

    A temporary is stale when it was last written at least ``older_than_s`` ago (so that a writer
    that has just created its file is never hit) and ``in_use`` (when given, e.g. "a process holds
    a lock on it") says it is not in use. Files that cannot be checked or removed are left alone
    (another process may be replacing or removing them).
    """
    removed = []
    now = time.time()
    for tmp in Path(folder).glob(pattern):
        try:
            if now - tmp.stat().st_mtime < older_than_s or (in_use is not None and in_use(tmp)):
                continue
            tmp.unlink()
        except (OSError, RadarAugError):
            continue
        removed.append(tmp)
    return removed


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
