"""HDF5Capture: reading, units, and every way a file can be bad."""

from __future__ import annotations

import json
import pickle
import warnings

import h5py
import numpy as np
import pytest
import torch
from radaraug_tests_io_data import pattern_counts, tiny_config, tone_counts

from radaraug.errors import CaptureError, ConfigError
from radaraug.io import CaptureWarning, CaptureWriter, HDF5Capture, open_capture, write_capture


def _expect_error(path, fragment):
    with pytest.raises(CaptureError, match=fragment) as err:
        open_capture(path)
    assert str(path) in str(err.value)
    return err.value


def _mutate(path, change):
    with h5py.File(path, "r+") as f:
        change(f)
    return path


def test_reads_frames_labels_and_timestamps(h5_capture, tiny_config):
    with open_capture(h5_capture) as cap:
        assert isinstance(cap, HDF5Capture)
        assert cap.config == tiny_config
        assert cap.shape == (6, 3, 4, 32) and len(cap) == 6 and cap.num_frames == 6
        np.testing.assert_array_equal(
            cap.read(2, 4, as_float=False).numpy(), pattern_counts(tiny_config, 2, first=2)
        )
        np.testing.assert_array_equal(
            cap.read(-2, as_float=False).numpy(), pattern_counts(tiny_config, 2, first=4)
        )
        np.testing.assert_array_equal(cap.labels["count"], [0, 0, 1, 1, 2, 2])
        np.testing.assert_array_equal(cap.labels["room"], [3] * 6)  # file-level label, broadcast
        np.testing.assert_allclose(cap.timestamps, 1.7e9 + 0.01 * np.arange(6))
        assert cap.duration_s == pytest.approx(0.06)
        assert cap.attrs["description"] == "frame pattern"
        assert cap[5].shape == (3, 4, 32) and cap[1:3].shape == (2, 3, 4, 32)
        torch.testing.assert_close(cap[-1], cap.read(5, 6)[0])


def test_float_and_count_units_follow_the_sdk_convention(h5_capture):
    with open_capture(h5_capture) as cap:
        counts = cap.read(as_float=False)
        floats = cap.read()
    assert counts.dtype == torch.int32 and floats.dtype == torch.float32
    expected = 2.0 * counts.double() / 4095.0 - 1.0
    torch.testing.assert_close(floats.double(), expected, rtol=0, atol=1e-6)
    assert floats.min() >= -1 and floats.max() <= 1


def test_point_target_lands_in_its_range_bin(tmp_path):
    """A tone written at R = 5 * range resolution peaks in range bin 5 with amplitude A/2."""
    config = tiny_config(num_samples_per_chirp=64)
    amplitude = 600.0
    path = write_capture(
        tmp_path / "tone.h5", tone_counts(config, 3, range_bin=5, amplitude_counts=amplitude), config
    )
    with open_capture(path) as cap:
        x = cap.read().double()
    x = x - x.mean(dim=-1, keepdim=True)
    spectrum = torch.fft.rfft(x, dim=-1).abs() / config.num_samples_per_chirp
    assert torch.all(spectrum.argmax(dim=-1) == 5)
    # A real tone of amplitude a splits into a/2 at +f and -f; a is 2*A/4095 in SDK floats.
    torch.testing.assert_close(
        spectrum[..., 5].mean(), torch.tensor(amplitude / 4095, dtype=torch.float64), rtol=0.01, atol=0
    )


def test_bad_read_ranges_and_closed_reader(h5_capture):
    cap = open_capture(h5_capture)
    for start, stop in [(4, 4), (0, 7), (6, None), (-7, None)]:
        with pytest.raises(CaptureError, match="cannot read frames"):
            cap.read(start, stop)
    with pytest.raises(IndexError):
        cap[6]
    with pytest.raises(CaptureError, match="step 1"):
        cap[::2]
    cap.close()
    cap.close()  # idempotent
    with pytest.raises(CaptureError, match="closed"):
        cap.read()


def test_reader_pickles_by_reopening(h5_capture):
    with open_capture(h5_capture) as cap:
        clone = pickle.loads(pickle.dumps(cap))
        torch.testing.assert_close(clone.read(), cap.read())
        clone.close()


# --------------------------------------------------------------------------- bad files
def test_missing_file(tmp_path):
    _expect_error(tmp_path / "nope.h5", "does not exist")


def test_garbage_bytes(tmp_path):
    path = tmp_path / "garbage.h5"
    path.write_bytes(b"this is not HDF5 at all " * 100)
    _expect_error(path, "not an HDF5 file")


def test_truncated_to_half(h5_capture):
    data = h5_capture.read_bytes()
    h5_capture.write_bytes(data[: len(data) // 2])
    _expect_error(h5_capture, "truncated")


def test_corrupted_chunk_is_reported_on_read(tmp_path, tiny_config):
    path = write_capture(tmp_path / "c.h5", pattern_counts(tiny_config, 6), tiny_config)
    with h5py.File(path, "r") as f:
        info = f["frames"].id.get_chunk_info(3)
    raw = bytearray(path.read_bytes())
    raw[info.byte_offset : info.byte_offset + info.size] = b"\xff" * info.size
    path.write_bytes(bytes(raw))
    with open_capture(path) as cap:  # first and last frame are intact
        cap.read(0, 3)
        with pytest.raises(CaptureError, match="corrupt") as err:
            cap.read(2, 5)
    assert str(path) in str(err.value)


def test_not_a_radaraug_capture(tmp_path):
    path = tmp_path / "other.h5"
    with h5py.File(path, "w") as f:
        f["frames"] = np.zeros((2, 3, 4, 32), np.uint16)
    _expect_error(path, "not a radaraug capture")


def test_unsupported_major_version(h5_capture):
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("format_version", "2.0"))
    _expect_error(h5_capture, "unsupported format_version")


def test_minor_version_is_accepted(h5_capture):
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("format_version", "1.7"))
    with open_capture(h5_capture) as cap:
        assert cap.num_frames == 6


