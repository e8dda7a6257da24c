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
# synthesis factor (60 and 69 of the 196,608 ADC codes of the files with people move by one; the
# empty room and the empty test file are unchanged). The files above are checked with both taken
# out (the old rules), so that these are all that changed; the files are these now.
# (Version 5, with only the turn in: test_count1 ea2f5c21, test_count2 fc13f0d0.)
FILES_V6 = {
    "calibration_empty": ("2e17704063206bdc7144d00c8ea6c2aca399b1af4dc643a8aaa962bd33bff883", "aa9effd2f9d38713"),
    "test_count0": ("9f757bcc10800827abc63e71043a09e051d89473d5307ff4916a95d446b5b4b3", "b501d6a99d770503"),
    "test_count1": ("64f4090b60b5b97a0d310edc4c28049a2fc3a50d07a2e9fa57b3713ee6309c66", "1a039263566d9ce3"),
    "test_count2": ("b6569e2594e657dbbbbaf7e9c8e6b56227746683617eaf5c5429c0ab4ee04a41", "dc63d789310165a5"),
}

# Version 7 (TWIN_MODEL_VERSION 4): the coupling of moving paths is a Chebyshev series with orders
# chosen per frame; 1 of the 196,608 ADC codes of test_count2 moves by one (FILES_V6 is checked under
# ``taylor_coupling``, the rule before).
FILES_V7 = {**FILES_V6,
            "test_count2": ("8b7032c1d110f08649e95f68ede06fa35cbded8f8b1dd5f3900c4b14983c1c73", "dc63d789310165a5")}


@pytest.mark.parametrize("rule", ["before", "v6", "now"])
def test_proxy_frames_are_bit_identical(tmp_path: Path, rule: str) -> None:
    if not torch.__version__.startswith(RECORDED_WITH):
        pytest.skip(f"digests recorded with torch {RECORDED_WITH}; this is {torch.__version__}")
    from radaraug.scene.people.skeleton import without_turn
    from radaraug.sensor.synthesis import per_channel_synthesis, taylor_coupling

    with contextlib.ExitStack() as rules:
        if rule in ("before", "v6"):
            rules.enter_context(taylor_coupling())
        if rule == "before":
            rules.enter_context(without_turn())
            rules.enter_context(per_channel_synthesis())
        made = proxy.make_proxy(tmp_path, frames_per_count=4, calibration_frames=4, seed=3, progress=False,
                                tracer_options={"rays": 16})
    recorded = {"before": FILES, "v6": FILES_V6, "now": FILES_V7}[rule]
    for path in [made.calibration, *(p for p, _ in made.tests)]:
        with open_capture(path) as cap:
            codes = cap.read(as_float=False).numpy().astype(np.uint16)
            stamps = np.asarray(cap.timestamps)
        frames, times = recorded[path.stem]
        assert hashlib.sha256(codes.tobytes()).hexdigest() == frames, f"{path.name}: the proxy's frames changed"
        assert hashlib.sha256(stamps.tobytes()).hexdigest()[:16] == times, f"{path.name}: its timestamps changed"
