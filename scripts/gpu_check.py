"""`make gpu-check`: the project's CUDA checks and benchmarks in one command on a bare GPU machine.

Each step runs as its own process with its own time limit (killed with SIGKILL, its whole process
group, when it runs over) and writes under one folder (``--out``, default ``gpu_check_out``):
``NAME.log`` per step, the benchmark JSON files, and ``summary.json`` (each step's exit status,
wall time and whether it ran out of time). A failing step is reported and the next one runs.

Steps:

1. ``install``: the wheels brought along (``make gpu-wheels`` made them on a machine with
   internet) and the package, ``pip install --no-index --no-deps`` into a folder on PYTHONPATH;
2. ``tests``: every CUDA variant of the test suite (``pytest -m '' -k cuda``);
3. ``bench_twin``, ``bench_transforms``, ``bench_training``, ``bench_predict``: the benchmarks on CUDA,
   each with its CPU baseline or bare-network baseline measured in the same process;
4. ``reproduce``: ``radaraug reproduce`` at a size that fits the step's time (``--reproduce-size``
   items, epochs), tasks x methods x seeds as in full mode's main runs, with a projection of the
   full run (6,000 items x 15 epochs, every ablation) from its measured simulation and training
   rates (``reproduce_projection.json``).

The limits add up to under 10 minutes; ``--scale`` shrinks every limit (a rerun of part of it).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: (name, time limit in s). The sum stays under 10 minutes with the install's minute.
STEPS = (("env", 30), ("install", 60), ("tests", 150), ("bench_twin", 90), ("bench_transforms", 30),
         ("bench_training", 45), ("bench_predict", 30), ("reproduce", 150))


def _command(name: str, out: Path, args: argparse.Namespace) -> list[str]:
    py = sys.executable
    cli = [py, "-m", "radaraug"]
    if name == "env":
        code = ("import json, platform, torch; print(json.dumps({'python': platform.python_version(), "
                "'torch': torch.__version__, 'cuda': torch.version.cuda, 'gpu': torch.cuda.get_device_name(0) "
                "if torch.cuda.is_available() else None, 'cpu_count': __import__('os').cpu_count()}))")
        return ["bash", "-c", f"nvidia-smi -L; {py} -c \"{code}\" | tee {out / 'env.json'}"]
    if name == "install":
        wheels = sorted(str(p) for p in Path(args.wheels).glob("*.whl"))
        pip = [py, "-m", "pip", "install", "-q", "--no-index", "--no-deps", "--no-compile", "--no-cache-dir",
               "--upgrade", "--target", args.site]
        return ["bash", "-c", f"set -e; {' '.join(pip + wheels)}; "
                f"{' '.join(pip)} --no-build-isolation {ROOT}; "
                f"{py} -c 'import radaraug, trimesh, jsonargparse; print(radaraug.__version__, radaraug.__file__)'"]
    if name == "tests":
        return [py, "-m", "pytest", "-q", "-m", "", "-k", "cuda", "-p", "no:cacheprovider", "-rfEs",
                f"--junitxml={out / 'tests.xml'}", "tests"]
    if name == "bench_twin":
        return cli + ["bench", "twin", "--accelerator", "cuda", "--no-compile", "--out", str(out / "twin_cuda.json")]
    if name == "bench_transforms":
        return cli + ["bench", "transforms", "--accelerator", "cuda", "--batch", "256",
                      "--out", str(out / "transforms_cuda.json")]
    if name == "bench_training":
        return cli + ["bench", "training", "--accelerator", "cuda", "--batch", "256", "--repeats", "10",
                      "--out", str(out / "training_cuda.json")]
    if name == "bench_predict":  # predict's time for docs/your_sensor.md's GPU column
        return cli + ["bench", "predict", "--accelerator", "cuda", "-o", str(out / "predict_cuda.json")]
    if name == "reproduce":
        return [py, str(Path(__file__).resolve()), "--reproduce-only", "--out", str(out),
                "--reproduce-size", args.reproduce_size]
    raise ValueError(name)


def _run_step(name: str, limit: float, out: Path, args: argparse.Namespace, env: dict[str, str]) -> dict:
    log = out / f"{name}.log"
    t0 = time.perf_counter()
    with log.open("w") as fh:
        proc = subprocess.Popen(_command(name, out, args), cwd=ROOT, stdout=fh, stderr=subprocess.STDOUT, env=env,
                                start_new_session=True)
        try:
            rc = proc.wait(timeout=limit)
            timed_out = False
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)  # the step and every worker it started
            rc = proc.wait()
            timed_out = True
    wall = time.perf_counter() - t0
    tail = log.read_text(errors="replace").splitlines()[-15:]
    status = "out of time" if timed_out else ("ok" if rc == 0 else f"failed (exit {rc})")
    print(f"[gpu-check] {name:17s} {status:18s} {wall:6.1f} s (limit {limit:.0f} s)", flush=True)
    if rc != 0:
        print("\n".join("    " + line for line in tail), flush=True)
    return {"status": status, "exit": rc, "wall_s": round(wall, 1), "limit_s": limit, "log_tail": tail}


def projection(fits: list[float], wall: float, items: int, val_items: int, epochs: int, proxy_frames: int,
               images_per_s: float | None) -> dict:
    """Full mode's wall time projected from a reduced reproduce (3 methods, 1 seed, one test set).

    The reduced run's runs share two simulated sets (RT/RandomDR's twin, CDR's quiet twin): the
    median run's fit time is training alone, the rest of the runs' time above it is simulation.
    Full mode simulates three sets (RT/RandomDR's, CDR's, ``cdr_profile``'s) of 6,000 + 600 items, trains 66 runs
    (2 tasks x (4 methods + 7 ablations) x 3 seeds) of 15 epochs and generates both test sets.
    Upper bound: per-run training time linear in images (the run's fixed overhead scaled too).
    Lower bound: the median run's time as fixed overhead plus the images at ``images_per_s`` (the
    training benchmark's pipeline rate), when given.
    """
    from radaraug.training.reproduce import ReproduceSettings

    full = ReproduceSettings.full()
    train_s = fits[len(fits) // 2]
    simulate_s = sum(fits) - train_s * len(fits)
    other_s = wall - sum(fits)  # test-set generation, tests, figures
    per_item = simulate_s / ((items + val_items) * 2)
    per_image_epoch = train_s / ((items + val_items) * epochs)
    full_items, full_images = (full.train_items + full.val_items) * 3, (full.train_items + full.val_items) * full.epochs
    full_runs = 2 * (len(full.methods) + len(full.ablations)) * 3
    other_full = other_s * full.proxy_frames_per_count / proxy_frames * 2  # both generated test sets
    upper = per_item * full_items + per_image_epoch * full_images * full_runs + other_full
    res = {"simulation_seconds_per_item": per_item, "training_seconds_per_image_epoch": per_image_epoch,
           "other_seconds": round(other_s, 1), "full_mode_runs": full_runs,
           "full_mode_projected_seconds_linear_upper_bound": round(upper)}
    if images_per_s:
        res["full_mode_projected_seconds_lower_bound"] = round(
            per_item * full_items + full_runs * (train_s + full_images / images_per_s) + other_full)
        medium = 1500 + 150
        res["medium_projection"] = {
            "size": "1500 train + 150 val items, 15 epochs, 128x64, 3 seeds, rt/randomdr/cdr, independent set, "
                    "no ablations",
            "projected_seconds": round(per_item * medium * 2 + 2 * 3 * 3 * (train_s + medium * 15 / images_per_s)
                                       + other_s * 150 / proxy_frames),
            "basis": "this run's simulation rate and per-run training overhead, the training benchmark's "
                     "pipeline rate; not measured"}
    return res


def proxy_frames(items: int) -> int:
    """The reduced run's proxy frames per count: full mode's, scaled to ``items``, at least 40."""
    from radaraug.training.reproduce import ReproduceSettings

    full = ReproduceSettings.full()
    return max(full.proxy_frames_per_count * items // full.train_items, 40)


def _reproduce(out: Path, size: str, accelerator: str = "cuda") -> None:
    """A reduced reproduce on the GPU and the full run's projected wall time from its rates."""
    import torch

    from radaraug.training.reproduce import ReproduceSettings, reproduce

    items, epochs = (int(v) for v in size.split(","))
    full = ReproduceSettings.full()
    workers = max(2, (os.cpu_count() or 2) - 2)
    settings = ReproduceSettings(train_items=items, val_items=max(items // 10, 30), epochs=epochs,
                                 image_size=full.image_size, batch_size=full.batch_size,
                                 proxy_frames_per_count=proxy_frames(items),
                                 num_workers=2, sim_workers=workers, methods=("rt", "randomdr", "cdr"),
                                 ablations=(), test_sets=("independent",))
    t0 = time.perf_counter()
    rep = reproduce(out / "reproduce", seeds=1, settings=settings, accelerator=accelerator, progress=False)
    wall = time.perf_counter() - t0
    fits = sorted(r["fit_seconds"] for r in rep["runs"])
    rate_file = out / "training_cuda.json"  # bench_training's pipeline rate, when that step ran first
    rate = json.loads(rate_file.read_text())["pipeline_images_per_s"] if rate_file.is_file() else None
    proj = projection(fits, wall, items, settings.val_items, epochs, settings.proxy_frames_per_count, rate)
    res = {
        "benchmark": "reproduce_cuda", "gpu": torch.cuda.get_device_name(0) if torch.cuda.is_available() else None, "torch_version": torch.__version__,
        "size": {"train_items": items, "val_items": settings.val_items, "epochs": epochs,
                 "image_size": list(settings.image_size), "seeds": 1, "methods": list(settings.methods),
                 "test_sets": ["independent"], "sim_workers": workers},
        "wall_seconds": round(wall, 1), "fit_seconds_per_run": fits,
        "results": {t: {m: v["balanced_accuracy"]["mean"] for m, v in ms.items()} for t, ms in rep["results"].items()},
        **proj,
    }
    (out / "reproduce_projection.json").write_text(json.dumps(res, indent=2))
    print(json.dumps(res, indent=2))


def main(argv: list[str] | None = None) -> int:
    """Run the steps; exit 0 only when every one passed."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="gpu_check_out", help="folder for logs, benchmark JSON and summary.json")
    p.add_argument("--wheels", default=str(ROOT / "gpu_wheels"), help="folder of the wheels made by make gpu-wheels")
    p.add_argument("--site", default="/tmp/radaraug_site", help="install target (put on PYTHONPATH for the steps)")
    p.add_argument("--steps", default=",".join(n for n, _ in STEPS), help="comma-separated steps to run")
    p.add_argument("--scale", type=float, default=1.0, help="multiply every step's time limit")
    p.add_argument("--reproduce-size", default="1000,5", help="reproduce step: training items, epochs")
    p.add_argument("--reproduce-only", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("--reproduce-accelerator", default="cuda", help=argparse.SUPPRESS)  # a CPU dry run
    args = p.parse_args(argv)
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    if args.reproduce_only:
        _reproduce(out, args.reproduce_size, args.reproduce_accelerator)
        return 0
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([args.site, str(ROOT), os.environ.get("PYTHONPATH", "")]),
               PYTHONUNBUFFERED="1", MPLBACKEND="Agg")
    wanted = args.steps.split(",")
    summary: dict[str, dict] = {}
    t0 = time.perf_counter()
    for name, limit in STEPS:
        if name in wanted:
            summary[name] = _run_step(name, limit * args.scale, out, args, env)
            (out / "summary.json").write_text(json.dumps(summary, indent=2))
    print(f"[gpu-check] {time.perf_counter() - t0:.0f} s in all; logs and figures in {out}", flush=True)
    return 0 if all(s["status"] == "ok" for s in summary.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
