"""Opening HDF5 captures so that damage fails in seconds (radaraug.io.hdf5_open / hdf5_format).

A writer is really killed (SIGKILL of a separate process): its file must still open (SWMR read),
and the same file with damaged metadata must fail fast instead of blocking in HDF5's SWMR
checksum retry loop (which sleeps twice as long at each of its 100 attempts).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import h5py
import numpy as np
import pytest

from radaraug.errors import CaptureError
from radaraug.io import CaptureWarning, open_capture
from radaraug.io.hdf5_format import lookup3, read_superblock

WRITER = r"""
import sys
import numpy as np
from radaraug.config import RadarConfig
from radaraug.io import CaptureWriter

c = RadarConfig(60e9, 61e9, 1e6, 32, 4, 100e-6, 0.01)
frame = np.full((3, 4, 32), 2000, np.uint16)
with CaptureWriter(sys.argv[1], c) as w:
    for i in range(10**7):
        w.append(frame + (i % 50), timestamp=1.7e9 + 0.01 * i)
        if i == 20:
            print("written", flush=True)
"""


@pytest.fixture
def killed_capture(tmp_path) -> Path:
    path = tmp_path / "killed.h5"
    proc = subprocess.Popen(
        [sys.executable, "-c", WRITER, str(path)], stdout=subprocess.PIPE, cwd=Path(__file__).parents[2]
    )
    try:
        assert proc.stdout.readline().strip() == b"written"
        time.sleep(0.2)
    finally:
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
    return path


def test_lookup3_matches_the_checksum_hdf5_stored(h5_capture, killed_capture) -> None:
    for path in (h5_capture, killed_capture):
        sb = read_superblock(path)
        assert sb is not None and sb.version >= 2 and sb.checksum_ok
    # Published lookup3 hashlittle test vectors (Bob Jenkins' driver5).
    assert lookup3(b"") == 0xDEADBEEF
    assert lookup3(b"Four score and seven years ago", 0) == 0x17770551
    assert lookup3(b"Four score and seven years ago", 1) == 0xCD628161


def test_killed_writer_file_opens_with_every_flushed_frame(killed_capture) -> None:
    sb = read_superblock(killed_capture)
    assert sb.open_for_write  # the writer never closed it
    with pytest.raises(OSError, match="already open for write"):
        h5py.File(killed_capture, "r")  # a plain open is refused: SWMR is needed
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cap = open_capture(killed_capture)
    # a kill mid-append leaves one frame declared but not counted: the reader says so and skips it
    assert all(w.category is CaptureWarning and "never written" in str(w.message) for w in caught), caught
    with cap:
        assert cap.num_frames >= 21
        counts = cap.read(as_float=False).numpy()
        expected = 2000 + (np.arange(cap.num_frames) % 50)
        np.testing.assert_array_equal(counts[:, 0, 0, 0], expected)
        np.testing.assert_allclose(np.diff(cap.timestamps), 0.01, atol=1e-6)


def _flip_root_header(path: Path) -> None:
    data = bytearray(path.read_bytes())
    so = data[9]
    root = int.from_bytes(data[12 + 3 * so : 12 + 4 * so], "little")
    data[root + 12] ^= 0x10  # inside the root group's object header (checksummed)
    path.write_bytes(bytes(data))


def test_damaged_killed_writer_file_fails_fast(killed_capture) -> None:
    _flip_root_header(killed_capture)
    t = time.monotonic()
    with pytest.raises(CaptureError) as err:
        open_capture(killed_capture)
    assert time.monotonic() - t < 5
    assert str(killed_capture) in str(err.value)


def test_damaged_closed_file_fails_fast(h5_capture) -> None:
    _flip_root_header(h5_capture)
    t = time.monotonic()
    with pytest.raises(CaptureError):
        open_capture(h5_capture)
    assert time.monotonic() - t < 5


@pytest.mark.parametrize("delta, fragment", [(-5000, "superblock says it ends"), (5000, "truncated")])
def test_wrong_end_of_file_field_with_a_valid_checksum(h5_capture, delta, fragment) -> None:
    data = bytearray(h5_capture.read_bytes())
    so = data[9]
    at = 12 + 2 * so
    data[at : at + so] = (int.from_bytes(data[at : at + so], "little") + delta).to_bytes(so, "little")
    end = 12 + 4 * so
    data[end : end + 4] = lookup3(bytes(data[:end])).to_bytes(4, "little")
    h5_capture.write_bytes(bytes(data))
    with pytest.raises(CaptureError, match=fragment):
        open_capture(h5_capture)


def test_superblock_bit_flip_is_a_checksum_error(h5_capture) -> None:
    data = bytearray(h5_capture.read_bytes())
    data[13] ^= 1
    h5_capture.write_bytes(bytes(data))
    with pytest.raises(CaptureError, match="superblock is damaged"):
        open_capture(h5_capture)


@pytest.mark.parametrize("name", ["capture.h5", "capture"])
def test_fifo_capture_path_does_not_block(tmp_path, name) -> None:
    p = tmp_path / name
    os.mkfifo(p)
    with pytest.raises(CaptureError, match="not a regular file"):
        open_capture(p)
