"""The ray-triangle kernel's benchmark runs and reports consistent figures (small sizes, eager only)."""

from __future__ import annotations

from radaraug.bench.intersection import benchmark_intersection


def test_benchmark_intersection_reports_eager_throughput() -> None:
    out = benchmark_intersection(num_rays=64, num_triangles=16, device="cpu", compiled=False, repeats=1)
    assert out["eager_tests_per_s"] > 0 and out["num_rays"] * out["num_triangles"] == 64 * 16
    assert out["compiled_tests_per_s"] is None and out["speedup"] is None
