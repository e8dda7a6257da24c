"""CaptureWriter / write_capture: layout, validation, crash safety."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest
import torch
from radaraug_tests_io_data import frame_pattern, pattern_counts

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, InputTensorError
from radaraug.io import CaptureWriter, open_capture, write_capture
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION


def test_file_layout_and_attributes(h5_capture, tiny_config):
    with h5py.File(h5_capture, "r") as f:
        a = f.attrs
        assert a["format"] == "radaraug-capture"
        assert a["format_version"] == "1.1"
        assert a["sample_units"] == "adc_counts"
        assert a["float_convention"] == FLOAT_CONVENTION
        assert a["db_convention"] == DB_CONVENTION
        assert a["source"] == "tests" and a["description"] == "frame pattern"
        assert "T" in a["created"]
        assert RadarConfig.from_dict(json.loads(a["radar_config"])) == tiny_config
        assert a["label_room"] == 3
        frames = f["frames"]
        assert frames.dtype == np.uint16
        assert frames.shape == (6, 3, 4, 32)
        assert frames.chunks == (1, 3, 4, 32)
        assert frames.maxshape == (None, 3, 4, 32)
        assert frames.compression == "gzip" and frames.shuffle
        assert f["timestamps"].dtype == np.float64
        np.testing.assert_array_equal(f["labels/count"][()], [0, 0, 1, 1, 2, 2])
        assert f["frames_written"][()].tolist() == [6]


def test_round_trip_is_exact(tmp_path, tiny_config):
    counts = pattern_counts(tiny_config, 4)
    path = write_capture(tmp_path / "a.h5", counts, tiny_config, compression=None)
    with h5py.File(path, "r") as f:
        assert f["frames"].compression is None
    with open_capture(path) as cap:
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), counts)
        assert cap.timestamps is None
        assert cap.attrs["source"] == "unspecified"


def test_appends_of_frames_and_blocks_with_torch_input(tmp_path, tiny_config):
    path = tmp_path / "b.h5"
    with CaptureWriter(path, tiny_config, labels_schema={"count": "int64"}, compression="lzf") as w:
        w.append(frame_pattern(tiny_config, 0), timestamp=10.0, labels={"count": 1})
        block = torch.from_numpy(pattern_counts(tiny_config, 3, first=1).astype(np.int32))
        w.append(block, timestamp=[11.0, 12.0, 13.0], labels={"count": np.array([1, 2, 2])})
        assert w.num_frames == 4
    with open_capture(path) as cap:
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, 4))
        np.testing.assert_array_equal(cap.timestamps, [10.0, 11.0, 12.0, 13.0])
        np.testing.assert_array_equal(cap.labels["count"], [1, 1, 2, 2])
        assert cap.duration_s == pytest.approx(3.0 + tiny_config.frame_repetition_time_s)


def test_labels_schema_inferred_from_first_append(tmp_path, tiny_config):
    path = tmp_path / "c.h5"
    with CaptureWriter(path, tiny_config) as w:
        w.append(frame_pattern(tiny_config, 0), labels={"occupied": True})
        w.append(frame_pattern(tiny_config, 1), labels={"occupied": False})
    with open_capture(path) as cap:
        assert cap.labels["occupied"].tolist() == [True, False]


@pytest.mark.parametrize(
    "bad, fragment",
    [
        (np.zeros((3, 4, 32), np.float32), "integer ADC counts"),
        (torch.zeros(3, 4, 32), "integer ADC counts"),
        (np.zeros((2, 4, 32), np.uint16), "shape"),
        (np.zeros((3, 4, 31), np.uint16), "shape"),
        (np.zeros((1, 1, 3, 4, 32), np.uint16), "shape"),
        (np.full((3, 4, 32), 4096, np.uint16), "outside the 12-bit code range"),
        (np.full((3, 4, 32), -1, np.int32), "outside the 12-bit code range"),
        (np.zeros((0, 3, 4, 32), np.uint16), "empty block"),
    ],
)
def test_bad_frames_raise_input_tensor_error_naming_the_file(tmp_path, tiny_config, bad, fragment):
    path = tmp_path / "bad.h5"
    with CaptureWriter(path, tiny_config) as w:
        with pytest.raises(InputTensorError, match=fragment) as err:
            w.append(bad)
        assert str(path) in str(err.value)


def test_timestamp_and_label_layout_is_enforced(tmp_path, tiny_config):
    frame = frame_pattern(tiny_config, 0)
    with CaptureWriter(tmp_path / "t.h5", tiny_config) as w:
        w.append(frame, timestamp=1.0)
        with pytest.raises(CaptureError, match="needs one per frame"):
            w.append(frame)
        with pytest.raises(CaptureError, match="finite timestamp"):
            w.append(np.stack([frame, frame]), timestamp=2.0)
        with pytest.raises(CaptureError, match="labels"):
            w.append(frame, timestamp=2.0, labels={"count": 1})
    with CaptureWriter(tmp_path / "v.h5", tiny_config, labels_schema={"count": "int64"}) as w:
        with pytest.raises(CaptureError, match="do not match"):
            w.append(frame)
        with pytest.raises(CaptureError, match="does not fit"):
            w.append(frame, labels={"count": 1.5})
        # Rejected appends wrote nothing.
        w.append(frame, labels={"count": 2})
        assert w.num_frames == 1
    with open_capture(tmp_path / "v.h5") as cap:
        assert cap.num_frames == 1 and cap.labels["count"].tolist() == [2]
    with CaptureWriter(tmp_path / "w.h5", tiny_config) as w:
        w.append(frame)
        with pytest.raises(CaptureError, match="stores none"):
            w.append(frame, timestamp=3.0)
    with pytest.raises(CaptureError, match="closed"):
        w.append(frame)


def test_writer_argument_errors(tmp_path, tiny_config):
    with pytest.raises(CaptureError, match="set by the writer"):
        CaptureWriter(tmp_path / "a.h5", tiny_config, attrs={"format": "x"})
    with pytest.raises(CaptureError, match="compression"):
        CaptureWriter(tmp_path / "a.h5", tiny_config, compression="blosc")
    with pytest.raises(CaptureError, match="numeric or bool"):
        CaptureWriter(tmp_path / "a.h5", tiny_config, labels_schema={"name": "U8"})
    with pytest.raises(CaptureError, match="cannot create"):
        CaptureWriter(tmp_path / "missing_dir" / "a.h5", tiny_config)


def test_dict_attrs_are_stored_as_json_and_read_as_file_labels(tmp_path, tiny_config):
    path = write_capture(
        tmp_path / "j.h5",
        pattern_counts(tiny_config, 3),
        tiny_config,
        attrs={"labels": {"count": 2, "room": "lab"}},
    )
    with open_capture(path) as cap:
        assert cap.labels["count"].tolist() == [2, 2, 2]
        assert cap.labels["room"].tolist() == ["lab"] * 3


# --------------------------------------------------------------------------- crash safety
CHILD = """
import runpy, sys
from radaraug.config import RadarConfig
from radaraug.io import CaptureWriter
helpers = runpy.run_path(sys.argv[3])
config = RadarConfig.from_json(sys.argv[2])
with CaptureWriter(sys.argv[1], config, labels_schema={"index": "int64"}) as w:
    for i in range(1_000_000):
        w.append(helpers["frame_pattern"](config, i), timestamp=1e9 + i, labels={"index": i})
        print(i + 1, flush=True)
