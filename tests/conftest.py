"""Shared test fixtures."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import torch

REPO_ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True, scope="session")
def _static_room_cache(tmp_path_factory: pytest.TempPathFactory):
    """Traced static rooms go to a per-run folder, not the user's cache (shared by the run's tests)."""
    old = os.environ.get("RADARAUG_CACHE_DIR")
    os.environ["RADARAUG_CACHE_DIR"] = str(tmp_path_factory.mktemp("static_room_cache"))
    yield
    if old is None:
        os.environ.pop("RADARAUG_CACHE_DIR", None)
    else:
        os.environ["RADARAUG_CACHE_DIR"] = old


def real_data_root() -> Path | None:
    """Folder of third-party BGT60TR13C recordings, if present.

    ``RADARAUG_REAL_DATA`` wins; otherwise ``shared/real`` beside the repository (where CI puts
    it). Users' clones do not have it: tests that need it skip.
    """
    env = os.environ.get("RADARAUG_REAL_DATA")
    candidates = [Path(env)] if env else []
    candidates.append(REPO_ROOT.parent / "shared" / "real")
    for c in candidates:
        if c.is_dir():
            return c
    return None


@pytest.fixture
def real_data() -> Path:
    """Path to the real recordings, or skip the test."""
    root = real_data_root()
    if root is None:
        pytest.skip("third-party real recordings (shared/real) not present")
    return root


DEVICES = ["cpu"] + (["cuda"] if torch.cuda.is_available() else [])


@pytest.fixture(params=["cpu", "cuda"])
def device(request: pytest.FixtureRequest) -> torch.device:
    """CPU always; CUDA when present (skipped otherwise)."""
    if request.param == "cuda" and not torch.cuda.is_available():
        pytest.skip("no CUDA device")
    return torch.device(request.param)


@pytest.fixture(params=[torch.float32, torch.float64], ids=["f32", "f64"])
def dtype(request: pytest.FixtureRequest) -> torch.dtype:
    """Both float precisions."""
    return request.param
