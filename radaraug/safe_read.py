"""Bounded, non-blocking reads of the files radaraug parses, and one safe JSON loader.

Every JSON document radaraug reads (an Infineon ``config.json`` and ``meta.json``, the HDF5
``radar_config`` and ``labels`` attributes, a ``CalibratedDR`` file, a twin profile) goes through
:func:`parse_json` / :func:`load_json`, and every small text file (timestamps, ``format.version``)
through :func:`read_bytes`. They turn hostile input into one :class:`~radaraug.errors.RadarAugError`
subclass (chosen by the caller) that names the file:

* only regular files are opened: a FIFO would block ``open()`` forever, a character device such
  as ``/dev/zero`` would be read without end; the check is made on the path and again on the
  open descriptor, which is opened with ``O_NONBLOCK`` so a file swapped for a FIFO in between
  cannot block either;
* at most ``limit`` bytes are read (:data:`MAX_JSON_BYTES` for JSON), whatever the file claims;
* JSON nesting deeper than :data:`MAX_JSON_DEPTH` and integers longer than
  :data:`MAX_JSON_INT_DIGITS` digits are refused (100,000 nested brackets overflow Python's
  recursion; a 5,000-digit integer exceeds Python's int-to-text limit; a 401-digit one overflows
  a float), as is anything that is not UTF-8.
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Iterable
from typing import Any

from radaraug.errors import RadarAugError

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
    """A read-only descriptor of the regular file ``path``; the caller closes it.

    Opened with ``O_NONBLOCK`` and checked again on the descriptor.
    """
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
        children: Iterable[Any]
        if isinstance(node, dict):
            children = node.values()
        elif isinstance(node, list):
            children = node
        else:
            continue
        if depth > limit:
            return True
        stack.extend((child, depth + 1) for child in children)
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
    """``repr(value)`` cut to ``width`` characters, safe for values whose repr fails.

    E.g. a 5,000-digit integer exceeds Python's int-to-text limit.
    """
    try:
        text = repr(value)
    except (ValueError, RecursionError):
        if isinstance(value, int):
            return f"<an integer of about {int(value.bit_length() * 0.30103) + 1} digits>"
        return f"<a {type(value).__name__}>"
    return text if len(text) <= width else text[: width - 3] + "..."
