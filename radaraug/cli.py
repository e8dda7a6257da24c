"""The `radaraug` command line.

Sub-commands, their shared conventions (``--accelerator``, ``--radar-config``, ``--overwrite`` /
``--resume``, ``--json``) and exit statuses are described in docs/cli.md. Exit status: 0 success, 2 usage
error, 3 bad input or unwritable output (one ``error:`` line), 4 missing package, 130 interrupted,
141 stdout closed early.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, TypeAlias

from radaraug.errors import ConfigError, DependencyNotFoundError, RadarAugError

EXIT_OK = 0
EXIT_USAGE = 2
"""argparse's own status for a usage error."""
EXIT_DATA = 3
"""Bad input or an output that cannot be written (RadarAugError, OSError)."""
EXIT_DEPENDENCY = 4
"""A package that the command needs is not installed (DependencyNotFoundError)."""
EXIT_INTERRUPTED = 130
"""128 + SIGINT, what shells report for Ctrl-C."""
EXIT_BROKEN_PIPE = 141
"""128 + SIGPIPE, what shells report for a writer whose reader went away."""


Result: TypeAlias = dict[str, Any] | int
"""What a command returns: its ``--json`` object (printed on stdout, status 0), or its exit status."""


def _print_json(data: object) -> None:
    """The ``--json`` result: one object on stdout (paths and other objects as strings)."""
    print(json.dumps(data, default=str))


def _stdout_for(args: argparse.Namespace) -> contextlib.AbstractContextManager[Any]:
    """With ``--json``, everything the work prints goes to stderr, so stdout holds only the JSON."""
    if getattr(args, "json", False):
        return contextlib.redirect_stdout(sys.stderr)
    return contextlib.nullcontext()


def _exists(path: Path, folder: bool) -> bool:
    """An earlier output at ``path``: a file (or link), or a folder that is not empty."""
    if folder and path.is_dir():
        return any(path.iterdir())
    return path.exists() or path.is_symlink()


def _remove(folder: Path, names: Sequence[str]) -> None:
    """Remove the entries ``names`` of ``folder`` that exist: the ones a command owns there."""
    import shutil

    for name in names:
        path = folder / name
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif path.exists() or path.is_symlink():
            path.unlink()


def _check_output(args: argparse.Namespace, path: str | os.PathLike, *, folder: bool = False,
                  owned: Sequence[str] = ()) -> bool:
    """Refuse an existing output unless ``--overwrite`` (or ``--resume``, where the command has it).

    With ``--overwrite``, the entries ``owned`` of the folder ``path`` are removed first; other files stay.

    Returns:
        True when ``path`` exists and is to be replaced or continued (False: a new output).

    Raises:
        ConfigError: ``path`` exists and neither ``--overwrite`` nor ``--resume`` was given.
    """
    path = Path(path)
    if not _exists(path, folder):
        return False
    if args.overwrite:
        _remove(path, owned)
        return True
    if getattr(args, "resume", False):
        return True
    what = "a folder that is not empty" if path.is_dir() else "exists"
    how = "pass --overwrite to replace it"
    if hasattr(args, "resume"):
        how += f", or --resume to {args.resume_means}"
    raise ConfigError(f"{path}: {what}; choose another output, or {how}")


def _output_args(parser: argparse.ArgumentParser, output_help: str, *, default: str | None = None,
                 resume: str | None = None) -> None:
    """``-o/--output`` (required unless it has a default), ``--overwrite`` and, where it applies, ``--resume``."""
    parser.add_argument("-o", "--output", required=default is None, default=default, help=output_help)
    if resume is None:
        parser.add_argument("--overwrite", action="store_true", help="replace an existing output (else it is refused)")
        return
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--overwrite", action="store_true",
                       help="replace an existing output (without --overwrite or --resume it is refused)")
    group.add_argument("--resume", action="store_true", help=f"use an existing output: {resume}")
    parser.set_defaults(resume_means=resume)


def _cmd_info(args: argparse.Namespace) -> Result:
    from radaraug.io import open_capture
    from radaraug.transforms.summary import summarize_capture

    with open_capture(args.path) as reader:
        info = summarize_capture(reader, max_frames=args.max_frames)
    if args.json:
        print(json.dumps(info, indent=2))
        return 0
    print(f"capture      {info['path']}")
    print(f"radar        {info['summary']}")
    print(f"shape        {tuple(info['shape'])} (frames, rx, chirps, samples)")
    print(f"duration     {info['duration_s']:.2f} s ({info['num_frames']} frames)")
    print(f"labels       {info['labels'] or 'none'}")
    mid = (2 ** info["config"]["adc_bits"] - 1) / 2
    print(f"DC offset    {info['dc_offset_counts']} counts (mid-scale {mid})")
    print(f"noise RMS    {info['slow_time_noise_rms_counts']} counts (slow time)")
    print(f"clipping     {[f'{v:.2%}' for v in info['clipped_fraction']]}")
    floor = info["noise_floor_db"]
    floor_text = "n/a (too few chirps)" if floor is None else f"{floor} dBFS"
    print(f"noise floor  {floor_text} (median RD cell, far half of range, off zero Doppler)")
    s = info["strongest_static_return"]
    print(f"strongest    {s['level_db']} dBFS at {s['range_m']} m (bin {s['range_bin']}, zero Doppler)")
    mo = info["motion"]
    if mo is not None:
        print(f"motion       {'YES' if mo['motion'] else 'no'} ({mo['explanation']})")
    return 0


def _cmd_fit_cdr(args: argparse.Namespace) -> Result:
    from radaraug.diagnosis.record import PERSISTENT_THRESHOLD_DB, fit_record, recipes_map_chain
    from radaraug.transforms import CalibratedDR

    _check_output(args, args.output)
    with _stdout_for(args):
        # the calibration record: the floor fit (on the recipes' maps) and the capture's identity (its content digest)
        record = fit_record(args.path, max_frames=args.max_frames, progress=True, floor=args.floor,
                            persistent_db=PERSISTENT_THRESHOLD_DB,
                            pipeline=recipes_map_chain(_record_interference_db(args.excise_interference_db)))
        record.save(args.output)
        cdr = CalibratedDR.from_record(record)
    if args.json:
        return {"output": str(args.output), **record.to_dict()}
    print(f"CalibratedDR: m_t = {cdr.mean_db:.2f} dB, s_t = {cdr.std_db:.2f} dB, {cdr.floor} floor -> {args.output}")
    return 0


