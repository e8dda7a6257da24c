"""How many ray-triangle tests the BVH holds at once: simulate time at each budget, one process, interleaved.

The budget (``radaraug.raytrace.accel._PAIR_BUDGET``) only chunks the candidate (ray, leaf) pairs: every
budget gives the same hits (checked here, frame for frame). What it changes is how much of each chunk's
gathered planes stays in the CPU's cache. Three workloads, each timed at every budget in turn over
``--rounds`` rounds (the median is kept), against the budget before this change (2^22) in the same run:

* a randomized room (~5,500 faces with furniture) simulating one 16-frame call of a two-person item;
* the same room's single-frame items, as the training sets make them (8 items);
* the two-walker corridor's 16-frame blocks of ``radaraug bench twin`` (4 blocks).

    python scripts/pair_budget_bench.py [--rounds 3] [-o benchmarks/bvh_pair_budget_cpu.json]
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import time
from pathlib import Path

import torch

import radaraug.raytrace.accel as accel
from radaraug.bench.twin import BLOCK, _frames_per_s
from radaraug.scene.scene import Scene
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.twin import DigitalTwin

BEFORE = 22
SHIPPED = accel._PAIR_BUDGET  # the package's value, before the runs below change it
BUDGETS = (22, 20, 19, 18, 17, 16)
RECIPE_RANDOMIZATION = {"catalog": {"spur_tone": {"probability": 0.0}, "vibrating_clutter": {"probability": 0.0}}}


def main() -> None:
    """Time every workload at every budget and write the JSON record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("-o", "--output", type=Path, default=None)
    args = ap.parse_args()
    torch.set_num_threads(1)
    ds = SimulatedRadarDataset("corridor", length=200, seed=0, randomization=RECIPE_RANDOMIZATION,
                               target="count").prepare()
    two = [i for i in range(200) if ds.scenario(i).count == 2]
    item = two[0]
    scenario = ds.scenario(item)
    rz = ds._drawn_randomization
    assert rz is not None
    draw = rz.item(ds.seed, item, scenario.count)
    twin = ds.variant_twin(draw.variant)
    faces = int(twin.tracer.bvh.num_faces) if getattr(twin.tracer, "bvh", None) is not None else None
    bench = DigitalTwin(Scene.builtin("corridor_two_walkers"))
    bench.static_signal()
    singles = list(range(8))

    def block() -> torch.Tensor:
        return twin.simulate(scenario.people, twin.frame_times(range(BLOCK)),
                             generators=torch.Generator().manual_seed(0), draw=draw)

    def items() -> list[torch.Tensor]:
        return [ds[i][0] for i in singles]

    reference = (block(), items())
    times: dict[str, dict[int, list[float]]] = {"randomized_room_16_frame_call_s": {}, "randomized_room_8_items_s": {},
                                                "bench_twin_frames_per_s": {}}
    for _ in range(args.rounds):
        for b in BUDGETS:
            accel._PAIR_BUDGET = 1 << b
            t = time.perf_counter()
            x = block()
            times["randomized_room_16_frame_call_s"].setdefault(b, []).append(time.perf_counter() - t)
            t = time.perf_counter()
            y = items()
            times["randomized_room_8_items_s"].setdefault(b, []).append(time.perf_counter() - t)
            if not (torch.equal(x, reference[0]) and all(torch.equal(a, r) for a, r in zip(y, reference[1]))):
                raise SystemExit(f"budget 2^{b} changed the frames")
            times["bench_twin_frames_per_s"].setdefault(b, []).append(_frames_per_s(bench, BLOCK, 4, lambda: None))
    medians = {k: {f"2^{b}": round(statistics.median(v), 3) for b, v in per.items()} for k, per in times.items()}
    ratios = {}
    for k, per in medians.items():
        before = per[f"2^{BEFORE}"]
        # Seconds: before / after; frames per second: after / before. Above 1: faster than 2^22.
        ratios[k] = {b: round(v / before if k.endswith("per_s") else before / v, 3) for b, v in per.items()}
    out = {"benchmark": "BVH pair budget (tests held at once), simulate time", "command": "python scripts/pair_budget_bench.py",
           "machine": f"{platform.machine()}, {torch.get_num_threads()} thread, torch {torch.__version__}",
           "rounds": args.rounds, "before": f"2^{BEFORE}", "shipped": f"2^{SHIPPED.bit_length() - 1}",
           "randomized_room_faces": faces, "medians": medians, "speedup_vs_before": ratios, "frames_identical": True}
    text = json.dumps(out, indent=1)
    print(text)
    if args.output:
        args.output.write_text(text + "\n")


if __name__ == "__main__":
    main()
