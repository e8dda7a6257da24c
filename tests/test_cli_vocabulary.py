"""One command-line vocabulary (docs/cli.md, "Conventions"), checked command by command.

Fast: the parser is read, the cheap commands run on tiny inputs, and the long jobs (training,
diagnosis, proxy generation, live devices) are replaced by stand-ins that record what reached them.
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import torch

import radaraug.cli as cli
from radaraug import RadarConfig
from radaraug.cli import build_parser, main
from radaraug.errors import ConfigError
from radaraug.io import write_capture

ROOT = Path(__file__).resolve().parents[1]


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _option(parser: argparse.ArgumentParser, flag: str) -> argparse.Action | None:
    return next((a for a in parser._actions if flag in a.option_strings), None)


def _capture(path: Path, frames: int = 20) -> Path:
    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, sample_rate_Hz=2e6,
                                 chirp_repetition_time_s=100e-6, frame_repetition_time_s=0.05)
    counts = 2000 + np.random.default_rng(0).normal(0, 1.4, size=(frames, 3, 16, 64))
    write_capture(path, np.round(counts).astype(np.uint16), cfg)
    return path


class Reached(ConfigError):
    """A stand-in for a long job raises this: the command got past its argument checks."""


def _reached(*args, **kwargs):
    raise Reached("reached the work")


# --------------------------------------------------------------------------- 1. --accelerator / --board
TORCH_COMMANDS = {"simulate": ["corridor", "--frames", "1", "-o", "x.h5"], "bench": ["transforms"]}
BOARD_COMMANDS = ("capture", "calibrate", "predict")


@pytest.mark.parametrize("name", sorted(_subparsers()))
def test_board_means_a_board_and_accelerator_a_torch_device(name) -> None:
    parser = _subparsers()[name]
    board, accelerator = _option(parser, "--board"), _option(parser, "--accelerator")
    assert _option(parser, "--device") is None, name  # one word per idea: no --device anywhere
    if name in BOARD_COMMANDS:
        assert board.dest == "board" and "board" in board.help and accelerator is None
    elif name in TORCH_COMMANDS:
        assert accelerator.choices == cli.ACCELERATORS == ("auto", "cpu", "cuda") and board is None
    elif name == "reproduce":
        assert board is None and accelerator.choices == cli.ACCELERATORS
    else:
        assert board is None and accelerator is None, name


@pytest.mark.parametrize("name", sorted(TORCH_COMMANDS))
def test_accelerator_picks_the_torch_device(name, monkeypatch) -> None:
    def device_of(*argv: str) -> str:
        return cli._torch_device(build_parser().parse_args([name, *TORCH_COMMANDS[name], *argv]))

    assert device_of() == "cpu"  # the default: a simulated file's frames depend on the device type
    assert device_of("--accelerator", "cpu") == "cpu"
    monkeypatch.setattr(torch.cuda, "is_available", lambda: False)
    assert device_of("--accelerator", "auto") == "cpu"
    with pytest.raises(ConfigError, match="--accelerator 'cuda': CUDA is not available"):
        device_of("--accelerator", "cuda")
    monkeypatch.setattr(torch.cuda, "is_available", lambda: True)
    assert device_of("--accelerator", "auto") == "cuda"
    with pytest.raises(SystemExit):
        device_of("--accelerator", "gpu:0")


def test_reproduce_accelerator_reaches_lightning(monkeypatch, tmp_path) -> None:
    import radaraug.training.reproduce as rep

    seen = []
    monkeypatch.setattr(rep, "reproduce", lambda out, **kw: seen.append(kw["accelerator"]) or _reached())
    for given in ("auto", "cpu", "cuda"):
        assert main(["reproduce", "--quick", "--accelerator", given, "-o", str(tmp_path / given)]) == 3
        assert seen[-1] == given
    with pytest.raises(SystemExit):  # one word per device: cuda, not Lightning's "gpu"
        build_parser().parse_args(["reproduce", "--accelerator", "gpu"])


def test_reproduce_interference_excision_off_overrides_the_recipe(monkeypatch, tmp_path) -> None:
    import radaraug.training.reproduce as rep

    seen = []
    monkeypatch.setattr(rep, "reproduce", lambda out, **kw: seen.append(kw["settings"]) or _reached())
    assert main(["reproduce", "--quick", "--excise-interference-db", "off", "-o", str(tmp_path / "a")]) == 3
    assert seen[-1].excise_interference_db is None and seen[-1].epochs == rep.ReproduceSettings.quick().epochs
    for bad in ("0", "-3", "six"):
        with pytest.raises(SystemExit):
            build_parser().parse_args(["reproduce", "--excise-interference-db", bad, "-o", "x"])


# --------------------------------------------------------------------------- 2. --config / --radar-config
@pytest.mark.parametrize("name", sorted(_subparsers()))
def test_config_is_a_recipe_and_radar_config_a_radar_json(name) -> None:
    parser = _subparsers()[name]
    config, radar = _option(parser, "--config"), _option(parser, "--radar-config")
    if name in BOARD_COMMANDS:
        assert radar is not None and "radar config JSON" in radar.help
        assert config is None
    else:  # train's --config (a recipe) is LightningCLI's: its parser here is a stub for --help
        assert config is None and radar is None, name


def _classifier_file(tmp_path: Path) -> Path:
    """A small untrained classifier file at the config of :func:`_capture`."""
    from radaraug.inference import ChainSpec, RadarClassifier
    from radaraug.training.models import resnet18

    cfg = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, sample_rate_Hz=2e6,
                                 chirp_repetition_time_s=100e-6, frame_repetition_time_s=0.05)
    chain = ChainSpec({}, "floor_relative", 1, (-5.0, 30.0), (16, 8))
    clf = RadarClassifier(resnet18(2), arch="resnet18", task="occupancy", config=cfg, chain=chain)
    return clf.save(tmp_path / "classifier.pt")


@pytest.mark.parametrize("name", BOARD_COMMANDS)
def test_radar_config_reaches_the_device(name, tmp_path, monkeypatch, capsys) -> None:
    import radaraug.capture as capture

    cfg = RadarConfig.bgt60tr13c(num_chirps_per_frame=16)
    cfg.to_json(tmp_path / "radar.json")
    got = []
    monkeypatch.setattr(capture, "open_device", lambda spec, config, **kw: got.append((spec, config)) or _reached())
    head = [name] if name != "predict" else [name, str(_classifier_file(tmp_path))]
    argv = [*head, "--board", "virtual", "--radar-config", str(tmp_path / "radar.json"), "-o", str(tmp_path / "out")]
    assert main(argv) == 3
    assert got == [("virtual", cfg)]
    assert "reached the work" in capsys.readouterr().err


# --------------------------------------------------------------------------- 3. --json: "output"
def test_simulate_json_names_its_file_output(tmp_path, capsys) -> None:
    out = tmp_path / "s.h5"
    assert main(["simulate", "corridor", "--frames", "1", "-o", str(out), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["output"] == str(out) and list(printed)[0] == "output" and "path" not in printed


def test_capture_and_calibrate_json_name_their_file_output(tmp_path, monkeypatch, capsys) -> None:
    import radaraug.capture as capture
    from radaraug.capture.record import RecordResult

    rec = RecordResult(path=tmp_path / "c.h5", frames=3, dropped=0, requested=3, seconds=0.3, interrupted=False,
                       device={"name": "virtual"})
    monkeypatch.setattr(capture, "open_device", lambda *a, **k: None)
    monkeypatch.setattr(capture, "record", lambda device, path, **kw: rec)
    assert main(["capture", "--board", "virtual", "-o", str(tmp_path / "c.h5"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    rest = {k: v for k, v in rec.to_dict().items() if k not in ("path", "device")}
    assert printed == {"output": str(tmp_path / "c.h5"), "board": {"name": "virtual"}, **rest}

    cdr = SimpleNamespace(mean_db=-90.0, std_db=2.0, floor="normal", motion=0.0, chain=[])
    run = SimpleNamespace(cdr=cdr, output=tmp_path / "cdr.json", recording=rec)
    monkeypatch.setattr(capture, "calibrate", lambda device, output, **kw: run)
    assert main(["calibrate", "--board", "virtual", "-o", str(tmp_path / "cdr.json"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["output"] == str(tmp_path / "cdr.json") and printed["recording"]["board"] == {"name": "virtual"}


def test_fit_cdr_demo_make_proxy_reproduce_json_name_their_output(tmp_path, monkeypatch, capsys) -> None:
    import radaraug.demo as demo
    import radaraug.testsets.proxy as proxy
    import radaraug.training.reproduce as rep

    cap = _capture(tmp_path / "room.h5")
    assert main(["fit-cdr", str(cap), "-o", str(tmp_path / "cdr.json"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["output"] == str(tmp_path / "cdr.json")
    monkeypatch.setattr(demo, "run_demo", lambda out: {"cdr": {"file": "cdr.json"}})
    assert main(["demo", "-o", str(tmp_path / "demo"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["output"] == str(tmp_path / "demo")
    monkeypatch.setattr(proxy, "make_proxy", lambda out, **kw: proxy.ProxySet(Path(out) / "cal.h5", [],
                                                                            RadarConfig.bgt60tr13c()))
    assert main(["make-proxy", "-o", str(tmp_path / "proxy"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["output"] == str(tmp_path / "proxy")
    monkeypatch.setattr(rep, "reproduce", lambda out, **kw: {"kind": "quick", "wall_seconds": 1.0, "test_sets": {}})
    assert main(["reproduce", "--quick", "-o", str(tmp_path / "repro"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["output"] == str(tmp_path / "repro")


# --------------------------------------------------------------------------- 4. existing outputs
def _fit_cdr(tmp_path, monkeypatch):
    return ["fit-cdr", str(_capture(tmp_path / "room.h5"))], False


def _simulate(tmp_path, monkeypatch):
    return ["simulate", "corridor", "--frames", "1"], False


def _demo(tmp_path, monkeypatch):
    import radaraug.demo as demo

    monkeypatch.setattr(demo, "run_demo", _reached)
    return ["demo"], True


def _make_proxy(tmp_path, monkeypatch):
    import radaraug.testsets.proxy as proxy

    monkeypatch.setattr(proxy, "make_proxy", _reached)
    return ["make-proxy"], True


def _reproduce(tmp_path, monkeypatch):
    import radaraug.training.reproduce as rep

    monkeypatch.setattr(rep, "reproduce", _reached)
    return ["reproduce", "--quick"], True


def _diagnose(tmp_path, monkeypatch):
    import radaraug.diagnosis as calibration

    monkeypatch.setattr(calibration, "diagnose", _reached)
    return ["diagnose", str(_capture(tmp_path / "room.h5"))], True


def _live(name):
    def setup(tmp_path, monkeypatch):
        import radaraug.capture as capture

        monkeypatch.setattr(capture, "open_device", _reached)
        return [name, "--board", "virtual"], False
    return setup


def _predict(tmp_path, monkeypatch):
    import radaraug.inference.predict as predict

    monkeypatch.setattr(predict, "predict_captures", _reached)
    return ["predict", str(_classifier_file(tmp_path)), str(_capture(tmp_path / "walk.h5"))], False


def _export(tmp_path, monkeypatch):
    import radaraug.inference.export as export

    monkeypatch.setattr(export, "export", _reached)
    return ["export", str(_classifier_file(tmp_path))], True


def _bench(tmp_path, monkeypatch):
    import radaraug.bench.transforms as transforms

    monkeypatch.setattr(transforms, "run_transforms_benchmark", _reached)
    return ["bench", "transforms"], False


WRITERS = {"bench": _bench, "fit-cdr": _fit_cdr, "simulate": _simulate, "demo": _demo, "make-proxy": _make_proxy,
           "reproduce": _reproduce, "diagnose": _diagnose, "capture": _live("capture"),
           "calibrate": _live("calibrate"), "predict": _predict, "export": _export}
RESUMABLE = {"simulate", "make-proxy", "reproduce"}


def test_every_command_that_writes_takes_overwrite_and_only_those() -> None:
    parsers = _subparsers()
    assert {n for n, p in parsers.items() if _option(p, "--overwrite")} == set(WRITERS)
    assert {n for n, p in parsers.items() if _option(p, "--resume")} == RESUMABLE


@pytest.mark.parametrize("name", sorted(WRITERS))
def test_an_existing_output_is_refused_without_overwrite(name, tmp_path, monkeypatch, capsys) -> None:
    argv, folder = WRITERS[name](tmp_path, monkeypatch)
    out = tmp_path / "out"
    if folder:
        out.mkdir()
        (out / "mine.txt").write_text("old")
    else:
        out.write_text("old")
    assert main([*argv, "-o", str(out)]) == cli.EXIT_DATA
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"error: {out}: ") and "--overwrite" in err, err
    assert ("--resume" in err) == (name in RESUMABLE)
    assert (out / "mine.txt" if folder else out).read_text() == "old"  # nothing touched

    # --overwrite gets past the check (to the work, or its stand-in)
    code = main([*argv, "-o", str(out), "--overwrite"])
    err = capsys.readouterr().err
    assert "choose another output" not in err
    if name in ("fit-cdr", "simulate"):  # the real thing, on tiny input: the file is replaced
        assert code == 0 and out.read_bytes() != b"old"
    else:
        assert code == 3 and "reached the work" in err


@pytest.mark.parametrize("name", sorted(WRITERS))
def test_an_empty_folder_or_a_new_path_is_not_an_existing_output(name, tmp_path, monkeypatch, capsys) -> None:
    argv, folder = WRITERS[name](tmp_path, monkeypatch)
    if name in ("fit-cdr", "simulate"):
        return  # covered by their own tests with a real run
    out = tmp_path / "new"
    if folder:
        out.mkdir()
    assert main([*argv, "-o", str(out)]) == 3
    assert "reached the work" in capsys.readouterr().err


def test_calibrate_refuses_an_existing_kept_recording(tmp_path, monkeypatch, capsys) -> None:
    import radaraug.capture as capture

    monkeypatch.setattr(capture, "open_device", _reached)
    (tmp_path / "rec.h5").write_text("old")
    argv = ["calibrate", "--board", "virtual", "-o", str(tmp_path / "cdr.json"), "--keep-recording",
            str(tmp_path / "rec.h5")]
    assert main(argv) == 3
    assert f"error: {tmp_path / 'rec.h5'}: exists" in capsys.readouterr().err
    assert main([*argv, "--overwrite"]) == 3
    assert "reached the work" in capsys.readouterr().err


def test_simulate_resumes_only_with_resume(tmp_path, capsys) -> None:
    out = tmp_path / "s.h5"
    argv = ["simulate", "corridor", "--frames", "1", "-o", str(out), "--json"]
    assert main(argv) == 0
    first = out.read_bytes()
    capsys.readouterr()
    assert main(argv) == 3  # re-running the same command no longer resumes silently
    assert "--resume to continue it" in capsys.readouterr().err
    assert main([*argv, "--resume"]) == 0
    assert json.loads(capsys.readouterr().out)["resumed_from"] == 1 and out.read_bytes() == first
    with pytest.raises(SystemExit):  # one or the other
        build_parser().parse_args([*argv, "--resume", "--overwrite"])


def test_simulate_shard_checks_the_shard_file(tmp_path, capsys) -> None:
    from radaraug.sim.offline import shard_path

    (tmp_path / "s.h5").write_text("not this shard's file")
    argv = ["simulate", "corridor", "--frames", "2", "--shard", "1/2", "-o", str(tmp_path / "s.h5")]
    shard = shard_path(tmp_path / "s.h5", (1, 2))
    shard.write_text("old")
    assert main(argv) == 3
    assert f"error: {shard}: exists" in capsys.readouterr().err


def test_make_proxy_resume_reuses_and_overwrite_regenerates(tmp_path, monkeypatch) -> None:
    import radaraug.testsets.proxy as proxy

    seen = []
    monkeypatch.setattr(proxy, "make_proxy", lambda out, **kw: seen.append((Path(out) / proxy.MANIFEST_NAME).exists())
                        or _reached())
    (tmp_path / proxy.MANIFEST_NAME).write_text("{}")
    (tmp_path / "mine.txt").write_text("x")
    assert main(["make-proxy", "-o", str(tmp_path), "--resume"]) == 3
    assert main(["make-proxy", "-o", str(tmp_path), "--overwrite"]) == 3
    assert seen == [True, False]  # no manifest: the generator makes the whole set again
    assert (tmp_path / "mine.txt").exists()


def test_reproduce_resume_keeps_its_caches_and_overwrite_removes_only_what_it_wrote(tmp_path, monkeypatch) -> None:
    import radaraug.training.reproduce as rep

    seen = []
    monkeypatch.setattr(rep, "reproduce", lambda out, **kw: seen.append(sorted(p.name for p in Path(out).iterdir()))
                        or _reached())
    for name in ("cache", "independent", "runs"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "f").write_text("x")
    (tmp_path / "report.json").write_text("{}")
    (tmp_path / "mine.txt").write_text("x")
    assert main(["reproduce", "--quick", "-o", str(tmp_path), "--resume"]) == 3
    assert main(["reproduce", "--quick", "-o", str(tmp_path), "--overwrite"]) == 3
    assert seen == [["cache", "independent", "mine.txt", "report.json", "runs"], ["mine.txt"]]


# --------------------------------------------------------------------------- 5. reproduce flags = recipe keys
def _doc_flag_table() -> dict[str, str]:
    """docs/cli.md's table of reproduce flags and the recipe keys they set."""
    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    section = text[text.index("| `reproduce` flag | recipe key |"):]
    rows = re.findall(r"^\| `(--[a-z-]+)[^`]*` \| `([a-z_.]+)`", section, re.M)
    return dict(rows)


