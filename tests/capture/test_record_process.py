"""A separate `radaraug capture --board virtual` process, killed for real (SIGKILL, SIGINT), and a
full disk (the process's file-size limit, SIGXFSZ ignored) refused before recording starts.

Frames are a pure function of (seed, frame index), so what a killed recording holds is checked
against the virtual sensor's stream; the file is reopened by radaraug's reader alone (no h5clear).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

from radaraug.capture import VirtualSensor
from radaraug.cli import main
from radaraug.config import RadarConfig
from radaraug.errors import CaptureError
from radaraug.io import RadarCaptureDataset, open_capture
from radaraug.io.hdf5_recovery import status_flags
from radaraug.units import float_to_counts

REPO = Path(__file__).resolve().parents[2]
CLI = "import sys; from radaraug.cli import main; sys.exit(main(sys.argv[1:]))"
FULL_DISK = ("import resource, signal; signal.signal(signal.SIGXFSZ, signal.SIG_IGN); "
             "resource.setrlimit(resource.RLIMIT_FSIZE, ({limit}, resource.RLIM_INFINITY)); ")


def _start(cfg_file: Path, out: Path, seed: int = 7) -> subprocess.Popen:
    args = ["capture", "--board", "virtual", "--radar-config", str(cfg_file), "--seconds", "60", "--realtime",
            "--seed", str(seed), "--no-progress", "-o", str(out)]
    return subprocess.Popen([sys.executable, "-c", CLI, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, cwd=REPO, env={**os.environ, "PYTHONPATH": str(REPO)})


def _wait_for_frames(proc: subprocess.Popen, out: Path, frames: int) -> int:
    """Poll the file as a reader (SWMR) until it holds ``frames``; returns the count seen."""
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        assert proc.poll() is None, f"capture ended early: {proc.communicate()}"
        if out.exists():
            try:
                with open_capture(out) as cap:
                    if cap.num_frames >= frames:
                        return cap.num_frames
            except CaptureError:
                pass  # between the rename and the first flush
        time.sleep(0.05)
    raise AssertionError("no frames were recorded in time")


def _stream(cfg_file: Path, n: int, seed: int = 7) -> np.ndarray:
    cfg = RadarConfig.from_json(cfg_file)
    return float_to_counts(VirtualSensor("corridor", config=cfg, seed=seed).frames(0, n)).numpy()


def test_sigkill_mid_recording_keeps_every_flushed_frame(tmp_path, cfg_file) -> None:
    out = tmp_path / "killed.h5"
    proc = _start(cfg_file, out)
    try:
        seen = _wait_for_frames(proc, out, 3)
    finally:
        os.kill(proc.pid, signal.SIGKILL)
        proc.communicate(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    t0 = time.monotonic()
    with open_capture(out) as cap:  # radaraug's reader only
        n = cap.num_frames
        got = cap.read(as_float=False).numpy()
    reopen_s = time.monotonic() - t0
    assert n >= seen >= 3 and reopen_s < 5
    assert np.array_equal(got, _stream(cfg_file, n))
    assert len(RadarCaptureDataset(out)) == n
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".partial")] == []


def test_sigint_ends_with_a_complete_closed_file_and_status_130(tmp_path, cfg_file) -> None:
    out = tmp_path / "stopped.h5"
    proc = _start(cfg_file, out)
    try:
        _wait_for_frames(proc, out, 3)
        os.kill(proc.pid, signal.SIGINT)
        stdout, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.kill(proc.pid, signal.SIGKILL)
            proc.communicate()
    assert proc.returncode == 130, stderr
    assert "interrupted" in stderr and "complete and closed" in stderr and "Traceback" not in stderr
    assert "interrupted" in stdout
    assert status_flags(out) == 0  # closed cleanly: no SWMR/write flags left
    with h5py.File(out, "r") as f:  # a plain (non-SWMR) open works
        n = int(f["frames"].shape[0])
        assert f["frames_written"][0] == n >= 3
        assert f["timestamps"].shape == (n,)
    with open_capture(out) as cap:
        assert np.array_equal(cap.read(as_float=False).numpy(), _stream(cfg_file, n))


def test_full_disk_and_unwritable_path_fail_before_recording(tmp_path, cfg_file, capsys) -> None:
    def run(*argv, limit=None):
        pre = FULL_DISK.format(limit=limit) if limit else ""
        return subprocess.run([sys.executable, "-c", pre + CLI, *argv], capture_output=True, text=True, cwd=REPO,
                              timeout=120, env={**os.environ, "PYTHONPATH": str(REPO)})

    base = ["capture", "--board", "virtual", "--radar-config", str(cfg_file), "--no-progress"]
    r = run(*base, "--seconds", "600", "-o", str(tmp_path / "big.h5"), limit=2 << 20)
    assert r.returncode == 3, r.stderr
    assert "not enough space" in r.stderr and "ulimit -f" in r.stderr and "nothing was written" in r.stderr
    (tmp_path / "file").write_text("x")
    assert main([*base, "--seconds", "1", "-o", str(tmp_path / "file" / "out.h5")]) == 3  # in this process
    err = capsys.readouterr().err
    assert err.startswith("error: ") and "cannot create its folder" in err and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cfg.json", "file"]
