"""The ray tracer's documentation figures (radaraug.raytrace.figures)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from radaraug.raytrace.figures import plot_walker_shadowing


def test_walker_shadowing_figure(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    out = tmp_path / "sub" / "walker_shadowing.png"
    summary = plot_walker_shadowing(out, frames=17)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert all(math.isfinite(v) for v in summary.values())
    # A walker on the radar-wall line shadows the wall; one far off the line does not.
    assert summary["along_model_db_mean"] < -10
    assert summary["cross_model_db_max_off_line"] < 0.01