def test_missing_frames_dataset(h5_capture):
    _mutate(h5_capture, lambda f: f.__delitem__("frames"))
    _expect_error(h5_capture, "no 'frames' dataset")


def _replace_frames(data):
    def change(f):
        del f["frames"]
        f["frames"] = data

    return change


def test_frames_of_wrong_dtype(h5_capture):
    _mutate(h5_capture, _replace_frames(np.zeros((6, 3, 4, 32), np.float32)))
    _expect_error(h5_capture, "dtype float32")


def test_frames_of_wrong_rank(h5_capture):
    _mutate(h5_capture, _replace_frames(np.zeros((6, 12, 32), np.uint16)))
    _expect_error(h5_capture, "4-D")


@pytest.mark.parametrize(
    "shape, axis", [((6, 2, 4, 32), "rx"), ((6, 3, 8, 32), "chirps"), ((6, 3, 4, 16), "samples")]
)
def test_frames_not_matching_config(h5_capture, shape, axis):
    _mutate(h5_capture, _replace_frames(np.zeros(shape, np.uint16)))
    _expect_error(h5_capture, f"{axis} .*radar_config says")


def test_radar_config_missing(h5_capture):
    _mutate(h5_capture, lambda f: f.attrs.__delitem__("radar_config"))
    _expect_error(h5_capture, "no 'radar_config'")


def test_radar_config_not_json(h5_capture):
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("radar_config", "{not json"))
    _expect_error(h5_capture, "not valid JSON")


def test_radar_config_invalid_is_wrapped_with_the_config_error_chained(h5_capture, tiny_config):
    bad = dict(tiny_config.to_dict(), end_frequency_Hz=59e9)
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("radar_config", json.dumps(bad)))
    err = _expect_error(h5_capture, "radar_config' is invalid.*end_frequency_Hz")
    assert isinstance(err.__cause__, ConfigError)


def test_empty_capture(tmp_path, tiny_config):
    path = tmp_path / "empty.h5"
    CaptureWriter(path, tiny_config).close()
    _expect_error(path, "empty capture")


def test_adc_codes_above_full_scale_are_an_error_on_read(tmp_path, tiny_config):
    counts = pattern_counts(tiny_config, 6)
    path = write_capture(tmp_path / "hot.h5", counts, tiny_config)

    def poke(f):
        f["frames"][2, 1, 0, 0] = 5000

    _mutate(path, poke)
    with open_capture(path) as cap:
        cap.read(0, 2)
        with pytest.raises(CaptureError, match="frame 2 holds ADC code 5000 outside 0..4095"):
            cap.read()


def test_fewer_timestamps_than_frames_warns_and_drops_them(h5_capture):
    def shorten(f):
        f["timestamps"].resize((4,))

    _mutate(h5_capture, shorten)
    with pytest.warns(CaptureWarning, match="4 timestamps for 6 frames"):
        cap = open_capture(h5_capture)
    assert cap.timestamps is None
    assert cap.duration_s == pytest.approx(6 * cap.config.frame_repetition_time_s)
    cap.close()


def test_extra_timestamps_and_labels_of_an_interrupted_append_are_trimmed(h5_capture):
    def grow(f):
        f["timestamps"].resize((7,))
        f["labels/count"].resize((7,))

    _mutate(h5_capture, grow)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with open_capture(h5_capture) as cap:
            assert len(cap.timestamps) == 6 and len(cap.labels["count"]) == 6


def test_short_per_frame_label_is_an_error(h5_capture):
    _mutate(h5_capture, lambda f: f["labels/count"].resize((3,)))
    _expect_error(h5_capture, "label 'labels/count' has 3 values for 6 frames")


def test_bad_file_level_labels(h5_capture):
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("labels", "[1, 2"))
    _expect_error(h5_capture, "'labels' is not valid JSON")
    _mutate(h5_capture, lambda f: f.attrs.__setitem__("labels", json.dumps({"count": [1, 2]})))
    _expect_error(h5_capture, "label 'count' has shape")


@pytest.mark.parametrize(
    "damage, fragment",
    [
        (lambda f: f["timestamps"].__setitem__(2, np.nan), "NaN or Inf"),
        (lambda f: (f.__delitem__("timestamps"), f.create_group("timestamps")), "not a dataset"),
        (
            lambda f: (f.__delitem__("timestamps"), f.create_dataset("timestamps", data=np.array([b"x"] * 6))),
            "expected float64",
        ),
        (
            lambda f: (f.__delitem__("timestamps"), f.create_dataset("timestamps", data=np.zeros((6, 2)))),
            "expected float64",
        ),
    ],
    ids=["nan", "group", "strings", "2-D"],
)
def test_unusable_timestamps_warn_and_are_dropped(h5_capture, damage, fragment):
    # Before: a bare TypeError/ValueError from h5py/numpy, or NaN durations / a flattened 2-D array.
    _mutate(h5_capture, damage)
    with pytest.warns(CaptureWarning, match=fragment):
        cap = open_capture(h5_capture)
    with cap:
        assert cap.timestamps is None
        assert cap.duration_s == pytest.approx(6 * cap.config.frame_repetition_time_s)
        assert cap.read().shape[0] == 6  # the frames stay readable
