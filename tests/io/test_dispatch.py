"""open_capture chooses the right reader."""

from __future__ import annotations

import shutil

import pytest

from radaraug.errors import CaptureError
from radaraug.io import HDF5Capture, InfineonRecording, open_capture


def test_dispatch_by_kind(h5_capture, infineon_recording, tmp_path):
    with open_capture(h5_capture) as cap:
        assert isinstance(cap, HDF5Capture)
    with open_capture(str(infineon_recording)) as cap:
        assert isinstance(cap, InfineonRecording)
    # An HDF5 capture under another suffix is recognised by its signature.
    other = shutil.copy(h5_capture, tmp_path / "capture.hdf")
    with open_capture(other) as cap:
        assert isinstance(cap, HDF5Capture)


def test_unknown_and_missing_paths(tmp_path):
    text = tmp_path / "notes.txt"
    text.write_text("hello")
    with pytest.raises(CaptureError, match="unknown capture type") as err:
        open_capture(text)
    assert str(text) in str(err.value)
    with pytest.raises(CaptureError, match="does not exist"):
        open_capture(tmp_path / "missing.h5")
