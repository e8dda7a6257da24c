"""RadarCaptureDataset (radaraug/io/dataset.py): indexing, labels, lazy files, spawn workers."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest
import torch
from radaraug_tests_io_data import pattern_counts, tiny_config
from torch.utils.data import DataLoader

from radaraug.errors import CaptureError
from radaraug.io import CaptureWarning, RadarCaptureDataset, write_capture


@pytest.fixture
def two_files(h5_capture, infineon_recording):
    """6 HDF5 frames (pattern 0..5) then 5 Infineon frames (pattern 0..4), same config."""
    return [h5_capture, infineon_recording]


def test_single_frames_across_files(two_files, tiny_config):
    ds = RadarCaptureDataset(two_files, as_counts=True)
    assert len(ds) == 11 and ds.config == tiny_config and ds.num_frames == [6, 5]
    assert ds[0].shape == (3, 4, 32) and ds[0].dtype == torch.int32
    expected = np.concatenate([pattern_counts(tiny_config, 6), pattern_counts(tiny_config, 5)])
    for i in range(len(ds)):
        np.testing.assert_array_equal(ds[i].numpy(), expected[i])
    np.testing.assert_array_equal(ds[-1].numpy(), expected[-1])
    assert ds.locate(7) == (Path(two_files[1]), 1)
    with pytest.raises(IndexError):
        ds[11]


@pytest.mark.parametrize(
    "stride, starts",
    [
        (None, [(0, 0), (0, 2), (0, 4), (1, 0), (1, 2)]),
        (1, [(0, i) for i in range(5)] + [(1, i) for i in range(4)]),
    ],
)
def test_windows_and_stride(two_files, tiny_config, stride, starts):
    # File 0 has 6 frames, file 1 has 5: (F - 2) // stride + 1 windows each (stride defaults to 2).
    ds = RadarCaptureDataset(two_files, frames_per_item=2, stride=stride, as_counts=True)
    assert len(ds) == len(starts)
    for i, (k, start) in enumerate(starts):
        window = ds[i]
        assert window.shape == (2, 3, 4, 32)
        np.testing.assert_array_equal(window.numpy(), pattern_counts(tiny_config, 2, first=start))
        assert ds.locate(i) == (Path(two_files[k]), start)
    assert ds.items_per_file == [sum(1 for k, _ in starts if k == f) for f in (0, 1)]


def test_float_items_are_sdk_floats(h5_capture, tiny_config):
    ds = RadarCaptureDataset(h5_capture)
    x = ds[3]
    assert x.dtype == torch.float32
    expected = 2 * torch.from_numpy(pattern_counts(tiny_config, 1, first=3)[0]).double() / 4095 - 1
    torch.testing.assert_close(x.double(), expected, rtol=0, atol=1e-6)


def test_named_label_takes_the_last_frame_of_a_window(h5_capture):
    ds = RadarCaptureDataset(h5_capture, frames_per_item=3, label="count")
    # labels/count = [0, 0, 1, 1, 2, 2]; windows [0..2] and [3..5].
    assert [ds[i][1] for i in range(len(ds))] == [1, 2]
    ds_room = RadarCaptureDataset(h5_capture, label="room")  # file-level label
    assert {ds_room[i][1] for i in range(len(ds_room))} == {3}


def test_named_label_missing_from_a_file(two_files):
    with pytest.raises(CaptureError, match="has no label 'count'") as err:
        RadarCaptureDataset(two_files, label="count")
    assert str(two_files[1]) in str(err.value)


def test_constant_dict_and_callable_labels(two_files):
    ds = RadarCaptureDataset(two_files, label=7, target_transform=lambda y: y + 1)
    assert ds[0][1] == 8 and ds[10][1] == 8
    ds = RadarCaptureDataset(two_files, label={str(two_files[0]): "empty", two_files[1]: "person"})
    assert ds[5][1] == "empty" and ds[6][1] == "person"
    with pytest.raises(CaptureError, match="no entry in the label dict"):
        RadarCaptureDataset(two_files, label={str(two_files[0]): 0})
    calls = []

    def label(path, frame):
        calls.append((Path(path), frame))
        return frame * 10

    ds = RadarCaptureDataset(two_files, frames_per_item=2, label=label, transform=lambda x: x.sum())
    x, y = ds[4]
    assert y == 30 and calls[-1] == (Path(two_files[1]), 3)
    assert x.ndim == 0


def test_files_with_different_configs_are_refused(tmp_path, h5_capture):
    other = tiny_config(if_gain_dB=40)
    path = write_capture(tmp_path / "other.h5", pattern_counts(other, 3), other)
    with pytest.raises(CaptureError, match="different radar configurations.*if_gain_dB") as err:
        RadarCaptureDataset([h5_capture, path])
    assert str(path) in str(err.value) and str(h5_capture) in str(err.value)


def test_short_files_and_bad_arguments(tmp_path, h5_capture, tiny_config):
    short = write_capture(tmp_path / "short.h5", pattern_counts(tiny_config, 2), tiny_config)
    with pytest.warns(CaptureWarning, match="fewer than frames_per_item"):
        ds = RadarCaptureDataset([short, h5_capture], frames_per_item=3)
    assert len(ds) == 2
    with pytest.warns(CaptureWarning), pytest.raises(CaptureError, match="no file holds a window"):
        RadarCaptureDataset(short, frames_per_item=3)
    with pytest.raises(CaptureError, match="frames_per_item"):
        RadarCaptureDataset(h5_capture, frames_per_item=0)
    with pytest.raises(CaptureError, match="no capture paths"):
        RadarCaptureDataset([])
    with pytest.raises(CaptureError, match="does not exist"):
        RadarCaptureDataset(tmp_path / "missing.h5")


def test_lazy_handles_are_not_pickled_and_lru_bounded(two_files, tiny_config):
    ds = RadarCaptureDataset(two_files, as_counts=True, max_open_files=1)
    assert len(ds._readers) == 0  # nothing open after construction
    ds[0]
    ds[10]
    assert len(ds._readers) == 1
    clone = pickle.loads(pickle.dumps(ds))
    assert len(clone._readers) == 0
    np.testing.assert_array_equal(clone[2].numpy(), pattern_counts(tiny_config, 1, first=2)[0])
    ds.close()
    clone.close()


def test_dataloader_with_spawned_workers(two_files, tiny_config):
    ds = RadarCaptureDataset(
        two_files, frames_per_item=2, stride=1, label={str(p): i for i, p in enumerate(two_files)}
    )
    ds[0]  # hold an open HDF5 handle in the parent: it must not travel to the workers
    loader = DataLoader(ds, batch_size=3, num_workers=2, multiprocessing_context="spawn")
    xs, ys = zip(*loader)
    x, y = torch.cat(xs), torch.cat(ys)
    assert x.shape == (9, 2, 3, 4, 32)
    assert y.tolist() == [0] * 5 + [1] * 4
    expected = torch.stack([ds[i][0] for i in range(len(ds))])
    torch.testing.assert_close(x, expected)


