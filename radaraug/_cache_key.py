"""The content key of every cache file the package writes (simulated maps, fits on a capture), and a capture's digest."""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

from radaraug.errors import CaptureError


def cache_key(spec: dict[str, Any] | list[Any]) -> str:
    """A 20-hex-digit content hash of a cache spec (JSON-able; key order does not matter)."""
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:20]


def content_digest(path: str | os.PathLike) -> str:
    """SHA-256 of a file's bytes, or of a folder's files (relative names and bytes, sorted).

    The name and modification time of ``path`` do not count: a copied capture keeps its digest.

    Raises:
        CaptureError: ``path`` does not exist.
    """
    root = Path(path)
    if not root.exists():
        raise CaptureError(f"{root}: does not exist")
    files = [root] if root.is_file() else sorted(p for p in root.rglob("*") if p.is_file())
    h = hashlib.sha256()
    for f in files:
        name = b"" if f == root else f.relative_to(root).as_posix().encode()
        h.update(name + b"\0" + f.stat().st_size.to_bytes(8, "little"))  # unambiguous boundaries
        with open(f, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    return h.hexdigest()