REPRODUCE_FLAGS = {  # flag -> (extra arguments, the value expected at the recipe key)
    "--calibration": ([], None),  # the base arguments give it; checked against the file below
    "--test": ([], None),
    "--cdr-floor": (["--cdr-floor", "empirical", "--methods", "cdr"], "empirical"),
    "--representation": (["--representation", "paper"], "paper"),
    "--resample": (["--resample", "max"], "max"),
    "--excise-interference-db": (["--excise-interference-db", "7.5"], 7.5),
    "--test-dr": (["--test-dr"], True),
    "--accelerator": (["--accelerator", "cpu"], "cpu"),
}


def test_the_documented_flag_table_is_the_tested_one() -> None:
    table = _doc_flag_table()
    assert set(table) == set(REPRODUCE_FLAGS)
    for flag, key in table.items():  # each flag is named after its key (a CDR method's floor: --cdr-floor)
        assert flag.endswith("-" + key.split(".")[-1].replace("_", "-")), (flag, key)


@pytest.mark.parametrize("flag", sorted(REPRODUCE_FLAGS))
def test_each_reproduce_flag_reaches_its_recipe_key(flag, tmp_path, monkeypatch) -> None:
    pytest.importorskip("lightning")
    import radaraug.training.data as data
    import radaraug.training.module as module
    import radaraug.training.reproduce as rep

    cal, test = _capture(tmp_path / "empty.h5"), _capture(tmp_path / "walk.h5")
    got: dict[str, object] = {}

    def flatten(prefix, kw):
        for k, v in kw.items():
            got[f"{prefix}.{k}"] = v
            if isinstance(v, dict):
                flatten(f"{prefix}.{k}", v)

    def from_recipe(kw):
        flatten("data", kw)
        return SimpleNamespace(hparams=kw)

    datamodule = SimpleNamespace(from_recipe=from_recipe)

    def trainer(settings, accelerator, run_dir, **kw):
        got["trainer.accelerator"] = accelerator
        _reached()

    monkeypatch.setattr(data, "RadarDataModule", datamodule)
    monkeypatch.setattr(module, "RDClassifier", lambda **kw: SimpleNamespace(hparams=kw))
    monkeypatch.setattr(rep, "_trainer", trainer)
    extra, expected = REPRODUCE_FLAGS[flag]
    argv = ["reproduce", "--quick", "--seeds", "1", "--no-ablation", "--calibration", str(cal), "--test",
            f"{cal}:0", "--test", f"{test}:1", *extra, "-o", str(tmp_path / "out")]
    assert main(argv) == 3  # stopped at the first Trainer
    key = _doc_flag_table()[flag]
    if flag == "--calibration":
        expected = str(cal)
    elif flag == "--test":
        expected = [{"path": str(cal), "count": 0}, {"path": str(test), "count": 1}]
    assert got[key] == expected


# --------------------------------------------------------------------------- 5. --seed, --max-frames
def test_seed_is_one_idea_with_the_documented_defaults() -> None:
    # docs/cli.md: 0 unless given (None: the virtual sensor's 0, refused for a board), make-proxy's 1234
    for name, parser in _subparsers().items():
        seed = _option(parser, "--seed")
        if seed is not None:
            assert seed.type is int and seed.default in ((1234,) if name == "make-proxy" else (0, None)), name
        assert _option(parser, "--seeds") is None or name == "reproduce"
    text = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    assert "| a random seed |" in text and "| frames read |" in text and "| floor distributions |" in text


def test_max_frames_defaults_are_the_documented_ones() -> None:
    defaults = {n: _option(p, "--max-frames").default for n, p in _subparsers().items() if _option(p, "--max-frames")}
    assert defaults == {"info": 256, "fit-cdr": None, "diagnose": 100, "predict": None}