ACCELERATORS = ("auto", "cpu", "cuda")
"""``--accelerator`` values (Lightning's word; ``auto``: cuda where there is one, else cpu)."""


def _db_or_off(text: str) -> float | str:
    """A positive dB threshold, or ``"off"``."""
    if text.strip().lower() == "off":
        return "off"
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a threshold in dB or 'off', got {text!r}") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"the threshold must be > 0 dB, got {text!r}")
    return value


def _interference_arg(parser: argparse.ArgumentParser) -> None:
    """``--excise-interference-db`` of the commands that fit a calibration record."""
    parser.add_argument("--excise-interference-db", type=_db_or_off, default=None, metavar="DB|off",
                        help="fit on maps with another radar's bursts excised at this threshold, as the recipes make "
                        "them (default: the recipes' threshold, data.image.excise_interference_db); off: "
                        "RangeDoppler -> ToDecibels alone (the paper's chain)")


def _off_as_none(value: float | str) -> float | None:
    """A :func:`_db_or_off` value: ``"off"`` -> None."""
    return None if value == "off" else float(value)


def _record_interference_db(value: float | str | None) -> float | None:
    """The interference threshold a calibration record is fitted with (None given: the recipes')."""
    from radaraug.diagnosis.record import INTERFERENCE_THRESHOLD_DB

    return INTERFERENCE_THRESHOLD_DB if value is None else _off_as_none(value)


def _device_arg(text: str, option: str = "--accelerator") -> str:
    """Check a torch device that must exist on this machine (``cpu``, ``cuda``, ``cuda:N``)."""
    import torch

    from radaraug._torch import parse_device

    dev = parse_device(text, option)
    if dev.type == "cuda" and not torch.cuda.is_available():
        raise ConfigError(f"{option} {text!r}: CUDA is not available on this machine")
    if dev.type == "cuda" and dev.index is not None and dev.index >= torch.cuda.device_count():
        raise ConfigError(f"{option} {text!r}: this machine has {torch.cuda.device_count()} CUDA device(s)")
    if dev.type not in ("cpu", "cuda"):
        raise ConfigError(f"{option} {text!r}: only cpu and cuda are supported")
    return text


def _accelerator_args(parser: argparse.ArgumentParser, default: str) -> None:
    """``--accelerator``: the torch device."""
    parser.add_argument("--accelerator", choices=ACCELERATORS, default=default,
                        help="torch device: cpu, cuda, or auto (cuda where there is one, else cpu)")


def _torch_device(args: argparse.Namespace) -> str:
    """The torch device that ``--accelerator`` picks, checked."""
    if args.accelerator == "auto":
        import torch

        return "cuda" if torch.cuda.is_available() else "cpu"
    return _device_arg(args.accelerator, "--accelerator")


MICRO_DOPPLER_PNG = "micro_doppler_before_after.png"
"""Where ``bench micro-doppler`` draws its figure without ``-o``."""


def _cmd_bench(args: argparse.Namespace) -> Result:
    device = _torch_device(args)
    if args.what == "micro-doppler" and args.output is None:
        args.output = MICRO_DOPPLER_PNG
    for path in (args.output, args.figure):  # every file it writes: refused if it exists, unless --overwrite
        if path is not None:
            _check_output(args, path)
    if args.what == "transforms":
        from radaraug.bench.transforms import run_transforms_benchmark

        result = run_transforms_benchmark(batch=args.batch or 32, repeats=args.repeats, device=device, out=args.output)
    elif args.what == "diagnose":
        from radaraug.bench.diagnose import run_diagnose_benchmark

        result = run_diagnose_benchmark(out=args.output)
    elif args.what == "static-room":
        from radaraug.bench.static_room import run_static_room_benchmark

        result = run_static_room_benchmark(out=args.output, figure=args.figure)
    elif args.what == "micro-doppler":
        from radaraug.bench.micro_doppler import micro_doppler_before_after

        result = micro_doppler_before_after(args.output)
    elif args.what == "people-level":
        from radaraug.bench.people_level import run_people_level_benchmark

        result = run_people_level_benchmark(args.capture or [], out=args.output)
    elif args.what == "predict":
        from radaraug.bench.predict import run_predict_benchmark

        result = run_predict_benchmark(batch=args.batch or 32, repeats=args.repeats, device=device, out=args.output)
    elif args.what == "steps":
        from radaraug.bench.steps import run_steps_benchmark

        if device != "cpu":
            raise ConfigError("bench steps: calibrate's fit and export run on the CPU (neither command takes "
                              "--accelerator); leave --accelerator out")
        result = run_steps_benchmark(out=args.output)
    elif args.what == "items":
        from radaraug.bench.items import run_items_benchmark

        result = run_items_benchmark(batch=args.batch or 16, out=args.output)
    elif args.what == "contract":
        from radaraug.bench.contract import run_contract_benchmark

        result = run_contract_benchmark(out=args.output)
    elif args.what == "training":
        from radaraug.bench.training import run_training_benchmark

        result = run_training_benchmark(batch=args.batch or 32, steps=args.repeats, device=device, out=args.output)
    else:
        from radaraug.bench.twin import run_twin_benchmark

        result = run_twin_benchmark(blocks=args.blocks, workers=args.workers, device=device,
                                    compiled=not args.no_compile, out=args.output)
    if args.json:
        return result
    for key, value in result.items():
        print(f"{key:28s} {value}")
    return 0


def _scene_arg(text: str):
    from radaraug.scene.scene import Scene

    return Scene.load(text)


