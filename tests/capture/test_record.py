"""record(): device -> radaraug HDF5 capture through CaptureWriter; refusals come before the device starts."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
import torch

from radaraug.capture import Frame, RadarDevice, VirtualSensor, record
from radaraug.errors import CaptureError, DeviceError
from radaraug.io import RadarCaptureDataset, hdf5_writer, open_capture
from radaraug.units import counts_to_float, float_to_counts


class ScriptedDevice(RadarDevice):
    """Frames with the given indices (a gap is a dropped frame); frame ``i`` is filled with code ``i``;
    ``fail_at``: reading the ``fail_at``-th frame raises (a board unplugged)."""

    def __init__(self, config, indices, fail_at=None):
        super().__init__()
        self._config, self.indices, self.fail_at = config, list(indices), fail_at
        self.started = 0
        self._pos = 0

    @property
    def config(self):
        return self._config

    @property
    def info(self):
        return {"kind": "scripted", "name": "scripted device"}

    def _open(self):
        self.started += 1
        self._pos = 0

    def _read(self):
        if self.fail_at is not None and self._pos == self.fail_at:
            raise DeviceError("scripted device: USB transfer failed")
        i = self.indices[self._pos]
        self._pos += 1
        c = self._config
        data = counts_to_float(torch.full((c.num_rx, c.num_chirps_per_frame, c.num_samples_per_chirp), i))
        return Frame(data, i * c.frame_repetition_time_s, i)

    def _close(self):
        pass


def test_a_recording_opens_as_a_capture_dataset_and_equals_the_stream(tmp_path, cfg) -> None:
    path = tmp_path / "walk.h5"
    result = record(VirtualSensor("corridor", config=cfg, seed=1, realtime=False), path, seconds=1.0, label=2)
    assert result.frames == 20 == result.requested and result.dropped == 0 and not result.interrupted
    ds = RadarCaptureDataset(path, label="count")  # no conversion
    assert len(ds) == 20 and ds.config == cfg
    x, y = ds[7]
    want = VirtualSensor("corridor", config=cfg, seed=1).frames(0, 20)
    assert y == 2 and torch.equal(x, counts_to_float(float_to_counts(want[7])))
    with open_capture(path) as cap:
        assert np.array_equal(cap.read(as_float=False).numpy(), float_to_counts(want).numpy())
        assert np.allclose(np.diff(cap.timestamps), cfg.frame_repetition_time_s)
        assert set(cap.labels["occupancy"].tolist()) == {1}
        assert json.loads(cap.attrs["device"])["kind"] == "virtual"


def test_dropped_frames_are_counted_from_index_gaps(tmp_path, cfg) -> None:
    dev = ScriptedDevice(cfg, [0, 1, 3, 4, 7, 8])
    result = record(dev, tmp_path / "d.h5", frames=8)
    assert (result.frames, result.dropped) == (5, 3)  # 2, 5, 6 missing; 8 is past the 8 frames asked
    with open_capture(tmp_path / "d.h5") as cap:
        assert cap.read(as_float=False)[:, 0, 0, 0].tolist() == [0, 1, 3, 4, 7]


def test_full_disk_is_refused_before_the_device_starts(tmp_path, cfg, monkeypatch) -> None:
    free = shutil.disk_usage(tmp_path)._replace(free=512 * 1024)
    monkeypatch.setattr(hdf5_writer.shutil, "disk_usage", lambda p: free)
    dev = ScriptedDevice(cfg, range(100))
    with pytest.raises(CaptureError, match="not enough space.*nothing was written"):
        record(dev, tmp_path / "big.h5", seconds=600)
    assert dev.started == 0 and list(tmp_path.iterdir()) == []


def test_unwritable_or_existing_output_is_refused_before_the_device_starts(tmp_path, cfg) -> None:
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    dev = ScriptedDevice(cfg, range(10))
    with pytest.raises(CaptureError, match="cannot create its folder"):
        record(dev, blocker / "out.h5", frames=3)
    with pytest.raises(CaptureError, match="exists.*--overwrite"):
        record(dev, blocker, frames=3)
    (tmp_path / "d").mkdir()
    with pytest.raises(CaptureError, match="is a folder"):
        record(dev, tmp_path / "d", frames=3, overwrite=True)
    assert dev.started == 0 and blocker.read_text() == "x"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", "d"]


def test_a_device_lost_mid_recording_keeps_the_frames_before(tmp_path, cfg) -> None:
    path = tmp_path / "lost.h5"
    with pytest.raises(DeviceError, match="keeps the 3 frames"):
        record(ScriptedDevice(cfg, range(10), fail_at=3), path, frames=10)
    with open_capture(path) as cap:
        assert cap.num_frames == 3


def test_a_device_that_cannot_start_leaves_no_file(tmp_path, cfg) -> None:
    class Broken(ScriptedDevice):
        def _open(self):
            raise DeviceError("cannot open the board")

    with pytest.raises(DeviceError, match="no frame was recorded"):
        record(Broken(cfg, range(3)), tmp_path / "none.h5", frames=3)
    assert list(tmp_path.iterdir()) == []
