"""The `radaraug` command line: info, fit-cdr, bench, demo, and clean errors."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import pytest

from radaraug import RadarConfig
from radaraug.cli import main
from radaraug.io import sample_recording_path, write_capture


def _empty_room(path, frames=24, seed=0):
    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, sample_rate_Hz=2e6,
                                 chirp_repetition_time_s=100e-6, frame_repetition_time_s=0.05)
    rng = np.random.default_rng(seed)
    n = np.arange(64) / 2e6
    static = 200 * np.cos(2 * np.pi * 150e3 * n)  # a static reflector
    counts = 2000 + static + rng.normal(0, 1.4, size=(frames, 3, 16, 64))
    write_capture(path, np.round(counts).astype(np.uint16), cfg)
    return cfg


def test_info_json_on_bundled_recording(capsys) -> None:
    assert main(["info", str(sample_recording_path()), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["shape"] == [256, 3, 8, 64]
    assert info["duration_s"] == pytest.approx(256 * 0.07726884633302689, rel=1e-6)
    # measured on a BGT60TR13C: RX1 ~1580-1655, RX3 ~2065-2070 counts; slow-time noise ~1-1.6 counts.
    assert 1550 < info["dc_offset_counts"][0] < 1660
    assert 2050 < info["dc_offset_counts"][2] < 2080
    assert all(0.8 < v < 2.0 for v in info["slow_time_noise_rms_counts"])
    assert info["motion"]["motion"] is False


def test_info_flags_motion_and_reports_static_return(tmp_path, capsys) -> None:
    path = tmp_path / "room.h5"
    cfg = _empty_room(path)
    assert main(["info", str(path), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    expected_bin = round(150e3 / cfg.beat_Hz_per_m / cfg.range_resolution_m)
    assert info["strongest_static_return"]["range_bin"] == expected_bin
    assert info["motion"]["motion"] is False
    assert info["clipped_fraction"] == [0.0, 0.0, 0.0]


def test_fit_cdr_writes_calibration(tmp_path, capsys) -> None:
    from radaraug.transforms import CalibratedDR

    path = tmp_path / "room.h5"
    _empty_room(path)
    out = tmp_path / "cdr.json"
    assert main(["fit-cdr", str(path), "-o", str(out)]) == 0
    cdr = CalibratedDR.load(out)
    assert "m_t" in capsys.readouterr().out
    assert np.isfinite(cdr.mean_db) and cdr.std_db > 0


def test_bad_input_is_one_line_error(tmp_path, capsys) -> None:
    bad = tmp_path / "broken.h5"
    bad.write_bytes(b"\x89HDF\r\n\x1a\n" + b"\x00" * 100)
    assert main(["info", str(bad)]) == 3
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "broken.h5" in err and "Traceback" not in err
    assert main(["info", str(tmp_path / "missing.h5")]) == 3


def test_bench_transforms_json(tmp_path, capsys) -> None:
    out = tmp_path / "b.json"
    assert main(["bench", "transforms", "--batch", "2", "--repeats", "1", "--json", "-o", str(out)]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result == json.loads(out.read_text())
    assert result["torch_frames_per_s"] > 0 and result["numpy_frames_per_s"] > 0
    # Both implementations compute the same dB maps.
    assert result["max_abs_diff_db_vs_numpy"] < 1e-2


def test_demo_writes_outputs(tmp_path, capsys) -> None:
    assert main(["demo", "-o", str(tmp_path / "out"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)  # stdout holds only the JSON ("[demo] wrote" went to stderr)
    assert summary["output"] == str(tmp_path / "out") and summary["cdr"]["file"] == "cdr.json"
    assert summary == {"output": str(tmp_path / "out"), **json.loads((tmp_path / "out" / "summary.json").read_text())}
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"cdr.json", "noise_floor_histogram.png", "summary.json"} <= names
    assert sum(n.startswith("rd_frame") for n in names) == 4


def test_info_max_frames_must_be_positive(tmp_path, capsys) -> None:
    path = tmp_path / "room.h5"
    _empty_room(path)
    # Before: 0 gave a confusing "cannot read frames 0:0", -3 silently analysed all but 3 frames.
    for bad in ("0", "-3"):
        assert main(["info", str(path), "--max-frames", bad, "--json"]) == 3
        err = capsys.readouterr().err
        assert "max_frames must be a positive integer" in err and "room.h5" in err


def test_info_json_is_valid_json_when_the_floor_cannot_be_computed(tmp_path, capsys) -> None:
    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=4)
    counts = np.random.default_rng(0).integers(1900, 2100, size=(20, 3, 4, 64)).astype(np.uint16)
    write_capture(tmp_path / "few_chirps.h5", counts, cfg)
    assert main(["info", str(tmp_path / "few_chirps.h5"), "--json"]) == 0
    out = capsys.readouterr().out
    info = json.loads(out, parse_constant=lambda c: pytest.fail(f"invalid JSON constant {c}"))
    assert info["noise_floor_db"] is None


def test_fit_cdr_bad_input_and_unwritable_output_are_one_line_errors(tmp_path, capsys) -> None:
    path = tmp_path / "room.h5"
    _empty_room(path)
    # Before: a bare FileNotFoundError traceback from CalibratedDR.save.
    out = tmp_path / "no_such_dir" / "cdr.json"
    assert main(["fit-cdr", str(path), "-o", str(out)]) == 3
    err = capsys.readouterr().err.split("\r")[-1]  # after the progress bar
    assert err.startswith("error: ") and "cdr.json" in err and "Traceback" not in err
    # Before: --max-frames -3 silently fitted on all but the last 3 frames of a tensor source.
    assert main(["fit-cdr", str(path), "-o", str(tmp_path / "c.json"), "--max-frames", "-3"]) == 3
    assert "max_frames must be a positive integer" in capsys.readouterr().err
    trunc = tmp_path / "trunc.h5"
    trunc.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    assert main(["fit-cdr", str(trunc), "-o", str(tmp_path / "c.json")]) == 3
    assert "trunc.h5" in capsys.readouterr().err


def test_diagnose_on_bundled_recording_writes_report_and_profile(tmp_path, capsys) -> None:
    out = tmp_path / "diag"
    assert main(["diagnose", str(sample_recording_path()), "-o", str(out), "--max-frames", "16", "--no-figures",
                 "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    report = json.loads((out / "report.json").read_text())
    assert printed["held_out_error_db"]["final"] == pytest.approx(report["error_after"]["overall"], abs=1e-4)  # report rounds
    assert printed["output"] == str(out) and printed["profile"] == str(out / "profile.json")
    assert printed["mode"] == "estimated"
    assert report["mode"] == "estimated" and report["scene"] is None
    assert report["error_after"]["overall"] <= report["error_before"]["overall"] + 1e-9
    assert (out / "profile.json").is_file() and (out / "summary.md").is_file()
    assert len(printed["verdict"]) == len(report["verdict"]) >= 9  # one line per detector at least
    assert {s["effect"] for s in report["signatures"]} >= {"adc_clipping", "spur_tone", "if_highpass"}


def test_diagnose_and_simulate_profile_bad_input_are_one_line_errors(tmp_path, capsys) -> None:
    assert main(["diagnose", str(tmp_path / "missing.h5"), "-o", str(tmp_path / "d")]) == 3
    assert main(["diagnose", str(sample_recording_path()), "-o", str(tmp_path / "d"), "--max-frames", "2"]) == 3
    bad = tmp_path / "profile.json"
    bad.write_text('{"format": "something else"}')
    assert main(["simulate", "corridor", "--frames", "1", "-o", str(tmp_path / "s.h5"), "--profile", str(bad)]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(line.startswith("error: ") for line in err)
    assert "twin profile" in err[-1]


# --------------------------------------------------------------------------- exit status
def _cli(*argv: str, limit: int | None = None, cwd=None):
    """Run the real `radaraug` in a separate process (optionally under a file-size limit that
    stands in for a full disk: SIGXFSZ ignored, so writes past it fail with EFBIG)."""
    import subprocess
    import sys
    from pathlib import Path

    pre = ""
    if limit is not None:
        pre = ("import resource, signal; signal.signal(signal.SIGXFSZ, signal.SIG_IGN); "
               f"resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, resource.RLIM_INFINITY)); ")
    code = pre + "import sys; from radaraug.cli import main; sys.exit(main(sys.argv[1:]))"
    root = Path(__file__).resolve().parents[1]
    return subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True,
                          cwd=cwd or root, timeout=300)


def test_exit_status_usage_2_data_3_interrupted_130(tmp_path, capsys, monkeypatch) -> None:
    import radaraug.cli as cli

    with pytest.raises(SystemExit) as usage:
        main(["info"])  # missing argument: argparse
    assert usage.value.code == cli.EXIT_USAGE == 2
    with pytest.raises(SystemExit) as usage:
        main(["no-such-command"])
    assert usage.value.code == 2
    capsys.readouterr()
    assert main(["info", str(tmp_path / "missing.h5")]) == cli.EXIT_DATA == 3
    assert capsys.readouterr().err.startswith("error: ")

    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "_cmd_info", interrupted)
    assert main(["info", "x"]) == cli.EXIT_INTERRUPTED == 130
    assert capsys.readouterr().err.strip() == "interrupted"


def test_exit_status_of_the_real_command(tmp_path) -> None:
    usage = _cli("info")
    assert usage.returncode == 2 and "required: path" in usage.stderr
    data = _cli("info", str(tmp_path / "missing.h5"))
    assert data.returncode == 3 and data.stderr.count("\n") == 1 and "Traceback" not in data.stderr


def test_trace_json_into_a_closed_pipe_is_quiet() -> None:
    import subprocess
    import sys
    from pathlib import Path

    # `radaraug trace --json | head -1`: the reader goes away after its first bytes.
    code = "import sys; from radaraug.cli import main; sys.exit(main(sys.argv[1:]))"
    proc = subprocess.Popen([sys.executable, "-c", code, "trace", "corridor", "--json"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            cwd=Path(__file__).resolve().parents[1])
    assert proc.stdout.read(100).startswith(b'{"scene"')  # the JSON is ~1 MB, far beyond a pipe's buffer
    proc.stdout.close()
    err = proc.stderr.read().decode()
    proc.wait(timeout=120)
    assert proc.returncode == 141
    assert "Traceback" not in err and "BrokenPipeError" not in err and err == ""


def test_fit_cdr_on_a_full_disk_keeps_the_old_calibration(tmp_path) -> None:
    path = tmp_path / "room.h5"
    _empty_room(path)
    out = tmp_path / "cdr.json"
    out.write_text("old calibration\n")
    # 200 bytes: the capture is read, but cdr.json (~1.4 kB) cannot be written.
    run = _cli("fit-cdr", str(path), "-o", str(out), "--overwrite", limit=200)
    assert run.returncode == 3, run.stderr[-2000:]
    last = run.stderr.strip().split("\r")[-1].splitlines()[-1]
    assert "exists" not in last  # the write failed, not the existing-output check
    assert last.startswith("error: ") and "cdr.json" in last and "Traceback" not in run.stderr
    assert out.read_text() == "old calibration\n"  # not a 0-byte file
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cdr.json", "room.h5"]  # no temporary left


def test_version_and_python_m_entry_point():
    """``python -m radaraug --version`` runs the same command as the ``radaraug`` script."""
    import subprocess
    import sys

    import radaraug

    r = subprocess.run([sys.executable, "-m", "radaraug", "--version"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == f"radaraug {radaraug.__version__}"


def test_every_argument_has_help_and_defaults_are_shown():
    import argparse

    from radaraug.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    missing = [(name, a.dest) for name, sp in sub.choices.items() for a in sp._actions
               if a.help is None and not isinstance(a, argparse._HelpAction)]
    assert missing == []
    assert "(default: 1234)" in sub.choices["make-proxy"].format_help()


def test_fit_cdr_and_simulate_json(tmp_path, capsys) -> None:
    path = tmp_path / "room.h5"
    _empty_room(path)
    assert main(["fit-cdr", str(path), "-o", str(tmp_path / "cdr.json"), "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec == {"output": str(tmp_path / "cdr.json"), **json.loads((tmp_path / "cdr.json").read_text())}
    assert main(["simulate", "corridor", "--frames", "1", "-o", str(tmp_path / "s.h5"), "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res == {"output": str(tmp_path / "s.h5"), "frames": [0, 1],
                   "resumed_from": 0, "simulated": 1}


def test_make_proxy_and_reproduce_json(tmp_path, capsys, monkeypatch) -> None:
    # The long jobs themselves are tested elsewhere; here only what the CLI prints from their results.
    import radaraug.testsets.proxy as proxy
    import radaraug.training.reproduce as rep

    def fake_proxy(out, **kw):
        print("noise from the job")  # must not reach stdout under --json
        return proxy.ProxySet(Path(out) / "calibration.h5", [(Path(out) / "one.h5", 1)], RadarConfig.bgt60tr13c())

    def fake_reproduce(out, **kw):
        return {"kind": "quick", "wall_seconds": 60.0,
                "results": {"occupancy": {"cdr": {"balanced_accuracy": {"mean": 0.9, "std": 0.01}}}}}

    monkeypatch.setattr(proxy, "make_proxy", fake_proxy)
    monkeypatch.setattr(rep, "reproduce", fake_reproduce)
    assert main(["make-proxy", "-o", str(tmp_path), "--json"]) == 0
    out = capsys.readouterr()
    assert json.loads(out.out) == {"output": str(tmp_path), "calibration": str(tmp_path / "calibration.h5"),
                                   "tests": [{"path": str(tmp_path / "one.h5"), "people": 1}]}
    assert "noise from the job" in out.err
    assert main(["reproduce", "--quick", "-o", str(tmp_path), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["report"] == str(tmp_path / "report.md") and printed["kind"] == "quick"


def test_every_reporting_command_has_json() -> None:
    from radaraug.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    lacking = [name for name, p in sub.choices.items()
               if name != "train" and not any("--json" in a.option_strings for a in p._actions)]
    assert lacking == []


def test_recipes_are_installed_listed_printed_and_taken_by_name(tmp_path, capsys, monkeypatch) -> None:
    import yaml

    from radaraug import recipes
    from radaraug.cli import resolve_train_args

    names = recipes.recipe_names()
    assert len(names) == 8 and "occupancy_randomdr" in names
    assert (recipes.RECIPES_DIR / "base.yaml").is_file()  # installed with the package (tests/test_packaging.py)
    assert main(["recipes"]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in listed] == names
    assert main(["recipes", "--json"]) == 0
    listing = json.loads(capsys.readouterr().out)
    rows = listing["recipes"]
    assert {(r["name"], r["task"], r["method"]) for r in rows} >= {("counting_cdr_profile", "counting", "cdr_profile")}
    assert "rt_paper_image" in listing["ablations"]
    assert main(["recipes", "occupancy_rt"]) == 0  # a copy to edit: radaraug recipes NAME > my.yaml
    assert yaml.safe_load(capsys.readouterr().out) == recipes.compose("occupancy_rt")
    assert main(["recipes", "occupancy_nope"]) == 3
    assert "no recipe named 'occupancy_nope'" in capsys.readouterr().err

    monkeypatch.chdir(tmp_path)  # no recipes/ folder here: names resolve to the installed recipes
    # A recipe name is its base + task + method files, merged into one config as `radaraug recipes` merges them.
    for given in ("counting_rt", "counting_rt.yaml", "recipes/counting_rt.yaml", "--config=counting_rt"):
        argv = ["fit", given] if given.startswith("--") else ["fit", "--config", given]
        args = resolve_train_args([*argv, "--trainer.max_epochs", "1"])
        assert args[:2] == ["fit", "--config"] and args[3:] == ["--trainer.max_epochs", "1"]
        assert yaml.safe_load(args[2]) == recipes.compose("counting_rt")
    # Consecutive files merge mappings at every depth (LightningCLI alone replaces data.twin.randomization whole).
    args = resolve_train_args(["fit", "-c", "occupancy_rt", "-c", "ablation/rt_narrow_people"])
    merged = yaml.safe_load(args[2])["data"]["twin"]["randomization"]
    assert args[1] == "-c" and set(merged) == {"catalog", "people"}
    assert merged == recipes.compose("occupancy_rt", "ablation/rt_narrow_people")["data"]["twin"]["randomization"]
    assert resolve_train_args(["fit", "-c", "ablation/rt_paper_image"]) == [
        "fit", "-c", str(recipes.RECIPES_DIR / "ablation" / "rt_paper_image.yaml")]
    (tmp_path / "counting_rt.yaml").write_text("seed_everything: 1\n")  # a file of that name wins
    assert resolve_train_args(["fit", "-c", "counting_rt.yaml"]) == ["fit", "-c", "counting_rt.yaml"]
    assert main(["train", "fit", "--config", "counting_typo"]) == 3
    assert "not the name of an installed recipe" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        main(["train", "fit", "--config", "occupancy_randomdr", "--print_config"])
    printed = yaml.safe_load(capsys.readouterr().out)
    assert e.value.code == 0 and printed["data"]["task"] == "occupancy"
    assert printed["data"]["method"]["class_path"] == "radaraug.training.methods.RandomDR"

    def within(given, full):  # every key the recipe gives, at every depth (LightningCLI adds the defaults)
        if isinstance(given, dict):
            return all(within(v, full[k]) for k, v in given.items())
        return given == full

    # the merged recipe LightningCLI sees is the one `radaraug recipes NAME` prints (model.task is linked)
    for section in ("data", "trainer"):
        for key, value in recipes.compose("occupancy_randomdr")[section].items():
            if key != "logger":
                assert within(value, printed[section][key]), (section, key)


def test_demo_help_does_not_call_it_the_main_job() -> None:
    from radaraug.cli import build_parser

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    text = " ".join(sub.choices["demo"].format_help().split())
    assert "capture walkthrough" in text and "the main job, `make demo`, is `radaraug reproduce --quick`" in text
