"""IF synthesis against the closed-form beat signal, and fast vs exact agreement."""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.sensor.synthesis import (
    ChirpTiming,
    chebyshev_orders_needed,
    synthesize_exact,
    synthesize_fast,
)

#: The tolerance these tests check the series' bounds at (relative to the strongest path). The default
#: is chosen by the error contract against the noise (tests/sim/test_synthesis_contract.py).
TOL = 1e-5


def closed_form_beat(config, coef, tau0, rate):
    """x[m, n] = Re{C exp(j 2 pi (f0 tau + S tau t - S tau^2 / 2))}, tau = tau0 + rate (m T + t_d + t),
    written independently in numpy float64 (f0 = RF frequency at the first ADC sample)."""
    f0 = config.start_frequency_Hz + config.slope_Hz_per_s * config.adc_delay_s
    S = config.slope_Hz_per_s
    m = np.arange(config.num_chirps_per_frame)[:, None]
    t = np.arange(config.num_samples_per_chirp)[None, :] / config.sample_rate_Hz
    tau = tau0 + rate * (m * config.chirp_repetition_time_s + config.adc_delay_s + t)
    cycles = f0 * tau + S * tau * t - S * tau**2 / 2
    return np.real(coef * np.exp(2j * np.pi * (cycles - np.round(cycles))))


def _inputs(config, ranges, speeds, coefs, rx=1):
    tau = torch.tensor([2 * r / SPEED_OF_LIGHT for r in ranges], dtype=torch.float64).expand(rx, -1)
    rate = torch.tensor([2 * v / SPEED_OF_LIGHT for v in speeds], dtype=torch.float64).expand(rx, -1)
    c = torch.tensor(coefs, dtype=torch.complex128).expand(rx, -1)
    return c, tau, rate


@pytest.mark.parametrize("method", ["fast", "exact"])
@pytest.mark.parametrize("speed", [0.0, 1.3, -4.7])
def test_single_path_matches_closed_form(small_cfg, method, speed):
    c, tau, rate = _inputs(small_cfg, [7.3], [speed], [0.8 * np.exp(0.7j)])
    timing = ChirpTiming.from_config(small_cfg)
    fn = synthesize_fast if method == "fast" else synthesize_exact
    x = fn(c, tau, rate, timing, dtype=torch.float64)[0].numpy()
    ref = closed_form_beat(small_cfg, 0.8 * np.exp(0.7j), 2 * 7.3 / SPEED_OF_LIGHT, 2 * speed / SPEED_OF_LIGHT)
    assert np.abs(x - ref).max() < 2e-5


def _walker_paths(g: torch.Generator, P: int, RX: int, max_range_m: float) -> tuple[torch.Tensor, torch.Tensor]:
    """Delays ``(RX, P)`` of targets at 0.5 m to ``max_range_m`` (an antenna spacing apart per RX) and
    their delay rates at up to 5 m/s, drawn from ``g`` (range first, then speed)."""
    r = 0.5 + (max_range_m - 0.5) * torch.rand(P, generator=g, dtype=torch.float64)
    v = (torch.rand(P, generator=g, dtype=torch.float64) * 2 - 1) * 5.0
    tau = (2 * r / SPEED_OF_LIGHT)[None, :] + 1e-12 * torch.arange(RX, dtype=torch.float64)[:, None]
    return tau, (2 * v / SPEED_OF_LIGHT)[None, :].expand(RX, P)


def test_fast_agrees_with_exact_at_walker_speeds(cfg):
    """Documented tolerance: relative RMS error < 1e-5 and max abs error < 1e-5 of the peak
    signal (float64), targets at 0.5-20 m moving at up to 5 m/s."""
    g = torch.Generator().manual_seed(1)
    P, RX = 60, 3
    tau, rate = _walker_paths(g, P, RX, 20.0)
    coef = torch.polar(torch.rand(RX, P, generator=g, dtype=torch.float64),
                       2 * math.pi * torch.rand(RX, P, generator=g, dtype=torch.float64))
    timing = ChirpTiming.from_config(cfg)
    xe = synthesize_exact(coef, tau, rate, timing, dtype=torch.float64)
    for dtype, tol in ((torch.float64, 1e-5), (torch.float32, 1e-5)):
        xf = synthesize_fast(coef, tau, rate, timing, dtype=dtype, taylor_tol=TOL).double()
        err = xf - xe
        assert xf.shape == (RX, 64, 256)
        assert (err.pow(2).mean() / xe.pow(2).mean()).sqrt() < tol
        assert err.abs().max() < 1e-5 * xe.abs().max() * 10


