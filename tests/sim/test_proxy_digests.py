"""The held-out proxy's frames are pinned (its simulation moved onto the shared twin without changing them)."""

from __future__ import annotations

import contextlib
import hashlib
from pathlib import Path

import numpy as np
import pytest
import torch

from radaraug.io import open_capture
from radaraug.sim import proxy

# sha256 of the uint16 ADC codes (and of the float64 timestamps) of
# make_proxy(out, frames_per_count=4, calibration_frames=4, seed=3, tracer_options={"rays": 16}),
# computed on the CPU with the proxy's own simulator (generator version 3), before it became data plus
# DigitalTwin.simulate (version 4), which gives this set bit for bit. (On larger sets version 4 moves about one
# ADC sample in a million by one code: the room's signal less its strongest returns is rounded differently.)
RECORDED_WITH = "2.14.1"  # torch version the digests were computed with (float results may differ on another)
FILES = {
    "calibration_empty": ("2e17704063206bdc7144d00c8ea6c2aca399b1af4dc643a8aaa962bd33bff883", "aa9effd2f9d38713"),
    "test_count0": ("9f757bcc10800827abc63e71043a09e051d89473d5307ff4916a95d446b5b4b3", "b501d6a99d770503"),
    "test_count1": ("0cb57f36e70f61b5fef9bd897ec469549d5f0f9f52c1dfe696a29ac952f42ad1", "1a039263566d9ce3"),
    "test_count2": ("641f60bb6b690f5cf46bbd1447e284b44ea2ac0d3374a166fa0605662b3c6fb8", "dc63d789310165a5"),
}
# Generator version 5 (the twin's TWIN_MODEL_VERSION 2, issue 22): the people's echoes move with their
# specular points' velocity; version 6 (TWIN_MODEL_VERSION 3): the RX channels share the fast-time
# synthesis factor (6 to 35 of each file's 196,608 ADC codes move by one). The files above are checked
# with both taken out (the old rules), so that these are all that changed; the files are these now.
# (Version 5, with only the turn in: test_count1 ea2f5c21, test_count2 fc13f0d0.)
FILES_V6 = {
    "calibration_empty": ("4fb54647639142c8430cf05b3a09523153d4ff3e284aadcff8696bed2f3c4c3f", "aa9effd2f9d38713"),
    "test_count0": ("b8b44702aa2468458248de9c0378e1452949e5f81ced61c028b767ed6621e39e", "b501d6a99d770503"),
    "test_count1": ("23cc9d78f75fa5e970a5c84e50a026c586ccca5f4ca5c836672370c9d23427e4", "1a039263566d9ce3"),
    "test_count2": ("d0289a288385a0c7f4489c5a92cdec0e91ac49dd459b6ba3d21ef146c3244ef7", "dc63d789310165a5"),
}


@pytest.mark.parametrize("rule", ["before", "now"])
def test_proxy_frames_are_bit_identical(tmp_path: Path, rule: str) -> None:
    if not torch.__version__.startswith(RECORDED_WITH):
        pytest.skip(f"digests recorded with torch {RECORDED_WITH}; this is {torch.__version__}")
    from radaraug.scene.people.skeleton import without_turn
    from radaraug.sensor.synthesis import per_channel_synthesis

    old = rule == "before"
    with contextlib.ExitStack() as rules:
        if old:
            rules.enter_context(without_turn())
            rules.enter_context(per_channel_synthesis())
        made = proxy.make_proxy(tmp_path, frames_per_count=4, calibration_frames=4, seed=3, progress=False,
                                tracer_options={"rays": 16})
    recorded = FILES if old else FILES_V6
    for path in [made.calibration, *(p for p, _ in made.tests)]:
        with open_capture(path) as cap:
            codes = cap.read(as_float=False).numpy().astype(np.uint16)
            stamps = np.asarray(cap.timestamps)
        frames, times = recorded[path.stem]
        assert hashlib.sha256(codes.tobytes()).hexdigest() == frames, f"{path.name}: the proxy's frames changed"
        assert hashlib.sha256(stamps.tobytes()).hexdigest()[:16] == times, f"{path.name}: its timestamps changed"
