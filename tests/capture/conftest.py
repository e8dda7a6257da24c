"""Fixtures of the live-capture tests: small radar configs that the twin simulates in milliseconds."""

from __future__ import annotations

import pytest

from radaraug.config import RadarConfig
from radaraug.scene.scene import Scene


def small_config(frame_period_s: float = 0.05, chirps: int = 16) -> RadarConfig:
    """The corridor's BGT60TR13C config cut to 16 chirps x 64 samples (3 RX)."""
    return Scene.builtin("corridor").config.replace(num_chirps_per_frame=chirps, num_samples_per_chirp=64,
                                                    frame_repetition_time_s=frame_period_s)


@pytest.fixture
def cfg() -> RadarConfig:
    return small_config()


@pytest.fixture
def cfg_file(tmp_path, cfg):
    path = tmp_path / "cfg.json"
    cfg.to_json(path)
    return path