def _cmd_trace(args: argparse.Namespace) -> Result:
    import torch

    from radaraug.raytrace.tracer import RayTracer, paths_to_json

    if not math.isfinite(args.time):
        raise ConfigError(f"--time must be a finite number of seconds, got {args.time}")
    scene = _scene_arg(args.scene)
    tracer = RayTracer(scene.room, scene.radar, scene.config, method=args.method, max_bounces=args.bounces,
                       rays=args.rays)
    t = torch.tensor([args.time], dtype=torch.float64)
    ell = scene.people_ellipsoids(t) if scene.people else None
    if ell is not None:
        omega = ell.angular_velocities
        ell = type(ell)(*(x.float()[0] for x in (ell.centers, ell.semi_axes, ell.rotations, ell.velocities)),
                        ell.material, None if omega is None else omega.float()[0])
    paths = tracer.trace(ellipsoids=ell)
    data = {"scene": scene.name, "time_s": args.time, "convex_room": bool(tracer.convex_room),
            **paths_to_json(paths, scene.config)}
    if args.json:
        return data
    print(f"{scene.name} at t = {args.time} s: {data['num_paths']} paths ({data['convention']})")
    strongest = sorted(data["paths"], key=lambda p: -p["power_dB"])[:10]
    for p in sorted(strongest, key=lambda p: p["range_m"]):
        print(f"  {p['range_m']:8.3f} m  {p['radial_velocity_m_s']:+7.3f} m/s  {p['power_dB']:8.2f} dB  {p['kind']}")
    return 0


def _cmd_simulate(args: argparse.Namespace) -> Result:
    from radaraug.sim.offline import parse_shard, shard_path, simulate_capture

    shard = parse_shard(args.shard)
    if args.frames < 1:
        raise ConfigError(f"--frames must be >= 1, got {args.frames}")
    device = _torch_device(args)
    out = shard_path(args.output, shard)
    if _check_output(args, out) and args.overwrite:
        from radaraug.io.hdf5_recovery import writer_is_alive

        if writer_is_alive(out):  # never pull a file from under a live writer
            raise ConfigError(f"{out}: another process has this file open; wait for it or choose another output")
        out.unlink()
    with _stdout_for(args):
        result = simulate_capture(_scene_arg(args.scene), args.output, frames=args.frames, seed=args.seed,
                                  shard=shard, device=device, profile=args.profile)
    if args.json:
        return {"output": result.pop("path"), **result}
    print(f"{result['path']}: frames [{result['frames'][0]}, {result['frames'][1]}), "
          f"{result['simulated']} simulated, resumed from frame {result['resumed_from']}")
    return 0


def _train_configs(value: str) -> list[str]:
    """A ``--config`` value of ``radaraug train``: a file as given, else the installed recipe files it names."""
    from radaraug import recipes

    if os.path.lexists(value):
        return [value]
    if recipes.is_recipe_name(value):
        return [str(p) for p in recipes.recipe_files(value)]
    if any(c in value for c in ":{\n"):  # inline YAML: LightningCLI reads (or refuses) it
        return [value]
    raise ConfigError(f"--config {value}: no such file, and not the name of an installed recipe "
                      f"({', '.join(recipes.recipe_names())}; radaraug recipes lists them)")


def resolve_train_args(argv: Sequence[str]) -> list[str]:
    """``radaraug train`` arguments with each run of ``--config`` / ``-c`` values merged into one.

    A recipe name stands for its base + task + method files (:mod:`radaraug.recipes`). Consecutive
    config files are merged as :func:`radaraug.recipes.compose` merges them (mappings key by key, at
    every depth) and given to LightningCLI as one inline YAML: LightningCLI alone would replace a
    mapping value such as ``data.twin.randomization`` whole when a later file sets one of its keys.
    """
    import yaml

    from radaraug import recipes

    out: list[str] = []
    group: list[str] = []
    flag = "--config"

    def flush() -> None:
        files = [p for p in group if os.path.lexists(p)]
        if len(files) > 1 and len(files) == len(group):
            out.extend([flag, yaml.safe_dump(recipes.compose(*files), default_flow_style=True, width=1 << 30)])
        else:
            for p in group:
                out.extend([flag, p])
        group.clear()

    it = iter(argv)
    for arg in it:
        if arg in ("--config", "-c"):
            value = next(it, None)
            if value is None:
                flush()
                out.append(arg)
            else:
                flag = flag if group else arg
                group.extend(_train_configs(value))
        elif arg.startswith("--config="):
            flag = flag if group else "--config"
            group.extend(_train_configs(arg.split("=", 1)[1]))
        else:
            flush()
            out.append(arg)
    flush()
    return out


def _cmd_train(argv: Sequence[str]) -> int:
    from radaraug.training.cli import main as train_main

    return train_main(resolve_train_args(argv))


def _cmd_recipes(args: argparse.Namespace) -> Result:
    from radaraug import recipes

    if args.name is not None:
        files = [str(p) for p in recipes.recipe_files(args.name)]
        text = recipes.recipe_text(args.name)
        if args.json:
            return {"name": args.name, "files": files, "text": text}
        print(text, end="")
        return 0
    rows = []
    for name in recipes.recipe_names():
        data = recipes.compose(name)["data"]
        rows.append({"name": name, "files": [str(p) for p in recipes.recipe_files(name)], "task": data["task"],
                     "method": recipes.method_of(data["method"])})
    if args.json:
        return {"folder": str(recipes.RECIPES_DIR), "recipes": rows, "ablations": recipes.ablations()}
    for r in rows:
        print(f"{r['name']:24s} task {r['task']:10s} method {r['method']}")
    print(f"installed in {recipes.RECIPES_DIR} (base.yaml + task/ + method/; ablation/ overrides: "
          f"{', '.join(recipes.ablations())}); run one with `radaraug train fit --config NAME [--config ablation/A]`, "
          "or edit a copy: `radaraug recipes NAME > my.yaml`", file=sys.stderr)
    return 0


def _cmd_demo(args: argparse.Namespace) -> Result:
    from radaraug.demo import run_demo

    _check_output(args, args.output, folder=True)
    with _stdout_for(args):
        summary = run_demo(Path(args.output))
    return {"output": str(args.output), **summary} if args.json else 0


REPRODUCE_OUTPUTS = ("report.md", "report.json", "runs", "figures", "cache", "proxy", "independent", "standing")
"""What ``reproduce`` writes in its output folder (``--overwrite`` removes these first, nothing else)."""


