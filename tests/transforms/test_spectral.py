import math

import pytest
import torch

from radaraug.errors import InputTensorError
from radaraug.transforms import (
    CombineRx,
    DopplerFFT,
    RangeDoppler,
    RangeFFT,
    RemoveMean,
    StaticClutterRemoval,
    ToDecibels,
    noise_power_gain,
)

from .conftest import beat_cube

FULL_SCALE_DBFS = 20 * math.log10(0.5)  # -6.02: a real tone splits its amplitude over +-f
# Worst-case scalloping loss (tone half-way between bins), textbook values in dB.
SCALLOPING_DB = {"rect": 3.92, "hann": 1.42, "hamming": 1.75, "blackman": 1.10, "blackmanharris": 0.83}
EULER_GAMMA = 0.5772156649015329


def tone(n: int, cycles: float, chirps: int = 8, dtype=torch.float64, amplitude: float = 1.0) -> torch.Tensor:
    t = torch.arange(n, dtype=torch.float64)
    return (amplitude * torch.cos(2 * math.pi * cycles * t / n + 0.3)).expand(2, chirps, n).to(dtype)


@pytest.mark.parametrize("window", ["rect", "hann", "hamming", "blackman", "blackmanharris"])
def test_on_bin_full_scale_tone_reads_minus_6_dbfs(window, dtype, device):
    n, k = 256, 37
    db = ToDecibels()(RangeFFT(window)(tone(n, k, dtype=dtype).to(device)))
    assert db.shape == (2, 8, n // 2)
    assert (db.argmax(dim=-1) == k).all()
    tol = 1e-4 if window == "rect" else 0.01  # symmetric windows leak a hair from the image at -k
    torch.testing.assert_close(
        db[..., k].cpu().double(), torch.full((2, 8), FULL_SCALE_DBFS, dtype=torch.float64), atol=tol, rtol=0
    )


@pytest.mark.parametrize("window", sorted(SCALLOPING_DB))
def test_half_bin_tone_is_within_scalloping_loss(window):
    n, k = 256, 40
    db = ToDecibels()(RangeFFT(window)(tone(n, k + 0.5, amplitude=0.25)))
    peak = db[..., k : k + 2].amax(dim=-1)
    expected = 20 * math.log10(0.125)
    assert (db.argmax(dim=-1) >= k).all() and (db.argmax(dim=-1) <= k + 1).all()
    assert (peak <= expected + 1e-6).all()
    assert (peak >= expected - SCALLOPING_DB[window] - 0.05).all()


@pytest.mark.parametrize("k", [5, -5, 0])
@pytest.mark.parametrize("m", [16, 15])
def test_phase_ramp_lands_in_doppler_bin(k, m):
    # Range bin 20 with a slow-time phase ramp exp(j 2 pi fd m PRT), fd = k / (M PRT).
    n, prt = 128, 400e-6
    fd = k / (m * prt)
    t = torch.arange(n, dtype=torch.float64)
    c = torch.arange(m, dtype=torch.float64)[:, None]
    x = torch.cos(2 * math.pi * (20 * t / n + fd * c * prt))[None]
    db = ToDecibels()(RangeDoppler("rect", "rect")(x))
    assert db.shape == (1, n // 2, m)
    r, d = divmod(int(db.argmax()), m)
    assert (r, d) == (20, m // 2 + k)
    assert db[0, 20, m // 2 + k].item() == pytest.approx(FULL_SCALE_DBFS, abs=1e-6)


@pytest.mark.parametrize("v_bins", [10, -7])
def test_moving_target_from_beat_formula(cfg, v_bins):
    """Positive Doppler index = moving away (range increasing), as RadarConfig.velocity_axis_m_s."""
    v = v_bins * cfg.velocity_resolution_m_s
    r0 = 30.3 * cfg.range_resolution_m
    rd = ToDecibels()(RangeDoppler()(beat_cube(cfg, r0, v)))
    r, d = divmod(int(rd[0].argmax()), cfg.num_chirps_per_frame)
    assert d == cfg.num_chirps_per_frame // 2 + v_bins
    assert cfg.velocity_axis_m_s()[d] == pytest.approx(v)
    assert abs(r - r0 / cfg.range_resolution_m) <= 1.0


@pytest.mark.parametrize("windows", [("rect", "rect"), ("hann", "hann"), ("blackmanharris", "hamming")])
def test_white_noise_db_statistics_match_closed_form(windows, dtype):
    """|X|^2 ~ Exp(P), P = sigma^2 g_r g_d: E[dB] = 10 log10 P - 10 gamma / ln 10, std = 10/ln10 pi/sqrt 6."""
    g = torch.Generator().manual_seed(1)
    sigma, n, m = 0.01, 256, 32
    x = (sigma * torch.randn(12, 3, m, n, generator=g, dtype=torch.float64)).to(dtype)
    db = ToDecibels()(RangeDoppler(*windows)(x)).double()
    cells = db[..., 4 : n // 2 - 4, :]  # away from DC (mean removal) and Nyquist (real-signal image)
    p = sigma**2 * noise_power_gain(windows[0], n) * noise_power_gain(windows[1], m)
    assert cells.mean().item() == pytest.approx(10 * math.log10(p) - 10 * EULER_GAMMA / math.log(10), abs=0.1)
    assert cells.std().item() == pytest.approx(10 / math.log(10) * math.pi / math.sqrt(6), abs=0.1)


def test_range_doppler_equals_primitive_chain(dtype):
    x = torch.randn(2, 3, 16, 64, dtype=dtype) + 0.3
    for sc in (False, True):
        ref = x - x.mean(-1, keepdim=True)
        ref = StaticClutterRemoval()(ref) if sc else ref
        ref = DopplerFFT("blackman")(RangeFFT("hamming")(ref))
        got = RangeDoppler("hamming", "blackman", static_clutter=sc)(x)
        assert got.shape == (2, 3, 32, 16) and got.dtype == ref.dtype
        torch.testing.assert_close(got, ref)


def test_mean_removal_and_mti():
    x = (
        torch.randn(3, 8, 32, dtype=torch.float64)
        + torch.tensor([0.5, -0.2, 0.1], dtype=torch.float64)[:, None, None]
    )
    assert RemoveMean()(x).mean(-1).abs().max() < 1e-12
    assert StaticClutterRemoval()(x).mean(-2).abs().max() < 1e-12
    # A static target only has zero-Doppler energy: MTI removes it entirely.
    static = tone(64, 9)
    assert RangeDoppler(static_clutter=True)(static).abs().max() < 1e-12


def test_todecibels_floor_and_magnitude():
    z = torch.tensor([[[0j, 3 + 4j]]])
    torch.testing.assert_close(ToDecibels()(z), torch.tensor([[[-240.0, 20 * math.log10(5)]]]))
    torch.testing.assert_close(ToDecibels()(torch.tensor([[[-5.0]]])), torch.tensor([[[20 * math.log10(5)]]]))


def test_combine_rx_modes():
    x = torch.randn(2, 3, 4, 5, dtype=torch.complex128)
    mag2 = x.abs() ** 2
    torch.testing.assert_close(CombineRx()(x), mag2.mean(-3, keepdim=True).sqrt())
    torch.testing.assert_close(CombineRx("coherent")(x), x.mean(-3, keepdim=True))
    torch.testing.assert_close(CombineRx("max")(x), x.abs().amax(-3, keepdim=True))
    torch.testing.assert_close(CombineRx("select", index=2)(x), x[..., 2:3, :, :])
    db = ToDecibels()(x)
    torch.testing.assert_close(CombineRx(db=True)(db), ToDecibels()(CombineRx()(x)))
    torch.testing.assert_close(CombineRx("max", db=True)(db), ToDecibels()(CombineRx("max")(x)))
    with pytest.raises(InputTensorError):
        CombineRx("select", index=3)(x)
    with pytest.raises(InputTensorError):
        CombineRx("coherent", db=True)


@pytest.mark.parametrize(
    "bad, match",
    [
        (torch.zeros(8, 64), "at least 3 dims"),
        (torch.zeros(1, 8, 64, dtype=torch.int16), "floating"),
        (torch.tensor([[[0.0, float("nan")]]]).expand(1, 4, 2), "NaN or Inf"),
        (torch.tensor([[[0.0, float("inf")]]]).expand(1, 4, 2), "NaN or Inf"),
        ([[[0.0]]], "torch.Tensor"),
        # before: bare NotImplementedError from torch.fft / RuntimeError "Invalid number of data points"
        (torch.zeros(1, 4, 8, dtype=torch.float16), "float32 or float64"),
        (torch.zeros(1, 4, 8, dtype=torch.bfloat16), "float32 or float64"),
        (torch.zeros(1, 0, 8), "empty event"),
        (torch.zeros(0, 4, 8), "empty event"),
    ],
)
def test_bad_input_raises_input_tensor_error(bad, match):
    with pytest.raises(InputTensorError, match=match):
        RangeDoppler()(bad)


def test_huge_finite_input_is_not_flagged():
    x = torch.full((1, 4, 8), 3e38)  # sums overflow to inf, but every value is finite
    assert RemoveMean().check_input(x) is x


def test_fft_steps_refuse_half_precision_and_empty_events():
    for t, x in (
        (RangeFFT(), torch.zeros(3, 4, 8, dtype=torch.float16)),
        (DopplerFFT(), torch.zeros(3, 4, 8, dtype=torch.bfloat16)),
        (DopplerFFT(), torch.zeros(3, 0, 8, dtype=torch.complex64)),
    ):
        with pytest.raises(InputTensorError, match=type(t).__name__):
            t(x)
    # an empty *batch* is fine: the output is an empty batch of RD maps
    assert RangeDoppler()(torch.zeros(0, 3, 4, 8)).shape == (0, 3, 4, 4)
