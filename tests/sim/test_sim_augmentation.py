"""SimulatedRadarDataset with the docs' random transform chain: per-item reproducible augmentation."""

from __future__ import annotations

import pytest
import torch
from torch.utils.data import DataLoader

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels

FAST = {"tracer_options": {"rays": 48}}


def _items(ds, workers: int) -> torch.Tensor:
    return torch.cat([x for x, _ in DataLoader(ds, batch_size=2, num_workers=workers, shuffle=False)])


def test_item_i_is_the_same_with_0_and_2_workers_and_changes_with_the_epoch() -> None:
    chain = RadarCompose([RangeDoppler(), ToDecibels(), CalibratedDR(-95.0, 4.0)])
    small = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16, sample_rate_Hz=2e6,
                                   chirp_repetition_time_s=100e-6, frame_repetition_time_s=0.05)
    ds = SimulatedRadarDataset("corridor", length=4, seed=3, config=small, twin_options=FAST, transform=chain,
                               augmentation="per_item").prepare()
    ref = _items(ds, 0)
    assert torch.equal(_items(ds, 2), ref)
    ds.set_epoch(1)
    assert not torch.equal(ds[0][0], ref[0])
    ds.set_epoch(0)
    assert torch.equal(ds[2][0], ref[2])
    with pytest.raises(ConfigError, match="augmentation"):
        SimulatedRadarDataset("corridor", augmentation="sometimes")
