"""Fixtures of the inference tests: small classifiers at a config the twin simulates in milliseconds."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.inference import ChainSpec, RadarClassifier
from radaraug.io import write_capture
from radaraug.scene.scene import Scene
from radaraug.training.models import resnet18
from radaraug.units import float_to_counts

RD = {"range_window": "hann", "doppler_window": "hann", "remove_mean": True, "static_clutter": False}


def small_config() -> RadarConfig:
    """The corridor's config cut to 16 chirps x 64 samples (3 RX)."""
    return Scene.builtin("corridor").config.replace(num_chirps_per_frame=16, num_samples_per_chirp=64,
                                                    frame_repetition_time_s=0.05)


def chain(representation: str = "floor_relative", size: tuple[int, int] | None = (16, 8),
          excise: torch.Tensor | None = None, interference_db: float | None = None,
          resample: str = "bilinear") -> ChainSpec:
    clip = (-5.0, 30.0) if representation == "floor_relative" else (-110.0, -40.0)
    return ChainSpec(dict(RD), representation, 1, clip, size, excise, interference_db, resample)


def classifier(task: str = "occupancy", *, constant: int | None = None, seed: int = 0,
               interference_db: float | None = None, resample: str = "bilinear", **kw) -> RadarClassifier:
    """An untrained ResNet18 classifier; ``constant``: one whose answer is always that class (p ~ 0.99)."""
    torch.manual_seed(seed)
    net = resnet18(2 if task == "occupancy" else 3)
    if constant is not None:
        with torch.no_grad():
            net.fc.weight.zero_()
            net.fc.bias.fill_(0.0)
            net.fc.bias[constant] = 6.0
    return RadarClassifier(net, arch="resnet18", task=task, config=small_config(),
                           chain=chain(interference_db=interference_db, resample=resample), **kw)


def room_frames(n: int, seed: int = 0, target: float = 0.0) -> torch.Tensor:
    """``(n, 3, 16, 64)`` SDK-float frames: noise and a static wall return (+ a static target of amplitude ``target``)."""
    g = torch.Generator().manual_seed(seed)
    t = torch.arange(64, dtype=torch.float32)
    x = 0.004 * torch.randn(n, 3, 16, 64, generator=g) + 0.03 * torch.cos(2 * torch.pi * 20 / 64 * t)
    return (x + target * torch.cos(2 * torch.pi * 9 / 64 * t)).clamp(-1, 1)


def with_bursts(x: torch.Tensor) -> torch.Tensor:
    """``x`` with an interferer's burst (a chirp sweeping the IF band) on chirp 5 of every other frame."""
    t = torch.arange(x.shape[-1], dtype=x.dtype)
    x = x.clone()
    x[::2, :, 5] += 0.3 * torch.cos(2 * torch.pi * 0.002 * t * t)
    return x.clamp(-1, 1)


def write_frames(path, frames: torch.Tensor, config: RadarConfig | None = None):
    return write_capture(path, float_to_counts(frames).numpy().astype(np.uint16), config or small_config())


@pytest.fixture
def clf() -> RadarClassifier:
    return classifier()
