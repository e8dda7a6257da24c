"""RadarCaptureDataset with the docs' random transform chain: per-item reproducible augmentation."""

from __future__ import annotations

import pytest
import torch
from torch.utils.data import DataLoader

from radaraug.errors import CaptureError
from radaraug.io import RadarCaptureDataset
from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels


def _chain() -> RadarCompose:
    # The docs' chain; the DR level is high so that its noise replaces most cells.
    return RadarCompose([RangeDoppler(), ToDecibels(), CalibratedDR(-40.0, 6.0)])


def _items(ds, workers: int) -> torch.Tensor:
    loader = DataLoader(ds, batch_size=2, num_workers=workers, shuffle=False)
    return torch.cat([x for x, _ in loader])


def test_per_item_augmentation_is_the_same_with_any_number_of_workers(h5_capture) -> None:
    ds = RadarCaptureDataset(h5_capture, label="count", transform=_chain(), augmentation="per_item",
                             augmentation_seed=5)
    ref = _items(ds, 0)
    assert torch.equal(_items(ds, 2), ref)
    assert torch.equal(ds[3][0], ref[3])  # and read alone, in any order
    assert not torch.equal(ref[0], ref[1])
    ds.set_epoch(1)
    other = _items(ds, 2)
    assert not torch.equal(other, ref)  # a new epoch, new augmentation
    assert torch.equal(other, _items(ds, 0))
    ds.set_epoch(0)
    assert torch.equal(_items(ds, 0), ref)
    seed6 = RadarCaptureDataset(h5_capture, label="count", transform=_chain(), augmentation="per_item",
                                augmentation_seed=6)
    assert not torch.equal(_items(seed6, 0), ref)


def test_stream_mode_depends_on_the_worker_split(h5_capture) -> None:
    # The default mode (kept): each worker draws its own stream, so item i differs with num_workers.
    ds = RadarCaptureDataset(h5_capture, label="count", transform=_chain())
    torch.manual_seed(0)
    zero = _items(ds, 0)
    torch.manual_seed(0)
    two = _items(ds, 2)
    assert not torch.equal(zero, two)


def test_bad_augmentation_arguments(h5_capture) -> None:
    with pytest.raises(CaptureError, match="augmentation must be"):
        RadarCaptureDataset(h5_capture, augmentation="worker")
    with pytest.raises(CaptureError, match="augmentation_seed"):
        RadarCaptureDataset(h5_capture, augmentation_seed=1.5)
    with pytest.raises(CaptureError, match="epoch"):
        RadarCaptureDataset(h5_capture).set_epoch(-1)
