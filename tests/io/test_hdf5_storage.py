"""HDF5 captures that declare more than they store, or point elsewhere: links are refused,
unwritten chunks never read as data, and declared sizes never size an allocation."""

from __future__ import annotations

import contextlib
import json
import time

import h5py
import numpy as np
import pytest
from radaraug_tests_io_data import pattern_counts

from radaraug.errors import CaptureError
from radaraug.io import CaptureWarning, RadarCaptureDataset, open_capture
from radaraug.transforms.summary import summarize_capture


def _edit(path, edit) -> None:
    with h5py.File(path, "r+") as f:
        edit(f)


def _relink(name, link):
    def edit(f):
        del f[name]
        f[name] = link

    return edit


@pytest.mark.parametrize(
    "edit, fragment",
    [
        (_relink("frames", h5py.SoftLink("/frames")), "'frames' is a soft link"),
        (_relink("timestamps", h5py.SoftLink("/nowhere")), "'timestamps' is a soft link"),
        (_relink("labels/count", h5py.SoftLink("/nowhere")), "'labels/count' is a soft link"),
    ],
)
def test_soft_links_are_refused(h5_capture, edit, fragment) -> None:
    _edit(h5_capture, edit)
    with pytest.raises(CaptureError, match=fragment):
        open_capture(h5_capture)


def test_external_links_are_refused(h5_capture, tmp_path) -> None:
    other = tmp_path / "other.h5"
    other.write_bytes(h5_capture.read_bytes())
    _edit(h5_capture, _relink("frames", h5py.ExternalLink(str(other), "/frames")))
    with pytest.raises(CaptureError, match="external link"):
        open_capture(h5_capture)


def _without_count(f) -> None:
    """A file from a writer that keeps no ``frames_written`` count (format 1.0, other tools): only
    the stored chunks tell which frames hold data."""
    if "frames_written" in f:
        del f["frames_written"]


def test_frames_past_the_committed_count_are_not_served(h5_capture, tiny_config) -> None:
    # radaraug's writer extends, writes, flushes, then commits the count: a kill in between
    # leaves declared frames past the count, which are never served (with a warning).
    _edit(h5_capture, lambda f: f["frames"].resize(9, axis=0))
    with pytest.warns(CaptureWarning, match=r"frames 6\.\.8 were declared but never written .*'frames_written'"):
        cap = open_capture(h5_capture)
    with cap:
        assert cap.num_frames == 6


def test_trailing_unwritten_frames_are_not_served(h5_capture, tiny_config) -> None:
    def edit(f):
        _without_count(f)
        f["frames"].resize(9, axis=0)  # frames 6..8 have no chunk

    _edit(h5_capture, edit)
    with pytest.warns(CaptureWarning, match="frames 6..8 were declared but never written"):
        cap = open_capture(h5_capture)
    with cap:
        assert cap.num_frames == 6
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, 6))


def test_an_unwritten_frame_between_written_ones_is_an_error(h5_capture) -> None:
    def gap(f):
        _without_count(f)
        f["frames"].resize(12, axis=0)
        f["frames"][11] = f["frames"][0]
        f["timestamps"].resize(12, axis=0)
        f["labels/count"].resize(12, axis=0)

    _edit(h5_capture, gap)
    with pytest.raises(CaptureError, match=r"frames 6\.\.10 of 12 were never written"):
        open_capture(h5_capture)


def test_unallocated_contiguous_frames_are_an_error(h5_capture) -> None:
    def contiguous(f):
        shape = f["frames"].shape
        del f["frames"]
        f.create_dataset("frames", shape=shape, dtype=np.uint16)  # never written: fill values

    _edit(h5_capture, contiguous)
    with pytest.raises(CaptureError, match="none of its 6 frames was ever written"):
        open_capture(h5_capture)


