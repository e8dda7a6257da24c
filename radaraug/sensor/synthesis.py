"""IF synthesis: the real beat signal of a set of paths over fast and slow time.

Each path contributes ``Re{C exp(j Phi[m, n])}``, ``Phi = 2 pi (f0 tau + S tau t - S tau^2 / 2)`` with the
delay ``tau`` moving over the frame. ``fast`` splits ``Phi`` into slow-time, fast-time and coupling terms,
expands the coupling in a Chebyshev series to ``taylor_tol`` and sums the paths with real GEMMs; ``exact``
evaluates ``Phi`` for every sample in float64 (the reference). Phases are reduced modulo one cycle in float64
before the trig. Phase model, accuracy and speed: ``docs/receiver.md``, "How it is computed".
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import torch

from radaraug.config import RadarConfig

SYNTHESIS_METHODS = ("fast", "exact")
DEFAULT_TAYLOR_TOL = 1e-5
"""Largest neglected term of the coupling's expansion (its bound ``2 (theta/2)^K / K!``) times the
path's amplitude, relative to the amplitude of the strongest path of the call (the name is from
when the expansion was a Taylor series)."""

_EXACT_CHUNK_ELEMENTS = 1 << 22
_FAST_CHUNK_ELEMENTS = 1 << 19  # fast-time factors per chunk of rows (2 MiB in float32)
# On a GPU the chunk loop's cost is its kernel launches, not cache misses: at the CPU's chunk a
# 256-frame corridor batch was ~7,000 GEMMs and ~100,000 launches, 2.8 s of CPU time for 0.22 s of
# GPU work (H200 profile). 256 MiB of fast-time factors per chunk takes ~200 paper-config frames
# per launch and keeps the chunk's temporaries within a few GiB.
_FAST_CHUNK_ELEMENTS_GPU = 1 << 26
_MAX_ORDERS = 60
_PER_FRAME_TOL = 0.25  # the share of ``taylor_tol`` each path's orders are chosen for, per frame (see synthesize_fast)


@dataclass(frozen=True)
class ChirpTiming:
    """The constants of the phase model, from a :class:`RadarConfig`.

    Attributes:
        f0: RF frequency at the first ADC sample, Hz.
        slope: chirp slope S, Hz/s.
        prt: chirp repetition time T, s.
        adc_delay: ramp start to first sample t_d, s.
        fs: ADC sample rate, Hz.
        num_chirps: M.
        num_samples: N.
    """

    f0: float
    slope: float
    prt: float
    adc_delay: float
    fs: float
    num_chirps: int
    num_samples: int

    @classmethod
    def from_config(cls, config: RadarConfig) -> ChirpTiming:
        """Timing constants of ``config``."""
        return cls(
            f0=config.sampled_start_frequency_Hz,
            slope=config.slope_Hz_per_s,
            prt=config.chirp_repetition_time_s,
            adc_delay=config.adc_delay_s,
            fs=config.sample_rate_Hz,
            num_chirps=config.num_chirps_per_frame,
            num_samples=config.num_samples_per_chirp,
        )


def beat_frequency_Hz(delay_s: torch.Tensor, delay_rate: torch.Tensor, timing: ChirpTiming) -> torch.Tensor:
    """IF frequency ``S tau + f0 r`` (Hz) of a path at the first sample: range beat plus Doppler."""
    tau = delay_s.double() + delay_rate.double() * timing.adc_delay
    return timing.slope * tau + timing.f0 * delay_rate.double()


def _frac(cycles: torch.Tensor) -> torch.Tensor:
    """Reduce cycles to [-0.5, 0.5) so the later cast to float32 keeps the phase exact."""
    return cycles - torch.round(cycles)


def _phase_terms(
    delay_s: torch.Tensor, delay_rate: torch.Tensor, timing: ChirpTiming, chirp_delay: torch.Tensor | None = None,
):
    """Per-path phase pieces of the separable form (float64).

    With ``chirp_delay`` ``d_m`` ``(…, P, M)`` the delay at chirp ``m`` is ``tau_m = tau0 + r (m T + t_d) + d_m``.
    The coupling ``g_m n`` is split about the mid-range ``g_bar`` of ``g_m`` and the centre sample ``nc``; what
    remains is the residual ``theta w_m v_n`` with ``w_m, v_n`` in [-1, 1].

    Returns:
        ``(slow, rate, theta, quad, w)``: slow-time cycles mod 1 ``(…, P, M)``; fast-time cycles per sample
        ``(…, P)``; largest residual coupling phase ``(…, P)``, rad; the quadratic term ``S r (1 - r/2) t_n^2``
        in cycles per sample^2 ``(…, P)``; the residual's slow factor ``w`` ``(…, P, M)``.
    """
    dev = delay_s.device
    tau0 = delay_s.double()
    r = delay_rate.double()
    m = torch.arange(timing.num_chirps, device=dev, dtype=torch.float64)
    nc = (timing.num_samples - 1) / 2
    excess = r[..., None] * (m * timing.prt)  # tau_m - tau0 - r t_d
    if chirp_delay is not None:
        excess = excess + chirp_delay.double()
    tau_m = (tau0 + r * timing.adc_delay)[..., None] + excess
    g = (timing.slope * (1 - r) / timing.fs)[..., None] * excess  # coupling, cycles per sample
    g_hi, g_lo = g.amax(dim=-1), g.amin(dim=-1)
    g_bar, half = (g_hi + g_lo) / 2, (g_hi - g_lo) / 2
    slow = tau_m * (timing.f0 - 0.5 * timing.slope * tau_m) + (g - g_bar[..., None]) * nc
    per_sample, quad = _fast_time_rate(tau0, r, g_bar, timing)
    theta = 2 * math.pi * half * nc
    w = (g - g_bar[..., None]) / torch.where(half > 0, half, torch.ones_like(half))[..., None]
    return _frac(slow), per_sample, theta, quad, w


def _fast_time_rate(
    tau0: torch.Tensor, r: torch.Tensor, g_bar: torch.Tensor, timing: ChirpTiming,
) -> tuple[torch.Tensor, torch.Tensor]:
    """A path's fast-time rate (cycles per sample, incl. ``g_bar``) and quadratic term (cycles per sample^2)."""
    lin = timing.f0 * r + timing.slope * (tau0 + r * timing.adc_delay) * (1 - r)
    return lin / timing.fs + g_bar, timing.slope * r * (1 - r / 2) / timing.fs**2


