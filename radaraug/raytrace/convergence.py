"""Is the static room converged? Its noise-free range profile against a denser trace, in dB.

See ``docs/raytracer.md``, "Convergence of the static room".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.paths import Paths


def static_range_profile(paths: Paths, config: RadarConfig) -> tuple[torch.Tensor, torch.Tensor]:
    """``(range_m, power_dB)`` of static ``paths`` ``(P, RX)``: ideal receiver, Hann window, mean chirp.

    Args:
        paths: static paths (delay rate ignored).
        config: the radar configuration (chirp and ADC).

    Returns:
        Range of each bin (m) and its power in dB re 1 ADC float^2 (mean over RX), first half of the spectrum.
    """
    from radaraug.sensor.receiver import FMCWReceiver

    rx = FMCWReceiver(config, effects=[]).to(paths.delay_s.device)
    x = rx.static_signal(paths.map(lambda t: t.to(torch.float64) if t.is_floating_point() else
                                   (t.to(torch.complex128) if t.is_complex() else t)))
    mean_chirp = x.mean(-2)  # (RX, N)
    n = mean_chirp.shape[-1]
    win = torch.hann_window(n, periodic=False, dtype=mean_chirp.dtype, device=mean_chirp.device)
    spec = torch.fft.rfft(mean_chirp * win, dim=-1)[..., : n // 2]
    power = (spec.abs() ** 2).mean(0) / win.sum() ** 2
    bins = torch.arange(n // 2, dtype=torch.float64)
    range_m = bins * config.range_resolution_m
    return range_m, 10 * torch.log10(power.double().cpu().clamp_min(1e-30))


@dataclass(frozen=True)
class ProfileComparison:
    """Two static range profiles compared (dB).

    Attributes:
        far_peak_range_m: range of the strongest bin beyond ``far_from_m`` in the reference (the
            end wall of a corridor; searched up to the last bin, not only within the interval).
        far_peak_error_dB: ``test - reference`` at that bin.
        rms_error_dB: RMS of ``test - reference`` over the interval (bins above the floor).
        max_error_dB: largest ``|test - reference|`` over the same bins.
        bins: number of bins compared.
    """

    far_peak_range_m: float
    far_peak_error_dB: float
    rms_error_dB: float
    max_error_dB: float
    bins: int


def compare_profiles(
    range_m: torch.Tensor, test_dB: torch.Tensor, reference_dB: torch.Tensor, *,
    interval_m: tuple[float, float] = (2.0, 19.5), far_from_m: float = 10.0, floor_dB: float = 60.0,
) -> ProfileComparison:
    """Compare a profile with a reference: the error at the strongest far bin and over ``interval_m``.

    Only bins within ``floor_dB`` of the reference's strongest count (weaker ones are under any noise floor).
    """
    in_range = (range_m >= interval_m[0]) & (range_m <= interval_m[1])
    strong = reference_dB >= float(reference_dB[in_range].max()) - floor_dB
    sel = in_range & strong
    diff = (test_dB - reference_dB)[sel]
    far = range_m >= far_from_m
    far_idx = int(torch.where(far, reference_dB, torch.full_like(reference_dB, -math.inf)).argmax())
    return ProfileComparison(
        far_peak_range_m=float(range_m[far_idx]),
        far_peak_error_dB=float(test_dB[far_idx] - reference_dB[far_idx]),
        rms_error_dB=float(diff.pow(2).mean().sqrt()) if diff.numel() else 0.0,
        max_error_dB=float(diff.abs().max()) if diff.numel() else 0.0,
        bins=int(sel.sum()),
    )