@pytest.mark.parametrize(
    "edit, warns",
    [
        (lambda f: f["frames"].resize(2**40, axis=0), "never written"),
        (lambda f: f["timestamps"].resize(2**31, axis=0), None),
        (lambda f: f["labels/count"].resize(2**31, axis=0), None),
    ],
)
def test_huge_declared_sizes_cost_nothing(h5_capture, edit, warns) -> None:
    """A 30 kB file declaring 2**40 frames or 2**31 timestamps/labels reads its real content,
    in well under a second, allocating nothing for the declared size."""
    _edit(h5_capture, edit)
    t = time.monotonic()
    with pytest.warns(CaptureWarning) if warns else contextlib.nullcontext():
        cap = open_capture(h5_capture)
    with cap:
        assert cap.num_frames == 6
        assert len(cap.timestamps) == 6 and cap.duration_s == pytest.approx(0.06)
        assert len(cap.labels["count"]) == 6
        summarize_capture(cap)
    assert time.monotonic() - t < 2


def test_unwritten_timestamps_are_dropped_not_served(h5_capture) -> None:
    def ts_gap(f):
        _without_count(f)
        f["frames"].resize(9, axis=0)
        for i in range(6, 9):
            f["frames"][i] = f["frames"][0]
        f["labels/count"].resize(9, axis=0)
        f["labels/count"][6:] = 2
        f["timestamps"].resize(9, axis=0)  # timestamps 6..8 stay unwritten (fill value 0)

    _edit(h5_capture, ts_gap)
    # Storage is known per chunk: rows 6..8 share a stored chunk with rows 0..5, so they read as
    # the fill value 0, which the monotonic check catches (a later timestamp cannot be earlier).
    with pytest.warns(CaptureWarning, match="never written|go backwards"):
        cap = open_capture(h5_capture)
    with cap:
        assert cap.timestamps is None and cap.duration_s > 0


def test_backwards_timestamps_are_dropped_with_a_warning(h5_capture) -> None:
    _edit(h5_capture, lambda f: f["timestamps"].__setitem__(slice(None), 1.7e9 - np.arange(6.0)))
    with pytest.warns(CaptureWarning, match="timestamps go backwards"):
        cap = open_capture(h5_capture)
    with cap:
        assert cap.timestamps is None and cap.duration_s == pytest.approx(0.06)


@pytest.mark.parametrize(
    "labels, fragment",
    [
        ('{"who": null}', "label 'who' is NoneType"),
        ('{"who": {"a": 1}}', "label 'who' is dict"),
        ('{"who": [1, "a", 2, 3, 4, 5]}', "mixes kinds"),
        ('{"who": [[1], [2], [3], [4], [5], [6]]}', "holds \\['list'\\] values"),
    ],
)
def test_unusable_file_labels_are_an_error(h5_capture, labels, fragment) -> None:
    _edit(h5_capture, lambda f: f.attrs.__setitem__("labels", labels))
    with pytest.raises(CaptureError, match=fragment):
        open_capture(h5_capture)


def test_empty_label_attribute_is_an_error(h5_capture) -> None:
    _edit(h5_capture, lambda f: f.attrs.__setitem__("label_x", h5py.Empty("f8")))
    with pytest.raises(CaptureError, match="label 'x' is NoneType"):
        RadarCaptureDataset([h5_capture])


def test_string_per_frame_labels_are_an_error(h5_capture) -> None:
    def strings(f):
        del f["labels/count"]
        f.create_dataset("labels/count", data=[b"a"] * 6)

    _edit(h5_capture, strings)
    with pytest.raises(CaptureError, match="per-frame labels must be numbers or bools"):
        open_capture(h5_capture)


@pytest.mark.parametrize("bits", [64, 1000])
def test_implausible_adc_bits_are_refused(h5_capture, bits) -> None:
    def edit(f):
        cfg = json.loads(f.attrs["radar_config"])
        cfg["adc_bits"] = bits
        f.attrs["radar_config"] = json.dumps(cfg)

    _edit(h5_capture, edit)
    with pytest.raises(CaptureError, match="adc_bits must be a positive integer in 8..16"):
        open_capture(h5_capture)
