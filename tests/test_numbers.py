"""One source of numbers: every figure a page quotes from a ``benchmarks/*.json`` record matches it.

:data:`FIGURES` lists the quoted figures: the page, the quoted text as it stands there, the record
under ``benchmarks/`` it comes from, the key path(s) into the record and how the values are written
in the quote. The test formats the record's values and checks that the result is in the quote and
that the quote is in the page, so a re-recorded benchmark whose page was not updated fails here, and
so does a page whose figure was edited by hand. Whitespace runs count as one space (a page wraps its
lines anywhere).

A key path is the keys from the record's root joined by ``/`` (a list index is a number; a key that
itself holds a ``/``, e.g. ``occupancy/randomdr``, is matched whole). ``fmt`` is a format string filled
with the values in order (each multiplied by ``scale`` first), or a function of the values.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"


class Figure(NamedTuple):
    """A figure quoted on a page from a benchmark record."""

    page: str                            # relative to the checkout, e.g. "docs/gpu.md"
    quote: str                           # the text as it stands on the page (any whitespace run = one space)
    record: str                          # file name under benchmarks/
    keys: str | tuple[str, ...]          # key path(s) into the record, "a/b/0/c"
    fmt: str | Callable[..., str]        # "{:.3f} ± {:.3f}", or a function of the values
    scale: float | tuple[float, ...] = 1.0   # each value times this before formatting (one per key, or one for all)


def _min_sec(seconds: float) -> str:
    return f"{int(seconds) // 60}:{int(seconds) % 60:02d}"


def _range3(*values: float) -> str:
    return f"{min(values):.3f}–{max(values):.3f}"


def _passed_skipped(tests: int, failures: int, errors: int, skipped: int, seconds: float) -> str:
    return f"{tests - failures - errors - skipped} passed, {skipped} skipped in {seconds:.0f} s"


_QUICK = "test_sets/independent/results"
_BA = "balanced_accuracy/mean"
_SD = "balanced_accuracy/std"
_SF = "single_frame_balanced_accuracy/mean"
_R2 = "suite_mean_over_seeds"
_TWIN_K = "frames_per_s_by_frames_per_call"
_SEED_STDS = tuple(f"{_QUICK}/{t}/{m}/{_SD}" for t in ("occupancy", "counting") for m in ("rt", "randomdr", "cdr"))

FIGURES: list[Figure] = [
    Figure("docs/your_sensor.md", "| 397.7 s (`reproduce_quick_cpu.json`) | full mode projected 1,342-6,024 s from an H200 "
           "run of 88.0 s", "reproduce_quick_cpu.json", ("wall_seconds",),
           "| {:.1f} s (`reproduce_quick_cpu.json`) | full mode projected 1,342-6,024 s from an H200 run of 88.0 s"),
    Figure("docs/your_sensor.md", "full mode projected 1,342-6,024 s from an H200 run of 88.0 s", "reproduce_cuda.json",
           ("full_mode_projected_seconds_lower_bound", "full_mode_projected_seconds_linear_upper_bound", "wall_seconds"),
           "full mode projected {:,}-{:,} s from an H200 run of {:.1f} s"),
    Figure("docs/your_sensor.md", "| 74.6 images/s (`training_cpu.json`) | 15,503.7 images/s", "training_cpu.json",
           ("pipeline_images_per_s",), "| {:.1f} images/s (`training_cpu.json`) | 15,503.7 images/s"),
    Figure("docs/your_sensor.md", "15,503.7 images/s on an H200", "training_cuda.json", ("pipeline_images_per_s",),
           "{:,.1f} images/s on an H200"),
    Figure("docs/your_sensor.md", "| 824.3 frames/s on a file, 85.2 frames/s live", "predict_cpu.json",
           ("predict_frames_per_s", "live_one_frame_at_a_time_frames_per_s"), "| {:.1f} frames/s on a file, {:.1f} frames/s live"),
    Figure("docs/your_sensor.md", "| 58.62 s (`diagnose_cpu.json`)", "diagnose_cpu.json", ("diagnose_s",),
           "| {:.2f} s (`diagnose_cpu.json`)"),
    Figure("docs/your_sensor.md", "runs 824.3 frames/s on a file (in batches) and 85.2 frames/s one frame at a time as "
           "live, 8.52× the sensor's", "predict_cpu.json",
           ("predict_frames_per_s", "live_one_frame_at_a_time_frames_per_s", "live_vs_sensor_frame_rate"),
           "runs {:.1f} frames/s on a file (in batches) and {:.1f} frames/s one frame at a time as live, {:.2f}× the "
           "sensor's"),
    Figure("benchmarks/README.md", "measured chain occupancy **0.927 ± 0.095**, counting **0.859 ± 0.100**",
           "own_loop_cpu.json", ("results/randomdr (the measured chain, default)/occupancy/mean",
                                 "results/randomdr (the measured chain, default)/occupancy/std",
                                 "results/randomdr (the measured chain, default)/counting/mean",
                                 "results/randomdr (the measured chain, default)/counting/std"),
           "measured chain occupancy **{:.3f} ± {:.3f}**, counting **{:.3f} ± {:.3f}**"),
    Figure("README.md", "balanced accuracy 0.927 occupancy and 0.859 counting", "own_loop_cpu.json",
           ("results/randomdr (the measured chain, default)/occupancy/mean",
            "results/randomdr (the measured chain, default)/counting/mean"),
           "balanced accuracy {:.3f} occupancy and {:.3f} counting"),
    Figure("benchmarks/README.md", "**824.3 vs 908.8 frames/s = 0.907**", "predict_cpu.json",
           ("predict_frames_per_s", "network_alone_frames_per_s", "predict_vs_network_alone"),
           "**{:.1f} vs {:.1f} frames/s = {:.3f}**"),
    Figure("docs/predict.md", "| one frame at a time through `stream()`, as live | 85.2 | 8.52× the sensor's",
           "predict_cpu.json", ("live_one_frame_at_a_time_frames_per_s", "live_vs_sensor_frame_rate"),
           "| one frame at a time through `stream()`, as live | {:.1f} | {:.2f}× the sensor's"),
    Figure("benchmarks/README.md", "**94.2 frames/s** (9.42× real time", "twin_cpu.json",
           ("frames_per_s_workers", "realtime_ratio_workers"), "**{:.1f} frames/s** ({:.2f}× real time"),
    Figure("benchmarks/README.md", "same, one process, one thread | 48.1 frames/s (4.81× real time)", "twin_cpu.json",
           ("frames_per_s_1proc", "realtime_ratio_1proc"), "{:.1f} frames/s ({:.2f}× real time)"),
    Figure("benchmarks/README.md", "**1.20 G** vs 0.110 G tests/s (10.9×)", "twin_cpu.json",
           ("intersection/compiled_tests_per_s", "intersection/eager_tests_per_s", "intersection/speedup"),
           "**{:.2f} G** vs {:.3f} G tests/s ({:.1f}×)", (1e-9, 1e-9, 1.0)),
    # README.md: the quick-mode headline (make demo) and the held-out report suite
    Figure("README.md", "occupancy RT 0.992 ± 0.012, RandomDR **1.000 ± 0.000**, CDR 1.000 ± 0.000",
           "reproduce_quick_cpu.json",
           tuple(f"{_QUICK}/occupancy/{m}/{k}" for m in ("rt", "randomdr", "cdr") for k in (_BA, _SD)),
           "occupancy RT {:.3f} ± {:.3f}, RandomDR **{:.3f} ± {:.3f}**, CDR {:.3f} ± {:.3f}"),
    Figure("README.md", "counting RT **0.954 ± 0.023**, RandomDR 0.848 ± 0.069, CDR 0.783 ± 0.047",
           "reproduce_quick_cpu.json",
           tuple(f"{_QUICK}/counting/{m}/{k}" for m in ("rt", "randomdr", "cdr") for k in (_BA, _SD)),
           "counting RT **{:.3f} ± {:.3f}**, RandomDR {:.3f} ± {:.3f}, CDR {:.3f} ± {:.3f}"),
    Figure("README.md", "occupancy 0.943 / 0.974 / 0.946, counting 0.809 / 0.820 / 0.709",
           "reproduce_quick_cpu.json",
           tuple(f"{_QUICK}/{t}/{m}/{_SF}" for t in ("occupancy", "counting") for m in ("rt", "randomdr", "cdr")),
           "occupancy {:.3f} / {:.3f} / {:.3f}, counting {:.3f} / {:.3f} / {:.3f}"),
    Figure("README.md", "Recorded (`benchmarks/reproduce_quick_cpu.json`, 6.6 min;", "reproduce_quick_cpu.json",
           "wall_seconds", "{:.1f} min", 1 / 60),
    Figure("README.md", "`make demo` on a fresh clone 7:51 with the set-up", "reproduce_quick_cpu.json",
           "make_demo_on_a_fresh_clone_s", _min_sec),
    Figure("README.md", "occupancy **0.691 ± 0.005** and counting **0.524 ± 0.007**", "heldout_report2_cpu.json",
           (f"{_R2}/occupancy/randomdr/{_BA}", f"{_R2}/occupancy/randomdr/{_SD}",
            f"{_R2}/counting/randomdr/{_BA}", f"{_R2}/counting/randomdr/{_SD}"),
           "occupancy **{:.3f} ± {:.3f}** and counting **{:.3f} ± {:.3f}**"),
    Figure("README.md", "(RandomDR, 3 seeds; worst world 0.500 / 0.333)", "heldout_report2_cpu.json",
           ("suite/results/occupancy/randomdr/worst", "suite/results/counting/randomdr/worst"),
           "worst world {:.3f} / {:.3f}"),
    Figure("README.md", "**0.823 ± 0.002** / **0.605 ± 0.005**", "heldout_report2_cpu.json",
           (f"{_R2}/occupancy/randomdr/static_gate_{_BA}", f"{_R2}/occupancy/randomdr/static_gate_{_SD}",
            f"{_R2}/counting/randomdr/static_gate_{_BA}", f"{_R2}/counting/randomdr/static_gate_{_SD}"),
           "**{:.3f} ± {:.3f}** / **{:.3f} ± {:.3f}**"),
    Figure("README.md", "the paper's normal floor + the gate: 0.835 occupancy", "heldout_report2_cpu.json",
           f"{_R2}/occupancy/cdr_normal_floor/static_gate_{_BA}", "{:.3f} occupancy"),
    Figure("README.md", "on an H200 it projects to 22-100 min", "reproduce_cuda.json",
           ("full_mode_projected_seconds_lower_bound", "full_mode_projected_seconds_linear_upper_bound"),
           "{:.0f}-{:.0f} min", 1 / 60),
    Figure("README.md", "the twin at 3,274 frames/s on an H100", "twin_cuda.json", "frames_per_s_best",
           "{:,.0f} frames/s"),
    # benchmarks/README.md: the table of records
    Figure("benchmarks/README.md", "4730 vs 495 frames/s = **9.56×**", "transforms_cpu.json",
           ("torch_frames_per_s", "numpy_frames_per_s", "speedup_vs_numpy"), "{:.0f} vs {:.0f} frames/s = **{:.2f}×**"),
    Figure("benchmarks/README.md", "same, torch single-threaded | 3109 frames/s = 6.28×", "transforms_cpu.json",
           ("torch_frames_per_s_by_threads/1", "speedup_vs_numpy_by_threads/1"), "{:.0f} frames/s = {:.2f}×"),
    Figure("benchmarks/README.md", "**58.6 s** (323 twin evaluations) = 47.0x the simulation", "diagnose_cpu.json",
           ("diagnose_s", "evaluations", "ratio_diagnose_to_simulate"),
           "**{:.1f} s** ({:d} twin evaluations) = {:.1f}x the simulation"),
    Figure("benchmarks/README.md", "held-out error 2.57 -> 0.54 dB", "diagnose_cpu.json",
           ("error_before_dB", "error_after_dB"), "{:.2f} -> {:.2f} dB"),
    Figure("benchmarks/README.md", "**397.7 s** (6.6 min;", "reproduce_quick_cpu.json",
           ("wall_seconds", "wall_seconds"), "**{:.1f} s** ({:.1f} min", (1.0, 1 / 60)),
    Figure("benchmarks/README.md", "RT 0.992 ± 0.012 (0.943), RandomDR **1.000 ± 0.000** (0.974), CDR 1.000 ± 0.000 (0.946)",
           "reproduce_quick_cpu.json",
           tuple(f"{_QUICK}/occupancy/{m}/{k}" for m in ("rt", "randomdr", "cdr") for k in (_BA, _SD, _SF)),
           "RT {:.3f} ± {:.3f} ({:.3f}), RandomDR **{:.3f} ± {:.3f}** ({:.3f}), CDR {:.3f} ± {:.3f} ({:.3f})"),
    Figure("benchmarks/README.md",
           "H100 **3,273.9 frames/s** at 4,096 frames per call (2,528.1 at 1,024; 152.5 at 16), 97.6× the CPU's 33.5",
           "twin_cuda.json",
           (f"{_TWIN_K}/4096", f"{_TWIN_K}/1024", f"{_TWIN_K}/16", "speedup_vs_cpu_1proc", "cpu_frames_per_s_1proc"),
           "H100 **{:,.1f} frames/s** at 4,096 frames per call ({:,.1f} at 1,024; {:.1f} at 16), {:.1f}× the CPU's {:.1f}"),
    Figure("benchmarks/README.md", "74.6 vs 80.0 images/s = **0.933**", "training_cpu.json",
           ("pipeline_images_per_s", "bare_resnet18_images_per_s", "pipeline_vs_bare"), "{:.1f} vs {:.1f} images/s = **{:.3f}**"),
    Figure("benchmarks/README.md", "**88.0 s** wall", "reproduce_cuda.json", "wall_seconds", "**{:.1f} s** wall"),
    # docs/your_sensor.md
    Figure("docs/your_sensor.md", "the recorded figure on a 2-core CPU is 58.6 s (`benchmarks/diagnose_cpu.json`)",
           "diagnose_cpu.json", "diagnose_s", "is {:.1f} s"),
    Figure("docs/your_sensor.md", "48.1 frames/s of the two-walker corridor in one process, 94.2 with 2 workers",
           "twin_cpu.json", ("frames_per_s_1proc", "frames_per_s_workers", "workers"),
           "{:.1f} frames/s of the two-walker corridor in one process, {:.1f} with {:d} workers"),
    Figure("docs/your_sensor.md", "the std over 3 seeds is 0.000–0.069 per method and task", "reproduce_quick_cpu.json",
           _SEED_STDS, _range3),
    Figure("docs/your_sensor.md", "its best method reached 1.000 occupancy and 0.954 counting", "reproduce_quick_cpu.json",
           (f"{_QUICK}/occupancy/randomdr/{_BA}", f"{_QUICK}/counting/rt/{_BA}"), "{:.3f} occupancy and {:.3f} counting"),
    Figure("docs/your_sensor.md", "held-out report suite 0.691 / 0.524 (RandomDR", "heldout_report2_cpu.json",
           (f"{_R2}/occupancy/randomdr/{_BA}", f"{_R2}/counting/randomdr/{_BA}"), "{:.3f} / {:.3f}"),
    Figure("docs/your_sensor.md", "a recipe training step (74.6 images/s,", "training_cpu.json",
           "pipeline_images_per_s", "({:.1f} images/s"),
    Figure("docs/your_sensor.md", "took 88.0 s on an H200 and projects full mode to 1,342-6,024 s", "reproduce_cuda.json",
           ("wall_seconds", "full_mode_projected_seconds_lower_bound", "full_mode_projected_seconds_linear_upper_bound"),
           "took {:.1f} s on an H200 and projects full mode to {:,d}-{:,d} s"),
    Figure("docs/your_sensor.md", "the twin makes 3,273.9 frames/s on one H100", "twin_cuda.json", "frames_per_s_best",
           "{:,.1f} frames/s"),
    # docs/gpu.md
    Figure("docs/gpu.md", "| **3,273.9 frames/s** | one CPU thread 33.5 frames/s (97.6x) |", "twin_cuda.json",
           ("frames_per_s_best", "cpu_frames_per_s_1proc", "speedup_vs_cpu_1proc"),
           "| **{:,.1f} frames/s** | one CPU thread {:.1f} frames/s ({:.1f}x) |"),
    Figure("docs/gpu.md", "| 2,528.1 / 1,142.9 / 152.5 frames/s |", "twin_cuda.json",
           (f"{_TWIN_K}/1024", f"{_TWIN_K}/256", f"{_TWIN_K}/16"), "| {:,.1f} / {:,.1f} / {:,.1f} frames/s |"),
    Figure("docs/gpu.md", "| 2,662.6 frames/s | one CPU thread 28.8 frames/s (92.4x) |", "twin_cuda.json",
           ("h200_runs/both_chunks/frames_per_s_best", "h200_runs/both_chunks/cpu_frames_per_s_1proc",
            "h200_runs/both_chunks/speedup_vs_cpu_1proc"),
           "| {:,.1f} frames/s | one CPU thread {:.1f} frames/s ({:.1f}x) |"),
    Figure("docs/gpu.md", "1,913.0 frames/s on the H200", "twin_cuda.json",
           "h200_runs/synthesis_chunk_only/frames_per_s_best", "{:,.1f} frames/s"),
    Figure("docs/gpu.md", "| 202,215 frames/s | NumPy 252 frames/s (804x) |", "transforms_cuda.json",
           ("torch_frames_per_s", "numpy_frames_per_s", "speedup_vs_numpy"), "| {:,.0f} frames/s | NumPy {:.0f} frames/s ({:.0f}x) |"),
    Figure("docs/gpu.md", "| 15,504 images/s | bare ResNet18 17,756 images/s (0.87) |", "training_cuda.json",
           ("pipeline_images_per_s", "bare_resnet18_images_per_s", "pipeline_vs_bare"),
           "| {:,.0f} images/s | bare ResNet18 {:,.0f} images/s ({:.2f}) |"),
    Figure("docs/gpu.md", "| 83 passed, 2 skipped in 46 s |", "cuda_tests.json",
           ("tests", "failures", "errors", "skipped", "seconds"),
           _passed_skipped),
    Figure("docs/gpu.md", "projects to 1,342-6,024 s (22-100 min;", "reproduce_cuda.json",
           ("full_mode_projected_seconds_lower_bound", "full_mode_projected_seconds_linear_upper_bound",
            "full_mode_projected_seconds_lower_bound", "full_mode_projected_seconds_linear_upper_bound"),
           "{:,.0f}-{:,.0f} s ({:.0f}-{:.0f} min", (1.0, 1.0, 1 / 60, 1 / 60)),
    Figure("docs/gpu.md", "The projection counts 66 runs", "reproduce_cuda.json", "full_mode_runs", "counts {:d} runs"),
    # the other pages
    Figure("docs/simulation.md", "`intra_frame_cost_ratio` (1.359 in `benchmarks/twin_cpu.json`)", "twin_cpu.json",
           "intra_frame_cost_ratio", "({:.3f} in"),
    Figure("docs/simulation.md", "the default twin makes 94.2 frames/s with 2 workers and 48.1 in one process",
           "twin_cpu.json", ("frames_per_s_workers", "workers", "frames_per_s_1proc"),
           "{:.1f} frames/s with {:d} workers and {:.1f} in one process"),
    Figure("docs/calibration.md",
           "**58.6 s** on a 2-core CPU (target: at most 2 minutes), 323 twin evaluations, 47.0x the time of "
           "simulating the capture itself (1.25 s)", "diagnose_cpu.json",
           ("diagnose_s", "target_s", "evaluations", "ratio_diagnose_to_simulate", "simulate_capture_s"),
           "**{:.1f} s** on a 2-core CPU (target: at most {:.0f} minutes), {:d} twin evaluations, {:.1f}x the time of "
           "simulating the capture itself ({:.2f} s)", (1.0, 1 / 60, 1, 1.0, 1.0)),
    Figure("docs/transforms.md",
           "4730 frames/s with 2 torch threads against 495 frames/s in NumPy (9.56x), 3109 frames/s with 1 thread (6.28x)",
           "transforms_cpu.json",
           ("torch_frames_per_s_by_threads/2", "numpy_frames_per_s", "speedup_vs_numpy_by_threads/2",
            "torch_frames_per_s_by_threads/1", "speedup_vs_numpy_by_threads/1"),
           "{:.0f} frames/s with 2 torch threads against {:.0f} frames/s in NumPy ({:.2f}x), {:.0f} frames/s with 1 thread ({:.2f}x)"),
    Figure("docs/transforms.md", "202,215 frames/s against 252 in NumPy (804x)", "transforms_cuda.json",
           ("torch_frames_per_s", "numpy_frames_per_s", "speedup_vs_numpy"), "{:,.0f} frames/s against {:.0f} in NumPy ({:.0f}x)"),
    Figure("docs/raytracer.md",
           "eager 0.110 G tests/s, `torch.compile`-d 1.20 G tests/s (10.9x), first-call compilation 4.0 s", "twin_cpu.json",
           ("intersection/eager_tests_per_s", "intersection/compiled_tests_per_s", "intersection/speedup",
            "intersection/compile_warmup_s"),
           "eager {:.3f} G tests/s, `torch.compile`-d {:.2f} G tests/s ({:.1f}x), first-call compilation {:.1f} s",
           (1e-9, 1e-9, 1.0, 1.0)),
    Figure("docs/raytracer.md", "512 x 512 rays: 26.5 s, 3720 merged paths", "static_room_cpu.json",
           ("sbr/2/rays", "sbr/2/rays", "sbr/2/trace_s", "sbr/2/paths"), "{:d} x {:d} rays: {:.1f} s, {:d} merged paths"),
    Figure("docs/receiver.md", "64.5x faster than the exact sum (9.7 ms per frame), relative RMS error 4.7e-06",
           "twin_cpu.json",
           ("receiver_speedup_fast_vs_exact", "receiver_synthesis_fast_s_per_frame", "receiver_fast_vs_exact_rel_rms_error"),
           "{:.1f}x faster than the exact sum ({:.1f} ms per frame), relative RMS error {:.1e}", (1.0, 1e3, 1.0)),
    Figure("docs/heldout_worlds.md", "0.905 / 0.622 (occupancy / counting) on the design suite", "heldout_design_cpu.json",
           ("variants/nopersist/context_sweep/occupancy/randomdr/K8/mean",
            "variants/nopersist/context_sweep/counting/randomdr/K8/mean"), "{:.3f} / {:.3f} (occupancy / counting)"),
    Figure("docs/heldout_worlds.md", "0.660 / 0.450 on the report suite", "heldout_report_cpu.json",
           ("suite/results/occupancy/randomdr/mean", "suite/results/counting/randomdr/mean"), "{:.3f} / {:.3f}"),
    Figure("docs/heldout_worlds.md",
           "the networks gave 0.691 / 0.524 (occupancy / counting, RandomDR), and with the static-change gate "
           "([static_change.md](static_change.md)) 0.823 / 0.605; CDR with the paper's normal floor and the gate 0.835 occupancy",
           "heldout_report2_cpu.json",
           (f"{_R2}/occupancy/randomdr/{_BA}", f"{_R2}/counting/randomdr/{_BA}",
            f"{_R2}/occupancy/randomdr/static_gate_{_BA}", f"{_R2}/counting/randomdr/static_gate_{_BA}",
            f"{_R2}/occupancy/cdr_normal_floor/static_gate_{_BA}"),
           "gave {:.3f} / {:.3f} (occupancy / counting, RandomDR), and with the static-change gate "
           "([static_change.md](static_change.md)) {:.3f} / {:.3f}; CDR with the paper's normal floor and the gate {:.3f} occupancy"),
    Figure("docs/static_change.md", "leave-one-out score reaches 12.2 dB, the threshold 15.2 dB",
           "static_change_design_cpu.json",
           ("worlds/design-w01/calibration_max_db", "worlds/design-w01/threshold_db"), "reaches {:.1f} dB, the threshold {:.1f} dB"),
    Figure("docs/twin_observability.md", "| on | 11.7 | 32.9 | 45.1 | 40.6 % |", "twin_observability_cpu.json",
           tuple(f"summary/empty_peak_on/{k}" for k in ("median", "p90", "max", "frac_over_17db")),
           "| on | {:.1f} | {:.1f} | {:.1f} | {:.1f} % |", (1.0, 1.0, 1.0, 100.0)),
]

#: Figures a page quotes from an older record than the one it names (its ``previous_run`` chain): each is
#: expected to fail until the page is updated; then move it to FIGURES with the page's new text.


def normalize(text: str) -> str:
    """The text with every run of whitespace as one space."""
    return " ".join(text.split())


def lookup(record: Any, path: str) -> Any:
    """The value at ``path`` ("a/b/0/c") in ``record``; a key holding a "/" is matched whole (longest first)."""
    node, parts, i = record, path.split("/"), 0
    while i < len(parts):
        if isinstance(node, list):
            node, i = node[int(parts[i])], i + 1
            continue
        if not isinstance(node, dict):
            raise KeyError(f"{path!r}: {'/'.join(parts[:i])!r} is a {type(node).__name__}, not a mapping")
        for j in range(len(parts), i, -1):
            key = "/".join(parts[i:j])
            if key in node:
                node, i = node[key], j
                break
        else:
            raise KeyError(f"{path!r}: no key {parts[i]!r} under {'/'.join(parts[:i]) or 'the root'!r}")
    return node


def render(figure: Figure, record: Any) -> str:
    """The figure's values from ``record``, scaled and formatted as the page writes them."""
    keys: Sequence[str] = (figure.keys,) if isinstance(figure.keys, str) else figure.keys
    scales = figure.scale if isinstance(figure.scale, tuple) else (figure.scale,) * len(keys)
    assert len(scales) == len(keys), f"{figure.quote!r}: {len(scales)} scales for {len(keys)} keys"
    values = []
    for key, scale in zip(keys, scales):
        value = lookup(record, key)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError(f"{figure.record}: {key!r} is {value!r}, not a number")
        values.append(value if scale == 1 else value * scale)
    return figure.fmt(*values) if callable(figure.fmt) else figure.fmt.format(*values)


