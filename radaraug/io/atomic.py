"""Whole-file outputs written atomically, and the one naming convention of temporary files.

The helpers live in :mod:`radaraug._files`, below every layer (a scene or a figure writer that
imports them does not import the capture layer); this public path re-exports them.
"""

from radaraug._files import (
    PARTIAL_SUFFIX,
    TMP_SUFFIX,
    atomic_open,
    atomic_save,
    atomic_savefig,
    atomic_write_bytes,
    atomic_write_json,
    atomic_write_text,
    remove_stale_temporaries,
    temporaries_of,
    temporary_name,
)

__all__ = [
    "PARTIAL_SUFFIX",
    "TMP_SUFFIX",
    "atomic_open",
    "atomic_save",
    "atomic_savefig",
    "atomic_write_bytes",
    "atomic_write_json",
    "atomic_write_text",
    "remove_stale_temporaries",
    "temporaries_of",
    "temporary_name",
]
