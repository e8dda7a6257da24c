"""Motion inside a frame: sub-frame snapshots of moving targets -> per-chirp path delays and gains.

Each path slot's delay rate is interpolated between ``K + 1`` traced knots across the frame and
integrated to every chirp: a fitted line (``delay_s``, ``delay_rate``) plus ``Paths.chirp_delay_s`` and
``Paths.chirp_gain``; ``K`` is chosen per frame and slot. See docs/simulation.md ("Motion inside a frame").
"""

from __future__ import annotations

from collections.abc import Callable

import torch

from radaraug.errors import ConfigError
from radaraug.sensor.paths import Paths
from radaraug.sensor.synthesis import ChirpTiming

DEFAULT_TOL_CYCLES = 0.05
"""Bound on the interpolation error of a path's delay, in carrier cycles ``f0 * delta_tau``, that the
automatic choice of sub-frame snapshots accepts (conservative: docs/simulation.md measures what it leaves)."""

LIVE_BELOW_DB = 120.0
"""Paths weaker than this below a frame's strongest do not steer the refinement (below the float32
synthesis' own relative error, ~1e-6)."""

FIRST_INTERVALS = 2
"""Intervals of the first (coarsest) level of the automatic refinement."""


def chirp_times(timing: ChirpTiming) -> torch.Tensor:
    """Time of each chirp's first ADC sample from the frame's first ramp start, ``(M,)`` float64."""
    m = torch.arange(timing.num_chirps, dtype=torch.float64)
    return m * timing.prt + timing.adc_delay


def _hermite(y: torch.Tensor, x: torch.Tensor) -> torch.Tensor:
    """Interpolate knot values ``y`` ``(..., K+1)`` (uniform knots at 0..K) at ``x`` ``(Q,)`` in [0, K].

    Piecewise-cubic Hermite with centred finite-difference slopes (one-sided second order at the ends;
    linear for two knots). Returns ``(..., Q)``.
    """
    k = y.shape[-1] - 1
    if k == 1:
        return y[..., :1] + (y[..., 1:] - y[..., :1]) * x
    s = _slopes(y)
    i, u = _cell(x, k)
    u2, u3 = u * u, u * u * u
    h00, h10, h01, h11 = 2 * u3 - 3 * u2 + 1, u3 - 2 * u2 + u, -2 * u3 + 3 * u2, u3 - u2
    return (h00 * y[..., i] + h10 * s[..., i] + h01 * y[..., i + 1] + h11 * s[..., i + 1])


def _hermite_integral(y: torch.Tensor, x: torch.Tensor) -> torch.Tensor:
    """``int_0^x`` of :func:`_hermite`'s interpolant of ``y`` ``(..., K+1)`` (knot units).

    At ``x`` ``(Q,)`` in [0, K]: closed form (the cubic's antiderivative), ``(..., Q)``.
    """
    k = y.shape[-1] - 1
    if k == 1:
        return y[..., :1] * x + (y[..., 1:] - y[..., :1]) * x * x / 2
    s = _slopes(y)
    # Whole intervals: (y_i + y_i+1) / 2 + (s_i - s_i+1) / 12, accumulated.
    whole = (y[..., :-1] + y[..., 1:]) / 2 + (s[..., :-1] - s[..., 1:]) / 12
    before = torch.cat([torch.zeros_like(whole[..., :1]), torch.cumsum(whole, dim=-1)], dim=-1)
    i, u = _cell(x, k)
    u2, u3, u4 = u * u, u * u * u, u * u * u * u
    a00, a10, a01, a11 = u4 / 2 - u3 + u, u4 / 4 - 2 * u3 / 3 + u2 / 2, -u4 / 2 + u3, u4 / 4 - u3 / 3
    return before[..., i] + a00 * y[..., i] + a10 * s[..., i] + a01 * y[..., i + 1] + a11 * s[..., i + 1]


def _slopes(y: torch.Tensor) -> torch.Tensor:
    """Finite-difference slopes (per knot) of knot values ``(..., K+1)``, ``K >= 2``."""
    s = torch.empty_like(y)
    s[..., 1:-1] = (y[..., 2:] - y[..., :-2]) / 2
    s[..., 0] = (-3 * y[..., 0] + 4 * y[..., 1] - y[..., 2]) / 2
    s[..., -1] = (3 * y[..., -1] - 4 * y[..., -2] + y[..., -3]) / 2
    return s


def _cell(x: torch.Tensor, k: int) -> tuple[torch.Tensor, torch.Tensor]:
    """The interval ``i`` (of ``k`` between knots 0..k) holding each ``x`` and the position ``u`` in it."""
    i = x.floor().clamp(0, k - 1).long()
    return i, x - i


