"""Fixtures for the capture I/O tests: tiny synthetic HDF5 captures and Infineon recordings."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest


def _load_helpers(name: str, filename: str):
    # Register a helper file of this folder under a unique module name: a bare "data" module
    # could clash with another test folder's helper of the same name on sys.path.
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, Path(__file__).with_name(filename))
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


io_data = _load_helpers("radaraug_tests_io_data", "data.py")
# The fuzz corpus generator (imported by test_fuzz.py as radaraug_tests_io_fuzz_data).
_load_helpers("radaraug_tests_io_fuzz_data", "fuzz_data.py")


@pytest.fixture
def tiny_config():
    """A small valid RadarConfig (3 RX, 4 chirps, 32 samples)."""
    return io_data.tiny_config()


@pytest.fixture
def h5_capture(tmp_path, tiny_config) -> Path:
    """A 6-frame radaraug HDF5 capture of :func:`frame_pattern` frames, with timestamps and labels."""
    from radaraug.io import write_capture

    counts = io_data.pattern_counts(tiny_config, 6)
    return write_capture(
        tmp_path / "pattern.h5",
        counts,
        tiny_config,
        timestamps=1.7e9 + 0.01 * np.arange(6),
        labels={"count": np.array([0, 0, 1, 1, 2, 2]), "room": 3},
        attrs={"source": "tests", "description": "frame pattern"},
    )


@pytest.fixture
def infineon_recording(tmp_path, tiny_config) -> Path:
    """A 5-frame Infineon recording folder of :func:`frame_pattern` frames, with timestamps."""
    from radaraug.io import write_infineon_recording

    counts = io_data.pattern_counts(tiny_config, 5)
    return write_infineon_recording(
        tmp_path / "rec", counts, tiny_config, timestamps=1.7e9 + 0.01 * np.arange(5)
    )
