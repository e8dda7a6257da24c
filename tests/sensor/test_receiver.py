"""Receiver plumbing: shapes, devices, dtypes, batching, RNG, input validation."""

from __future__ import annotations

import pytest
import torch

from radaraug.bench.receiver import benchmark_receiver
from radaraug.errors import InputTensorError
from radaraug.sensor import FMCWReceiver, Paths, point_target_paths
from radaraug.units import FLOAT_CONVENTION


def test_shape_dtype_device_units(cfg, make_paths, device, dtype):
    rx = FMCWReceiver(cfg)
    paths = make_paths(cfg, [2.0, 6.0], [0.5, -1.0], [1e-4, 1e-5], dtype=dtype, device=device)
    gen = torch.Generator(device=device).manual_seed(0)
    x = rx(paths, generator=gen)
    assert x.shape == (3, 64, 256) and x.dtype == dtype and x.device.type == device.type
    assert float(x.abs().max()) <= 1.0
    assert rx.units == FLOAT_CONVENTION


def test_same_seed_same_frame_and_no_input_mutation(cfg, make_paths):
    rx = FMCWReceiver(cfg)
    paths = make_paths(cfg, [2.0], [1.0], [1e-4])
    before = [t.clone() for t in (paths.delay_s, paths.delay_rate, paths.amplitude)]
    a = rx(paths, generator=torch.Generator().manual_seed(5))
    b = rx(paths, generator=torch.Generator().manual_seed(5))
    c = rx(paths, generator=torch.Generator().manual_seed(6))
    assert torch.equal(a, b) and not torch.equal(a, c)
    for t0, t1 in zip(before, (paths.delay_s, paths.delay_rate, paths.amplitude)):
        assert torch.equal(t0, t1)


def test_batch_equals_frames_and_mask(cfg, make_paths):
    rx = FMCWReceiver(cfg, effects=[])
    p1 = make_paths(cfg, [2.0, 4.0], [1.0, 0.0], [1.0, 0.5])
    p2 = make_paths(cfg, [3.0, 9.0], [-2.0, 4.0], [0.2, 1.0])
    batch = Paths(*(torch.stack([getattr(p1, n), getattr(p2, n)]) for n in ("delay_s", "delay_rate", "amplitude")))
    xb = rx(batch)
    # The Taylor order of the fast synthesis follows the fastest path of the whole batch, so
    # frames agree to the synthesis tolerance (1e-5 of the peak), not bit for bit.
    for i, p in enumerate((p1, p2)):
        x1 = rx(p)
        torch.testing.assert_close(xb[i], x1, atol=1e-5 * float(x1.abs().max()), rtol=0)
    masked = Paths(p1.delay_s, p1.delay_rate, p1.amplitude, mask=torch.tensor([True, False]))
    torch.testing.assert_close(rx(masked), rx(make_paths(cfg, [2.0], [1.0], [1.0])))


def test_point_target_paths_radar_equation(cfg):
    p = point_target_paths(cfg, torch.tensor([[0.0, 0.0, 4.0]], dtype=torch.float64),
                           torch.tensor([[0.0, 0.0, 1.5]], dtype=torch.float64), rcs_m2=2.0)
    assert p.delay_s.shape == (1, 3)
    torch.testing.assert_close(p.delay_s, torch.full((1, 3), 8.0 / 299_792_458.0, dtype=torch.float64), rtol=1e-5, atol=0)
    torch.testing.assert_close(p.delay_rate, torch.full((1, 3), 3.0 / 299_792_458.0, dtype=torch.float64), rtol=1e-5, atol=0)
    a2 = cfg.wavelength_m**2 * 2.0 / ((4 * torch.pi) ** 3 * 4.0**4)
    torch.testing.assert_close(p.amplitude.abs() ** 2, torch.full((1, 3), a2, dtype=torch.float64), rtol=1e-4, atol=0)


@pytest.mark.parametrize(
    "mutate, match",
    [
        (lambda p: Paths(p.delay_s[:, :2], p.delay_rate[:, :2], p.amplitude[:, :2]), "RX channels"),
        (lambda p: Paths(p.delay_s * float("nan"), p.delay_rate, p.amplitude), "NaN"),
        (lambda p: Paths(-p.delay_s, p.delay_rate, p.amplitude), ">= 0"),
        (lambda p: Paths(p.delay_s, p.delay_rate[:1], p.amplitude), "shape"),
        (lambda p: Paths(p.delay_s.to(torch.int64), p.delay_rate, p.amplitude), "float32 or float64"),
        (lambda p: Paths(p.delay_s, p.delay_rate, p.amplitude, mask=torch.ones(5, dtype=torch.bool)), "mask"),
        (lambda p: "not paths", "Paths"),
    ],
)
def test_bad_input_raises(cfg, make_paths, mutate, match):
    rx = FMCWReceiver(cfg)
    with pytest.raises(InputTensorError, match=match):
        rx(mutate(make_paths(cfg, [2.0, 3.0])))


def test_generator_on_wrong_device(cfg, make_paths):
    if not torch.cuda.is_available():
        pytest.skip("needs CUDA")
    rx = FMCWReceiver(cfg)
    with pytest.raises(InputTensorError, match="generator"):
        rx(make_paths(cfg, [2.0], device="cuda"), generator=torch.Generator())


def test_benchmark_reports_agreement(small_cfg):
    res = benchmark_receiver(small_cfg, num_paths=40, num_frames=2, device="cpu", exact_frames=1)
    assert res["fast_frames_per_s"] > 0 and res["exact_frames_per_s"] > 0
    assert res["rel_rms_error"] < 1e-4


def test_noise_referenced_orders_round_trip_and_stay_under_the_noise(cfg, make_paths):
    from radaraug.errors import ConfigError

    rx = FMCWReceiver(cfg, noise_tol=3e-3)
    back = FMCWReceiver.from_dict(cfg, rx.to_dict())
    assert back.noise_tol == 3e-3 and FMCWReceiver.from_dict(cfg, FMCWReceiver(cfg).to_dict()).noise_tol is None
    with pytest.raises(ConfigError, match="noise_tol"):
        FMCWReceiver(cfg, noise_tol=0.0)
    # A fast walker: the frame with noise-referenced orders differs from the default's by far less than the noise.
    paths = make_paths(cfg, [3.0], [4.0], [1e-3])
    a = rx(paths, generator=torch.Generator().manual_seed(1))
    b = FMCWReceiver(cfg)(paths, generator=torch.Generator().manual_seed(1))
    noise = FMCWReceiver(cfg)(make_paths(cfg, [3.0], [4.0], [0.0]), generator=torch.Generator().manual_seed(2))
    assert float((a - b).std()) < 0.05 * float((noise - noise.mean(dim=-1, keepdim=True)).std())
