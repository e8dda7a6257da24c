"""The registry of generator streams (`radaraug.sim.seeding.Stream`): unique, stable values, and items unchanged."""

from __future__ import annotations

import hashlib
import re
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
# twin_options={"tracer_options": {"rays": 16}})[i], and its label, on the CPU (TWIN_MODEL_VERSION 4).
# Recorded first before the streams were named, then carried through each model version (the history:
# docs/simulation.md, "Model versions"): the registry, the merged simulation branches and the effect
# catalog's redesign each left every item bit-identical.
RECORDED_WITH = "2.14.1"  # torch version the digests were computed with (float results may differ on another)
ITEMS = {
    0: (2, "8d9c7d0366219eda5ee14def5e1701fc2abd2fc82efe8eafa17a9a8657e63055"),
    1: (2, "33123c896787f459ce25db5c74be9b9bc2da1d3c3db13b1472e936e782fb14ed"),
    2: (0, "05ba94a5f1c184f875e8bee2a2fa9eccb49051395128e67ff41a8711bda8776d"),
    3: (1, "56eaa01b0040d2b594b326cda463af3953d65d61e74fca7c78b05dd2204d7187"),
}
# The same for randomized items: SimulatedRadarDataset("corridor", length=4, seed=3,
# randomization=TwinRandomization(room={"variants": 1}), twin_options={"tracer_options": {"rays": 16}})[i].
# Between them the items draw the effect catalog's spur tone, vibrating clutter, RX gain/phase mismatch
# (with people shadowing the room), frame drift, wide levels and the room's static phase noise.
RANDOMIZED_ITEMS = {
    0: (2, "44ba925d4d73e8d92026cdba2482fadd93f5994e087d7dda107234be367ba0b2"),
    1: (2, "7658567124eb2b59d042b4b1f75a44975230abc9745e17d6071afd1b7a43fadb"),
    2: (0, "9ae268fd9168f14b3758e7d7b6516f57ba3159bc5e9808179efc8472a69d0e58"),
    3: (1, "a700eaf11b74d3654e4c8296c9697ca3a190d9f667ee4b22310b99364058ed70"),
}


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
def test_known_items_are_bit_identical(index: int) -> None:
    ds = SimulatedRadarDataset("corridor", length=4, seed=3, twin_options={"tracer_options": {"rays": 16}})
    _assert_recorded(ds, index, ITEMS, "item")


@pytest.fixture
def randomized_dataset() -> SimulatedRadarDataset:
    from radaraug.sim.randomization import TwinRandomization

    return SimulatedRadarDataset("corridor", length=4, seed=3, randomization=TwinRandomization(room={"variants": 1}),
                                 twin_options={"tracer_options": {"rays": 16}})


@pytest.mark.parametrize("index", sorted(RANDOMIZED_ITEMS))
def test_known_randomized_items_are_bit_identical(index: int, randomized_dataset: SimulatedRadarDataset) -> None:
    _assert_recorded(randomized_dataset, index, RANDOMIZED_ITEMS, "randomized item")
