"""Many items per call on the CPU: the training sets' items one by one against ``simulate_items`` batches.

The items are the recipes' (randomized corridor, one frame each, the catalog without spur and fan), as
``reproduce`` simulates them into its map caches. Each round times the same items three ways, in turn:
one ``dataset[i]`` call each, ``dataset.__getitems__`` batches (what a DataLoader fetches), and those
batches with the BVH's previous pair budget (2^22 tests at once; the code before batching ran one by
one at that budget). Medians over the rounds; figures as ratios within this run (docs/benchmarks.md).
"""

from __future__ import annotations

import os
import platform
import statistics
import time
from typing import Any

import torch

from radaraug.bench import torch_threads, write_figures

PREVIOUS_PAIR_BUDGET = 1 << 22
RECIPE_RANDOMIZATION = {"catalog": {"spur_tone": {"probability": 0.0}, "vibrating_clutter": {"probability": 0.0}}}


def run_items_benchmark(*, items: int = 64, batch: int = 16, rounds: int = 3,
                        out: str | os.PathLike | None = None) -> dict[str, Any]:
    """Items per second one by one and in batches of ``batch``, one process, one thread.

    Returns the figures (also written as JSON to ``out``): ``items_per_s`` per way, the ratios, and the
    largest difference between a batched item and the same item alone, in ADC counts.
    """
    import radaraug.raytrace.accel as accel
    from radaraug.sim.dataset import SimulatedRadarDataset

    shipped = accel._PAIR_BUDGET
    with torch_threads(1):
        ds = SimulatedRadarDataset("corridor", length=items, seed=0, randomization=RECIPE_RANDOMIZATION,
                                   target="count", batched=True).prepare()
        # Batches of one room variant each, as the map caches' loader orders them (training/cache.py).
        ordered = sorted(range(items), key=lambda i: ds.room_variant(i) or 0)
        chunks = [ordered[s:s + batch] for s in range(0, items, batch)]
        alone = [ds[i][0] for i in range(items)]  # warm-up (every variant's room caches) and the reference
        batched = {i: x for c in chunks for i, (x, _) in zip(c, ds.__getitems__(c))}
        counts = float(max((alone[i] - x).abs().max() for i, x in batched.items())) * ds.config.adc_full_scale_counts / 2

        def one_by_one() -> None:
            for i in range(items):
                ds[i]

        def in_batches() -> None:
            for c in chunks:
                ds.__getitems__(c)

        times: dict[str, list[float]] = {"one_by_one": [], "batched": [], "batched_previous_pair_budget": [],
                                         "one_by_one_previous_pair_budget": []}
        try:
            for _ in range(rounds):
                for key, fn, budget in (("one_by_one", one_by_one, shipped), ("batched", in_batches, shipped),
                                        ("batched_previous_pair_budget", in_batches, PREVIOUS_PAIR_BUDGET),
                                        ("one_by_one_previous_pair_budget", one_by_one, PREVIOUS_PAIR_BUDGET)):
                    accel._PAIR_BUDGET = budget
                    t0 = time.perf_counter()
                    fn()
                    times[key].append(time.perf_counter() - t0)
        finally:
            accel._PAIR_BUDGET = shipped
    rate = {k: items / statistics.median(v) for k, v in times.items()}
    result: dict[str, Any] = {
        "benchmark": "items",
        "items": items, "batch": batch, "rounds": rounds,
        "items_per_s": {k: round(v, 2) for k, v in rate.items()},
        "batched_speedup": round(rate["batched"] / rate["one_by_one"], 3),
        "speedup_vs_before": round(rate["batched"] / rate["one_by_one_previous_pair_budget"], 3),
        "pair_budget": {"shipped": shipped, "previous": PREVIOUS_PAIR_BUDGET,
                        "batched_speedup": round(rate["batched"] / rate["batched_previous_pair_budget"], 3),
                        "one_by_one_speedup": round(rate["one_by_one"] / rate["one_by_one_previous_pair_budget"], 3)},
        "max_difference_adc_counts": round(counts, 3),
        "machine": f"{platform.machine()}, 1 thread, torch {torch.__version__}",
    }
    write_figures(out, result)
    return result
