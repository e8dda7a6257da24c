"""Crash recovery of HDF5 captures: superblock flags and checksum, writer lock, SIGKILL, full disk.

The crashes here are real: a separate writer process killed with SIGKILL, and a writer process
whose file-size limit (``RLIMIT_FSIZE``, with SIGXFSZ ignored so writes fail with EFBIG) stands in
for a full disk without needing root to mount a small filesystem.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path
from types import SimpleNamespace

import h5py
import numpy as np
import pytest
from radaraug_tests_io_data import frame_pattern, pattern_counts

from radaraug.errors import CaptureError
from radaraug.io import CaptureWarning, CaptureWriter, hdf5_writer, open_capture, write_capture
from radaraug.io.hdf5_format import lookup3
from radaraug.io.hdf5_recovery import clear_status_flags, status_flags, writer_is_alive

REPO = Path(__file__).resolve().parents[2]
DATA = Path(__file__).with_name("data.py")


# --------------------------------------------------------------------------- lookup3 / superblock
def test_lookup3_matches_the_reference_values_of_its_author() -> None:
    # Test vectors printed by the driver in Bob Jenkins' lookup3.c (hashlittle, seeds 0 and 1).
    assert lookup3(b"") == 0xDEADBEEF
    assert lookup3(b"Four score and seven years ago") == 0x17770551
    assert lookup3(b"Four score and seven years ago", 1) == 0xCD628161


@pytest.mark.parametrize("n_datasets", [0, 1, 5])
def test_lookup3_reproduces_the_superblock_checksum_hdf5_wrote(tmp_path, n_datasets) -> None:
    path = tmp_path / "f.h5"
    with h5py.File(path, "w", libver="latest") as f:
        for i in range(n_datasets):
            f.create_dataset(f"d{i}", data=np.arange(100 * (i + 1)))
    head = path.read_bytes()[:48]
    assert head[8] in (2, 3) and head[9] == 8
    assert lookup3(head[:44]) == int.from_bytes(head[44:48], "little")
    assert status_flags(path) == 0


def test_flags_set_then_reset_with_a_fixed_checksum_open_normally(tmp_path) -> None:
    path = tmp_path / "f.h5"
    with h5py.File(path, "w", libver="latest") as f:
        f["x"] = np.arange(10)
    raw = bytearray(path.read_bytes())
    raw[11] = 0x05  # "open for write + SWMR write", what a killed SWMR writer leaves
    raw[44:48] = lookup3(bytes(raw[:44])).to_bytes(4, "little")
    path.write_bytes(bytes(raw))
    with pytest.raises(OSError, match="already open for write"):
        h5py.File(path, "r")
    assert status_flags(path) == 5
    assert clear_status_flags(path) is True
    assert clear_status_flags(path) is False  # already clean
    with h5py.File(path, "r") as f:
        assert f["x"][()].tolist() == list(range(10))
    with h5py.File(path, "a") as f:
        f["y"] = 1


def test_damaged_or_foreign_superblocks_are_refused(tmp_path) -> None:
    path = tmp_path / "f.h5"
    with h5py.File(path, "w", libver="latest") as f:
        f["x"] = 1
    raw = bytearray(path.read_bytes())
    raw[20] ^= 0x01  # a bit flip in the base/extension address: the checksum no longer matches
    path.write_bytes(bytes(raw))
    with pytest.raises(CaptureError, match="checksum"):
        clear_status_flags(path)
    stub = tmp_path / "stub.h5"
    stub.write_bytes(raw[:12])
    with pytest.raises(CaptureError, match="damaged HDF5 superblock"):
        status_flags(stub)
    old = tmp_path / "old.h5"
    with h5py.File(old, "w", libver="earliest") as f:
        f["x"] = 1
    with pytest.raises(CaptureError, match="superblock version 0"):
        clear_status_flags(old)
    text = tmp_path / "t.h5"
    text.write_text("not hdf5")
    with pytest.raises(CaptureError, match="not an HDF5 file"):
        status_flags(text)


# --------------------------------------------------------------------------- SIGKILL and resume
WRITER = """
import runpy, sys, time
from radaraug.config import RadarConfig
from radaraug.io import CaptureWriter
helpers = runpy.run_path(sys.argv[3])
config = RadarConfig.from_json(sys.argv[2])
n, sleep = int(sys.argv[4]), sys.argv[5] == "sleep"
w = CaptureWriter(sys.argv[1], config, labels_schema={"index": "int64"})
for i in range(n):
    w.append(helpers["frame_pattern"](config, i), timestamp=1e9 + i, labels={"index": i})
    print(i + 1, flush=True)
if sleep:
    time.sleep(600)
