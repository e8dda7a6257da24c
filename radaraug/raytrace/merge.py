"""Coherent merging of many nearly-equal-delay paths (SBR tube contributions) into few paths.

Paths whose mean delay falls in the same bin of ``bin_m`` metres of path length (and of the
same kind) are summed coherently at the carrier: per RX, the merged delay is the
power-weighted mean ``tau_bar`` of the members and the merged amplitude is
``sum_i a_i exp(-j 2 pi f_c (tau_i - tau_bar))``, so the carrier phase of every member is kept.
Across the sweep the members' delays differ from ``tau_bar`` by at most ``bin_m / c``: the phase
error at the band edges is at most ``pi * B * bin_m / c`` (0.09 rad for 1 cm at 882 MHz).
Merged paths weaker than ``floor_dB`` below the strongest are dropped.
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.sensor.paths import Paths


def merge_paths(paths: Paths, frequency_Hz: float, *, bin_m: float = 0.01, floor_dB: float = -100.0) -> Paths:
    """Merge the paths of one snapshot (``delay_s`` ``(P, RX)``); see the module docstring."""
    if paths.delay_s.ndim != 2 or paths.num_paths == 0:
        return paths
    delay, amp = paths.delay_s, paths.amplitude
    kind = paths.kind if paths.kind is not None else torch.zeros(delay.shape[0], dtype=torch.int8,
                                                                   device=delay.device)
    length_bin = torch.round(delay.mean(-1) * SPEED_OF_LIGHT / bin_m).long()
    key = length_bin * 4 + kind.long()
    uniq, inv = torch.unique(key, return_inverse=True)
    g = uniq.numel()
    n_rx = delay.shape[1]
    power = (amp.abs() ** 2).clamp_min(1e-300 if delay.dtype == torch.float64 else 1e-38)
    idx = inv[:, None].expand(-1, n_rx)
    wsum = torch.zeros(g, n_rx, dtype=delay.dtype, device=delay.device).scatter_add_(0, idx, power)
    tsum = torch.zeros_like(wsum).scatter_add_(0, idx, power * delay)
    tau_bar = tsum / wsum
    phase = -2 * math.pi * frequency_Hz * (delay - tau_bar[inv])
    rot = torch.polar(torch.ones_like(phase), phase)
    merged = torch.zeros(g, n_rx, dtype=amp.dtype, device=amp.device).scatter_add_(0, idx, amp * rot)
    kinds = torch.zeros(g, dtype=torch.int8, device=delay.device).scatter_(0, inv, kind)
    p = (merged.abs() ** 2).amax(-1)
    keep = p >= p.max() * 10 ** (floor_dB / 10) if g else p.bool()
    keep &= p > 0
    return Paths(tau_bar[keep], torch.zeros_like(tau_bar[keep]), merged[keep], kinds[keep])
