"""`radaraug bench twin`: end-to-end simulation throughput of the paper's scene, with baselines.

The corridor with two walkers at the paper's config; each figure against a baseline measured in the same
process (docs/benchmarks.md).
"""

from __future__ import annotations

import math
import os
import platform
import sys
import time
from typing import TYPE_CHECKING, Any

import torch
from torch.utils.data import DataLoader, Dataset

from radaraug.bench import torch_threads, write_figures

if TYPE_CHECKING:
    from radaraug.sim.twin import DigitalTwin

BLOCK = 16


class _Blocks(Dataset):
    """Blocks of consecutive frames of one scene (module level: picklable for workers).

    Item ``i`` is block ``i % wrap``, so the workers simulate the frames the one-process figure does.
    """

    def __init__(self, scene_name: str, n: int, device: str, static: torch.Tensor | None, wrap: int) -> None:
        self.scene_name, self.n, self.device, self.static, self.wrap = scene_name, n, device, static, wrap
        self.twin: DigitalTwin | None = None

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, i: int) -> torch.Tensor:
        from radaraug.scene.scene import Scene
        from radaraug.sim.seeding import item_generator
        from radaraug.sim.twin import DigitalTwin

        twin = self.twin
        if twin is None:
            twin = self.twin = DigitalTwin(Scene.builtin(self.scene_name), device=self.device, static_signal=self.static)
        j = i % self.wrap
        times = twin.frame_times(range(j * BLOCK, (j + 1) * BLOCK))
        return twin.simulate(twin.scene.people, times, generators=item_generator(0, j))

    def __getstate__(self) -> dict[str, Any]:
        return {**self.__dict__, "twin": None}