def check(figure: Figure, page_text: str, record: Any) -> list[str]:
    """What is wrong with one quoted figure (empty: the quote is on the page and agrees with the record)."""
    problems = []
    quote, expected = normalize(figure.quote), normalize(render(figure, record))
    if expected not in quote:
        problems.append(f"{figure.page}: {figure.quote!r} does not agree with benchmarks/{figure.record} "
                        f"({figure.keys}): the record gives {expected!r}")
    if quote not in normalize(page_text):
        problems.append(f"{figure.page}: the quoted text {figure.quote!r} is not on the page (edited? then update "
                        f"the entry in tests/test_numbers.py to the page's new text)")
    return problems


def _load_record(name: str) -> Any:
    return json.loads((BENCHMARKS / name).read_text(encoding="utf-8"))


def _id(figure: Figure) -> str:
    return f"{figure.page}:{figure.quote[:40]}"


@pytest.mark.parametrize("figure", FIGURES, ids=_id)
def test_quoted_figure_matches_its_record(figure: Figure) -> None:
    problems = check(figure, (ROOT / figure.page).read_text(encoding="utf-8"), _load_record(figure.record))
    assert not problems, "\n".join(problems)


def test_the_table_covers_the_headline_pages() -> None:
    pages = {f.page for f in FIGURES}
    assert {"README.md", "benchmarks/README.md", "docs/your_sensor.md", "docs/gpu.md"} <= pages
    assert len(FIGURES) >= 12
    assert len({(f.page, f.quote) for f in FIGURES}) == len(FIGURES), "a quote is listed twice"
    for f in FIGURES:
        assert (ROOT / f.page).is_file(), f.page
        assert (BENCHMARKS / f.record).is_file(), f.record