def _linear(y: torch.Tensor, x: torch.Tensor) -> torch.Tensor:
    i, u = _cell(x, y.shape[-1] - 1)
    return y[..., i] * (1 - u) + y[..., i + 1] * u


def _weights(interpolant: Callable[[torch.Tensor, torch.Tensor], torch.Tensor], knots: int, x: torch.Tensor,
             like: torch.Tensor) -> torch.Tensor:
    """The ``(knots, Q)`` matrix ``W`` with ``interpolant(y, x) == y @ W`` for any knot values ``y``.

    The interpolants are linear in the knot values: applied to the identity they give their weights,
    and one small GEMM replaces the gathers of every (frame, slot) row.
    """
    return interpolant(torch.eye(knots, dtype=like.dtype, device=like.device), x.to(like.device, like.dtype))


def _knot_tensors(p: Paths, t: int, knots: int) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Delay and rate ``(T, P, RX, K+1)`` float64 and amplitude ``(T, P, RX, K+1)`` (masked -> 0)."""
    d = p.delay_s.double().reshape(t, knots, *p.delay_s.shape[1:])
    r = p.delay_rate.double().reshape(t, knots, *p.delay_s.shape[1:])
    a = p.amplitude
    if p.mask is not None:
        a = a * p.mask[..., None].to(a.real.dtype)
    a = a.reshape(t, knots, *a.shape[1:])
    return d.permute(0, 2, 3, 1), r.permute(0, 2, 3, 1), a.permute(0, 2, 3, 1)


def _refinement_error(r_coarse: torch.Tensor, r_mid: torch.Tensor, amp: torch.Tensor, f0: float,
                      interval_s: float) -> torch.Tensor:
    """Bound on the delay error (carrier cycles) per frame and slot ``(T, P)`` of the interpolated rate.

    ``f0 (2/3) H sum_k |e_k|``, ``e_k`` the rate error at interval ``k``'s midpoint, over the live paths.
    ``r_coarse`` ``(T, P, RX, K+1)``, ``r_mid`` ``(T, P, RX, K)``, ``amp`` ``(T, P, RX, 2K+1)`` (fine knots).
    """
    k = r_coarse.shape[-1] - 1
    x = torch.arange(k, dtype=torch.float64, device=r_coarse.device) + 0.5
    err = (r_coarse @ _weights(_hermite, k + 1, x, r_coarse) - r_mid).abs().mean(dim=-2)  # (T, P, K), mean over RX
    mag = amp.abs().mean(dim=-2)  # (T, P, 2K+1)
    floor = mag.flatten(1).amax(dim=1).clamp_min(1e-300) * 10 ** (-LIVE_BELOW_DB / 20)
    live = (mag[..., 0:-1:2] > floor[:, None, None]) & (mag[..., 1::2] > floor[:, None, None]) \
        & (mag[..., 2::2] > floor[:, None, None])
    err = torch.where(live, err, torch.zeros_like(err)).sum(-1)  # (T, P)
    return err * (2 / 3) * interval_s * f0


def check_intra_frame(intervals: int | str, tol_cycles: float) -> None:
    """Raise ConfigError unless ``intervals`` is ``"auto"`` or an int >= 0 and ``tol_cycles`` > 0."""
    if not (intervals == "auto" or (isinstance(intervals, int) and not isinstance(intervals, bool)
                                    and intervals >= 0)):
        raise ConfigError(f"intra_frame must be 'auto' or a number of knot intervals >= 0, got {intervals!r}")
    if not (tol_cycles > 0):
        raise ConfigError(f"intra-frame tolerance must be positive, got {tol_cycles!r}")


def intra_frame_paths(
    trace: Callable[[torch.Tensor, torch.Tensor], Paths],
    times: torch.Tensor,
    timing: ChirpTiming,
    *,
    intervals: int | str = "auto",
    tol_cycles: float = DEFAULT_TOL_CYCLES,
    trace_slots: Callable[[torch.Tensor, torch.Tensor, torch.Tensor], Paths] | None = None,
) -> tuple[Paths, torch.Tensor]:
    """Paths of moving targets over each frame, with per-chirp delays and gains.

    Args:
        trace: maps snapshot times ``(n,)`` (float64, s) and the frame each belongs to ``(n,)`` (long,
            an index into ``times``: frames may hold different targets) to the targets' :class:`Paths`
            ``(n, P, RX)`` (same slots at every time).
        times: frame start times ``(T,)``, s.
        timing: the chirp timing (chirp times, carrier frequency).
        intervals: ``"auto"`` (halve the knot spacing per frame and slot until the delay error bound
            is under ``tol_cycles``), or a fixed number of knot intervals per frame (``0``: one
            snapshot, linear model).
        tol_cycles: the automatic refinement's tolerance, carrier cycles.
        trace_slots: optional ``trace`` of some slots, ``(times, slots (P,) bool, frames) -> Paths (n, P, RX)``
            (other slots anything finite): the finer knots are traced only for the slots that need them.

    Returns:
        ``(paths, intervals_used)``: ``paths`` ``(T, P, RX)`` with ``chirp_delay_s`` and
        ``chirp_gain`` ``(T, P, M)`` (none when ``intervals == 0``), and the number of knot
        intervals each frame used ``(T,)`` (long).
    """
    t64 = times.to(torch.float64).reshape(-1)
    n_frames = int(t64.shape[0])
    every = torch.arange(n_frames)
    if intervals == 0:
        return trace(t64, every), torch.zeros(n_frames, dtype=torch.long)
    tc = chirp_times(timing)
    span = float(tc[-1])
    if span <= 0 or timing.num_chirps < 2:
        return trace(t64, every), torch.zeros(n_frames, dtype=torch.long)
    max_k = 1
    while max_k < timing.num_chirps - 1:
        max_k *= 2
    check_intra_frame(intervals, tol_cycles)
    fixed = None if intervals == "auto" else int(intervals)

    def knots_of(t_idx: torch.Tensor, k: int, odd_only: bool = False) -> torch.Tensor:
        j = torch.arange(1, k, 2) if odd_only else torch.arange(k + 1)
        return (t64[t_idx][:, None] + span * j.to(torch.float64)[None, :] / k).reshape(-1)

    def traced(t_idx: torch.Tensor, k: int, odd_only: bool = False, slots: torch.Tensor | None = None):
        t = knots_of(t_idx, k, odd_only)
        knots = k // 2 if odd_only else k + 1
        rows = t_idx.repeat_interleave(knots)  # knots_of's order: frame-major
        p = (trace(t, rows) if slots is None or trace_slots is None or bool(slots.all())
             else trace_slots(t, slots, rows))
        return (*_knot_tensors(p, int(t_idx.shape[0]), knots), p)

    all_idx = every
    first = fixed if fixed is not None else FIRST_INTERVALS
    # The automatic choice always needs the first level's midpoints: trace both levels' knots
    # in one call (one tracer call less per batch) and split them.
    d, r, a, p0 = traced(all_idx, first if fixed is not None else 2 * first)
    kind = None if p0.kind is None else p0.kind.reshape(n_frames, -1, p0.kind.shape[-1])[:, 0]
    groups: list[tuple] = []  # (frames, K, delays, rates, amps, slot levels) per finest level
    if fixed is not None:
        groups.append((all_idx, first, d, r, a, torch.full(d.shape[:2], first, dtype=torch.long)))
    else:
        # Each slot takes the first level at which its own check passes, so a person's paths do
        # not depend on who else is in the frame; a frame is refined while any slot needs it.
        (d, dm), (r, rm), (a, am) = ((t[..., 0::2], t[..., 1::2]) for t in (d, r, a))
        idx, k = all_idx, first
        level = torch.zeros(d.shape[:2], dtype=torch.long)  # 0: not converged yet
        while True:
            if k > first:
                # Only the slots some of these frames still refine need the new knots: a slot that
                # converged uses every (2k / its level)-th knot, none of these.
                dm, rm, am, _ = traced(idx, 2 * k, odd_only=True, slots=(level == 0).any(dim=0))
            fine = [_interleave(c, m) for c, m in ((d, dm), (r, rm), (a, am))]
            if 2 * k >= max_k:
                level = torch.where(level == 0, torch.full_like(level, 2 * k), level)
                groups.append((idx, 2 * k, *fine, level))
                break
            err = _refinement_error(r, rm, fine[2], timing.f0, span / k).cpu()
            level = torch.where((level == 0) & (err <= tol_cycles), torch.full_like(level, 2 * k), level)
            ok = (level > 0).all(dim=1)
            if bool(ok.any()):
                groups.append((idx[ok], 2 * k, *(f[ok.to(f.device)] for f in fine), level[ok]))
            if bool(ok.all()):
                break
            idx, k, level = idx[~ok], 2 * k, level[~ok]
            d, r, a = (f[(~ok).to(f.device)] for f in fine)
    return _assemble(groups, n_frames, tc, span, kind, p0), _intervals(groups, n_frames)


def _interleave(coarse: torch.Tensor, mid: torch.Tensor) -> torch.Tensor:
    """Knot values of the next level: ``coarse`` ``(..., K+1)`` and ``mid`` ``(..., K)`` alternated."""
    out = coarse.new_empty(*coarse.shape[:-1], coarse.shape[-1] + mid.shape[-1])
    out[..., 0::2] = coarse
    out[..., 1::2] = mid
    return out


def _intervals(groups, n_frames: int) -> torch.Tensor:
    """Knot intervals each frame traced ``(T,)`` (the finest any of its slots needed)."""
    used = torch.zeros(n_frames, dtype=torch.long)
    for idx, k, *_ in groups:
        used[idx] = k
    return used


def _assemble(groups, n_frames: int, tc: torch.Tensor, span: float, kind: torch.Tensor | None, like: Paths) -> Paths:
    """Fit the reference line per slot and RX and collect the per-chirp residual and gain."""
    p_count, n_rx = like.delay_s.shape[-2:]
    dev, dt = like.delay_s.device, like.delay_s.dtype
    m = tc.shape[0]
    delay = torch.zeros(n_frames, p_count, n_rx, dtype=torch.float64, device=dev)
    rate = torch.zeros_like(delay)
    amp = torch.zeros(n_frames, p_count, n_rx, dtype=like.amplitude.dtype, device=dev)
    chirp_delay = torch.zeros(n_frames, p_count, m, dtype=torch.float64, device=dev)
    gain = torch.zeros(n_frames, p_count, m, dtype=torch.float64, device=dev)
    tcd = tc.to(dev)
    t_mean = tcd.mean()
    tcen = tcd - t_mean
    for idx, k_max, d_all, r_all, a_all, level in groups:
        idx = idx.to(dev)
        level = level.to(dev)
        motion = torch.zeros(*d_all.shape[:2], m, dtype=torch.float64, device=dev)
        g = torch.zeros_like(motion)
        a_ref = torch.zeros(a_all.shape[:-1], dtype=a_all.dtype, device=dev)
        for k in sorted(set(level.flatten().tolist())):
            # The slots that converged at k intervals use every (k_max / k)-th knot.
            sel = level == k
            r, a = (t[..., :: k_max // k] for t in (r_all, a_all))
            r_mean = r.mean(dim=-2)  # (F, P, K+1): the RX channels share the motion's shape
            # Delay change since t = 0: the interpolated rate integrated in closed form.
            integral = r_mean @ (_weights(_hermite_integral, k + 1, tcd / span * k, r_mean) * (span / k))  # (F, P, M)
            motion = torch.where(sel[..., None], integral, motion)
            mag = a.abs().mean(dim=-2)  # (F, P, K+1)
            # Amplitude relative to the first knot where the slot is live (its phase, RX balance).
            live = mag > 0
            ref_k = live.to(torch.int8).argmax(-1)  # 0 when never live
            m_ref = mag.gather(-1, ref_k[..., None])  # (F, P, 1)
            a_k = a.gather(-1, ref_k[..., None, None].expand(*a.shape[:-1], 1))[..., 0]  # (F, P, RX)
            a_ref = torch.where(sel[..., None], a_k, a_ref)
            rel = mag / torch.where(m_ref > 0, m_ref, torch.ones_like(m_ref))
            g = torch.where(sel[..., None], rel @ _weights(_linear, k + 1, tcd / span * k, rel), g)
        # Bistatic rate offset of each RX from the RX mean, from the frame's end knots (which every
        # level shares): ~1e-3 of the rate, constant over a frame to well below that.
        ends = r_all[..., [0, -1]]
        r_off = (ends - ends.mean(dim=-2, keepdim=True)).mean(dim=-1)  # (F, P, RX)
        d = d_all
        # Least-squares line over the chirps: the reference delay (at t = 0) and rate.
        slope = (motion * tcen).sum(-1) / (tcen * tcen).sum()
        icpt = motion.mean(-1) - slope * t_mean
        resid = motion - icpt[..., None] - slope[..., None] * tcd
        tau0 = d[..., 0] + icpt[..., None]
        rate_rx = slope[..., None] + r_off
        delay[idx], rate[idx], amp[idx] = tau0, rate_rx, a_ref
        chirp_delay[idx], gain[idx] = resid, g
    mask = gain.amax(-1) > 0
    # A slot that exists at no knot of its frame contributes nothing; its geometry (e.g. a wall
    # bounce point far off its wall) need not be smooth, so give it a plain zero-motion line.
    first = like.delay_s.reshape(n_frames, -1, p_count, n_rx)[:, 0].double().abs()
    dead = ~mask
    delay = torch.where(dead[..., None], first, delay)
    rate = torch.where(dead[..., None], torch.zeros_like(rate), rate)
    chirp_delay = torch.where(dead[..., None], torch.zeros_like(chirp_delay), chirp_delay)
    return Paths(delay.to(dt), rate.to(dt), amp, kind, mask, chirp_delay.to(dt), gain.to(dt))