def run_twin_benchmark(
    *, blocks: int = 8, workers: int = 2, device: str = "cpu", compiled: bool = True,
    out: str | os.PathLike | None = None,
) -> dict[str, Any]:
    """Measure and return the figures (also written as JSON to ``out``).

    On CUDA the figures are those of :func:`run_twin_benchmark_cuda` (batched frames per call,
    with this run's one-process CPU figure beside them).
    """
    if torch.device(device).type == "cuda":
        return run_twin_benchmark_cuda(device=device, compiled=compiled, out=out)
    from radaraug.bench.intersection import benchmark_intersection
    from radaraug.scene.scene import Scene
    from radaraug.sensor.receiver import FMCWReceiver
    from radaraug.sensor.synthesis import ChirpTiming, synthesize
    from radaraug.sim.twin import DigitalTwin

    with torch_threads(1):
        scene = Scene.builtin("corridor_two_walkers")
        t0 = time.perf_counter()
        twin = DigitalTwin(scene, device=device)
        static = twin.static_signal()
        room_s = time.perf_counter() - t0

        def frames_per_s(tw: DigitalTwin) -> float:
            """Frames/s of ``tw`` on ``blocks`` blocks of 16 frames, after a warm-up block (CPU: no sync)."""
            return _frames_per_s(tw, BLOCK, blocks, lambda: None)

        fps_1 = frames_per_s(twin)
        assert twin.last_intervals is not None  # set by every paths() call, so by the blocks above
        knots = float(twin.last_intervals.double().mean())
        # The same blocks with one snapshot per frame (the cost of motion inside the frame).
        fps_one = frames_per_s(DigitalTwin(scene, device=device, static_signal=static, intra_frame=0))
        # The same twin with the people's shadow moving inside the frame (shadow_intervals=2).
        fps_shadow_moving = frames_per_s(DigitalTwin(scene, device=device, static_signal=static, shadow_intervals=2))

        # The cost of each of the twin's fidelity additions, added one at a time to the issue-7
        # twin (one snapshot per frame, specular-only room, no shadowing), same blocks.
        def fps_of(**options: Any) -> float:
            tw = DigitalTwin(scene, device=device, **options)
            tw.static_signal()
            return frames_per_s(tw)

        plain = {"intra_frame": 0, "shadowing": False, "tracer_options": {"diffuse": False}}
        ladder = {
            "specular room, one snapshot, no shadowing": fps_of(**plain),
            "+ diffuse clutter": fps_of(**{**plain, "tracer_options": {}}),
            "+ shadowing": fps_of(**{**plain, "tracer_options": {}, "shadowing": True}),
            "+ motion inside the frame (the default twin)": fps_1,
        }

        # Receiver alone on the twin's own paths: fast (GEMM) vs exact synthesis, same paths.
        paths = twin.paths(scene.people, twin.frame_times(range(BLOCK)))
        cfg = twin.config
        timing = ChirpTiming.from_config(cfg)
        rx = FMCWReceiver(cfg, effects=[]).to(device)
        st = rx._initial_state(paths, None, 0.0)
        args = (st.coef, st.delay_s, st.delay_rate)

        def synth(method: str) -> torch.Tensor:
            return synthesize(*args, timing=timing, dtype=torch.float64 if method == "exact" else st.dtype,
                              method=method, taylor_tol=rx.taylor_tol, chirp_delay=st.chirp_delay,
                              chirp_gain=st.chirp_gain)

        fast = synth("fast")
        t0 = time.perf_counter()
        fast = synth("fast")
        t_fast = time.perf_counter() - t0
        t0 = time.perf_counter()
        exact = synth("exact")
        t_exact = time.perf_counter() - t0
        err = (fast.double() - exact).norm() / exact.norm()

    fps_w = None
    if workers > 0 and torch.device(device).type == "cpu":
        # Start the clock only after the DataLoader's prefetched blocks are drained (2 per worker
        # queued while the warm-up blocks were consumed): counting them made the worker figure
        # ~1.3x too high before.
        warm = 4 * workers
        ds = _Blocks("corridor_two_walkers", blocks * workers + warm, device, static.cpu(), wrap=blocks)
        loader = DataLoader(ds, batch_size=None, num_workers=workers, shuffle=False, prefetch_factor=1)
        it = iter(loader)
        for _ in range(warm):  # worker start, first blocks, prefetched blocks
            next(it)
        t0 = time.perf_counter()
        n = 0
        for x in it:
            n += x.shape[0]
        fps_w = n / (time.perf_counter() - t0)

    ix = benchmark_intersection(num_rays=65536, num_triangles=1024, device=device, compiled=compiled)
    sensor_fps = 1 / twin.config.frame_repetition_time_s
    result: dict[str, Any] = {
        "benchmark": "twin",
        "scene": "corridor_two_walkers (2 walkers, 20 m corridor, people's multipath up to wall-person-wall)",
        "frame_shape": list(cfg.frame_shape),
        "device": device,
        "room_trace_and_synthesis_s": round(room_s, 2),
        "room_static_paths": int(twin.tracer.static_paths().delay_s.shape[0]),
        "people_paths_per_frame": int(paths.delay_s.shape[-2]),
        "frames_per_s_1proc": round(fps_1, 1),
        "realtime_ratio_1proc": round(fps_1 / sensor_fps, 2),
        "frames_per_s_1proc_one_snapshot": round(fps_one, 1),
        "frames_per_s_1proc_additions": {k: round(v, 1) for k, v in ladder.items()},
        "additions_note": "second-order people multipath (wall-person-wall) is in every rung: it has no switch",
        "intra_frame_cost_ratio": round(fps_one / fps_1, 3),
        "frames_per_s_1proc_shadow_intervals_2": round(fps_shadow_moving, 1),
        "shadow_intervals_2_cost_ratio": round(fps_1 / fps_shadow_moving, 3),
        "intra_frame_knot_intervals_mean": round(knots, 2),
        "workers": workers,
        "frames_per_s_workers": None if fps_w is None else round(fps_w, 1),
        "realtime_ratio_workers": None if fps_w is None else round(fps_w / sensor_fps, 2),
        "receiver_synthesis_fast_s_per_frame": t_fast / BLOCK,
        "receiver_synthesis_exact_s_per_frame": t_exact / BLOCK,
        "receiver_speedup_fast_vs_exact": round(t_exact / t_fast, 1),
        "receiver_fast_vs_exact_rel_rms_error": float(err),
        "intersection": ix,
        "torch_version": torch.__version__,
        "cpu": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(),
    }
    write_figures(out, result)
    return result


#: Frames per simulate() call on CUDA: the paper-config blocks of the CPU figure (16) up to batches
#: that fill the GPU (the kernels' launch cost is paid once per call, not per frame).
CUDA_FRAMES_PER_CALL = (16, 64, 256, 1024, 4096)
CUDA_TARGET_FRAMES_PER_S = 2000.0
"""Issue 23's target for one H100 (simulated frames/s of the paper's scene and config)."""


def _frames_per_s(twin: DigitalTwin, per_call: int, calls: int, sync: Any, *, wrap: int | None = None,
                  budget_s: float | None = None) -> float:
    """Frames/s of ``calls`` calls of ``per_call`` frames of the scene's people, after a warm-up call (call 0).

    Frame indices wrap modulo ``wrap`` (128 = 12.8 s, while the walkers are in the corridor). With
    ``budget_s``, fewer calls (at least one) are timed when the warm-up shows ``calls`` would take longer.
    """
    from radaraug.sim.seeding import item_generator

    def call(i: int) -> None:
        idx = torch.arange(i * per_call, (i + 1) * per_call)
        idx = idx if wrap is None else idx % wrap
        twin.simulate(twin.scene.people, twin.frame_times(idx), generators=item_generator(0, i, device=twin.device))

    t0 = time.perf_counter()
    call(0)
    sync()
    if budget_s is not None:
        calls = max(1, min(calls, int(budget_s / (time.perf_counter() - t0))))
    t0 = time.perf_counter()
    for i in range(calls):
        call(i)
    sync()
    return calls * per_call / (time.perf_counter() - t0)