def test_proxy_generator_version_quoted_in_proxy_md_is_the_code_constant() -> None:
    spec = (ROOT / "radaraug" / "data" / "proxy.yaml").read_text(encoding="utf-8")
    version = re.search(r"^generator_version:\s*(\d+)\s*$", spec, re.M)
    assert version, "radaraug/data/proxy.yaml has no generator_version"
    page = normalize((ROOT / "docs" / "proxy.md").read_text(encoding="utf-8"))
    assert f"The current version is {version.group(1)} " in page


# The check itself, on a made-up page and record.

_RECORD = {"twin": {"frames_per_s": 94.2, "runs": [88.0, 94.2]}, "occupancy/rt": {"mean": 0.99166, "std": 0.01179},
           "wall_seconds": 397.7}
_PAGE = "The twin makes **94.2 frames/s**\n  with 2 workers; occupancy RT 0.992 ±\n0.012 in 6.6 min."


def test_check_passes_a_figure_that_agrees() -> None:
    figures = [Figure("p.md", "**94.2 frames/s** with 2 workers", "r.json", "twin/frames_per_s", "**{:.1f} frames/s**"),
               Figure("p.md", "RT 0.992 ± 0.012", "r.json", ("occupancy/rt/mean", "occupancy/rt/std"), "{:.3f} ± {:.3f}"),
               Figure("p.md", "in 6.6 min", "r.json", "wall_seconds", "{:.1f} min", 1 / 60),
               Figure("p.md", "**94.2 frames/s**", "r.json", "twin/runs/1", lambda v: f"{v:.1f}")]
    for figure in figures:
        assert check(figure, _PAGE, _RECORD) == [], figure


