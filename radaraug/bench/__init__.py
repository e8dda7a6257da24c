"""Benchmarks: each reports figures as a ratio against a baseline run in the same process."""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import torch

from radaraug._torch import torch_threads as torch_threads  # re-exported: the benchmarks run on set threads
from radaraug.files import atomic_write_json


def write_figures(out: str | os.PathLike | None, figures: dict[str, Any], *, newline: bool = True) -> None:
    """Write a benchmark's figures as indented JSON to ``out`` (its folder made first); None: nothing."""
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        atomic_write_json(out, figures, newline=newline, indent=2)


def best_seconds(fn: Callable[[], Any], repeats: int, device: torch.device | None = None) -> float:
    """Seconds of the fastest of ``repeats`` calls of ``fn`` (warm-up calls are the caller's).

    On a CUDA ``device`` each call is timed from an idle GPU to the end of its kernels.
    """
    sync = torch.cuda.synchronize if device is not None and device.type == "cuda" else (lambda _: None)
    best = math.inf
    for _ in range(repeats):
        sync(device)
        t0 = time.perf_counter()
        fn()
        sync(device)
        best = min(best, time.perf_counter() - t0)
    return best
