"""`radaraug bench people-level` recovers a known RCS scale from a capture file, and refuses no captures."""

from __future__ import annotations

import json

import pytest
import torch

from radaraug.cli import main
from radaraug.diagnosis.people_level import twin_walks
from radaraug.io import write_capture
from radaraug.units import float_to_counts


def test_people_level_bench_fits_a_capture_file(tmp_path, capsys):
    """A capture of twin walkers 6 dB brighter than the twin's (other seed), written as a file: the bench reads
    it and fits +6 dB (closed form: the receiver is linear up to the ADC)."""
    from tests.diagnosis.test_people_level import CONFIG, SPAN

    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        frames = twin_walks(CONFIG, SPAN, rcs_scale_dB=6.0, seed=1)
        path = write_capture(tmp_path / "walk.h5", float_to_counts(frames).numpy().astype("uint16"), CONFIG)
        out = tmp_path / "people_level.json"
        assert main(["bench", "people-level", "--capture", str(path), "--json", "-o", str(out)]) == 0
    finally:
        torch.set_num_threads(threads)
    printed = json.loads(capsys.readouterr().out)
    assert printed == json.loads(out.read_text())
    fit = printed["recordings"]["walk.h5"]
    assert fit["offset_dB"] == pytest.approx(6.0, abs=1.0)
    assert main(["bench", "people-level"]) != 0
