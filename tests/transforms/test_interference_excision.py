"""InterferenceExcision: burst chirps replaced by the mean of the other chirps, closed forms on a synthetic frame."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.errors import InputTensorError
from radaraug.transforms import InterferenceExcision, RadarCompose, RangeDoppler, ToDecibels
from radaraug.transforms import functional as F

RX, M, N = 3, 64, 128


def _frame(bursts: tuple[int, ...] = (), dtype: torch.dtype = torch.float64, seed: int = 0) -> torch.Tensor:
    """A walker-like target (range bin 20, Doppler bin +5), a static wall (bin 40), white noise, and
    Hann-windowed full-band sweeps (15 dB over the target's moving power) in the chirps ``bursts``."""
    g = torch.Generator().manual_seed(seed)
    n, m = torch.arange(N, dtype=torch.float64), torch.arange(M, dtype=torch.float64)[:, None]
    target = 0.05 * torch.cos(2 * math.pi * (20 * n / N + 5 * m / M))
    wall = 0.2 * torch.cos(2 * math.pi * 40 * n / N + 0.3)
    x = (target + wall).expand(RX, M, N) + 1e-3 * torch.randn(RX, M, N, generator=g, dtype=torch.float64)
    sweep = 0.5 * torch.hann_window(N, periodic=False, dtype=torch.float64) * torch.cos(math.pi * n**2 / (2 * N))
    x = x.clone()
    for k in bursts:
        x[:, k] += sweep
    return x.to(dtype)


def _db(x: torch.Tensor) -> torch.Tensor:
    return RadarCompose([RangeDoppler(), ToDecibels()])(x).mean(dim=0)  # (range, doppler), RX-mean dB


def test_bursts_are_removed_and_the_target_kept() -> None:
    clean, hit = _frame(), _frame(bursts=(3, 17, 40))
    out = InterferenceExcision()(hit)
    untouched = [k for k in range(M) if k not in (3, 17, 40)]
    # the burst chirps became the mean of the others: no share of the bursts is left in any chirp
    assert torch.allclose(out[:, [3, 17, 40]], hit[:, untouched].mean(dim=-2, keepdim=True).expand(RX, 3, N))
    assert torch.equal(out[:, untouched], hit[:, untouched])
    floor = lambda d: float(d[48:60, :].median())  # range bins away from the target and the wall  # noqa: E731
    assert floor(_db(hit)) > floor(_db(clean)) + 10  # the bursts raise the floor over every Doppler bin
    assert abs(floor(_db(out)) - floor(_db(clean))) < 1.0
    # the target keeps its peak: 61 of 64 chirps, 20 log10(61/64) = -0.42 dB of coherent gain
    peak = lambda d: float(d[20, M // 2 + 5])  # noqa: E731
    assert peak(_db(out)) - peak(_db(clean)) == pytest.approx(20 * math.log10(61 / 64), abs=0.15)


def test_a_frame_without_bursts_is_unchanged_and_inputs_are_kept() -> None:
    x = torch.stack([_frame(seed=s, dtype=torch.float32) for s in range(4)]).reshape(2, 2, RX, M, N)
    before = x.clone()
    out = F.interference_excision(x)
    assert torch.equal(out, x) and torch.equal(x, before) and out.dtype == torch.float32 and out.shape == x.shape


def test_each_frame_of_a_batch_has_its_own_median_and_bad_input_is_refused() -> None:
    x = torch.stack([_frame(), _frame(bursts=(5,))])
    out = InterferenceExcision(threshold_db=6.0)(x)
    assert torch.equal(out[0], x[0]) and not torch.equal(out[1, :, 5], x[1, :, 5])
    assert InterferenceExcision(threshold_db=6.0).extra_spec() == {"threshold_db": 6.0}
    with pytest.raises(InputTensorError):
        InterferenceExcision(threshold_db=0)
    with pytest.raises(InputTensorError):
        F.interference_excision(torch.zeros(4, 2))