"""


def test_sigkill_while_recording_keeps_every_flushed_frame(tmp_path, tiny_config):
    path = tmp_path / "crash.h5"
    flushed_before_kill = 25
    proc = subprocess.Popen(
        [
            sys.executable,
            "-c",
            CHILD,
            str(path),
            tiny_config.to_json(),
            str(Path(__file__).with_name("data.py")),
        ],
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        seen = 0
        while seen < flushed_before_kill:
            line = proc.stdout.readline()
            assert line, f"writer died early (exit code {proc.poll()})"
            seen = int(line)
        # The writer keeps appending in a tight loop: the kill lands mid-append.
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(timeout=30)
        proc.stdout.close()
    with open_capture(path) as cap:
        n = cap.num_frames
        assert n >= flushed_before_kill
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, n))
        np.testing.assert_array_equal(cap.labels["index"], np.arange(n))
        np.testing.assert_array_equal(cap.timestamps, 1e9 + np.arange(n))


def test_append_accepts_counts_on_any_device(tmp_path, tiny_config, device):
    counts = torch.from_numpy(pattern_counts(tiny_config, 3).astype(np.int32)).to(device)
    path = write_capture(tmp_path / "dev.h5", counts, tiny_config)
    with open_capture(path) as cap:
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, 3))


def test_discard_leaves_nothing_before_the_first_frame_and_keeps_frames_after(tmp_path, tiny_config) -> None:
    path = tmp_path / "d.h5"
    path.write_text("earlier file")
    CaptureWriter(path, tiny_config).discard()  # nothing appended: the earlier file stays, no temporary left
    assert path.read_text() == "earlier file" and sorted(p.name for p in tmp_path.iterdir()) == ["d.h5"]
    w = CaptureWriter(path, tiny_config)
    w.append(frame_pattern(tiny_config, 0))
    w.discard()  # appended: closed as by close(), the frame is kept
    with open_capture(path) as cap:
        assert cap.num_frames == 1


def test_a_killed_writers_partial_file_is_removed_by_the_next_writer(tmp_path, tiny_config):
    # A writer killed before its first frame leaves its hidden temporary; the next writer of the same
    # name removes it when it is unlocked and older than STALE_PARTIAL_S, and leaves any other alone.
    from radaraug.io.hdf5_recovery import hold_writer_lock, release_writer_lock
    from radaraug.io.hdf5_writer import STALE_PARTIAL_S

    out = tmp_path / "rec.h5"
    old = time.time() - 2 * STALE_PARTIAL_S
    stale = tmp_path / ".rec.h5.111.aaaaaaaa.partial"
    recent = tmp_path / ".rec.h5.222.bbbbbbbb.partial"
    locked = tmp_path / ".rec.h5.333.cccccccc.partial"
    other = tmp_path / ".other.h5.444.dddddddd.partial"
    for p in (stale, recent, locked, other):
        p.write_bytes(b"")
    for p in (stale, locked, other):
        os.utime(p, (old, old))
    fd = hold_writer_lock(locked)  # a live writer's lock (another open file description)
    try:
        with CaptureWriter(out, tiny_config) as w:
            w.append(torch.as_tensor(pattern_counts(tiny_config, 1)))
    finally:
        release_writer_lock(fd)
    assert not stale.exists()
    assert recent.exists() and locked.exists() and other.exists()
    with open_capture(out) as cap:
        assert cap.num_frames == 1