def _fast_time_cos_sin(
    per_sample: torch.Tensor, quad: torch.Tensor, num_samples: int, dtype: torch.dtype
) -> torch.Tensor:
    """``[cos, sin](2 pi (c n + q n^2))`` for n = 0..N-1 as ``(…, 2, P, N)`` in ``dtype``.

    ``n = L a + b`` with ``L ~ sqrt(N)`` and the fractions of ``L c`` and ``c`` taken in float64: the full-size
    work is one add and one cosine in ``dtype``, with a phase error of ~1e-5 rad in float32 (~1e-4 for ``c * n``).
    """
    dev = per_sample.device
    L = max(1, math.isqrt(num_samples - 1) + 1)
    A = -(-num_samples // L)
    two_pi = 2 * math.pi
    hi = (two_pi * _frac(per_sample * L)).to(dtype)
    lo = (two_pi * _frac(per_sample)).to(dtype)
    a = torch.arange(A, device=dev, dtype=dtype)
    b = torch.arange(L, device=dev, dtype=dtype)
    quarter = torch.tensor([0.0, -0.5 * math.pi], device=dev, dtype=dtype)  # cos(x - pi/2) = sin(x)
    coarse = (hi[..., None] * a)[..., None, :, :, None]  # (…, 1, P, A, 1)
    fine = (lo[..., None] * b)[..., None, :, None, :] + quarter[:, None, None, None]  # (…, 2, P, 1, L)
    ph = (coarse + fine).flatten(-2)[..., :num_samples]
    # The quadratic term (in-chirp range migration, ~0.05 rad at 5 m/s) is small: dtype suffices.
    n2 = torch.arange(num_samples, device=dev, dtype=torch.float64) ** 2
    quad_phase = ((two_pi * quad)[..., None] * n2).to(dtype)[..., None, :, :]
    if ph.is_contiguous():  # in place: one pass less over the full-size tensor
        return ph.add_(quad_phase).cos_()
    return torch.cos(ph + quad_phase)


def synthesize_fast(
    coef: torch.Tensor,
    delay_s: torch.Tensor,
    delay_rate: torch.Tensor,
    timing: ChirpTiming,
    *,
    dtype: torch.dtype,
    taylor_tol: float = DEFAULT_TAYLOR_TOL,
    chirp_delay: torch.Tensor | None = None,
    chirp_gain: torch.Tensor | None = None,
    abs_tol: float | None = None,
) -> torch.Tensor:
    """Separable (GEMM) synthesis of ``sum_p Re{C_p g_pm exp(j Phi_p[m, n])}``.

    Args:
        coef: ``(…, RX, P)`` complex coefficients.
        delay_s: ``(…, RX, P)`` delays at the frame's first ramp start, s.
        delay_rate: ``(…, RX, P)`` delay rates, s/s.
        timing: chirp constants.
        dtype: real output dtype.
        taylor_tol: largest neglected term of the coupling's expansion (:data:`DEFAULT_TAYLOR_TOL`).
        chirp_delay: optional ``(…, 1 or RX, P, M)`` extra delay ``d_m`` per chirp (motion beyond ``tau0 + r t``), s.
        chirp_gain: optional ``(…, 1 or RX, P, M)`` real amplitude factor ``g_pm`` per chirp.
        abs_tol: the largest neglected term in the samples' own units, instead of ``taylor_tol`` times the
            strongest path (the receiver sets it from its noise: ``FMCWReceiver(noise_tol=...)``).

    Returns:
        ``(…, RX, M, N)`` real samples.
    """
    M, N = timing.num_chirps, timing.num_samples
    dev = coef.device
    batch = coef.shape[:-1]
    if coef.shape[-1] == 0:
        return torch.zeros(*batch, M, N, dtype=dtype, device=dev)
    P = coef.shape[-1]
    mag = coef.abs().reshape(-1, P).amax(dim=0).double()
    if chirp_gain is not None:
        mag = mag * chirp_gain.abs().reshape(-1, P, chirp_gain.shape[-1]).amax(dim=(0, 2)).double()
    top = mag.max().clamp_min(1e-300)
    rel = mag / top
    tol = taylor_tol if abs_tol is None else max(float(abs_tol) / float(top), 1e-300)  # relative to ``top``
    # The RX channels of a frame see each path at delays a few picoseconds apart. Their fast-time
    # rates differ by a few mHz (a phase linear in the sample index: ~0.04 rad over a chirp) and
    # their in-chirp quadratic terms by ~1e-5 rad: the channels share one fast-time factor (its
    # trig and one GEMM whose slow side stacks the channels) and the linear difference joins the
    # coupling's expansion (``theta w_m v_n + phi v_n`` has the same form). Shared only where the
    # neglected quadratic difference is below the tolerance.
    theta_rows, shared_rows = _coupling_phase(delay_s, delay_rate, timing, chirp_delay, rel, tol)
    still = theta_rows.reshape(-1, P).amax(dim=0) == 0
    shared = None if shared_rows is None else shared_rows.reshape(-1, P).amax(dim=0)
    if shared is not None and bool(still.any()) and not bool(still.all()):
        # Static paths need no expansion term on their own channel; shared, the channels' linear
        # difference would give them some, whose truncation errors add up over a room's thousands
        # of paths: they are synthesized per channel (exact, one GEMM), the moving ones shared.
        def part(idx: torch.Tensor) -> torch.Tensor:
            return synthesize_fast(
                coef.index_select(-1, idx), delay_s.index_select(-1, idx), delay_rate.index_select(-1, idx), timing,
                dtype=dtype, taylor_tol=taylor_tol, abs_tol=abs_tol,
                chirp_delay=None if chirp_delay is None else chirp_delay.index_select(-2, idx),
                chirp_gain=None if chirp_gain is None else chirp_gain.index_select(-2, idx))
        return part(still.nonzero()[:, 0]) + part((~still).nonzero()[:, 0])
    share = shared is not None and not bool(still.all())
    # Orders per path: term k of a path is at most its bound (:func:`chebyshev_orders_needed`) times
    # its amplitude; it is kept while that is at least ``taylor_tol`` times the strongest path of
    # the call (so weak multipath needs fewer orders than the torso for the same error bound on the
    # frame). The orders are chosen per chunk of rows (a frame on the CPU: a limb that glints or
    # swings fast in one frame of the batch does not cost its orders in the others), and the
    # chunk's paths sorted by them, so those that need order k form a prefix: each order is one
    # pair of GEMMs on a view, and static clutter (theta = 0) costs one pair in all.
    cheb = _chebyshev_polynomials(N, dtype, dev)
    if share and shared_rows is not None:
        theta_rows = shared_rows
    amp_rows = coef.abs() if chirp_gain is None else coef.abs() * chirp_gain.abs().amax(dim=-1)
    # Every row's own orders, for a quarter of the tolerance: per frame, more paths sit near the
    # bound than with one set of orders per batch, and their errors add up (docs/receiver.md).
    need_rows = chebyshev_orders_needed(theta_rows, amp_rows / top, tol * _PER_FRAME_TOL)
    # Rows are the frames when the RX channels share the fast-time factor, else (frame, RX) pairs.
    # They are done in chunks whose per-path work (phases, slow factors P x M, fast-time factors
    # 2P x N per row) stays in the CPU's cache: the trig, the GEMMs and the expansion's updates then run
    # at cache speed instead of streaming (frames x RX x P x M) and (frames x RX x 2P x N) tensors
    # through memory many times (measured ~2x faster for a 16-frame corridor batch on a 2-core CPU).
    group = (1, *batch) if share else (1, *batch, 1)  # a leading 1: a batch of one row has a row index
    R = group[-1]
    rows = math.prod(group[:-1])
    step = max(1, (_FAST_CHUNK_ELEMENTS if dev.type == "cpu" else _FAST_CHUNK_ELEMENTS_GPU) // (2 * P * N))
    nc = (N - 1) / 2
    out = torch.empty(rows, R * M, N, dtype=dtype, device=dev)
    for r0 in range(0, rows, step):
        idx = _unravel(torch.arange(r0, min(r0 + step, rows), device=dev), group[:-1])

        def pick(t: torch.Tensor, tail: int, idx: tuple[torch.Tensor, ...] = idx) -> torch.Tensor:
            """Rows ``idx`` of ``t`` broadcast to (*batch, ...) -> (c, R, ...) (no full-size copy)."""
            full = t.expand(*batch, *t.shape[t.dim() - tail:])
            return full.reshape(*group, *full.shape[len(batch):])[idx]

        d, r = pick(delay_s, 1), pick(delay_rate, 1)
        cd, g = (None if t is None else pick(t, 2) for t in (chirp_delay, chirp_gain))
        c = pick(coef, 1)
        c, d, r, cd, g, counts = _sorted_by_orders(c, d, r, cd, g, pick(need_rows, 1).reshape(-1, P).amax(dim=0))
        K = len(counts) + 1
        slow, per_sample, theta, quad, w = _phase_terms(d, r, timing, cd)
        # The coupling theta w_m (c, R, P, M), rad, on the slow side of the expansion's terms.
        if R > 1:
            shared = per_sample.mean(dim=1, keepdim=True)
            dev_rate = per_sample - shared  # cycles per sample: 2 pi dev (n - nc) = 2 pi dev nc v_n
            slow = _frac(slow + (dev_rate * nc)[..., None])
            tw = (theta[..., None] * w + (2 * math.pi * nc * dev_rate)[..., None]).to(dtype) if K > 1 else None
            per_sample, quad = shared, quad.mean(dim=1, keepdim=True)
        else:
            tw = theta.to(dtype)[..., None] * w.to(dtype) if K > 1 else None
        cr, ci = c.real.to(dtype)[..., None], c.imag.to(dtype)[..., None]
        if g is not None:
            g = g.to(dtype)
            cr, ci = cr * g, ci * g
        slow_rad = (2 * math.pi * slow).to(dtype)
        cs, ss = torch.cos(slow_rad), torch.sin(slow_rad)

        def stack(t: torch.Tensor) -> torch.Tensor:
            """(c, R, P, M) -> (c, P, R M): the channels side by side on the GEMM's slow side."""
            return t.transpose(1, 2).reshape(t.shape[0], P, R * M)

        # Slow side: Re, Im of C e^{j slow} (c, P, R M); fast side: cos, sin (:func:`_fast_time_cos_sin`).
        ar, ai, z = stack(cr * cs - ci * ss), stack(cr * ss + ci * cs), None if tw is None else stack(tw)
        out[r0:r0 + step] = _fast_rows_chebyshev(ar, ai, per_sample[:, 0], quad[:, 0], z, counts, cheb, dtype)
    return out.reshape(*batch, M, N)


def _unravel(flat: torch.Tensor, shape: tuple[int, ...]) -> tuple[torch.Tensor, ...]:
    """Row-major coordinates of ``flat`` in ``shape`` (``torch.unravel_index`` without its per-call overhead)."""
    coords = []
    for size in reversed(shape):
        coords.append(flat % size)
        flat = flat // size
    return tuple(reversed(coords))


def _coupling_phase(
    delay_s: torch.Tensor, delay_rate: torch.Tensor, timing: ChirpTiming, chirp_delay: torch.Tensor | None,
    rel_amplitude: torch.Tensor, tol: float,
) -> tuple[torch.Tensor, torch.Tensor | None]:
    """Each row's largest residual coupling phase (rad) per path ``(…, RX, P)``, alone and with the RX shared.

    The second value (None when the channels cannot share the fast-time factor) adds the channels' linear rate
    difference ``2 pi nc |d rate|``. Sharing is allowed when every path's quadratic-term difference
    ``2 pi |d quad| (N - 1)^2`` rad times its relative amplitude stays below ``tol``.
    """
    r = delay_rate.double()
    nc = (timing.num_samples - 1) / 2
    if chirp_delay is None:
        span = r.abs() * ((timing.num_chirps - 1) * timing.prt)
        mid = r * ((timing.num_chirps - 1) * timing.prt / 2)
    else:
        # float32 (relative error ~1e-7) is plenty for choosing the orders and the sharing; the
        # phases themselves are computed in float64 by _phase_terms.
        m = torch.arange(timing.num_chirps, device=r.device, dtype=torch.float32) * timing.prt
        e = delay_rate.float()[..., None] * m + chirp_delay.float()
        hi, lo = e.amax(dim=-1).double(), e.amin(dim=-1).double()
        span, mid = (hi - lo) * (1 + 1e-5), (hi + lo) / 2
    k = timing.slope * (1 - r) / timing.fs
    theta = 2 * math.pi * (k * span / 2) * nc
    P = delay_s.shape[-1]
    if delay_s.dim() < 2 or delay_s.shape[-2] < 2:
        return theta, None
    rate, quad = _fast_time_rate(delay_s.double(), r, k * mid, timing)  # as _phase_terms gives them
    d_rate = (rate - rate.mean(dim=-2, keepdim=True)).abs()
    d_quad = (quad - quad.mean(dim=-2, keepdim=True)).abs()
    quad_err = (2 * math.pi * (timing.num_samples - 1) ** 2 * d_quad).reshape(-1, P).amax(dim=0)
    if bool((quad_err * rel_amplitude > tol).any()):
        return theta, None
    return theta, theta + 2 * math.pi * nc * d_rate


def _chebyshev_polynomials(num_samples: int, dtype: torch.dtype, device: torch.device) -> Callable[[int], torch.Tensor]:
    """``k -> T_k(v_n)`` over the centred fast time ``v_n`` in [-1, 1] (computed on first use)."""
    v = torch.linspace(-1, 1, num_samples, dtype=torch.float64, device=device)
    cheb = [torch.ones_like(v), v]
    cast: dict[int, torch.Tensor] = {}

    def poly(k: int) -> torch.Tensor:
        while len(cheb) <= k:
            cheb.append(2 * v * cheb[-1] - cheb[-2])
        if k not in cast:
            cast[k] = cheb[k].to(dtype)
        return cast[k]
    return poly


def _sorted_by_orders(
    coef: torch.Tensor, delay_s: torch.Tensor, delay_rate: torch.Tensor, chirp_delay: torch.Tensor | None,
    chirp_gain: torch.Tensor | None, need: torch.Tensor,
) -> tuple:
    """Paths sorted by the orders they ``need`` ``(P,)``, descending.

    Returns ``(coef, delay_s, delay_rate, chirp_delay, chirp_gain, counts)``, ``counts[k - 1]`` needing order ``k``.
    """
    order = torch.argsort(need, descending=True, stable=True)
    K = int(need.max()) + 1
    counts = [int(c) for c in (need[None, :] >= torch.arange(1, K, device=need.device)[:, None]).sum(dim=1).cpu()]
    return (*(t.index_select(-1, order) for t in (coef, delay_s, delay_rate)),
            *(None if t is None else t.index_select(-2, order) for t in (chirp_delay, chirp_gain)), counts)


def _bessel_ratios(x: torch.Tensor, orders: int, tol: float) -> list[torch.Tensor]:
    """``F_k(x) = J_k(x) k! / (x/2)^k`` for ``k = 0..orders`` (same shape as ``x``).

    The two highest orders by their power series (to ``tol``), the rest by the stable backward recurrence
    ``F_{k-1} = F_k - (x^2/4) F_{k+1} / (k (k + 1))`` (no division by ``x``).
    """
    y = (x * 0.5).square()
    y_max = float(y.amax()) if y.numel() else 0.0

    def series(k: int) -> torch.Tensor:
        terms, bound = 0, 1.0
        while bound >= tol:
            terms += 1
            bound *= y_max / (terms * (terms + k))
        total = torch.ones_like(y)
        for s in range(terms - 1, 0, -1):  # F = 1 - y/(1 (1+k)) (1 - y/(2 (2+k)) (1 - ...))
            total = torch.addcmul(torch.ones_like(y), y, total, value=-1.0 / (s * (s + k)))
        return total

    f = [series(orders + 1), series(orders)]  # f[-1] is the lowest order so far
    for k in range(orders, 0, -1):
        f.append(torch.addcmul(f[-1], y, f[-2], value=-1.0 / (k * (k + 1))))
    return f[:0:-1]


def _fast_rows_chebyshev(
    ar: torch.Tensor, ai: torch.Tensor, per_sample: torch.Tensor, quad: torch.Tensor, z: torch.Tensor | None,
    counts: list[int], cheb: Callable[[int], torch.Tensor], dtype: torch.dtype,
) -> torch.Tensor:
    """Chebyshev-series :func:`synthesize_fast` of a chunk of rows ``(c, R M, N)``.

    ``ar, ai`` ``(c, P, R M)``: Re and Im of ``A = C e^{j slow}``, paths sorted by order (``counts[k - 1]`` need
    order ``k``); ``z``: the coupling phase ``theta w_m`` (rad; None when no path needs an order). With
    ``e^{j z v} = sum_k eps_k j^k J_k(z) T_k(v)`` each order is a pair of real GEMMs on the paths that need it.
    """
    num_samples = cheb(0).shape[-1]
    cos_sin = _fast_time_cos_sin(per_sample, quad, num_samples, dtype)  # (c, 2, P, N)
    cos, sin = cos_sin[:, 0], cos_sin[:, 1]
    if z is None or not counts:
        return torch.bmm(ar.transpose(-1, -2), cos).baddbmm_(ai.transpose(-1, -2), sin, alpha=-1)
    p1 = counts[0]
    x = z[:, :p1]
    f = _bessel_ratios(x, len(counts), 1e-8)  # F_k to 1e-8 relative: far under any order's bound
    # J_0 on the paths that keep any order (the others' 1 - J_0 is below the tolerance).
    out = torch.bmm((ar[:, :p1] * f[0]).transpose(-1, -2), cos[:, :p1]).baddbmm_(
        (ai[:, :p1] * f[0]).transpose(-1, -2), sin[:, :p1], alpha=-1)
    if p1 < ar.shape[1]:
        out.baddbmm_(ar[:, p1:].transpose(-1, -2), cos[:, p1:]).baddbmm_(
            ai[:, p1:].transpose(-1, -2), sin[:, p1:], alpha=-1)
    power = None  # (x/2)^k / k!
    for k, pk in enumerate(counts, start=1):
        step = x[:, :pk] * (0.5 / k)
        power = step if power is None else power[:, :pk] * step
        coef = power.mul(f[k][:, :pk]).mul_(2)  # eps_k J_k
        re, im = ar[:, :pk] * coef, ai[:, :pk] * coef
        # j^k (re + j im) -> (Re, Im); Re cos - Im sin, the sign of j^k folded into T_k.
        if k % 2:
            term = torch.bmm(im.transpose(-1, -2), cos[:, :pk]).baddbmm_(re.transpose(-1, -2), sin[:, :pk])
        else:
            term = torch.bmm(re.transpose(-1, -2), cos[:, :pk]).baddbmm_(im.transpose(-1, -2), sin[:, :pk], alpha=-1)
        out.addcmul_(term, cheb(k), value=-1.0 if k % 4 in (1, 2) else 1.0)
    return out


def chebyshev_orders_needed(theta: torch.Tensor, rel_amplitude: torch.Tensor, tol: float) -> torch.Tensor:
    """Highest order ``k`` (0 = none) with ``rel_amplitude * 2 (theta/2)^k / k! >= tol``, elementwise.

    ``2 (theta/2)^k / k!`` bounds the order-``k`` term of the Jacobi-Anger series of ``e^{j theta w v}``
    (``|w|, |v| <= 1``). ``theta`` and ``rel_amplitude`` broadcast.
    """
    log_half = torch.log((theta.double() / 2).clamp_min(1e-300))
    excess = torch.log((2 * rel_amplitude.double()).clamp_min(1e-300)) - math.log(tol)
    active = (theta > 0) & (rel_amplitude > 0)
    need = torch.zeros(torch.broadcast_shapes(theta.shape, rel_amplitude.shape), dtype=torch.long,
                       device=theta.device)
    half_max = float(theta.amax()) / 2 if theta.numel() else 0.0
    log_fact = 0.0
    for k in range(1, _MAX_ORDERS):
        log_fact += math.log(k)
        kept = active & (excess + k * log_half - log_fact >= 0)
        if k > half_max and not bool(kept.any()):
            break
        need = torch.where(kept, k, need)
    return need


def synthesize_exact(
    coef: torch.Tensor,
    delay_s: torch.Tensor,
    delay_rate: torch.Tensor,
    timing: ChirpTiming,
    *,
    dtype: torch.dtype,
    chirp_delay: torch.Tensor | None = None,
    chirp_gain: torch.Tensor | None = None,
) -> torch.Tensor:
    """Direct float64 sum of ``Re{C_p g_pm exp(j Phi_p[m, n])}``, chunked over paths: the reference.

    Same arguments and result as :func:`synthesize_fast` (without ``taylor_tol``).
    """
    M, N = timing.num_chirps, timing.num_samples
    dev = coef.device
    batch = coef.shape[:-1]
    out = torch.zeros(*batch, M, N, dtype=torch.float64, device=dev)
    P = coef.shape[-1]
    if P == 0:
        return out.to(dtype)
    m = torch.arange(M, device=dev, dtype=torch.float64)
    n = torch.arange(N, device=dev, dtype=torch.float64)
    t_abs = (m * timing.prt + timing.adc_delay)[:, None] + (n / timing.fs)[None, :]  # (M, N)
    t_n = (n / timing.fs)[None, :]
    per_path = max(1, math.prod(batch)) * M * N
    chunk = max(1, _EXACT_CHUNK_ELEMENTS // per_path)
    c128 = coef.to(torch.complex128)
    for start in range(0, P, chunk):
        sl = slice(start, start + chunk)
        tau0 = delay_s[..., sl].double()[..., None, None]
        r = delay_rate[..., sl].double()[..., None, None]
        tau = tau0 + r * t_abs
        if chirp_delay is not None:
            tau = tau + chirp_delay[..., sl, :].double()[..., None]
        cycles = timing.f0 * tau + timing.slope * tau * t_n - 0.5 * timing.slope * tau**2
        ph = 2 * math.pi * _frac(cycles)
        c = c128[..., sl][..., None, None]
        term = c.real * torch.cos(ph) - c.imag * torch.sin(ph)
        if chirp_gain is not None:
            term = term * chirp_gain[..., sl, :].double()[..., None]
        out = out + term.sum(dim=-3)
    return out.to(dtype)


def synthesize(
    coef: torch.Tensor,
    delay_s: torch.Tensor,
    delay_rate: torch.Tensor,
    timing: ChirpTiming,
    *,
    dtype: torch.dtype,
    method: str = "fast",
    taylor_tol: float = DEFAULT_TAYLOR_TOL,
    chirp_delay: torch.Tensor | None = None,
    chirp_gain: torch.Tensor | None = None,
    abs_tol: float | None = None,
) -> torch.Tensor:
    """Dispatch to :func:`synthesize_fast` or :func:`synthesize_exact` (``method``)."""
    if method == "fast":
        return synthesize_fast(coef, delay_s, delay_rate, timing, dtype=dtype, taylor_tol=taylor_tol,
                               chirp_delay=chirp_delay, chirp_gain=chirp_gain, abs_tol=abs_tol)
    return synthesize_exact(coef, delay_s, delay_rate, timing, dtype=dtype, chirp_delay=chirp_delay,
                            chirp_gain=chirp_gain)