def run_twin_benchmark_cuda(
    *, device: str = "cuda", compiled: bool = True, cpu_blocks: int = 2, calls: int = 3,
    out: str | os.PathLike | None = None,
) -> dict[str, Any]:
    """The twin's throughput on a GPU, against the CPU in the same process.

    Figures: ``cpu_frames_per_s_1proc``; ``frames_per_s_by_frames_per_call`` for each of
    :data:`CUDA_FRAMES_PER_CALL` (``"out of memory"`` where a batch does not fit);
    ``speedup_vs_cpu_1proc`` of the best; the cost of ``shadow_intervals=2``; the intersection kernel.
    """
    from radaraug.bench.intersection import benchmark_intersection
    from radaraug.scene.scene import Scene
    from radaraug.sim.twin import DigitalTwin

    dev = torch.device(device)
    scene = Scene.builtin("corridor_two_walkers")

    def sync() -> None:
        torch.cuda.synchronize(dev)

    with torch_threads(1):
        cpu_twin = DigitalTwin(scene, device="cpu")
        cpu_twin.static_signal()
        fps_cpu = _frames_per_s(cpu_twin, BLOCK, cpu_blocks, lambda: None)
    print(f"bench twin: CPU (1 thread) {fps_cpu:.1f} frames/s", file=sys.stderr, flush=True)
    t0 = time.perf_counter()
    twin = DigitalTwin(scene, device=dev)
    twin.static_signal()
    sync()
    room_s = time.perf_counter() - t0
    print(f"bench twin: CUDA room trace + static signal {room_s:.1f} s", file=sys.stderr, flush=True)
    by_size: dict[str, float | str] = {}
    for n in CUDA_FRAMES_PER_CALL:
        t0 = time.perf_counter()
        try:
            by_size[str(n)] = round(_frames_per_s(twin, n, calls, sync, wrap=128, budget_s=8.0), 1)
        except torch.OutOfMemoryError:
            by_size[str(n)] = "out of memory"
            torch.cuda.empty_cache()
        print(f"bench twin: {n} frames per call: {by_size[str(n)]} frames/s ({time.perf_counter() - t0:.1f} s)",
              file=sys.stderr, flush=True)
        if time.perf_counter() - t0 > 12.0:  # the next size would take 4x longer: it says no more
            break
    numbers = [v for v in by_size.values() if isinstance(v, float)]
    best = max(numbers) if numbers else float("nan")
    shadow = DigitalTwin(scene, device=dev, static_signal=twin.static_signal(), shadow_intervals=2)
    fps_256 = by_size.get("256")
    try:
        fps_shadow = _frames_per_s(shadow, 256, calls, sync, wrap=128, budget_s=8.0)
    except torch.OutOfMemoryError:
        fps_shadow = float("nan")
    ix = benchmark_intersection(num_rays=1 << 18, num_triangles=1024, device=device, compiled=compiled)
    cfg = twin.config
    result: dict[str, Any] = {
        "benchmark": "twin",
        "scene": "corridor_two_walkers (2 walkers, 20 m corridor, people's multipath up to wall-person-wall)",
        "frame_shape": list(cfg.frame_shape),
        "device": str(dev),
        "gpu": torch.cuda.get_device_name(dev),
        "room_trace_and_synthesis_s": round(room_s, 2),
        "cpu_frames_per_s_1proc": round(fps_cpu, 1),
        "frames_per_s_by_frames_per_call": by_size,
        "frames_per_s_best": round(best, 1),
        "speedup_vs_cpu_1proc": round(best / fps_cpu, 1),
        "target_frames_per_s": CUDA_TARGET_FRAMES_PER_S,
        "target_met": bool(best >= CUDA_TARGET_FRAMES_PER_S),
        "shadow_intervals_2_cost_ratio_at_256": (round(fps_256 / fps_shadow, 3)
                                                 if isinstance(fps_256, float) and not math.isnan(fps_shadow) else None),
        "intersection": ix,
        "torch_version": torch.__version__,
        "cuda_version": torch.version.cuda,
        "cpu": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(),
    }
    write_figures(out, result)
    return result
