"""Coherent merging of many nearly-equal-delay paths (SBR tube contributions) into few paths.

Paths of one kind whose mean delay falls in the same ``bin_m`` path-length bin are summed at the carrier per
RX, at their power-weighted mean delay ``tau_bar``: ``sum_i a_i exp(-j 2 pi f_c (tau_i - tau_bar))``, so every
member's carrier phase is kept (error bound: ``docs/raytracer.md``, "Merging the static paths").
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.sensor.paths import Paths


def coherent_sum(paths: Paths, inv: torch.Tensor, frequency_Hz: float,
                  ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
    """Sum the paths ``(P, RX)`` of each group ``inv`` ``(P,)`` (values ``0..G-1``) coherently at the carrier.

    Returns:
        ``(tau_bar, amplitude, kind, weight)``: per group the power-weighted mean delay and summed amplitude
        ``(G, RX)`` and the kind ``(G,)``; per member its power weight ``(P,)`` (mean over RX).
    """
    delay, amp = paths.delay_s, paths.amplitude
    kind = paths.kind if paths.kind is not None else torch.zeros(delay.shape[0], dtype=torch.int8,
                                                                   device=delay.device)
    g = int(inv.max()) + 1 if inv.numel() else 0
    n_rx = delay.shape[1]
    power = (amp.abs() ** 2).clamp_min(1e-300 if delay.dtype == torch.float64 else 1e-38)
    idx = inv[:, None].expand(-1, n_rx)
    wsum = torch.zeros(g, n_rx, dtype=delay.dtype, device=delay.device).scatter_add_(0, idx, power)
    tau_bar = torch.zeros_like(wsum).scatter_add_(0, idx, power * delay) / wsum
    rot = torch.polar(torch.ones_like(delay), -2 * math.pi * frequency_Hz * (delay - tau_bar[inv]))
    merged = torch.zeros(g, n_rx, dtype=amp.dtype, device=amp.device).scatter_add_(0, idx, amp * rot)
    kinds = torch.zeros(g, dtype=torch.int8, device=delay.device).scatter_(0, inv, kind)
    return tau_bar, merged, kinds, power.mean(-1)


def weighted_mean(values: torch.Tensor, inv: torch.Tensor, weight: torch.Tensor, groups: int) -> torch.Tensor:
    """Per group ``inv`` the ``weight``-weighted mean of ``values`` ``(P, ...)``."""
    w = weight.to(values.dtype)
    shape = (-1,) + (1,) * (values.ndim - 1)
    total = torch.zeros(groups, dtype=w.dtype, device=w.device).scatter_add_(0, inv, w)
    vsum = torch.zeros(groups, *values.shape[1:], dtype=values.dtype, device=values.device)
    vsum.index_add_(0, inv, values * w.reshape(shape))
    return vsum / total.reshape(shape)


def merge_paths(paths: Paths, frequency_Hz: float, *, bin_m: float = 0.01, floor_dB: float = -100.0) -> Paths:
    """Merge the paths of one snapshot (``delay_s`` ``(P, RX)``), dropping those ``floor_dB`` below the strongest."""
    if paths.delay_s.ndim != 2 or paths.num_paths == 0:
        return paths
    kind = paths.kind if paths.kind is not None else torch.zeros(paths.num_paths, dtype=torch.int8,
                                                                   device=paths.delay_s.device)
    length_bin = torch.round(paths.delay_s.mean(-1) * SPEED_OF_LIGHT / bin_m).long()
    _, inv = torch.unique(length_bin * 4 + kind.long(), return_inverse=True)
    tau_bar, merged, kinds, _ = coherent_sum(paths, inv, frequency_Hz)
    p = (merged.abs() ** 2).amax(-1)
    keep = p >= p.max() * 10 ** (floor_dB / 10) if p.numel() else p.bool()
    keep &= p > 0
    return Paths(tau_bar[keep], torch.zeros_like(tau_bar[keep]), merged[keep], kinds[keep])


def merge_paths_with_vertices(
    paths: Paths, vertices: torch.Tensor, frequency_Hz: float, *, bin_m: float = 0.01, voxel_m: float = 0.1,
) -> tuple[Paths, torch.Tensor]:
    """:func:`merge_paths` that keeps where each merged path scatters (for shadowing).

    Members merge only when they also share the ``voxel_m`` cube of their first interaction point; a merged
    path's vertices are the power-weighted mean of its members', exact to ``voxel_m`` (below the first Fresnel
    zone). Nothing is dropped.

    Args:
        paths: ``(P, RX)`` static paths.
        vertices: ``(P, V, 3)`` their vertices.
        frequency_Hz: carrier frequency.
        bin_m: path-length bin.
        voxel_m: edge of the spatial cells.

    Returns:
        Merged ``(paths, vertices)``.
    """
    if paths.num_paths == 0:
        return paths, vertices
    kind = paths.kind if paths.kind is not None else torch.zeros(paths.num_paths, dtype=torch.int8,
                                                                   device=paths.delay_s.device)
    length_bin = torch.round(paths.delay_s.mean(-1) * SPEED_OF_LIGHT / bin_m).long()
    cell = torch.floor(vertices[:, 1].double() / voxel_m).long()
    key = torch.cat([length_bin[:, None], kind.long()[:, None], cell], dim=1)
    _, inv = torch.unique(key, dim=0, return_inverse=True)
    tau_bar, merged, kinds, weight = coherent_sum(paths, inv, frequency_Hz)
    verts = weighted_mean(vertices, inv, weight, tau_bar.shape[0])
    return Paths(tau_bar, torch.zeros_like(tau_bar), merged, kinds), verts
