"""Fixtures of the training tests: small captures from the independent generator in data.py."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from data import write_test_captures  # noqa: E402


@pytest.fixture(scope="session")
def captures(tmp_path_factory) -> tuple[Path, list[tuple[Path, int]]]:
    """(empty-room capture, [(capture, people count)]) in the small config."""
    return write_test_captures(tmp_path_factory.mktemp("captures"))