def _cmd_reproduce(args: argparse.Namespace) -> Result:
    from dataclasses import replace

    from radaraug.training.reproduce import ReproduceSettings, parse_test_arg, reproduce

    test = [parse_test_arg(t) for t in args.test] if args.test else None
    accelerator = args.accelerator
    _check_output(args, args.output, folder=True, owned=REPRODUCE_OUTPUTS)
    with _stdout_for(args):
        settings = None
        changes: dict[str, Any] = {}
        if args.representation is not None:
            changes["representation"] = args.representation
        if args.resample is not None:
            changes["resample"] = args.resample
        if args.excise_interference_db is not None:
            changes["excise_interference_db"] = _off_as_none(args.excise_interference_db)
        if changes:
            settings = replace(ReproduceSettings.quick() if args.quick else ReproduceSettings.full(), **changes)
        report = reproduce(args.output, quick=args.quick, seeds=args.seeds, calibration=args.calibration,
                           test=test, ablation=not args.no_ablation, accelerator=accelerator, progress=True,
                           cdr_floor=args.cdr_floor, test_dr=args.test_dr, settings=settings,
                           test_sets=None if args.test_sets is None else tuple(args.test_sets.split(",")),
                           methods=None if args.methods is None else [m for m in args.methods.split(",") if m],
                           worlds=args.worlds,
                           ablations=None if args.ablations is None else [a for a in args.ablations.split(",") if a])
    if args.json:
        return {"output": str(args.output), "report": str(Path(args.output) / "report.md"), **report}
    print(f"{Path(args.output) / 'report.md'} ({report['kind']}, {report['wall_seconds'] / 60:.1f} min)")
    for name, ts in report["test_sets"].items():
        for task, by in ts["results"].items():
            text = ", ".join(f"{m} {v['balanced_accuracy']['mean']:.3f}+-{v['balanced_accuracy']['std']:.3f}"
                             + (f" (+ static gate {v['static_gate_balanced_accuracy']['mean']:.3f})"
                                if "static_gate_balanced_accuracy" in v else "")
                             for m, v in by.items())
            print(f"  {name} {task}: {text}")
    return 0


def _cmd_make_proxy(args: argparse.Namespace) -> Result:
    from radaraug.testsets.proxy import MANIFEST_NAME, make_proxy

    # No manifest after --overwrite: the set is generated again, file by file.
    _check_output(args, args.output, folder=True, owned=[MANIFEST_NAME])
    with _stdout_for(args):
        proxy = make_proxy(args.output, frames_per_count=args.frames_per_count, seed=args.seed, progress=True)
    if args.json:
        return {"output": str(args.output), "calibration": str(proxy.calibration),
                "tests": [{"path": str(p), "people": int(c)} for p, c in proxy.tests]}
    print(f"calibration  {proxy.calibration}")
    for path, count in proxy.tests:
        print(f"test         {path} ({count} people)")
    return 0


def _cmd_diagnose(args: argparse.Namespace) -> Result:
    from radaraug.diagnosis import SearchSettings, diagnose, write_report
    from radaraug.diagnosis.diagnose import verdicts

    if args.max_frames < 4:
        raise ConfigError(f"--max-frames must be >= 4, got {args.max_frames}")
    settings = SearchSettings(seed=args.seed, use_signatures=not args.no_signatures)
    _check_output(args, args.output, folder=True)
    with _stdout_for(args):
        diag = diagnose(args.capture, scene=_scene_arg(args.scene) if args.scene else None,
                        max_frames=args.max_frames, settings=settings, start_profile=args.profile, progress=True)
        out = write_report(diag, args.output, figures=not args.no_figures)
    r = diag.result
    if args.json:
        return {
            "output": str(out), "report": str(out / "report.json"), "profile": str(out / "profile.json"),
            "mode": diag.mode, "runtime_s": diag.runtime_s,
            "held_out_error_db": {"default": r.before.overall, "base_refit": r.base.overall,
                                  "final": r.after.overall},
            "room": {k: {"before": r.room_before[k], "after": v} for k, v in sorted(r.room_after.items())},
            "effects_added": [{"effect": st["effect"], "error_before_db": st["error_before"],
                               "error_after_db": st["error_after"], "verdict": st.get("verdict")} for st in r.steps],
            "verdict": [v["text"] for v in verdicts(diag)],
            "unexplained": len(diag.unexplained),
            "base_not_physical": [b["text"] for b in diag.base_check if not b["ok"]],
        }
    print(f"{out / 'report.json'} ({diag.mode} mode, {diag.runtime_s:.1f} s)")
    print(f"  held-out error: default {r.before.overall:.2f} dB -> base refit {r.base.overall:.2f} dB -> "
          f"final {r.after.overall:.2f} dB")
    for k, v in sorted(r.room_after.items()):
        print(f"  room {k}: {r.room_before[k]:.2f} -> {v:.2f}")
    for s in r.steps:
        how = f" ({s['verdict']})" if s.get("verdict") not in (None, "clear") else ""
        print(f"  + {s['effect']}: {s['error_before']:.3f} -> {s['error_after']:.3f} dB{how}")
    for verdict in verdicts(diag):
        if verdict["verdict"] == "declared, refitted":
            print(f"  ~ {verdict['text']}")
        elif not verdict["added"] and verdict["verdict"] != "absent":
            print(f"  ! {verdict['text']}")
    for b in diag.base_check:
        if not b["ok"]:
            print(f"  ! base not physical: {b['text']}")
    print(f"  unexplained: {len(diag.unexplained)} item(s); profile {out / 'profile.json'}")
    return 0


def _live_device(args: argparse.Namespace, default_config: Any = None):
    """The board of ``capture`` / ``calibrate`` / ``predict`` (``--board``) from their arguments (nothing opened yet).

    ``default_config``: the radar config without ``--radar-config`` (None: the device's own default).
    """
    from radaraug.capture import open_device
    from radaraug.config import RadarConfig

    config = RadarConfig.from_json(args.radar_config) if args.radar_config else default_config
    # The virtual-only options default to None so that one given with a board is refused, not ignored.
    return open_device(args.board, config, scene=args.scene, profile=args.profile, seed=args.seed,
                       realtime=args.realtime)


def _cmd_devices(args: argparse.Namespace) -> Result:
    from radaraug.capture.devices import PERMISSION_DENIED, find_boards, permission_help, udev_rule_path

    if args.udev_rule:
        print(udev_rule_path().read_text(encoding="utf-8"), end="")
        return 0
    boards = find_boards()
    denied = any(b.access == PERMISSION_DENIED for b in boards)
    if args.json:
        return {"boards": [b.to_dict() for b in boards], "permission_denied": denied}
    if not boards:
        print("no Infineon radar board found on USB (vendor 0x058b: MCU7, V9, PSoC6 kit); "
              "check the cable, or record without one: radaraug capture --board virtual")
        return 0
    for b in boards:
        serial = b.serial or "serial unreadable"
        print(f"{b.name:24s} {b.vendor_id:04x}:{b.product_id:04x}  bus {b.bus} address {b.address}  {serial}"
              f"{'' if b.access == 'ok' else f'  ({b.access})'}")
    if denied:
        print(permission_help(), file=sys.stderr)
    return 0


