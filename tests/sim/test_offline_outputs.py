"""`radaraug simulate` output paths: unusable, foreign, damaged or too-full outputs are refused
with one error (exit status 3), quickly, and never overwritten."""

from __future__ import annotations

import os
import time
from types import SimpleNamespace

import h5py
import numpy as np
import pytest

from radaraug.cli import main
from radaraug.errors import CaptureError
from radaraug.io import hdf5_writer
from radaraug.sim import offline


def _one_line_error(capsys, *fragments: str) -> str:
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err and "Traceback" not in err, err
    for f in fragments:
        assert f in err, err
    return err


def test_output_under_a_file_is_one_error_naming_the_path(tmp_path, capsys) -> None:
    blocker = tmp_path / "notes.txt"
    blocker.write_text("x")
    out = blocker / "run.h5"
    assert main(["simulate", "corridor", "--frames", "2", "-o", str(out)]) == 3
    _one_line_error(capsys, str(out))
    assert blocker.read_text() == "x"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_output_in_a_read_only_folder_is_one_error(tmp_path, capsys) -> None:
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        assert main(["simulate", "corridor", "--frames", "2", "-o", str(ro / "run.h5")]) == 3
        _one_line_error(capsys, str(ro / "run.h5"))
    finally:
        ro.chmod(0o755)


def _foreign_h5(path) -> bytes:
    with h5py.File(path, "w", libver="latest") as f:
        f.create_dataset("data", data=np.arange(20_000))
        f.attrs["owner"] = "someone else"
    return path.read_bytes()


@pytest.mark.parametrize("cut", ["half", "stub12"])
def test_a_damaged_hdf5_file_at_the_output_is_refused_quickly_and_kept(tmp_path, capsys, cut) -> None:
    out = tmp_path / "run.h5"
    full = _foreign_h5(out)
    data = full[: len(full) // 2] if cut == "half" else full[:12]
    out.write_bytes(data)
    t0 = time.perf_counter()
    assert main(["simulate", "corridor", "--frames", "2", "-o", str(out), "--resume"]) == 3
    assert time.perf_counter() - t0 < 10  # a 12-byte stub used to hang in HDF5's SWMR retry loop
    _one_line_error(capsys, "not made by this job")
    assert out.read_bytes() == data


def test_a_foreign_hdf5_file_is_refused_and_kept(tmp_path) -> None:
    out = tmp_path / "run.h5"
    data = _foreign_h5(out)
    with pytest.raises(CaptureError, match="not made by this job"):
        offline.simulate_capture("corridor", out, frames=2, progress=False)
    assert out.read_bytes() == data


def test_not_enough_space_is_refused_before_the_twin_is_built(tmp_path, capsys, monkeypatch) -> None:
    monkeypatch.setattr(hdf5_writer.shutil, "disk_usage", lambda p: SimpleNamespace(total=2 << 20, used=0, free=2 << 20))
    built = []
    monkeypatch.setattr(offline, "DigitalTwin", lambda *a, **k: built.append(1))
    out = tmp_path / "run.h5"
    t0 = time.perf_counter()
    assert main(["simulate", "corridor_two_walkers", "--frames", "480", "-o", str(out)]) == 3
    elapsed = time.perf_counter() - t0
    _one_line_error(capsys, "not enough space", "480 frames need about 46.1 MiB", "2.0 MiB free")
    assert not built and not out.exists() and elapsed < 5
