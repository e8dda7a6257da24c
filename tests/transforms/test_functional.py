"""radaraug.transforms.functional: the kernels behind the classes, and their runnable Examples."""

import doctest
import importlib

import pytest
import torch

from radaraug.errors import ConfigError, InputTensorError
from radaraug.transforms import (
    CalibratedDR,
    ClipNormalize,
    Colormap,
    CombineRx,
    DopplerFFT,
    RandomDR,
    RangeDoppler,
    RangeFFT,
    RemoveMean,
    Resize,
    StaticClutterRemoval,
    ToDecibels,
)
from radaraug.transforms import functional as F

MODULES = [
    "radaraug.transforms.functional",
    "radaraug.transforms.functional._spectral",
    "radaraug.transforms.functional._dr",
    "radaraug.transforms.functional._image",
]


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    torch.manual_seed(0)
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


def test_every_public_function_documents_a_runnable_example():
    for name in F.__all__:
        doc = getattr(F, name).__doc__
        assert "Examples:" in doc and ">>>" in doc, name


def test_classes_equal_their_kernels_bit_for_bit():
    torch.manual_seed(1)
    cube = torch.randn(2, 3, 16, 32) * 0.1
    prof = torch.fft.rfft(cube, dim=-1)
    rd = F.range_doppler(cube)
    db = F.to_decibels(rd)
    unit = torch.rand(2, 1, 8, 6)
    pairs = [
        (RemoveMean()(cube), F.remove_mean(cube)),
        (StaticClutterRemoval()(prof), F.static_clutter_removal(prof)),
        (RangeFFT("blackman")(cube), F.range_fft(cube, "blackman")),
        (DopplerFFT("hamming")(prof[..., :15, :]), F.doppler_fft(prof[..., :15, :], "hamming")),
        (RangeDoppler("rect", "blackmanharris", static_clutter=True)(cube),
         F.range_doppler(cube, "rect", "blackmanharris", static_clutter=True)),
        (ToDecibels(1e-9)(rd), F.to_decibels(rd, 1e-9)),
        (CombineRx("max", db=True)(db), F.combine_rx(db, "max", db=True)),
        (CombineRx("select", index=-1)(rd), F.combine_rx(rd, "select", index=-1)),
        (ClipNormalize(-120, -40)(db), F.clip_normalize(db, -120, -40)),
        (Colormap("magma")(unit), F.colormap(unit, "magma")),
        (Resize((5, 9))(unit), F.resize(unit, (5, 9))),
    ]
    for got, ref in pairs:
        assert got.dtype == ref.dtype and torch.equal(got, ref)
    # the random ones: the class's draws, given to the kernel, give the class's output
    for t in (RandomDR(seed=2), CalibratedDR(-60, 4, seed=2)):
        y = t(db)
        assert torch.equal(y, F.dr_clamp(db, t.last_params["noise_db"]))
    floor = F.calibrated_floor(db.shape, -60, 4, like=db, generator=torch.Generator().manual_seed(2))
    assert torch.equal(floor, CalibratedDR(-60, 4, seed=2).make_params(db, torch.Generator().manual_seed(2))["noise_db"])
    q = torch.linspace(-80.0, -50.0, 9)
    emp = CalibratedDR(-60, 4, floor="empirical", quantiles_db=q, seed=2)
    assert torch.equal(emp(db), F.dr_clamp(db, emp.last_params["noise_db"]))
    floor = F.empirical_floor(db.shape, q, like=db, generator=torch.Generator().manual_seed(2))
    assert torch.equal(floor, emp.make_params(db, torch.Generator().manual_seed(2))["noise_db"])


def test_kernels_work_on_an_empty_batch_and_keep_float64():
    assert F.range_doppler(torch.zeros(0, 3, 4, 8)).shape == (0, 3, 4, 4)
    assert F.range_fft(torch.zeros(0, 3, 4, 8, dtype=torch.float64)).dtype == torch.complex128


@pytest.mark.parametrize(
    "call, error, match",
    [
        (lambda: F.range_fft(torch.zeros(3, 4, 8, dtype=torch.float16)), InputTensorError, "float32 or float64"),
        (lambda: F.range_doppler(torch.zeros(3, 4, 1)), InputTensorError, "at least 2 samples"),
        (lambda: F.remove_mean(torch.zeros(4, 8, dtype=torch.int32)), InputTensorError, "floating"),
        (lambda: F.combine_rx(torch.zeros(3, 4, 4), "select", index=3), InputTensorError, "out of range"),
        (lambda: F.combine_rx(torch.zeros(3, 4, 4), "sum"), InputTensorError, "mode"),
        (lambda: F.to_decibels(torch.ones(3), floor=0), InputTensorError, "floor"),
        (lambda: F.colormap(torch.zeros(3, 4, 4)), InputTensorError, "CombineRx"),
        (lambda: F.colormap(torch.zeros(1, 4, 4), torch.zeros(4)), InputTensorError, r"\(K, 3\)"),
        (lambda: F.dr_clamp(torch.zeros(1, 4, 4), -100.0), InputTensorError, "noise_db"),
        (lambda: F.resize(torch.zeros(1, 4, 4), 8), ConfigError, "height, width"),
    ],
)
def test_kernels_validate_their_arguments(call, error, match):
    with pytest.raises(error, match=match):
        call()
