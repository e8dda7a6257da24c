"""The static scene of a clipping capture: its mean chirp before the ADC's rails.

A capture that clips holds at each sample position the static chirp plus noise, cut at the rails.
The plain mean over chirps is pulled towards the rail, so an estimated static scene built from it is
weaker than the capture's, and a twin that adds its noise to it puts too few samples on the rails.
Under Gaussian noise the clipped mean is a known, monotone function of the static value (a censored
normal), so the static value follows from the measured mean and the noise's spread.
"""

from __future__ import annotations

import math

import torch

# Bisection steps for the static value: the bracket shrinks by 2**-60, far below an ADC code.
_STEPS = 60
# A sample this close to a rail is on it (float32 rounding of the rail code; the next code is 2**-11 in).
_ON_RAIL = 1e-6


def _phi(z: torch.Tensor) -> torch.Tensor:
    return torch.exp(-0.5 * z * z) / math.sqrt(2 * math.pi)


def normal_cdf(z: torch.Tensor) -> torch.Tensor:
    """The standard normal's CDF (also the clipping detector's Gaussian prediction)."""
    return 0.5 * torch.erfc(-z / math.sqrt(2))


def clipped_mean(s: torch.Tensor, sigma: torch.Tensor, rail: float = 1.0) -> torch.Tensor:
    """Mean of ``clip(s + e, -rail, rail)`` for ``e ~ N(0, sigma^2)`` (the censored normal's mean).

    Args:
        s: the static values.
        sigma: the noise's standard deviation (broadcast against ``s``).
        rail: the ADC's rail (SDK floats: 1).

    Returns:
        The expected clipped value, elementwise.
    """
    a = (-rail - s) / sigma
    b = (rail - s) / sigma
    Pa, Pb = normal_cdf(a), normal_cdf(b)
    return -rail * Pa + rail * (1 - Pb) + s * (Pb - Pa) + sigma * (_phi(a) - _phi(b))


def noise_sigma(x: torch.Tensor, rail: float = 1.0) -> torch.Tensor:
    """Each receiver's noise spread from chirp-to-chirp differences at its least clipped positions.

    A difference of neighbouring chirps cancels the static scene and slow drift and holds twice the
    noise's variance; the median absolute difference ignores bursts. Positions with the fewest rail
    samples (none, or the least clipped tenth) keep the censoring's bias small.

    Args:
        x: samples ``(F, R, M, N)`` in SDK floats.
        rail: the ADC's rail.

    Returns:
        ``(R,)`` standard deviations.
    """
    on_rail = x.abs() >= rail - _ON_RAIL
    q = on_rail.double().mean(dim=(0, 2))  # (R, N) clipped share per position
    d = (x[:, :, 1:] - x[:, :, :-1]).abs()  # (F, R, M-1, N)
    ok = ~(on_rail[:, :, 1:] | on_rail[:, :, :-1])
    out = []
    for r in range(x.shape[1]):
        limit = max(0.02, float(torch.quantile(q[r], 0.1)))
        cols = q[r] <= limit
        vals = d[:, r][..., cols][ok[:, r][..., cols]]
        out.append(1.4826 * float(vals.median()) / math.sqrt(2) if vals.numel() else 0.0)
    return torch.tensor(out, dtype=x.dtype)


def declipped_mean_chirp(x: torch.Tensor, rail: float = 1.0) -> torch.Tensor:
    """The mean chirp ``(R, N)`` of samples ``(F, R, M, N)`` with the rails' pull undone.

    Positions with no sample on a rail keep the plain mean. Elsewhere the static value solves
    :func:`clipped_mean` ``= measured mean`` (bisection; monotone in the static value), bounded where
    every chirp but half a sample would clip (beyond that the capture cannot tell values apart).

    Args:
        x: samples in SDK floats.
        rail: the ADC's rail.

    Returns:
        The estimated static chirp per receiver, in SDK floats (may exceed the rail).
    """
    x = x.to(torch.float64)
    mean = x.mean(dim=(0, 2))
    on_rail = (x.abs() >= rail - _ON_RAIL).any(dim=0).any(dim=1)  # (R, N)
    if not bool(on_rail.any()):
        return mean
    sigma = noise_sigma(x, rail).clamp_min(1e-9)[:, None].expand_as(mean)
    n = x.shape[0] * x.shape[2]
    reach = rail + sigma * math.sqrt(2) * float(torch.erfinv(torch.tensor(1 - 1 / n, dtype=torch.float64)))
    lo, hi = -reach.clone(), reach.clone()
    target = mean.clamp(-rail, rail)
    for _ in range(_STEPS):
        mid = (lo + hi) / 2
        below = clipped_mean(mid, sigma, rail) < target
        lo = torch.where(below, mid, lo)
        hi = torch.where(below, hi, mid)
    return torch.where(on_rail, (lo + hi) / 2, mean)