"""


def _start_writer(path: Path, config, frames: int, sleep: bool) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", WRITER, str(path), config.to_json(), str(DATA), str(frames),
         "sleep" if sleep else "loop"],
        stdout=subprocess.PIPE, text=True, cwd=REPO,
    )


def _wait_for(proc: subprocess.Popen, frames: int) -> None:
    seen = 0
    while seen < frames:
        line = proc.stdout.readline()
        assert line, f"writer died early (exit code {proc.poll()})"
        seen = int(line)


def _kill(proc: subprocess.Popen) -> None:
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=30)
    proc.stdout.close()


def _finish(path: Path, config, total: int) -> int:
    """Resume ``path`` and append the frames up to ``total``; the frame count it resumed from."""
    with CaptureWriter.resume(path, config, expected_frames=total) as w:
        start = w.num_frames
        for i in range(start, total):
            w.append(frame_pattern(config, i), timestamp=1e9 + i, labels={"index": i})
    return start


def _assert_equals_uninterrupted(path: Path, config, total: int, tmp_path: Path) -> None:
    ref = write_capture(tmp_path / "ref.h5", pattern_counts(config, total), config,
                        timestamps=1e9 + np.arange(total), labels={"index": np.arange(total)})
    with open_capture(path) as got, open_capture(ref) as want:
        assert got.num_frames == want.num_frames == total
        assert np.array_equal(got.read(as_float=False).numpy(), want.read(as_float=False).numpy())
        assert np.array_equal(got.timestamps, want.timestamps)
        assert np.array_equal(got.labels["index"], want.labels["index"])
    with h5py.File(path, "r") as f:  # closed cleanly: flags reset, count stored
        assert f["frames_written"][0] == total and f["frames"].shape[0] == total


def test_a_live_writer_is_never_touched_and_a_killed_one_resumes(tmp_path, tiny_config) -> None:
    path = tmp_path / "live.h5"
    proc = _start_writer(path, tiny_config, 5, sleep=True)
    try:
        _wait_for(proc, 5)
        # Alive (sleeping with the file open): readable, but no reset, resume or overwrite.
        assert status_flags(path) == 0x05 and writer_is_alive(path)
        with open_capture(path) as cap:
            assert cap.num_frames == 5
        with pytest.raises(CaptureError, match="another process has this file open"):
            clear_status_flags(path)
        with pytest.raises(CaptureError, match="another process has this file open"):
            CaptureWriter.resume(path, tiny_config)
        with pytest.raises(CaptureError, match="another process has this file open"):
            CaptureWriter(path, tiny_config)
        assert status_flags(path) == 0x05
    finally:
        _kill(proc)
    assert not writer_is_alive(path)
    with pytest.raises(OSError, match="already open for write"):
        h5py.File(path, "a")  # what every resume hit before radaraug reset the flags itself
    assert _finish(path, tiny_config, 12) == 5
    _assert_equals_uninterrupted(path, tiny_config, 12, tmp_path)


def test_sigkill_mid_append_then_resume_equals_an_uninterrupted_run(tmp_path, tiny_config) -> None:
    path = tmp_path / "crash.h5"
    proc = _start_writer(path, tiny_config, 1_000_000, sleep=False)
    try:
        _wait_for(proc, 30)  # the writer keeps appending in a tight loop: the kill lands mid-append
    finally:
        _kill(proc)
    with open_capture(path) as cap:
        n = cap.num_frames
        assert n >= 30
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, n))
    assert _finish(path, tiny_config, n + 7) == n
    _assert_equals_uninterrupted(path, tiny_config, n + 7, tmp_path)


def test_a_writer_killed_before_its_first_frame_leaves_no_file_at_the_target(tmp_path, tiny_config) -> None:
    path = tmp_path / "never.h5"
    w = CaptureWriter(path, tiny_config)
    assert not path.exists()  # built under a hidden temporary name until it is in SWMR mode
    w.append(frame_pattern(tiny_config, 0))
    assert path.exists() and not list(tmp_path.glob(".*.partial"))
    w.close()
    empty = tmp_path / "empty.h5"
    CaptureWriter(empty, tiny_config).close()  # closed without frames: published as it is
    assert empty.exists() and not list(tmp_path.glob(".*.partial"))


# --------------------------------------------------------------------------- full disk
FULL = """
import resource, runpy, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG instead
from radaraug.config import RadarConfig
from radaraug.errors import CaptureError
from radaraug.io import CaptureWriter
helpers = runpy.run_path(sys.argv[3])
config = RadarConfig.from_json(sys.argv[2])
resource.setrlimit(resource.RLIMIT_FSIZE, (int(sys.argv[4]), resource.RLIM_INFINITY))
w = CaptureWriter(sys.argv[1], config, labels_schema={"index": "int64"}, compression=None)
n = 0
try:
    for i in range(100_000):
        w.append(helpers["frame_pattern"](config, i), timestamp=1e9 + i, labels={"index": i})
        n = i + 1
