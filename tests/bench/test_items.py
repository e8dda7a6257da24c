"""``radaraug bench items`` at a tiny size: its figures are consistent (the timings are the benchmark's)."""

from __future__ import annotations

import json

from radaraug.bench.items import PREVIOUS_PAIR_BUDGET, run_items_benchmark


def test_items_benchmark_runs_and_writes(tmp_path) -> None:
    out = tmp_path / "items.json"
    r = run_items_benchmark(items=4, batch=2, rounds=1, out=out)
    assert json.loads(out.read_text()) == r
    assert set(r["items_per_s"]) == {"one_by_one", "batched", "batched_previous_pair_budget",
                                     "one_by_one_previous_pair_budget"}
    assert all(v > 0 for v in r["items_per_s"].values())
    assert r["pair_budget"]["previous"] == PREVIOUS_PAIR_BUDGET
    assert 0 <= r["max_difference_adc_counts"] <= 1.0  # batched items are the items, to an ADC code
