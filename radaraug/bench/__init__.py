"""Benchmarks: each reports figures as a ratio against a baseline run in the same process."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from radaraug._files import atomic_write_json


def write_figures(out: str | os.PathLike | None, figures: dict[str, Any], *, newline: bool = True) -> None:
    """Write a benchmark's figures as indented JSON to ``out`` (its folder made first); None: nothing."""
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        atomic_write_json(out, figures, newline=newline, indent=2)