except CaptureError as e:
    print(n)
    print(e)
"""


@pytest.mark.parametrize("limit", [60_000, 150_001])
def test_a_full_disk_stops_with_a_capture_error_and_serves_only_real_frames(tmp_path, tiny_config, limit) -> None:
    path = tmp_path / "full.h5"
    run = subprocess.run([sys.executable, "-c", FULL, str(path), tiny_config.to_json(), str(DATA), str(limit)],
                         capture_output=True, text=True, cwd=REPO, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]  # no crash at exit (it was a segfault)
    lines = run.stdout.splitlines()
    written, message = int(lines[0]), lines[1]
    assert written > 10 and "file-size limit" in message and str(path) in message
    assert "Traceback" not in run.stderr
    assert path.stat().st_size <= limit
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cap = open_capture(path)
    # where the limit struck mid-append (the frame declared, not counted), the reader says so
    assert all(w.category is CaptureWarning and "never written" in str(w.message) for w in caught), caught
    with cap:
        assert cap.num_frames == written  # every served frame is complete
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, written))
        np.testing.assert_array_equal(cap.labels["index"], np.arange(written))
    # More room later: the same file resumes after the last complete frame.
    assert _finish(path, tiny_config, written + 5) == written
    _assert_equals_uninterrupted(path, tiny_config, written + 5, tmp_path)


def test_not_enough_space_is_refused_before_anything_is_written(tmp_path, tiny_config, monkeypatch) -> None:
    free = 2 << 20  # 2 MiB left
    monkeypatch.setattr(hdf5_writer.shutil, "disk_usage", lambda p: SimpleNamespace(total=free, used=0, free=free))
    per_frame = 2 * 3 * 4 * 32
    with pytest.raises(CaptureError, match=r"not enough space: 10000 frames need about .* MiB .* 2\.0 MiB free"):
        CaptureWriter(tmp_path / "big.h5", tiny_config, expected_frames=10_000)
    assert not list(tmp_path.iterdir())  # nothing created
    fits = (free - hdf5_writer.SPACE_MARGIN_BYTES) // (per_frame + 256)
    CaptureWriter(tmp_path / "ok.h5", tiny_config, expected_frames=fits).close()
    with pytest.raises(CaptureError, match="not enough space"):
        CaptureWriter.resume(tmp_path / "ok.h5", tiny_config, expected_frames=fits + 1)


def test_the_file_size_limit_is_part_of_the_space_check(tmp_path, tiny_config) -> None:
    code = (
        "import resource, sys\n"
        "from radaraug.config import RadarConfig\n"
        "from radaraug.errors import CaptureError\n"
        "from radaraug.io import CaptureWriter\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (1 << 20, resource.RLIM_INFINITY))\n"
        "try:\n"
        "    CaptureWriter(sys.argv[1], RadarConfig.from_json(sys.argv[2]), expected_frames=10)\n"
        "except CaptureError as e:\n"
        "    print(e)\n"
    )
    t0 = time.perf_counter()
    run = subprocess.run([sys.executable, "-c", code, str(tmp_path / "x.h5"), tiny_config.to_json()],
                         capture_output=True, text=True, cwd=REPO, timeout=120)
    assert "file-size limit (ulimit -f)" in run.stdout, run.stderr[-2000:]
    assert time.perf_counter() - t0 < 30
    assert not list(tmp_path.iterdir())


# --------------------------------------------------------------------------- output paths
def test_unusable_output_paths_are_one_capture_error_naming_the_path(tmp_path, tiny_config) -> None:
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    for bad in (blocker / "out.h5", tmp_path / "missing" / "out.h5"):
        with pytest.raises(CaptureError, match=str(bad)):
            CaptureWriter(bad, tiny_config)
    (tmp_path / "folder.h5").mkdir()
    with pytest.raises(CaptureError, match="is a folder"):
        CaptureWriter(tmp_path / "folder.h5", tiny_config)
    with pytest.raises(CaptureError, match="no capture file to resume"):
        CaptureWriter.resume(tmp_path / "none.h5", tiny_config)


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_folder_is_a_capture_error(tmp_path, tiny_config) -> None:
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        with pytest.raises(CaptureError, match="Permission denied"):
            CaptureWriter(ro / "out.h5", tiny_config)
    finally:
        ro.chmod(0o755)
