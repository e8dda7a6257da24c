"""The one block writer of simulated captures (`radaraug.io.blocks`) and ``publish="close"``."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from radaraug_tests_io_data import pattern_counts

from radaraug.io import open_capture
from radaraug.io.blocks import BLOCK_FRAMES, COUNT_LABELS, BlockWriter, block_of, blocks_covering, frame_times


def test_block_arithmetic() -> None:
    assert BLOCK_FRAMES == 16  # part of every simulated frame's identity (its noise generator)
    assert block_of(15) == 0 and block_of(16) == 1
    assert list(blocks_covering(10, 40)) == [0, 1, 2]
    assert list(blocks_covering(16, 32)) == [1]
    t = frame_times(2, 5, 0.1)
    assert t.dtype == torch.float64 and torch.equal(t, torch.arange(2, 5, dtype=torch.float64) * 0.1)


def test_blocks_with_labels_and_resume(tmp_path, tiny_config) -> None:
    counts = pattern_counts(tiny_config, 5)
    out = tmp_path / "sim.h5"
    with BlockWriter.create(out, tiny_config, attrs={"source": "test"}) as w:
        w.write(counts[:3], torch.arange(3, dtype=torch.float64), np.array([0, 1, 2]))
        assert w.num_frames == 3
    with BlockWriter.resume(out, tiny_config) as w:
        w.write(torch.as_tensor(counts[3:]), np.array([3.0, 4.0]), torch.tensor([2, 0]))
    with open_capture(out) as cap:
        assert np.array_equal(cap.read(as_float=False).numpy(), counts)
        assert cap.labels["count"].tolist() == [0, 1, 2, 2, 0]
        assert cap.labels["occupancy"].tolist() == [0, 1, 1, 1, 0]
        assert set(cap.labels) == set(COUNT_LABELS)
        assert np.asarray(cap.timestamps).tolist() == [0.0, 1.0, 2.0, 3.0, 4.0]


def test_publish_on_close_appears_only_complete(tmp_path, tiny_config) -> None:
    counts = pattern_counts(tiny_config, 4)
    out = tmp_path / "gen.h5"
    out.write_bytes(b"an earlier run's file")
    with BlockWriter.create(out, tiny_config, publish="close") as w:
        w.write(counts[:2], [0.0, 0.1], [1, 1])
        assert out.read_bytes() == b"an earlier run's file"  # not replaced before the end
        assert len(list(tmp_path.glob(".gen.h5.*.partial"))) == 1
    with open_capture(out) as cap:
        assert cap.num_frames == 2
    assert list(tmp_path.glob(".gen.h5.*")) == []
    # An exception in the block: the temporary is dropped, the complete file stays.
    with pytest.raises(RuntimeError), BlockWriter.create(out, tiny_config, publish="close") as w:
        w.write(counts[2:], [0.2, 0.3], [0, 0])
        raise RuntimeError("stop")
    assert list(tmp_path.glob(".gen.h5.*")) == []
    with open_capture(out) as cap:
        assert cap.num_frames == 2
