"""Whole-file outputs: written to a temporary file, fsynced, renamed; never partial."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from radaraug.files import (
    atomic_save,
    atomic_savefig,
    atomic_write_bytes,
    atomic_write_json,
    atomic_write_text,
)

REPO = Path(__file__).resolve().parents[2]


def test_writes_replace_the_file_and_leave_no_temporary(tmp_path) -> None:
    p = tmp_path / "a.json"
    atomic_write_json(p, {"x": 1}, indent=2)
    assert json.loads(p.read_text()) == {"x": 1} and p.read_text().endswith("\n")
    atomic_write_text(p, "two")
    assert p.read_text() == "two"
    atomic_write_bytes(tmp_path / "b.bin", b"\x00\x01")
    atomic_save(tmp_path / "c.npy", lambda f: np.save(f, np.arange(5)))
    assert np.load(tmp_path / "c.npy").tolist() == [0, 1, 2, 3, 4]
    assert sorted(x.name for x in tmp_path.iterdir()) == ["a.json", "b.bin", "c.npy"]


def test_a_failed_write_keeps_the_old_file(tmp_path) -> None:
    p = tmp_path / "keep.json"
    p.write_text("old")

    def boom(f):
        f.write(b"half")
        raise OSError(28, "No space left on device")

    with pytest.raises(OSError, match="No space"):
        atomic_save(p, boom)
    with pytest.raises(TypeError):
        atomic_write_json(p, {"x": object()})  # not JSON: nothing is created
    assert p.read_text() == "old" and [x.name for x in tmp_path.iterdir()] == ["keep.json"]
    with pytest.raises(FileNotFoundError):
        atomic_write_text(tmp_path / "missing" / "x.txt", "x")


def test_savefig_picks_the_format_from_the_suffix(tmp_path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0, 1])
    atomic_savefig(fig, tmp_path / "f.png", dpi=20)
    atomic_savefig(fig, tmp_path / "f.svg")
    plt.close(fig)
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in (tmp_path / "f.svg").read_bytes()[:500]


def test_a_real_file_size_limit_never_leaves_a_partial_file(tmp_path) -> None:
    code = (
        "import resource, signal, sys\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (1000, resource.RLIM_INFINITY))\n"
        "from radaraug.files import atomic_write_text\n"
        "try:\n"
        "    atomic_write_text(sys.argv[1], 'x' * 5000)\n"
        "except OSError as e:\n"
        "    print(e.errno)\n"
    )
    out = tmp_path / "big.txt"
    out.write_text("previous")
    run = subprocess.run([sys.executable, "-c", code, str(out)], capture_output=True, text=True, cwd=REPO,
                         timeout=120)
    assert run.stdout.strip() == "27", run.stderr[-2000:]  # EFBIG
    assert out.read_text() == "previous" and [x.name for x in tmp_path.iterdir()] == ["big.txt"]
