"""The training chain's inputs: sizes and clip ranges are checked where they are given."""

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.training.chain import image_chain
from radaraug.training.data import RadarDataModule


def test_image_size_must_be_height_and_width():
    x = torch.full((2, 3, 8, 4), -90.0)
    assert image_chain(-120.0, -60.0, [6, 5])(x).shape == (2, 3, 6, 5)
    with pytest.raises(ConfigError, match=r"\[H, W\]"):
        image_chain(-120.0, -60.0, [6, 5, 4])


def test_clip_range_must_be_two_values_and_setup_must_run_first():
    with pytest.raises(ConfigError, match=r"\[vmin, vmax\]"):
        RadarDataModule(clip_range=[-120.0])
    dm = RadarDataModule(clip_range=[-120.0, -60.0])
    assert dm.clip == (-120.0, -60.0)
    with pytest.raises(ConfigError, match="setup"):
        dm.images(torch.zeros(1, 3, 8, 4))
    dm.load_state_dict({"clip_range": [-110.0, -50.0]})
    assert dm.clip == (-110.0, -50.0) and dm.state_dict() == {"clip_range": [-110.0, -50.0]}
