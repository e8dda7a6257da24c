"""The static scene of a clipping capture, against the censored normal's closed form."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.diagnosis.declip import clipped_mean, declipped_mean_chirp, noise_sigma


@pytest.mark.parametrize("s", [0.0, 0.7, 1.0, 1.4, -2.5])
@pytest.mark.parametrize("sigma", [0.05, 0.3, 1.5])
def test_clipped_mean_equals_the_integral_of_the_clipped_density(s, sigma):
    # E[clip(s + e)] by quadrature of the normal density over a fine grid (no closed form used).
    e = torch.linspace(-12 * sigma, 12 * sigma, 400_001, dtype=torch.float64)
    w = torch.exp(-0.5 * (e / sigma) ** 2) / (sigma * math.sqrt(2 * math.pi))
    numeric = float(torch.trapezoid((s + e).clamp(-1, 1) * w, e))
    closed = float(clipped_mean(torch.tensor(s, dtype=torch.float64), torch.tensor(sigma, dtype=torch.float64)))
    assert closed == pytest.approx(numeric, abs=1e-7)


def _clipped_capture(peak: float, sigma: float, seed: int = 0) -> tuple[torch.Tensor, torch.Tensor]:
    g = torch.Generator().manual_seed(seed)
    F, R, M, N = 8, 3, 32, 128
    n = torch.arange(N, dtype=torch.float64)
    static = torch.stack([peak * torch.sin(2 * math.pi * 7 * n / N + r) for r in range(R)])
    x = static[None, :, None, :] + sigma * torch.randn(F, R, M, N, generator=g, dtype=torch.float64)
    return x.clamp(-1, 1), static


def test_the_noise_spread_is_read_from_the_least_clipped_positions():
    x, _ = _clipped_capture(peak=1.6, sigma=0.3)
    assert (x.abs() >= 1).double().mean() > 0.5
    assert noise_sigma(x) == pytest.approx(torch.full((3,), 0.3, dtype=torch.float64), rel=0.05)


def test_a_static_chirp_past_the_rails_is_recovered():
    """Half the samples on the rails: the plain mean misses the peaks by ~0.6.

    Near the peaks 98 % of the 256 chirps clip, so a handful of samples carries the estimate there.
    """
    x, static = _clipped_capture(peak=1.6, sigma=0.3)
    plain = x.mean(dim=(0, 2))
    est = declipped_mean_chirp(x)
    assert (plain - static).abs().max() > 0.55
    assert (est - static).abs().max() < 0.3
    assert (est - static).pow(2).mean().sqrt() < 0.05  # rms over every position
    assert est.abs().max() > 1.3  # past the rail, as the static chirp is


def test_a_capture_that_never_clips_keeps_its_plain_mean():
    x, _ = _clipped_capture(peak=0.4, sigma=0.05)
    assert not bool((x.abs() >= 1).any())
    assert torch.equal(declipped_mean_chirp(x), x.mean(dim=(0, 2)))


def test_the_public_recordings_keep_their_plain_mean_chirp(real_data):
    """No public recording holds a sample on a rail, so declipping leaves their diagnoses as they were."""
    import importlib.util
    from pathlib import Path

    from radaraug.io import open_capture

    path = Path(__file__).resolve().parents[2] / "scripts" / "diagnose_public_recordings.py"
    spec = importlib.util.spec_from_file_location("diagnose_public_recordings", path)
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    for rel in script.RECORDINGS.values():
        with open_capture(real_data / rel) as reader:
            x = reader.read(0, min(reader.num_frames, script.MAX_FRAMES)).to(torch.float64)
        assert torch.equal(declipped_mean_chirp(x), x.mean(dim=(0, 2))), rel
