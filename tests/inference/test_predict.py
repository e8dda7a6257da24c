"""Predictions from captures, folders, a recording in progress and the virtual sensor; the CLI's rows."""

from __future__ import annotations

import csv
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import torch

from radaraug.capture import VirtualSensor
from radaraug.cli import main
from radaraug.errors import CaptureError, ConfigError
from radaraug.inference.predict import (
    expand_sources,
    follow_capture,
    predict_captures,
    predict_device,
    rows_text,
)
from tests.inference.conftest import room_frames, small_config, write_frames

REPO = Path(__file__).resolve().parents[2]


def test_captures_and_folders_each_their_own_recording(tmp_path, clf) -> None:
    a, b = room_frames(70, seed=1), room_frames(5, seed=2)
    folder = tmp_path / "day"
    folder.mkdir()
    write_frames(folder / "a.h5", a)
    write_frames(folder / "b.h5", b)
    (folder / "notes.txt").write_text("not a capture")
    assert [p.name for p in expand_sources([folder])] == ["a.h5", "b.h5"]
    chunks = list(predict_captures(clf, [folder], window=3, progress=False))
    assert [(p.name, first, len(c.probs)) for p, first, c in chunks] == [("a.h5", 0, 64), ("a.h5", 64, 6), ("b.h5", 0, 5)]
    # the same as predicting each recording whole (the read counts round to SDK floats)
    whole_a = clf.predict(_reread(folder / "a.h5"), window=3)
    assert torch.equal(torch.cat([c.decisions for p, _, c in chunks if p.name == "a.h5"]), whole_a.decisions)
    lines = rows_text(iter(chunks)).splitlines()
    assert len(lines) == 75 and json.loads(lines[70])["source"].endswith("b.h5") and json.loads(lines[70])["frame"] == 0
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(CaptureError, match="empty: folder holds no capture"):
        expand_sources([empty])


def _reread(path) -> torch.Tensor:
    from radaraug.io import open_capture

    with open_capture(path) as cap:
        return cap.read()


def test_a_capture_of_another_config_is_refused_before_any_row(tmp_path, clf, capsys) -> None:
    write_frames(tmp_path / "ok.h5", room_frames(3))
    other = small_config().replace(num_chirps_per_frame=32)
    write_frames(tmp_path / "other.h5", torch.zeros(2, 3, 32, 64), other)
    clf.save(tmp_path / "c.pt")
    out = tmp_path / "rows.jsonl"
    assert main(["predict", str(tmp_path / "c.pt"), str(tmp_path / "ok.h5"), str(tmp_path / "other.h5"),
                 "-o", str(out)]) == 3
    err = capsys.readouterr().err
    assert "other.h5 has radar config" in err and "this classifier was trained for" in err
    assert out.read_text() == ""  # nothing predicted before the check