def test_fast_handles_batch_dims_and_empty(small_cfg):
    timing = ChirpTiming.from_config(small_cfg)
    c, tau, rate = _inputs(small_cfg, [2.0, 5.0], [1.0, 0.0], [1.0, 0.5j], rx=3)
    one = synthesize_fast(c, tau, rate, timing, dtype=torch.float64)
    two = synthesize_fast(torch.stack([c, 2 * c]), torch.stack([tau, tau]), torch.stack([rate, rate]), timing,
                          dtype=torch.float64)
    assert two.shape == (2, 3, 16, 64)
    torch.testing.assert_close(two[0], one)
    torch.testing.assert_close(two[1], 2 * one)
    empty = synthesize_fast(c[:, :0], tau[:, :0], rate[:, :0], timing, dtype=torch.float32)
    assert empty.shape == (3, 16, 64) and not empty.any()


def test_chebyshev_order_bound():
    """A path keeps order k while |C| 2 (theta/2)^k / k! >= tol * (strongest |C|), elementwise over any shape;
    past theta = 2 the terms first grow, and the orders run past the largest one."""
    theta = torch.tensor([[0.0, 0.3, 1.1], [1.1, 1.9, 6.0]], dtype=torch.float64)
    rel = torch.tensor([[1.0, 1.0, 1.0], [1e-3, 1.0, 1e-2]], dtype=torch.float64)
    need = chebyshev_orders_needed(theta, rel, 1e-6)
    assert need.shape == theta.shape
    for t, r, k in zip(theta.flatten().tolist(), rel.flatten().tolist(), need.flatten().tolist()):
        bound = [r * 2 * (t / 2) ** j / math.factorial(j) for j in range(60)]
        assert all(b < 1e-6 for b in bound[k + 1:])
        if k > 0:
            assert bound[k] >= 1e-6
    assert need[0, 0] == 0 and need[1, 0] < need[0, 2]
    # about two orders fewer than the Taylor series' bound |C| theta^k / k! for the same tolerance
    for t, r, k in zip(theta[0, 1:].tolist(), rel[0, 1:].tolist(), need[0, 1:].tolist()):
        assert r * t ** (k + 1) / math.factorial(k + 1) >= 1e-6


def test_bessel_ratios_against_the_power_series():
    """F_k = J_k k! / (x/2)^k from the backward recurrence agrees with J_k's power series, written here
    in plain Python (x up to 3: beyond the walker's ~1.4 rad)."""
    from radaraug.sensor.synthesis import _bessel_ratios

    x = torch.tensor([0.0, 0.2, 0.9, 1.4, 3.0], dtype=torch.float64)
    f = _bessel_ratios(x, 7, 1e-12)
    for k in range(8):
        for xi, fk in zip(x.tolist(), f[k].tolist()):
            j_k = sum((-1) ** s * (xi / 2) ** (2 * s + k) / (math.factorial(s) * math.factorial(s + k)) for s in range(40))
            assert abs((xi / 2) ** k / math.factorial(k) * fk - j_k) < 1e-11


def test_frames_keep_their_own_orders(cfg):
    """Orders are chosen per frame: a frame of slow, weak paths next to a frame with a fast, strong one
    agrees with the exact sum to the bound its tolerance documents."""
    timing = ChirpTiming.from_config(cfg)
    g = torch.Generator().manual_seed(7)
    T, RX, P = 2, 3, 12
    tau = (2 * (1 + 9 * torch.rand(T, 1, P, generator=g, dtype=torch.float64)) / SPEED_OF_LIGHT
           + 1e-12 * torch.arange(RX, dtype=torch.float64)[:, None]).expand(T, RX, P)
    speed = torch.rand(T, 1, P, generator=g, dtype=torch.float64) * 0.5
    speed[1, 0, 0] = 6.0  # one fast path in the second frame only
    rate = (2 * speed / SPEED_OF_LIGHT).expand(T, RX, P)
    amp = torch.full((T, RX, P), 1e-2, dtype=torch.float64)
    amp[1, :, 0] = 1.0
    coef = torch.polar(amp, 2 * math.pi * torch.rand(T, RX, P, generator=g, dtype=torch.float64))
    exact = synthesize_exact(coef, tau, rate, timing, dtype=torch.float64)
    fast = synthesize_fast(coef, tau, rate, timing, dtype=torch.float64, taylor_tol=TOL)
    peak = exact.abs().max()
    for f in range(T):  # at taylor_tol 1e-5: max abs error < 1e-4 of the peak, RMS < 1e-5
        assert (fast[f] - exact[f]).abs().max() < 1e-4 * peak
        assert (fast[f] - exact[f]).pow(2).mean().sqrt() < 1e-5 * exact.pow(2).mean().sqrt()


