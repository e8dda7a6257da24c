"""RDClassifier takes its network as an object: the default ResNet18, or any backbone factory."""

from __future__ import annotations

import functools

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.training import RDClassifier, TorchvisionClassifier


def test_default_is_the_papers_resnet18_with_one_output_per_class():
    model = RDClassifier(task="counting")
    assert type(model.net).__name__ == "ResNet" and model.net.fc.out_features == 3
    # the checkpoint keys of earlier runs (net.*) are unchanged
    assert "net.conv1.weight" in model.state_dict()


def test_a_backbone_factory_gets_the_class_count():
    model = RDClassifier(task="occupancy", backbone=functools.partial(TorchvisionClassifier, arch="resnet18"))
    assert isinstance(model.net, TorchvisionClassifier)
    assert model(torch.rand(2, 3, 32, 16)).shape == (2, 2)
    assert "backbone" not in model.hparams  # an object: the saved config names it, not the hparams
    tiny = RDClassifier(task="counting", backbone=lambda k: torch.nn.Sequential(torch.nn.Flatten(),
                                                                                torch.nn.LazyLinear(k)))
    assert tiny(torch.rand(2, 3, 8, 4)).shape == (2, 3)


def test_an_unknown_torchvision_arch_is_one_error():
    with pytest.raises(ConfigError, match="resnet"):
        TorchvisionClassifier(2, arch="resnet_magic")