def test_check_fails_when_the_record_drifts() -> None:
    figure = Figure("p.md", "**94.2 frames/s** with 2 workers", "r.json", "twin/frames_per_s", "**{:.1f} frames/s**")
    drifted = {**_RECORD, "twin": {"frames_per_s": 83.5}}
    problems = check(figure, _PAGE, drifted)
    assert len(problems) == 1 and "does not agree" in problems[0] and "'**83.5 frames/s**'" in problems[0]
    # a change under the quoted precision is no drift; one at it is
    assert check(figure, _PAGE, {**_RECORD, "twin": {"frames_per_s": 94.24}}) == []
    assert check(figure, _PAGE, {**_RECORD, "twin": {"frames_per_s": 94.26}}) != []


def test_check_fails_when_the_page_drifts() -> None:
    figure = Figure("p.md", "**94.2 frames/s** with 2 workers", "r.json", "twin/frames_per_s", "**{:.1f} frames/s**")
    problems = check(figure, _PAGE.replace("94.2", "95.0"), _RECORD)
    assert len(problems) == 1 and "not on the page" in problems[0]


def test_check_fails_when_the_key_is_gone() -> None:
    figure = Figure("p.md", "RT 0.992 ± 0.012", "r.json", ("occupancy/rt/mean", "occupancy/rt/sd"), "{:.3f} ± {:.3f}")
    with pytest.raises(KeyError, match="sd"):
        check(figure, _PAGE, _RECORD)
    with pytest.raises(TypeError, match="not a number"):
        check(Figure("p.md", "x", "r.json", "twin", "{}"), _PAGE, _RECORD)


def test_lookup_reads_list_indices_and_keys_with_a_slash() -> None:
    assert lookup(_RECORD, "twin/runs/0") == 88.0
    assert lookup(_RECORD, "occupancy/rt/std") == 0.01179
    assert lookup({"a": {"b/c": 1}}, "a/b/c") == 1
