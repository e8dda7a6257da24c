"""Superposition: static paths precomputed once give the same frames as tracing them each call."""

from __future__ import annotations

import torch

from radaraug import RadarConfig
from radaraug.sensor import FMCWReceiver, point_target_paths
from radaraug.sensor.paths import Paths


def _cat(a: Paths, b: Paths) -> Paths:
    return Paths.cat([a, b])


def test_static_signal_equals_joint_synthesis() -> None:
    cfg = RadarConfig.bgt60tr13c()
    # Deterministic chain (no noise, no phase noise) so the comparison is exact up to rounding.
    rx = FMCWReceiver(cfg, synthesis="fast")
    keep = [e for e in rx.effects if e.name not in ("thermal_noise", "adc_noise", "phase_noise", "adc_quantization")]
    rx = FMCWReceiver(cfg, effects=keep)
    static = point_target_paths(cfg, positions_m=torch.tensor([[0.3, 0.0, 4.0], [-1.0, 0.2, 9.0]],
                                                               dtype=torch.float64), rcs_m2=2.0)
    moving = point_target_paths(cfg, positions_m=torch.tensor([[0.0, 0.0, 3.0]], dtype=torch.float64),
                                velocities_m_s=torch.tensor([[0.0, 0.0, 1.3]], dtype=torch.float64), rcs_m2=1.0)
    joint = rx(_cat(static, moving))
    cached = rx(moving, static_signal=rx.static_signal(static))
    scale = joint.abs().max()
    assert torch.allclose(joint, cached, atol=1e-9 * float(scale) + 1e-12)
    # And the static signal is really there: without it the frames differ.
    assert (rx(moving) - joint).abs().max() > 1e-3 * scale


def test_static_signal_broadcasts_over_frames_and_is_constant_over_chirps() -> None:
    cfg = RadarConfig.bgt60tr13c()
    rx = FMCWReceiver(cfg)
    static = point_target_paths(cfg, positions_m=torch.tensor([[0.0, 0.0, 5.0]]), rcs_m2=1.0)
    s = rx.static_signal(static)
    assert s.shape == (3, 64, 256)
    # A static path repeats identically in every chirp (no Doppler).
    assert torch.allclose(s, s[:, :1].expand_as(s), atol=1e-6 * float(s.abs().max()))
    moving = point_target_paths(cfg, positions_m=torch.tensor([[0.0, 0.0, 3.0]]),
                                velocities_m_s=torch.tensor([[0.0, 0.0, 1.0]]))
    batch = Paths(*(None if t is None else t.expand(4, *t.shape) for t in
                    (moving.delay_s, moving.delay_rate, moving.amplitude, moving.kind, moving.mask)))
    out = rx(batch, generator=torch.Generator().manual_seed(0), static_signal=s)
    assert out.shape == (4, 3, 64, 256)


def test_static_signal_of_another_shape_is_a_clear_error() -> None:
    import pytest

    from radaraug.errors import InputTensorError

    cfg = RadarConfig.bgt60tr13c()
    rx = FMCWReceiver(cfg, effects=[])
    moving = point_target_paths(cfg, positions_m=torch.tensor([[0.0, 0.0, 3.0]]))
    with pytest.raises(InputTensorError, match="static_signal has shape"):
        rx(moving, static_signal=torch.zeros(3, 64, 128))  # computed for a 128-sample config
    with pytest.raises(InputTensorError, match="real floating-point"):
        rx(moving, static_signal=torch.zeros(3, 64, 256, dtype=torch.complex64))


def test_static_chirp_is_the_static_signals_first_chirp() -> None:
    import pytest

    from radaraug.errors import InputTensorError

    cfg = RadarConfig.bgt60tr13c()
    rx = FMCWReceiver(cfg)
    static = point_target_paths(cfg, positions_m=torch.tensor([[0.3, 0.0, 4.0], [-1.0, 0.2, 9.0], [0.0, 0.1, 0.4]]),
                                rcs_m2=2.0)
    full = rx.static_signal(static)
    one = rx.static_chirp(static)
    # several paths: one GEMM of another shape sums them in another order (float32 rounding)
    assert one.shape == (3, 256) and torch.allclose(one, full[:, 0], rtol=0, atol=1e-6 * float(full.abs().max()))
    # a batch of single paths (how the twin's static basis calls it): nothing to sum, bit for bit
    single = static.select((slice(None), None))
    assert torch.equal(rx.static_chirp(single), rx.static_signal(single)[:, :, 0])
    moving = point_target_paths(cfg, positions_m=torch.tensor([[0.0, 0.0, 3.0]]),
                                velocities_m_s=torch.tensor([[0.0, 0.0, 1.0]]))
    with pytest.raises(InputTensorError, match="must not move"):
        rx.static_chirp(moving)
