"""On-disk cache of traced static rooms, keyed by (scene, radar, tracer options, tracer version).

Entries are ``static-<key>.pt`` files written atomically; an unreadable entry is traced again, an unwritable
folder warned about once. Key, folder and behaviour: ``docs/raytracer.md``, "The static-room cache".
"""

from __future__ import annotations

import hashlib
import os
import warnings
from pathlib import Path
from typing import Any

import torch

from radaraug.files import TMP_SUFFIX, atomic_save, remove_stale_temporaries

TRACER_VERSION = 2
"""Bump when a change to the tracer changes the static paths of an unchanged scene."""

STALE_TEMPORARY_S = 3600.0
"""A temporary file of an entry older than this was left by a killed writer (a live write takes
seconds): the next write of that entry removes it."""

_warned_dirs: set[str] = set()


def default_cache_dir() -> Path:
    """``$RADARAUG_CACHE_DIR``, else ``$XDG_CACHE_HOME/radaraug``, else ``~/.cache/radaraug``."""
    env = os.environ.get("RADARAUG_CACHE_DIR")
    if env:
        return Path(env)
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "radaraug"


def digest(parts: list[Any]) -> str:
    """SHA-256 hex digest of tensors (dtype, shape, bytes) and reprs of everything else."""
    h = hashlib.sha256()
    for p in parts:
        if isinstance(p, torch.Tensor):
            t = p.detach().cpu().contiguous()
            h.update(f"{t.dtype}{tuple(t.shape)}".encode())
            h.update(t.view(torch.uint8).numpy().tobytes() if t.numel() else b"")
        else:
            h.update(repr(p).encode())
        h.update(b"\x00")
    return h.hexdigest()


def load(folder: Path, key: str) -> dict[str, torch.Tensor] | None:
    """The cached entry of ``key`` or None (missing or unreadable: the caller traces again)."""
    path = folder / f"static-{key}.pt"
    if not path.is_file():
        return None
    try:
        data = torch.load(path, map_location="cpu", weights_only=True)
    except Exception as err:  # noqa: BLE001 - any damage to a cache entry means "trace again"
        warnings.warn(f"static-room cache entry {path} is unreadable ({type(err).__name__}); tracing again",
                      RuntimeWarning, stacklevel=3)
        return None
    if not isinstance(data, dict) or data.get("version") != TRACER_VERSION:
        return None
    return data


def store(folder: Path, key: str, data: dict[str, Any]) -> None:
    """Write an entry atomically; warn once per folder when it cannot be written."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        # Any temporary of this key's entry (radaraug.files' convention), however old its writer.
        remove_stale_temporaries(folder, f".static-{key}.*.{TMP_SUFFIX}", older_than_s=STALE_TEMPORARY_S)
        # Temporary name .static-<key>.pt.<pid>.<random>.tmp (radaraug.files).
        atomic_save(folder / f"static-{key}.pt", lambda f: torch.save({**data, "version": TRACER_VERSION}, f))
    except OSError as err:
        if str(folder) not in _warned_dirs:
            _warned_dirs.add(str(folder))
            warnings.warn(f"cannot write the static-room cache in {folder} ({err}); the room will be traced "
                          "again by every process (set RADARAUG_CACHE_DIR to a writable folder)",
                          RuntimeWarning, stacklevel=3)

