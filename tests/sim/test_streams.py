"""The registry of generator streams (`radaraug.sim.seeding.Stream`): unique, stable values, and items unchanged."""

from __future__ import annotations

import contextlib
import hashlib
import re
from collections.abc import Iterator
from pathlib import Path

import pytest
import torch

from radaraug.sim import SimulatedRadarDataset
from radaraug.sim.seeding import Stream, item_seed

ROOT = Path(__file__).resolve().parents[2]

# The values every recorded simulation was made with: a member may be added, never renumbered.
KNOWN = {
    "SCENARIO": 0, "ITEM_NOISE": 1, "BLOCK_NOISE": 2, "ITEM_DRAWS": 3, "ROOM_POOL": 4, "SCATTERERS": 5,
    "EFFECTS": 6, "NOISE_FIT": 7, "PROXY_WALKS": 30, "PROXY_NOISE": 31,
}

# sha256 of the float32 bytes of SimulatedRadarDataset("corridor", length=4, seed=3,
# twin_options={"tracer_options": {"rays": 16}})[i], and its label, computed on the CPU before the
# streams were named (the registry must leave every item bit-identical).
RECORDED_WITH = "2.14.1"  # torch version the digests were computed with (float results may differ on another)
ITEMS = {
    0: (2, "1deddb4f32edc7deb85fa6303c8bf9ee17a6737820671f59fc7d2ba964d1f2db"),
    1: (2, "e51f8411c1a90f9a9359b5f6d5c25a93d8eb90e6af76c485f53c1eb6303ccdf0"),
    2: (0, "05ba94a5f1c184f875e8bee2a2fa9eccb49051395128e67ff41a8711bda8776d"),
    3: (1, "bc7d7b07eca68318779b2ef431ae1da090c6073daf43ebb785a65ac1006f530c"),
}

# The same for randomized items: SimulatedRadarDataset("corridor", length=4, seed=3,
# randomization=TwinRandomization(room={"variants": 1}), twin_options={"tracer_options": {"rays": 16}})[i],
# recorded (torch 2.14.1, CPU) before the dataset's two simulation branches became one
# (`DigitalTwin.simulate(..., draw=...)`). Between them the items draw the effect catalog's spur tone,
# vibrating clutter, RX gain/phase mismatch (with people shadowing the room), frame drift, wide levels
# and the room's static phase noise.
RANDOMIZED_ITEMS = {
    0: (2, "96a94d198c29a1afd930335865476150b1bbbcb1b9024b42f455e7abd2de95a1"),
    1: (2, "2ca019ec1d4e76e6cbb2b79913b180e230f32547437a23abd2055a74aab90c2c"),
    2: (0, "9ae268fd9168f14b3758e7d7b6516f57ba3159bc5e9808179efc8472a69d0e58"),
    3: (1, "46ff0443bb8f64af56c90a380a55ce52daf14a6d44843690d9e0521fdd5f5699"),
}

# TWIN_MODEL_VERSION 2 (issue 22) moved a segment's echo with its specular point's material velocity,
# rotation included; version 3 lets the RX channels share the fast-time synthesis factor (10 to 38
# of the 49,152 samples of an item with people move by one ADC code; empty items are unchanged).
# The digests above are checked with both changes taken out (``without_turn``, ``per_channel_synthesis``), so that these two are all that moved
# them; the items are these now. (Between the two, with only the turn in, the items with people were
# c4ebd837, 273d81dd, a4a3a38e and randomized f6f7bbcf, 4928ac7f, b4083351.)
ITEMS_V3 = {
    0: (2, "8d9c7d0366219eda5ee14def5e1701fc2abd2fc82efe8eafa17a9a8657e63055"),
    1: (2, "33123c896787f459ce25db5c74be9b9bc2da1d3c3db13b1472e936e782fb14ed"),
    2: (0, "05ba94a5f1c184f875e8bee2a2fa9eccb49051395128e67ff41a8711bda8776d"),
    3: (1, "56eaa01b0040d2b594b326cda463af3953d65d61e74fca7c78b05dd2204d7187"),
}
RANDOMIZED_ITEMS_V3 = {
    0: (2, "44ba925d4d73e8d92026cdba2482fadd93f5994e087d7dda107234be367ba0b2"),
    1: (2, "7658567124eb2b59d042b4b1f75a44975230abc9745e17d6071afd1b7a43fadb"),
    2: (0, "9ae268fd9168f14b3758e7d7b6516f57ba3159bc5e9808179efc8472a69d0e58"),
    3: (1, "a700eaf11b74d3654e4c8296c9697ca3a190d9f667ee4b22310b99364058ed70"),
}


