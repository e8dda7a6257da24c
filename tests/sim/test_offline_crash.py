"""A real `radaraug simulate` process killed with SIGKILL resumes, with the same command, to a file
equal to an uninterrupted run (frames, timestamps, labels), also for a shard."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

from radaraug.errors import CaptureError
from radaraug.io import open_capture
from radaraug.io.hdf5_recovery import status_flags
from radaraug.sim import offline

REPO = Path(__file__).resolve().parents[2]
CLI = "import sys; from radaraug.cli import main; sys.exit(main(sys.argv[1:]))"


def _frames_in(path: Path) -> int:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with open_capture(path) as cap:
                return cap.num_frames
    except (CaptureError, OSError):
        return 0


@pytest.mark.slow
@pytest.mark.parametrize("shard", [None, "1/2"])
def test_simulate_killed_after_two_flushes_resumes_to_the_uninterrupted_file(tmp_path, shard) -> None:
    frames, kill_after = 48, 2
    argv = ["simulate", "corridor_two_walkers", "--frames", str(frames), "-o", str(tmp_path / "run.h5")]
    if shard:
        argv += ["--shard", shard]
    target = offline.shard_path(tmp_path / "run.h5", offline.parse_shard(shard))
    proc = subprocess.Popen([sys.executable, "-c", CLI, *argv], cwd=REPO, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    try:
        seen, deadline = 0, time.monotonic() + 600
        while seen < kill_after:  # poll the flushed frame count through the reader
            assert proc.poll() is None, proc.stderr.read().decode()[-2000:]
            assert time.monotonic() < deadline
            time.sleep(0.02)
            seen = _frames_in(target) if target.exists() else 0
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(timeout=60)
        proc.stderr.close()
    assert status_flags(target) != 0  # the killed writer left its flags: HDF5 alone refuses to append
    killed_at = _frames_in(target)
    assert killed_at >= kill_after

    again = subprocess.run([sys.executable, "-c", CLI, *argv, "--resume"], cwd=REPO, capture_output=True, text=True,
                           timeout=900)
    assert again.returncode == 0, again.stderr[-2000:]
    assert f"resumed from frame {offline.shard_range(frames, offline.parse_shard(shard))[0] + killed_at}" \
        in again.stdout

    ref = offline.simulate_capture("corridor_two_walkers", tmp_path / "ref.h5", frames=frames,
                                   shard=offline.parse_shard(shard), progress=False)
    with open_capture(target) as got, open_capture(ref["path"]) as want:
        assert got.num_frames == want.num_frames == ref["frames"][1] - ref["frames"][0]
        assert np.array_equal(got.read(as_float=False).numpy(), want.read(as_float=False).numpy())
        assert np.array_equal(got.timestamps, want.timestamps)
        assert got.labels.keys() == want.labels.keys()
        for k in got.labels:
            assert np.array_equal(got.labels[k], want.labels[k])
    assert status_flags(target) == 0