@pytest.mark.parametrize("chunk", [1, 3, 1 << 30])
def test_fast_chunked_rows_agree_with_exact_and_broadcast_chirp_terms(small_cfg, monkeypatch, chunk):
    """The fast synthesis works through the (frames x RX) rows in cache-sized chunks: any chunking
    (one row, uneven chunks, everything at once) gives the exact sum, with per-chirp delays and
    gains shared by the RX channels (``(T, 1, P, M)``, broadcast) as intra-frame motion gives them."""
    import radaraug.sensor.synthesis as synthesis

    timing = ChirpTiming.from_config(small_cfg)
    g = torch.Generator().manual_seed(4)
    T, RX, P, M = 5, 3, 7, timing.num_chirps
    tau = (2 * (1 + 9 * torch.rand(T, 1, P, generator=g, dtype=torch.float64)) / SPEED_OF_LIGHT
           + 1e-12 * torch.arange(RX, dtype=torch.float64)[:, None])
    rate = (2 * (torch.rand(T, 1, P, generator=g, dtype=torch.float64) * 8 - 4) / SPEED_OF_LIGHT).expand(T, RX, P)
    coef = torch.polar(torch.rand(T, RX, P, generator=g, dtype=torch.float64),
                       2 * math.pi * torch.rand(T, RX, P, generator=g, dtype=torch.float64))
    chirp_delay = 2e-12 * torch.sin(torch.linspace(0, 3, M, dtype=torch.float64) + torch.rand(T, 1, P, 1, generator=g))
    chirp_gain = 1 + 0.2 * torch.rand(T, 1, P, M, generator=g, dtype=torch.float64)
    monkeypatch.setattr(synthesis, "_FAST_CHUNK_ELEMENTS", chunk * 2 * P * timing.num_samples)
    kw = dict(dtype=torch.float64, chirp_delay=chirp_delay, chirp_gain=chirp_gain)
    fast = synthesize_fast(coef, tau, rate, timing, taylor_tol=TOL, **kw)
    exact = synthesize_exact(coef, tau, rate, timing, **kw)
    assert fast.shape == (T, RX, M, timing.num_samples)
    assert ((fast - exact).pow(2).mean() / exact.pow(2).mean()).sqrt() < 1e-5


@pytest.mark.parametrize("spread", ["antenna", "wide"])
def test_rx_channels_share_the_fast_time_factor_only_where_exact(cfg, spread):
    """The RX channels of a frame share one fast-time factor (their linear rate difference joins the
    coupling's expansion) when their delays differ by an antenna spacing (picoseconds, as the twin
    gives them); with rates far apart (in-chirp quadratic terms differing by more than the Taylor
    tolerance) they are synthesized apart. Either way the result is the exact sum."""
    import radaraug.sensor.synthesis as synthesis

    timing = ChirpTiming.from_config(cfg)
    g = torch.Generator().manual_seed(7)
    T, RX, P = 2, 3, 20
    r = 0.5 + 9.5 * torch.rand(T, 1, P, generator=g, dtype=torch.float64)
    v = (torch.rand(T, 1, P, generator=g, dtype=torch.float64) * 2 - 1) * 5.0
    step_s, step_rate = (8e-12, 5e-12) if spread == "antenna" else (3e-10, 2e-10)
    k = torch.arange(RX, dtype=torch.float64)[:, None]
    tau = 2 * r / SPEED_OF_LIGHT + step_s * k
    rate = 2 * v / SPEED_OF_LIGHT + step_rate * k
    coef = torch.polar(torch.rand(T, RX, P, generator=g, dtype=torch.float64),
                       2 * math.pi * torch.rand(T, RX, P, generator=g, dtype=torch.float64))
    mag = coef.abs().reshape(-1, P).amax(dim=0)
    _, shared = synthesis._coupling_phase(tau, rate, timing, None, mag / mag.max(), TOL)
    assert (shared is not None) == (spread == "antenna")
    exact = synthesize_exact(coef, tau, rate, timing, dtype=torch.float64)
    for dtype in (torch.float64, torch.float32):
        fast = synthesize_fast(coef, tau, rate, timing, dtype=dtype, taylor_tol=TOL).double()
        assert ((fast - exact).pow(2).mean() / exact.pow(2).mean()).sqrt() < 1e-5


def test_an_absolute_bound_holds_whatever_the_strongest_path(cfg):
    """``abs_tol`` bounds the neglected terms in the samples' units: the same error with a path 60 dB
    stronger in the call, where the relative ``taylor_tol`` would loosen by 60 dB."""
    g = torch.Generator().manual_seed(3)
    P, RX = 30, 3
    tau, rate = _walker_paths(g, P, RX, 10.0)
    coef = torch.polar(torch.full((RX, P), 1e-3, dtype=torch.float64),
                       2 * math.pi * torch.rand(RX, P, generator=g, dtype=torch.float64))
    timing = ChirpTiming.from_config(cfg)
    loud = coef.clone()
    loud[:, 0] = 1.0  # one path 60 dB over the others
    for c in (coef, loud):
        exact = synthesize_exact(c, tau, rate, timing, dtype=torch.float64)
        err = {a: (synthesize_fast(c, tau, rate, timing, dtype=torch.float64, abs_tol=a) - exact).abs().max()
               for a in (1e-9, 1e-6)}
        assert err[1e-9] < 1e-9 * 10 and err[1e-6] < 1e-6 * 10  # within a small factor of the bound
        assert err[1e-6] > err[1e-9]
