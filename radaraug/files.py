"""File helpers below every other layer: atomic whole-file writes, temporary names, safe reads.

Imports nothing of radaraug but :mod:`radaraug.errors`, so that every layer can use it. Whole-file outputs
go through :func:`atomic_open` (a hidden ``.<name>.<pid>.<random>.tmp`` file, flushed, then renamed over the
target); captures in the making use the ``.partial`` suffix. JSON and small text files are read through
:func:`parse_json` / :func:`load_json` / :func:`read_bytes`, which refuse non-regular files, oversized input
and hostile JSON with the caller's error type. Details: docs/captures.md and docs/radar_config.md.
"""

from __future__ import annotations

import glob
import json
import os
import secrets
import stat
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

    Stale: last written at least ``older_than_s`` ago and not ``in_use`` (when given, e.g. a lock check).
    Files that cannot be checked or removed are left alone.
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


def fsync_folder(folder: str | os.PathLike) -> None:
    """Make the renames in ``folder`` durable, where the filesystem can (errors are ignored)."""
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
    fsync_folder(target.parent)


def atomic_write_text(path: str | os.PathLike, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_open(path, "w", encoding=encoding) as fh:
        fh.write(text)
    return Path(path)


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; returns the path."""
    return atomic_save(path, lambda fh: fh.write(data))


def atomic_write_json(path: str | os.PathLike, obj: Any, *, newline: bool = True, **dumps: Any) -> Path:
    """Write ``json.dumps(obj, **dumps)`` to ``path`` atomically (serialised first) and return the path."""
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


MAX_JSON_BYTES = 16 * 1024 * 1024
"""Largest JSON file or attribute radaraug parses (16 MiB; its own files are a few kB)."""

MAX_JSON_DEPTH = 64
"""Deepest nesting of JSON arrays/objects accepted (radaraug's own files nest 4 deep)."""

MAX_JSON_INT_DIGITS = 40
"""Longest JSON integer accepted, in digits (a 64-bit integer has at most 20)."""

MAX_TEXT_BYTES = 64 * 1024 * 1024
"""Largest text file read whole (a ``radar_timestamp.csv`` of ~3 million frames)."""


def _fail(error: type[RadarAugError], path: Any, problem: str) -> RadarAugError:
    return error(f"{path}: {problem}")


def regular_file_size(path: str | os.PathLike, *, error: type[RadarAugError], what: str = "file") -> int:
    """Size in bytes of ``path`` after checking that it is a regular file (links followed).

    Raises:
        error: ``path`` does not exist, cannot be examined, or is not a regular file (a folder,
            FIFO, socket or device).
    """
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise _fail(error, path, f"{what} does not exist") from None
    except OSError as e:
        raise _fail(error, path, f"cannot examine {what} ({e.strerror or e})") from None
    if not stat.S_ISREG(st.st_mode):
        raise _fail(error, path, f"{what} is not a regular file ({_kind(st.st_mode)}); refusing to read it")
    return st.st_size


def _kind(mode: int) -> str:
    for test, name in (
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return name
    return "not a plain file"


def open_regular(path: str | os.PathLike, *, error: type[RadarAugError], what: str = "file") -> int:
    """A read-only descriptor of the regular file ``path`` (``O_NONBLOCK``, checked again); the caller closes it."""
    regular_file_size(path, error=error, what=what)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise _fail(error, path, f"cannot open {what} ({e.strerror or e})") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _fail(error, path, f"{what} is not a regular file ({_kind(st.st_mode)}); refusing to read it")
        # Back to blocking reads: O_NONBLOCK only guarded the open() itself.
        os.set_blocking(fd, True)
    except BaseException:
        os.close(fd)
        raise
    return fd


def read_bytes(
    path: str | os.PathLike, *, limit: int, error: type[RadarAugError], what: str = "file"
) -> bytes:
    """The content of a regular file of at most ``limit`` bytes.

    Raises:
        error: not a regular file, larger than ``limit`` (checked before reading, and again while
            reading in case the file grows), or unreadable.
    """
    size = regular_file_size(path, error=error, what=what)
    if size > limit:
        raise _fail(error, path, f"{what} is {size} bytes, more than the {limit}-byte limit radaraug reads")
    fd = open_regular(path, error=error, what=what)
    try:
        chunks: list[bytes] = []
        total = 0
        while True:
            block = os.read(fd, min(1 << 20, limit + 1 - total))
            if not block:
                break
            chunks.append(block)
            total += len(block)
            if total > limit:
                raise _fail(error, path, f"{what} grew past the {limit}-byte limit while being read")
    except OSError as e:
        raise _fail(error, path, f"cannot read {what} ({e.strerror or e})") from None
    finally:
        os.close(fd)
    return b"".join(chunks)


def _parse_int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_JSON_INT_DIGITS:
        raise ValueError(f"an integer of {len(text.lstrip('-'))} digits (more than {MAX_JSON_INT_DIGITS})")
    return int(text)


def _depth_exceeds(value: Any, limit: int) -> bool:
    # Iterative, so that checking a deep document cannot itself overflow the stack.
    stack = [(value, 1)]
    while stack:
        node, depth = stack.pop()
        if not isinstance(node, (dict, list)):
            continue
        if depth > limit:
            return True
        stack.extend((child, depth + 1) for child in (node.values() if isinstance(node, dict) else node))
    return False


def parse_json(
    text: str | bytes, *, source: Any, error: type[RadarAugError], limit: int = MAX_JSON_BYTES, what: str = "JSON text"
) -> Any:
    """Parse JSON text (or UTF-8 bytes) from ``source`` with the limits of this module.

    ``NaN`` and ``Infinity`` are accepted as Python's ``json`` does (the validators of the values
    refuse them where a finite number is needed).

    Raises:
        error: larger than ``limit``, not UTF-8, not valid JSON, nested deeper than
            :data:`MAX_JSON_DEPTH`, or holding an integer of more than :data:`MAX_JSON_INT_DIGITS`
            digits. The message starts with ``source``.
    """
    if isinstance(text, (bytes, bytearray, memoryview)):
        if len(text) > limit:
            raise _fail(error, source, f"{what} is {len(text)} bytes, more than the {limit}-byte limit")
        try:
            text = bytes(text).decode("utf-8")
        except UnicodeDecodeError as e:
            raise _fail(error, source, f"{what} is not UTF-8 text ({e.reason} at byte {e.start})") from None
    elif not isinstance(text, str):
        raise _fail(error, source, f"{what} must be text, got {type(text).__name__}")
    elif len(text) > limit:
        raise _fail(error, source, f"{what} is {len(text)} characters, more than the {limit} limit")
    try:
        value = json.loads(text, parse_int=_parse_int)
    except RecursionError:
        raise _fail(error, source, f"{what} is nested too deeply (more than {MAX_JSON_DEPTH} levels)") from None
    except json.JSONDecodeError as e:
        raise _fail(error, source, f"{what} is not valid JSON ({e.msg} at line {e.lineno} column {e.colno})") from None
    except (ValueError, OverflowError) as e:
        raise _fail(error, source, f"{what} is not usable JSON ({e})") from None
    if _depth_exceeds(value, MAX_JSON_DEPTH):
        raise _fail(error, source, f"{what} is nested too deeply (more than {MAX_JSON_DEPTH} levels)")
    return value


def load_json(
    path: str | os.PathLike, *, error: type[RadarAugError], limit: int = MAX_JSON_BYTES, what: str = "JSON file"
) -> Any:
    """Read and parse the JSON file ``path`` (see :func:`read_bytes` and :func:`parse_json`)."""
    return parse_json(read_bytes(path, limit=limit, error=error, what=what), source=path, error=error,
                      limit=limit, what=what)


def safe_repr(value: Any, width: int = 60) -> str:
    """``repr(value)`` cut to ``width`` characters, safe for values whose repr fails (a 5,000-digit int)."""
    try:
        text = repr(value)
    except (ValueError, RecursionError):
        if isinstance(value, int):
            return f"<an integer of about {int(value.bit_length() * 0.30103) + 1} digits>"
        return f"<a {type(value).__name__}>"
    return text if len(text) <= width else text[: width - 3] + "..."
