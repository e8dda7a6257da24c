"""Throughput of the brute-force ray-triangle kernel, eager vs ``torch.compile``, in one process."""

from __future__ import annotations

import time
from typing import Any

import torch

from radaraug.bench import best_seconds
from radaraug.raytrace.intersect import Hit, compile_failed, intersect


def _random_scene(num_rays: int, num_triangles: int, device: torch.device, dtype: torch.dtype, seed: int):
    g = torch.Generator().manual_seed(seed)
    centres = torch.rand(num_triangles, 1, 3, generator=g, dtype=dtype) * 10 - 5
    tri = centres + 0.2 * torch.randn(num_triangles, 3, 3, generator=g, dtype=dtype)
    o = torch.randn(num_rays, 3, generator=g, dtype=dtype)
    d = torch.randn(num_rays, 3, generator=g, dtype=dtype)
    d = d / d.norm(dim=1, keepdim=True)
    return o.to(device), d.to(device), tri.to(device)


def benchmark_intersection(
    num_rays: int = 65536,
    num_triangles: int = 1024,
    device: str | torch.device = "cpu",
    compiled: bool = True,
    *,
    repeats: int = 3,
    dtype: torch.dtype = torch.float32,
    seed: int = 0,
) -> dict[str, Any]:
    """Ray-triangle tests per second of the nearest-hit kernel, eager and (optionally) compiled.

    Both variants run on the same random rays and triangles, after one warm-up call each (for the
    compiled kernel the warm-up includes compilation, reported separately). The two results are
    checked to agree.

    Args:
        num_rays: rays per call.
        num_triangles: triangles per call (every ray meets every triangle: brute force).
        device: where to run.
        compiled: also time the ``torch.compile``-d kernel.
        repeats: timed calls per variant (the best is kept).
        dtype: float dtype.
        seed: seed of the random scene.

    Returns:
        ``{"num_rays", "num_triangles", "device", "threads", "eager_tests_per_s",
        "compiled_tests_per_s" (None when not run or compilation failed), "compile_warmup_s",
        "speedup", "agree"}``.
    """
    dev = torch.device(device)
    o, d, tri = _random_scene(num_rays, num_triangles, dev, dtype, seed)
    tests = num_rays * num_triangles

    def run(flag: bool) -> Hit:
        return intersect(o, d, tri, compiled=flag)

    ref = run(False)
    eager_s = best_seconds(lambda: run(False), repeats, dev)
    out: dict[str, Any] = {
        "num_rays": num_rays, "num_triangles": num_triangles, "device": str(dev),
        "threads": torch.get_num_threads(), "eager_tests_per_s": tests / eager_s,
        "compiled_tests_per_s": None, "compile_warmup_s": None, "speedup": None, "agree": None,
    }
    if compiled:
        t0 = time.perf_counter()
        hit = run(True)
        out["compile_warmup_s"] = time.perf_counter() - t0
        if not compile_failed():
            comp_s = best_seconds(lambda: run(True), repeats, dev)
            out["compiled_tests_per_s"] = tests / comp_s
            out["speedup"] = eager_s / comp_s
            out["agree"] = bool(torch.equal(hit.face, ref.face))
    return out
