"""The held-out proxy's frames are pinned (its simulation moved onto the shared twin without changing them)."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest
import torch

from radaraug.io import open_capture
from radaraug.testsets import proxy

# sha256 of the uint16 ADC codes (and of the float64 timestamps) of
# make_proxy(out, frames_per_count=4, calibration_frames=4, seed=3, tracer_options={"rays": 16}), on the
# CPU, generator version 8 (TWIN_MODEL_VERSION 4). First recorded with the proxy's own simulator
# (version 3) and carried through each version since (docs/proxy.md).
RECORDED_WITH = "2.14.1"  # torch version the digests were computed with (float results may differ on another)
FILES = {
    "calibration_empty": ("2e17704063206bdc7144d00c8ea6c2aca399b1af4dc643a8aaa962bd33bff883", "aa9effd2f9d38713"),
    "test_count0": ("9f757bcc10800827abc63e71043a09e051d89473d5307ff4916a95d446b5b4b3", "b501d6a99d770503"),
    "test_count1": ("8bffe6fd358a5ddc8cdd3fdb3c7ff586b8b58b39fbf426c6463dd9e737b55919", "1a039263566d9ce3"),
    "test_count2": ("72e95659cd78bc3ec9287e80a3e5469968cd666a7222acf1c41ec33cfd923ca9", "dc63d789310165a5"),
}


def test_proxy_frames_are_bit_identical(tmp_path: Path) -> None:
    if not torch.__version__.startswith(RECORDED_WITH):
        pytest.skip(f"digests recorded with torch {RECORDED_WITH}; this is {torch.__version__}")
    made = proxy.make_proxy(tmp_path, frames_per_count=4, calibration_frames=4, seed=3, progress=False,
                            tracer_options={"rays": 16})
    recorded = FILES
    for path in [made.calibration, *(p for p, _ in made.tests)]:
        with open_capture(path) as cap:
            codes = cap.read(as_float=False).numpy().astype(np.uint16)
            stamps = np.asarray(cap.timestamps)
        frames, times = recorded[path.stem]
        assert hashlib.sha256(codes.tobytes()).hexdigest() == frames, f"{path.name}: the proxy's frames changed"
        assert hashlib.sha256(stamps.tobytes()).hexdigest()[:16] == times, f"{path.name}: its timestamps changed"
