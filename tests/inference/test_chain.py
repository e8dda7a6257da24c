"""The matrix chain equals the library's chain: the DFTs, the resize and the image steps."""

from __future__ import annotations

import pytest
import torch
from torch.nn import functional as nnf

from radaraug.errors import CheckpointError
from radaraug.inference import ChainSpec, MatmulChain
from radaraug.inference.chain import _dft_matrices, _resize_matrix
from radaraug.transforms import functional as F
from tests.inference.conftest import RD, chain, room_frames, with_bursts


@pytest.mark.parametrize("chirps", [16, 15])  # odd: the complex fftshift window
def test_dft_matrices_are_the_range_doppler_transform(chirps) -> None:
    x = torch.randn(2, 3, chirps, 64, dtype=torch.float64)
    rr, ri, dr, di = _dft_matrices(64, chirps, RD)
    ar, ai = x @ rr.T, x @ ri.T
    got = torch.complex(dr @ ar - di @ ai, dr @ ai + di @ ar).transpose(-1, -2)
    assert torch.allclose(got, F.range_doppler(x), atol=1e-13)


def test_resize_matrices_are_the_antialiased_resize() -> None:
    img = torch.rand(3, 32, 16, dtype=torch.float64)
    want = nnf.interpolate(img[None], size=(24, 12), mode="bilinear", align_corners=False, antialias=True)[0]
    assert torch.allclose(_resize_matrix(32, 24) @ img @ _resize_matrix(16, 12).T, want, atol=1e-12)
    assert torch.allclose(_resize_matrix(8, 8), torch.eye(8, dtype=torch.float64), atol=1e-12)


@pytest.mark.parametrize("resample", ["bilinear", "max"])
@pytest.mark.parametrize("representation", ["floor_relative", "paper"])
@pytest.mark.parametrize("size", [(16, 8), (20, 8), None])
def test_matmul_chain_equals_the_eager_chain(representation, size, resample) -> None:
    excise = torch.zeros(32, 16, dtype=torch.bool)
    excise[20, 3] = True
    spec = chain(representation, size, excise, resample=resample)
    x = room_frames(6, target=0.01)
    eager, mat = spec.eager()(x), MatmulChain(spec, 64, 16)(x)
    assert eager.shape == mat.shape == (6, 3, *(size or (32, 16)))
    # float32 DFTs round differently from the FFT: a cell at a colormap-index boundary may step by one
    # index (at most 1/255 of the range, ~0.02 per channel after the resize weights)
    diff = (eager - mat).abs()
    assert float(diff.max()) < 0.03 and float((diff > 1e-4).double().mean()) < 0.005


def test_matmul_chain_excises_interference_as_the_eager_chain() -> None:
    x = with_bursts(room_frames(4, target=0.01))  # bursts in frames 0 and 2
    plain, excising = chain(), chain(interference_db=6.0)
    eager, before = excising.eager()(x), plain.eager()(x)
    assert torch.equal(eager[1::2], before[1::2])  # frames without a burst: untouched
    assert float((eager[::2] - before[::2]).abs().max()) > 0.1  # with one: the burst is gone
    diff = (eager - MatmulChain(excising, 64, 16)(x)).abs()
    assert float(diff.max()) < 0.03 and float((diff > 1e-4).double().mean()) < 0.005


def test_spec_round_trip_and_refusals() -> None:
    spec = chain(excise=torch.eye(32, 16, dtype=torch.bool))
    again = ChainSpec.from_dict(spec.to_dict(), source="x")
    assert again.to_dict()["clip_range_db"] == spec.to_dict()["clip_range_db"] and torch.equal(again.excise, spec.excise)
    assert again.interference_db is None and again.resample == "bilinear"
    assert ChainSpec.from_dict(chain(resample="max").to_dict(), source="x").resample == "max"
    with_excision = ChainSpec(dict(RD), "paper", 1, (-1.0, 1.0), None, None, 7.5)
    assert ChainSpec.from_dict(with_excision.to_dict(), source="x").interference_db == 7.5
    old = spec.to_dict()
    del old["interference_db"]  # a format-1 file: no interference excision
    assert ChainSpec.from_dict(old, source="x").interference_db is None
    del old["resample"]  # a format-2 file: the bilinear resize
    assert ChainSpec.from_dict(old, source="x").resample == "bilinear"
    with pytest.raises(CheckpointError, match="x: the test chain's resample must be"):
        ChainSpec.from_dict(old | {"resample": "nearest"}, source="x")
    with pytest.raises(CheckpointError, match="x: the test chain's interference_db"):
        ChainSpec.from_dict(old | {"interference_db": 0.0}, source="x")
    with pytest.raises(CheckpointError, match="x: the test chain"):
        ChainSpec.from_dict({"representation": "paper"}, source="x")
    with pytest.raises(CheckpointError, match="static-clutter"):
        MatmulChain(ChainSpec(RD | {"static_clutter": True}, "paper", 1, (-1, 1), None), 64, 16)
