"""The content key of every cache file the package writes (simulated maps, fits on a capture)."""

from __future__ import annotations

import hashlib
import json
from typing import Any


def cache_key(spec: dict[str, Any] | list[Any]) -> str:
    """A 20-hex-digit content hash of a cache spec (JSON-able; key order does not matter)."""
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:20]