def test_cli_rows_as_jsonl_or_csv_and_a_summary(tmp_path, clf, capsys) -> None:
    write_frames(tmp_path / "walk.h5", room_frames(7))
    clf.save(tmp_path / "c.pt")
    assert main(["predict", str(tmp_path / "c.pt"), str(tmp_path / "walk.h5"), "--window", "2"]) == 0
    captured = capsys.readouterr()
    rows = [json.loads(line) for line in captured.out.splitlines()]
    assert clf.gate is None and "carries no static-change gate" in captured.err  # the lost lever is said
    assert [r["frame"] for r in rows] == list(range(7)) and {r["decision"] for r in rows} <= {"empty", "occupied"}
    assert main(["predict", str(tmp_path / "c.pt"), str(tmp_path / "walk.h5"), "--format", "csv",
                 "-o", str(tmp_path / "rows.csv"), "--json", "--no-progress"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["frames"] == 7 and sum(summary["decisions"].values()) == 7 and summary["window"] == 1
    table = list(csv.DictReader(io.StringIO((tmp_path / "rows.csv").read_text())))
    assert len(table) == 7 and float(table[0]["p_empty"]) + float(table[0]["p_occupied"]) == pytest.approx(1, abs=1e-4)
    assert main(["predict", str(tmp_path / "c.pt")]) == 3  # no source
    assert "not both" in capsys.readouterr().err


RECORDER = """
import sys, time, torch
from radaraug.io import CaptureWriter
from tests.inference.conftest import small_config
from radaraug.units import float_to_counts
frames = torch.load(sys.argv[1])
writer = CaptureWriter(sys.argv[2], small_config())
for i in range(len(frames)):
    writer.append(float_to_counts(frames[i]).numpy())
    time.sleep(0.2)
writer.close()
"""


def test_follow_reads_a_recording_while_another_process_writes_it(tmp_path, clf) -> None:
    frames = room_frames(9)
    torch.save(frames, tmp_path / "frames.pt")
    path = tmp_path / "live.h5"
    proc = subprocess.Popen([sys.executable, "-c", RECORDER, str(tmp_path / "frames.pt"), str(path)], cwd=REPO,
                            env={**os.environ, "PYTHONPATH": str(REPO)})
    try:  # started before the recorder's file exists: it waits for the first flushed frame
        chunks = list(follow_capture(clf, path, window=2, poll_s=0.05, idle_timeout_s=60))
    finally:
        proc.wait(timeout=60)
    assert proc.returncode == 0
    firsts = [first for _, first, _ in chunks]
    assert firsts == sorted(firsts) and len(chunks) > 1  # frames arrived over several reads
    got = torch.cat([c.decisions for _, _, c in chunks])
    assert len(got) == 9 and torch.equal(got, clf.predict(_reread(path), window=2).decisions)
    with pytest.raises(CaptureError, match="never.h5: no capture appeared within 0.1 s"):
        next(follow_capture(clf, tmp_path / "never.h5", poll_s=0.02, idle_timeout_s=0.1))


def test_live_virtual_sensor_is_a_pure_function_of_its_seed(tmp_path, clf, capsys) -> None:
    cfg = small_config()
    sensor = VirtualSensor("corridor", config=cfg, seed=3, realtime=False)
    chunks = list(predict_device(clf, sensor, max_frames=4, window=2))
    assert [first for _, first, _ in chunks] == [0, 1, 2, 3]
    want = clf.predict(VirtualSensor("corridor", config=cfg, seed=3).frames(0, 4), window=2)
    assert torch.allclose(torch.cat([c.probs for _, _, c in chunks]), want.probs, atol=1e-6)
    clf.save(tmp_path / "c.pt")
    assert main(["predict", str(tmp_path / "c.pt"), "--board", "virtual", "--no-realtime", "--seed", "3",
                 "--max-frames", "4", "--window", "2", "-o", str(tmp_path / "live.jsonl")]) == 0
    rows = [json.loads(line) for line in (tmp_path / "live.jsonl").read_text().splitlines()]
    assert [r["frame"] for r in rows] == [0, 1, 2, 3]
    assert [r["decision"] for r in rows] == [clf.class_names[int(d)] for d in want.decisions]
    with pytest.raises(ConfigError, match="trained for"):
        next(predict_device(clf, VirtualSensor("corridor", config=cfg.replace(num_chirps_per_frame=32),
                                               realtime=False), max_frames=1))


def test_follow_ends_with_every_flushed_frame_when_the_recorder_is_killed(tmp_path, clf) -> None:
    # radaraug capture in another process, SIGKILLed mid-recording: follow reads what was flushed and
    # stops once the writer's lock is gone (not after the idle timeout)
    import signal

    small_config().to_json(tmp_path / "cfg.json")
    path = tmp_path / "live.h5"
    cli = "import sys; from radaraug.cli import main; sys.exit(main(sys.argv[1:]))"
    proc = subprocess.Popen([sys.executable, "-c", cli, "capture", "--board", "virtual", "--radar-config",
                             str(tmp_path / "cfg.json"), "--seconds", "60", "--realtime", "--no-progress", "-o", str(path)],
                            cwd=REPO, env={**os.environ, "PYTHONPATH": str(REPO)})
    chunks = []
    try:
        for chunk in follow_capture(clf, path, window=2, poll_s=0.05, idle_timeout_s=60):
            chunks.append(chunk)
            if sum(len(c.probs) for _, _, c in chunks) >= 10 and proc.poll() is None:
                os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(timeout=60)
    assert proc.returncode == -signal.SIGKILL
    got = torch.cat([c.decisions for _, _, c in chunks])
    frames = _reread(path)
    assert len(got) == len(frames) >= 10  # every flushed frame, none twice
    assert torch.equal(got, clf.predict(frames, window=2).decisions)