# TWIN_MODEL_VERSION 4 (the coupling of moving paths is a Chebyshev series with orders chosen per
# frame) leaves these eight items bit-identical: their ADC codes do not move. They are checked under
# ``taylor_coupling`` (the rule before) and as the twin is now.


@pytest.fixture(params=["before", "v3", "now"])
def model(request: pytest.FixtureRequest) -> Iterator[str]:
    """The twin under an earlier version's rules (their context managers), or as it is."""
    from radaraug.scene.people.skeleton import without_turn
    from radaraug.sensor.synthesis import per_channel_synthesis, taylor_coupling

    with contextlib.ExitStack() as rules:
        if request.param in ("before", "v3"):
            rules.enter_context(taylor_coupling())
        if request.param == "before":
            rules.enter_context(without_turn())
            rules.enter_context(per_channel_synthesis())
        yield str(request.param)


def test_stream_values_are_unique_and_unchanged() -> None:
    assert {m.name: int(m) for m in Stream} == KNOWN
    # An IntEnum silently turns a repeated value into an alias: every name must be its own member.
    assert len(Stream.__members__) == len(set(Stream.__members__.values())) == len(KNOWN)
    # A member seeds exactly as its bare integer did.
    assert item_seed(3, 5, Stream.PROXY_NOISE) == item_seed(3, 5, 31)


def test_no_bare_stream_integers_in_the_library() -> None:
    bare = re.compile(r"stream\s*=\s*\d")
    hits = [f"{p.relative_to(ROOT)}:{i}" for p in sorted((ROOT / "radaraug").rglob("*.py"))
            for i, line in enumerate(p.read_text().splitlines(), 1) if bare.search(line)]
    assert hits == []


def _assert_recorded(ds: SimulatedRadarDataset, index: int, recorded: dict[int, tuple[int, str]], what: str) -> None:
    if not torch.__version__.startswith(RECORDED_WITH):
        pytest.skip(f"digests recorded with torch {RECORDED_WITH}; this is {torch.__version__}")
    x, y = ds[index]
    assert x.dtype == torch.float32 and tuple(x.shape) == (3, 64, 256)
    label, digest = recorded[index]
    assert int(y) == label
    assert hashlib.sha256(x.contiguous().numpy().tobytes()).hexdigest() == digest, (
        f"{what} changed: a stream value, the order of draws or the simulation itself moved")


@pytest.mark.parametrize("index", sorted(ITEMS))
def test_known_items_are_bit_identical(index: int, model: str) -> None:
    ds = SimulatedRadarDataset("corridor", length=4, seed=3, twin_options={"tracer_options": {"rays": 16}})
    _assert_recorded(ds, index, ITEMS if model == "before" else ITEMS_V3, "item")  # V4: the same


@pytest.fixture
def randomized_dataset() -> SimulatedRadarDataset:
    from radaraug.sim.randomization import TwinRandomization

    return SimulatedRadarDataset("corridor", length=4, seed=3, randomization=TwinRandomization(room={"variants": 1}),
                                 twin_options={"tracer_options": {"rays": 16}})


@pytest.mark.parametrize("index", sorted(RANDOMIZED_ITEMS))
def test_known_randomized_items_are_bit_identical(index: int, model: str,
                                                  randomized_dataset: SimulatedRadarDataset) -> None:
    recorded = RANDOMIZED_ITEMS if model == "before" else RANDOMIZED_ITEMS_V3  # V4: the same
    _assert_recorded(randomized_dataset, index, recorded, "randomized item")
