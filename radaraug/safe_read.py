"""Bounded, non-blocking reads of the files radaraug parses, and one safe JSON loader.

The helpers live in :mod:`radaraug._files` (with the atomic writes, below every layer); this
public path re-exports them.
"""

from radaraug._files import (
    MAX_JSON_BYTES,
    MAX_JSON_DEPTH,
    MAX_JSON_INT_DIGITS,
    MAX_TEXT_BYTES,
    load_json,
    open_regular,
    parse_json,
    read_bytes,
    regular_file_size,
    safe_repr,
)

__all__ = [
    "MAX_JSON_BYTES",
    "MAX_JSON_DEPTH",
    "MAX_JSON_INT_DIGITS",
    "MAX_TEXT_BYTES",
    "load_json",
    "open_regular",
    "parse_json",
    "read_bytes",
    "regular_file_size",
    "safe_repr",
]