def _recording_json(result: Any) -> dict[str, Any]:
    """A recording's ``--json`` object: its file is ``output``, what recorded it ``board`` (the CLI's words)."""
    data = result.to_dict()
    return {"output": data.pop("path"), "board": data.pop("device"), **data}


def _cmd_capture(args: argparse.Namespace) -> Result:
    from radaraug.capture import record

    _check_output(args, args.output)
    result = record(_live_device(args), args.output, seconds=args.seconds, label=args.label,
                    overwrite=args.overwrite, progress=not args.no_progress)
    if args.json:
        _print_json(_recording_json(result))
    else:
        rate = result.frames / result.seconds if result.seconds > 0 else float("nan")
        where = result.path if result.path is not None else "no file (no frame recorded)"
        print(f"{where}: {result.frames} frames in {result.seconds:.1f} s ({rate:.1f} frames/s), "
              f"{result.dropped} dropped{', interrupted' if result.interrupted else ''}")
    if result.interrupted:
        print(f"interrupted: {result.path} is complete and closed" if result.path else "interrupted",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    return 0


def _cmd_calibrate(args: argparse.Namespace) -> Result:
    from radaraug.capture import calibrate

    _check_output(args, args.output)
    if args.keep_recording is not None:
        _check_output(args, args.keep_recording)
    run = calibrate(_live_device(args), args.output, seconds=args.seconds, keep_recording=args.keep_recording,
                    overwrite=args.overwrite, progress=not args.no_progress, floor=args.floor,
                    interference_db=_record_interference_db(args.excise_interference_db))
    cdr = run.cdr
    if args.json:
        return {"output": str(run.output), "mean_db": cdr.mean_db, "std_db": cdr.std_db, "floor": cdr.floor,
                "chain": cdr.chain, "motion_fraction": cdr.motion, "recording": _recording_json(run.recording)}
    kept = f"; recording kept in {run.recording.path}" if args.keep_recording else ""
    print(f"CalibratedDR: m_t = {cdr.mean_db:.2f} dB, s_t = {cdr.std_db:.2f} dB from {run.recording.frames} "
          f"empty-room frames (motion {100 * (cdr.motion or 0.0):.3f} %) -> {run.output}{kept}")
    return 0


def _classifier(args: argparse.Namespace) -> Any:
    """The classifier file of ``predict`` / ``export`` (and, with ``--calibration``, its gate refitted)."""
    from radaraug.inference import RadarClassifier

    clf = RadarClassifier.load(args.classifier)
    if getattr(args, "calibration", None):
        clf = clf.with_gate(args.calibration)
    return clf


def _cmd_predict(args: argparse.Namespace) -> Result:
    from radaraug.inference.predict import RowWriter, follow_capture, predict_captures, predict_device

    if bool(args.sources) == (args.board is not None):
        raise ConfigError("predict needs capture paths or --board (a board, or 'virtual'), not both")
    if args.follow and (args.board is not None or len(args.sources) != 1):
        raise ConfigError("--follow reads one capture while it is recorded: give exactly one path")
    if args.json and args.output == "-":
        raise ConfigError("--json prints a summary on stdout: write the rows to a file with -o")
    if args.output != "-":
        _check_output(args, args.output)
    clf = _classifier(args)
    gate = not args.no_gate
    if gate and clf.gate is None:  # the decision then is the network's alone: say so where a user looks
        print(f"{args.classifier}: the classifier file carries no static-change gate (it was trained without an "
              "empty-room capture); decisions are the network's alone. --calibration EMPTY fits one for this room",
              file=sys.stderr)
    if args.board is not None:
        chunks: Any = predict_device(clf, _live_device(args, clf.config), seconds=args.seconds,
                                     max_frames=args.max_frames, window=args.window, gate=gate)
    elif args.follow:
        chunks = follow_capture(clf, args.sources[0], window=args.window, gate=gate, idle_timeout_s=args.idle_timeout)
    else:
        chunks = predict_captures(clf, args.sources, window=args.window, gate=gate,
                                  progress=not args.no_progress and args.output != "-")
    with (contextlib.nullcontext(sys.stdout) if args.output == "-"
          else open(args.output, "w", encoding="utf-8", newline="")) as fh:
        writer = RowWriter(fh, args.format)
        try:
            writer.write_all(chunks)
        except KeyboardInterrupt:  # a live run ends with Ctrl-C: the rows written so far stay
            print(f"interrupted after {writer.rows} frames", file=sys.stderr)
            return EXIT_INTERRUPTED
    summary = {"output": args.output, "frames": writer.rows, "decisions": writer.decisions, "task": clf.task,
               "window": clf.context_frames if args.window is None else args.window,
               "gate": gate and clf.gate is not None}
    if args.json:
        return summary
    if args.output != "-":
        print(f"{args.output}: {writer.rows} frames; decisions {writer.decisions}")
    return 0


def _cmd_export(args: argparse.Namespace) -> Result:
    from radaraug.inference.export import FILES, export

    _check_output(args, args.output, folder=True, owned=[*FILES.values(), "export.json"])
    clf = _classifier(args)
    frames = None
    if args.check_capture:
        from radaraug.io import open_capture

        with open_capture(args.check_capture) as cap:
            clf.check_config(cap.config, args.check_capture)
            frames = cap.read(0, min(len(cap), 32))
    rec = export(clf, args.output, formats=args.format.split(","), frames=frames, overwrite=True)
    if args.json:
        return {"output": args.output, **rec["exports"]}
    for fmt, r in rec["exports"].items():
        print(f"{Path(args.output) / r['file']}: {fmt}, largest probability difference from the eager classifier "
              f"{r['max_abs_prob_diff']:.2g} on {rec['check_frames']} frames, classes agree on "
              f"{100 * r['class_agreement']:.0f} %")
    return 0


class _DefaultsShown(argparse.ArgumentDefaultsHelpFormatter):
    """Help with "(default: X)" for options that have a default (not for None or flags)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        if action.default is None or action.default is False or action.default is argparse.SUPPRESS:
            return action.help
        return super()._get_help_string(action)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (exposed for docs and tests)."""
    from radaraug import __version__

    p = argparse.ArgumentParser(prog="radaraug", description=__doc__.split("\n")[0])
    p.add_argument("--version", action="version", version=f"radaraug {__version__}")
    # Every subcommand's --help shows the defaults.
    sub = p.add_subparsers(dest="command", required=True)

    def command(name: str, func: Callable[..., Result], **kw: Any) -> argparse.ArgumentParser:
        """A subcommand's parser (its --help shows the defaults), whose arguments ``main`` passes to ``func``."""
        parser = sub.add_parser(name, formatter_class=_DefaultsShown, **kw)
        parser.set_defaults(func=func)
        return parser

    info = command("info", _cmd_info, help="summarize a capture (radaraug .h5 or Infineon recording folder)")
    info.add_argument("path", help="radaraug .h5 capture or Infineon recording folder")
    info.add_argument("--json", action="store_true", help="print one JSON object")
    info.add_argument("--max-frames", type=int, default=256, help="frames used for the statistics")

    fit = command("fit-cdr", _cmd_fit_cdr, help="fit CalibratedDR's floor and the persistent cells on an "
                  "empty-room capture (the JSON serves CDR and the excision; the static-change gate needs the "
                  "capture itself)")
    fit.add_argument("path", help="empty-room capture (radaraug .h5 or Infineon recording folder), recorded "
                     "like the test captures")
    _output_args(fit, "calibration JSON to write (CDR's floor and the persistent cells: no frames, so no gate or profile)")
    fit.add_argument("--max-frames", type=int, default=None, help="frames read (default: all)")
    fit.add_argument("--floor", choices=("normal", "empirical"), default="normal",
                     help="the floor distribution the calibration draws from: normal (the paper's CDR) or empirical "
                     "(the capture's measured one; its quantiles are recorded either way)")
    fit.add_argument("--json", action="store_true", help="print the calibration record (with the output path) as one JSON object")
    _interference_arg(fit)

    bench = command("bench", _cmd_bench, help="benchmarks (figures as ratios against a same-process baseline)")
    bench.add_argument("what", choices=["transforms", "twin", "training", "predict", "diagnose", "static-room",
                                        "micro-doppler", "people-level", "contract", "items", "steps"],
                       help="which benchmark (docs/benchmarks.md)")
    bench.add_argument("--capture", action="append", default=None,
                       help="people-level: a capture with a moving person (.h5 or Infineon folder); repeat for more")
    bench.add_argument("--batch", type=int, default=None,
                       help="transforms, training, predict: frames per batch (default: 32); items: items per call "
                       "(default: 16)")
    bench.add_argument("--repeats", type=int, default=5, help="transforms, predict: timed repetitions; training: steps")
    bench.add_argument("--blocks", type=int, default=8, help="twin: 16-frame blocks per process")
    bench.add_argument("--workers", type=int, default=2, help="twin: DataLoader worker processes")
    bench.add_argument("--no-compile", action="store_true", help="twin: skip the torch.compile kernel")
    _accelerator_args(bench, "cpu")
    bench.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    bench.add_argument("-o", "--output", default=None,
                       help=f"also write the JSON figures to this file (micro-doppler: the PNG, default {MICRO_DOPPLER_PNG})")
    bench.add_argument("--overwrite", action="store_true", help="replace an existing output (re-recording a benchmark)")
    bench.add_argument("--figure", default=None, help="static-room: write the range-profile figure (PNG) here")

    trace = command("trace", _cmd_trace, help="ray-trace one instant of a scene and print its paths")
    trace.add_argument("scene", help="scene file (.yaml/.json) or built-in scene name")
    trace.add_argument("--time", type=float, default=0.0, help="instant in seconds")
    trace.add_argument("--method", choices=["image", "sbr"], default="image",
                       help="static room: image method (exact specular orders, default) or SBR rays")
    trace.add_argument("--rays", type=int, default=256, help="SBR rays per axis (--method sbr)")
    trace.add_argument("--bounces", type=int, default=None,
                       help="most specular reflections (image method, default 3) or bounces per SBR ray (default 2)")
    trace.add_argument("--json", action="store_true", help="print the paths as one JSON object")

    sim = command("simulate", _cmd_simulate, help="simulate a scene into a radaraug HDF5 capture")
    sim.add_argument("scene", help="scene file (.yaml/.json) or built-in scene name")
    sim.add_argument("--frames", type=int, required=True, help="frames to simulate")
    sim.add_argument("--seed", type=int, default=0, help="seed of the receiver noise")
    _output_args(sim, "radaraug HDF5 capture to write",
                 resume="continue it after its last complete frame (the same job only)")
    sim.add_argument("--shard", default=None, help="i/n: simulate the i-th of n pieces (0-based)")
    _accelerator_args(sim, "cpu")  # cpu: a file's frames depend on the device type (part of the job)
    sim.add_argument("--profile", default=None, help="twin profile JSON (from radaraug diagnose) for the receiver")
    sim.add_argument("--json", action="store_true", help="print the result (output, frame range, frames simulated, resume point) as one JSON object")

    demo_text = ("capture walkthrough: the bundled recording through the paper's chain, a fitted CalibratedDR, RD "
                 "images and a noise-floor histogram (the main job, `make demo`, is `radaraug reproduce --quick`)")
    demo = command("demo", _cmd_demo, help=demo_text, description=demo_text)
    _output_args(demo, "output folder", default="demo_out")
    demo.add_argument("--json", action="store_true", help="print the demo's summary as one JSON object")

    # `train` is parsed by LightningCLI (radaraug.training.cli); listed here for --help only.
    sub.add_parser("train", help="LightningCLI recipes: radaraug train fit --config occupancy_randomdr "
                   "(an installed recipe's name, or a YAML file)", add_help=False)

    rec = command("recipes", _cmd_recipes, help="list the training recipes installed with radaraug, or print one "
                  "(radaraug recipes NAME > my.yaml: a copy to edit)")
    rec.add_argument("name", nargs="?", default=None,
                     help="the recipe to print (e.g. occupancy_randomdr); without it: list them")
    rec.add_argument("--json", action="store_true",
                     help="print the list (name, path, task, method) or the recipe (name, path, text) as one JSON object")

    rep = command("reproduce", _cmd_reproduce, help="the paper's experiment: 2 tasks x 4 methods (the paper's 3 + cdr_profile) x N seeds, report + figures")
    rep.add_argument("--quick", action="store_true", help="minutes on a 2-core CPU (what `make demo` runs)")
    rep.add_argument("--seeds", type=int, default=3, help="training seeds per method")
    rep.add_argument("--calibration", default=None,
                     help="empty-room capture recorded like the --test captures: the twin simulates its config, its "
                     "persistent lines are excised, CDR's floor and each classifier's static-change gate are "
                     "fitted on it, cdr_profile fits its profile on it (required with --test; the generated test "
                     "sets bring their own; a calibration record JSON serves what it holds, with a warning about the gate)")
    rep.add_argument("--test", action="append", default=None, metavar="PATH[:COUNT]",
                     help="test capture; COUNT labels the whole file, else per-frame 'count' labels (repeatable)")
    rep.add_argument("--cdr-floor", choices=("matched", "normal", "empirical"), default=None,
                     help="CalibratedDR's floor for the CDR methods: matched (default: the capture's distribution "
                     "deconvolved against the twin's own floor, so that max(S, N) has the capture's), normal (the "
                     "paper's) or empirical (the capture's measured distribution); docs/training.md")
    rep.add_argument("--representation", choices=("floor_relative", "paper"), default=None,
                     help="network input of the main runs: floor_relative (default: each range row referenced to "
                     "its Doppler median, zero Doppler blanked) or paper (the clipped dBFS map)")
    rep.add_argument("--resample", choices=("bilinear", "max"), default=None,
                     help="how each map shrinks to the image size: bilinear (the colour image resized, the paper's) "
                     "or max (each pixel the max of the levels it covers; default: the recipes'; docs/training.md)")
    rep.add_argument("--excise-interference-db", type=_db_or_off, default=None, metavar="DB|off",
                     help="replace each frame's chirps whose moving power stands DB over its median chirp (another "
                     "radar's burst) before the RD FFTs, in training and test alike, or off (default: the recipes'; "
                     "docs/training.md)")
    rep.add_argument("--test-sets", default=None,
                     help="generated test sets when no --test is given, comma-separated: proxy (the twin in "
                     "another room), independent (a NumPy generator sharing no code with the twin), standing (the "
                     "independent generator with 30 %% of its people standing), design (held-out worlds to look "
                     "at: validation numbers), report (held-out worlds run only to report), report-1, report-2, report-3 (the first three report suites, spent); default: independent "
                     "with --quick, proxy and independent in full mode")
    rep.add_argument("--worlds", type=int, default=None,
                     help="worlds per held-out suite (design/report in --test-sets; default 6 design, 4 report)")
    rep.add_argument("--methods", default=None,
                     help="comma-separated methods (default: the mode's: rt,randomdr,cdr with --quick)")
    rep.add_argument("--ablations", default=None,
                     help="comma-separated ablation variants (default: the mode's list; see docs/training.md)")
    rep.add_argument("--test-dr", action="store_true",
                     help="pass the test captures through each run's DR too (not the paper's protocol; "
                     "docs/training.md)")
    rep.add_argument("--no-ablation", action="store_true", help="skip the ablation variants")
    rep.add_argument("--accelerator", choices=ACCELERATORS, default="auto",
                     help="Lightning accelerator: cpu, cuda, or auto (cuda where there is one)")
    _output_args(rep, "output folder (report, runs, figures, cache)",
                 resume="run again in it, reusing its generated test sets and simulated sets (cached by "
                 "content, never stale)")
    rep.add_argument("--json", action="store_true", help="print the report (results per task and method, figures, settings) as one JSON object")

    proxy = command("make-proxy", _cmd_make_proxy, help="generate the held-out proxy test set (docs/proxy.md)")
    _output_args(proxy, "output folder",
                 resume="reuse the set it holds when made with the same arguments (else generate it again)")
    proxy.add_argument("--frames-per-count", type=int, default=120, help="frames per people count (0, 1, 2)")
    proxy.add_argument("--seed", type=int, default=1234, help="seed of the walks and the noise")
    proxy.add_argument("--json", action="store_true", help="print the calibration and test capture paths as one JSON object")

    dia = command("diagnose", _cmd_diagnose, help="compare a capture with the twin, fit the missing effects (docs/diagnosis.md)")
    dia.add_argument("capture", help="radaraug .h5 capture or Infineon recording folder (for a sensor "
                     "profile: the empty-room capture, as cdr_profile and catalog_priors: calibration use it)")
    dia.add_argument("--scene", default=None, help="the capture's scene (file or built-in name); "
                     "default: estimate the static scene from the capture")
    _output_args(dia, "report folder")
    dia.add_argument("--max-frames", type=int, default=100, help="frames read (half fit, half held out)")
    dia.add_argument("--profile", default=None, help="start from this twin profile instead of the default chain")
    dia.add_argument("--seed", type=int, default=0, help="seed of the twin's noise")
    dia.add_argument("--no-figures", action="store_true", help="skip the figures (faster)")
    dia.add_argument("--no-signatures", action="store_true",
                     help="do not read the effects' signatures first: every candidate competes on the error alone")
    dia.add_argument("--json", action="store_true", help="print the held-out errors, effects added and output paths as one JSON object")

    dev = command("devices", _cmd_devices, help="list Infineon radar boards on USB (docs/capture.md)")
    dev.add_argument("--json", action="store_true", help="print one JSON object")
    dev.add_argument("--udev-rule", action="store_true",
                     help="print the udev rule that lets users open the boards (Linux) and exit")

    def live(parser: argparse.ArgumentParser, output: str) -> None:
        parser.add_argument("--board", default="auto",
                            help="the radar board: 'auto' (first board, through Infineon's ifxradarsdk), 'virtual' "
                            "(the digital twin) or a board's serial")
        parser.add_argument("--radar-config", default=None,
                            help="radar config JSON (radaraug or Infineon config.json; default: the scene's "
                            "for virtual, the BGT60TR13C preset for a board)")
        parser.add_argument("--seconds", type=float, default=10.0, help="how long to record")
        parser.add_argument("--scene", default=None, help="virtual: scene file or built-in scene name "
                            "(default: corridor)")
        parser.add_argument("--profile", default=None, help="virtual: twin profile JSON (from radaraug diagnose)")
        parser.add_argument("--seed", type=int, default=None, help="virtual: noise seed (frames are a pure "
                            "function of seed and frame index; default: 0)")
        parser.add_argument("--realtime", action=argparse.BooleanOptionalAction, default=None,
                            help="virtual: hand frames out at the config's frame rate (--no-realtime: as fast "
                            "as the twin simulates; default: --realtime)")
        _output_args(parser, output)
        parser.add_argument("--no-progress", action="store_true", help="no progress bar")
        parser.add_argument("--json", action="store_true", help="print the result as one JSON object")

    pred = command("predict", _cmd_predict, help="run a classifier file (reproduce's runs/.../classifier.pt) on "
                   "captures, a recording in progress, a board or the virtual sensor (docs/predict.md)")
    pred.add_argument("classifier", help="classifier file (classifier.pt)")
    pred.add_argument("sources", nargs="*", help="captures: .h5 files, Infineon recording folders, or folders of them")
    pred.add_argument("-o", "--output", default="-", help="rows to write (- : stdout)")
    pred.add_argument("--overwrite", action="store_true", help="replace an existing output (else it is refused)")
    pred.add_argument("--format", choices=("jsonl", "csv"), default="jsonl", help="one row per frame")
    pred.add_argument("--window", type=int, default=None,
                      help="frames of the causal smoothing of the decision (default: the classifier's context)")
    pred.add_argument("--no-gate", action="store_true", help="do not fuse the static-change gate into the decision")
    pred.add_argument("--calibration", default=None,
                      help="an empty-room capture (.h5 or Infineon folder, not a JSON) of the room predicted in: "
                      "refits the static-change gate on it (the classifier file carries the gate of the room it "
                      "was tested in, or none)")
    pred.add_argument("--follow", action="store_true",
                      help="one radaraug capture still being recorded: classify frames as they are flushed")
    pred.add_argument("--idle-timeout", type=float, default=60.0,
                      help="--follow: stop after this many seconds without a new frame")
    pred.add_argument("--board", default=None,
                      help="live: the radar board: 'auto' (first board), 'virtual' (the digital twin) or a board's serial")
    pred.add_argument("--radar-config", default=None, help="live: radar config JSON (default: the classifier's)")
    pred.add_argument("--seconds", type=float, default=None, help="live: stop after this long (default: Ctrl-C)")
    pred.add_argument("--max-frames", type=int, default=None, help="live: stop after this many frames")
    pred.add_argument("--scene", default=None, help="virtual: scene file or built-in scene name (default: corridor)")
    pred.add_argument("--profile", default=None, help="virtual: twin profile JSON (from radaraug diagnose)")
    pred.add_argument("--seed", type=int, default=None, help="virtual: noise seed (default: 0)")
    pred.add_argument("--realtime", action=argparse.BooleanOptionalAction, default=None,
                      help="virtual: frames at the config's frame rate (default: --realtime)")
    pred.add_argument("--no-progress", action="store_true", help="no progress bar")
    pred.add_argument("--json", action="store_true",
                      help="print a summary (frames, decisions per class) as one JSON object (rows need -o)")

    exp = command("export", _cmd_export, help="export a classifier file with its chain to TorchScript, ONNX and "
                  "torch.export, each checked against the eager classifier (docs/predict.md)")
    exp.add_argument("classifier", help="classifier file (classifier.pt)")
    _output_args(exp, "output folder")
    exp.add_argument("--format", default="torchscript,onnx,torch_export",
                     help="comma-separated: torchscript, onnx (needs radaraug[export]), torch_export")
    exp.add_argument("--check-capture", default=None,
                     help="check the exports on this capture's first 32 frames (default: synthetic frames)")
    exp.add_argument("--json", action="store_true", help="print the exports and their differences as one JSON object")

    cap = command("capture", _cmd_capture, help="record a board or the virtual sensor into a radaraug HDF5 capture")
    live(cap, "radaraug HDF5 capture to write")
    cap.add_argument("--label", type=int, default=None,
                     help="people count of the whole recording (per-frame 'count' and 'occupancy' labels)")

    cal = command("calibrate", _cmd_calibrate, help="record the empty room and fit CalibratedDR in one step "
                  "(--keep-recording keeps the capture training needs)")
    live(cal, "calibration JSON to write (CDR's floor and the persistent cells: no frames, so no gate or profile)")
    cal.add_argument("--keep-recording", default=None, metavar="PATH",
                     help="also keep the empty-room recording here (.h5): the capture to give as data.calibration "
                     "or reproduce --calibration (the twin's config, excision, CDR floor, static-change gate, "
                     "cdr_profile)")
    cal.add_argument("--floor", choices=("normal", "empirical"), default="normal",
                     help="the floor distribution the calibration draws from (as fit-cdr --floor)")
    _interference_arg(cal)
    return p


def _run(func: Callable[..., Result], *args: Any) -> int:
    """Call a command and map how it ends to the documented exit status (docs/cli.md)."""
    try:
        result = func(*args)
        if isinstance(result, dict):
            _print_json(result)
            result = EXIT_OK
        sys.stdout.flush()  # a closed pipe shows up here, not at interpreter exit
        return int(result or 0)
    except BrokenPipeError:
        # The reader of our stdout went away (`| head`): stop quietly. Point stdout at /dev/null so
        # the interpreter's final flush does not raise again (Python's documented recipe).
        with contextlib.suppress(OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
            os.close(devnull)
        return EXIT_BROKEN_PIPE
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (DependencyNotFoundError, RadarAugError) as e:
        print(f"error: {e}", file=sys.stderr)
        return EXIT_DEPENDENCY if isinstance(e, DependencyNotFoundError) else EXIT_DATA
    except OSError as e:
        # A file-system problem outside radaraug's own checks (an output folder that is read-only,
        # a full disk while writing a report): one line naming the file.
        where = f": {e.filename}" if getattr(e, "filename", None) else ""
        print(f"error: {e.strerror or e}{where}", file=sys.stderr)
        return EXIT_DATA


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the `radaraug` script; returns the exit status (docs/cli.md)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["train"]:
        return _run(_cmd_train, argv[1:])
    args = build_parser().parse_args(argv)  # usage errors: SystemExit(2) from argparse
    return _run(args.func, args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
