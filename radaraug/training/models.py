"""Classifier backbones for :class:`~radaraug.training.RDClassifier` (``model.backbone`` in a recipe).

A backbone is a callable taking the class count and returning a module from ``(B, 3, H, W)`` images
to ``(B, classes)`` logits; docs/training.md shows it in a recipe.
"""

from __future__ import annotations

import torchvision
from torch import nn

from radaraug.errors import ConfigError


def resnet18(num_classes: int) -> nn.Module:
    """The paper's network: torchvision ResNet18, random initialization (the default backbone)."""
    # weights=None: torchvision refuses pretrained weights with num_classes != 1000.
    return torchvision.models.resnet18(weights=None, num_classes=num_classes)


class TorchvisionClassifier(nn.Module):
    """Any torchvision classification network by name, randomly initialized, with ``num_classes`` outputs.

    Args:
        num_classes: outputs (given by the task).
        arch: a name of ``torchvision.models.list_models(torchvision.models)`` (``resnet34``, ``efficientnet_b0``...).
    """

    def __init__(self, num_classes: int, arch: str = "resnet18") -> None:
        super().__init__()
        names = torchvision.models.list_models(torchvision.models)
        if arch not in names:
            raise ConfigError(f"backbone arch {arch!r} is not a torchvision classification model; e.g. "
                              f"{', '.join(n for n in names if n.startswith('resnet'))}")
        self.arch = arch
        # No pretrained weights: nothing is downloaded at run time (and RD images are not ImageNet's).
        self.net = torchvision.models.get_model(arch, weights=None, num_classes=num_classes)

    def forward(self, x):  # noqa: ANN001, ANN201 - nn.Module's signature
        """Logits ``(B, num_classes)`` of images ``x`` ``(B, 3, H, W)``."""
        return self.net(x)
