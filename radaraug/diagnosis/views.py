"""Residual views: the statistics of raw frames in which twin and capture are compared.

:func:`compute_views` reduces raw frames ``(F, rx, chirps, samples)`` (SDK floats) to nine small
vectors; :func:`view_errors` gives one error per view, every error in dB so that they can be
averaged (:func:`overall_error`). RD maps follow :data:`radaraug.units.DB_CONVENTION`. What each view
holds and how its error is measured: ``docs/diagnosis.md``, "Residual views".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError
from radaraug.io.summary import noise_floor_db
from radaraug.transforms import RangeDoppler, ToDecibels

VIEW_NAMES = (
    "rd_histogram", "noise_floor", "range_profile", "doppler_profile", "lines", "rx_balance",
    "adc_histogram", "frame_power", "static_ratio",
)
RD_QUANTILES = (0.005, 0.02, 0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95, 0.98, 0.995, 0.999)
ADC_QUANTILES = (0.001, 0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99, 0.999)
CHIRP_QUANTILES = (0.5, 0.9, 0.97, 0.99, 0.999)
_TINY = 1e-30


def _db(p: torch.Tensor) -> torch.Tensor:
    return 10 * torch.log10(p.clamp_min(_TINY))


def rd_noise_floor_db(frames: torch.Tensor, where: str = "") -> float:
    """The RD noise floor (dBFS) of raw frames, the statistic ``radaraug info`` prints.

    Raises:
        CalibrationError: too few chirps (<= 4) to leave zero Doppler out; ``where`` starts the message.
    """
    floor = noise_floor_db(ToDecibels()(RangeDoppler()(frames)))
    if floor is None:
        raise CalibrationError(f"{where}too few chirps per frame ({frames.shape[-2]}) to measure a noise floor")
    return floor


@dataclass
class FrameStats:
    """Everything the views need from a set of frames, computed once.

    Attributes:
        power: frame-averaged RD power ``(rx, range, doppler)`` (linear, dBFS convention).
        db_quantiles: RD dB quantiles at :data:`RD_QUANTILES`.
        floor_rx_range: median off-zero-Doppler RD power per RX and range bin (linear).
        static_cplx: mean zero-Doppler complex RD value ``(rx, range)``.
        code_quantiles: ``(rx, len(ADC_QUANTILES))`` ADC code quantiles; ``clipped``: ``(rx,)``.
        frame_power_db: ``(F,)`` power of each frame (mean-removed samples) in dB.
        chirp_noise: RMS (counts) of chirp-to-chirp sample differences / sqrt 2.
        frame_noise: RMS (counts) of frame-to-frame sample differences / sqrt 2 (None if F < 2).
        chirp_power_q: quantiles of each chirp's power (dB) at :data:`CHIRP_QUANTILES`.
        burst_fraction: fraction of chirps more than 3 dB above the median chirp power.
        num_frames: F.
    """

    power: torch.Tensor
    db_quantiles: torch.Tensor
    floor_rx_range: torch.Tensor
    static_cplx: torch.Tensor
    code_quantiles: torch.Tensor
    clipped: torch.Tensor
    frame_power_db: torch.Tensor
    chirp_noise: float
    frame_noise: float | None
    chirp_power_q: torch.Tensor
    burst_fraction: float
    num_frames: int


def _guard_slice(m: int) -> torch.Tensor:
    """Doppler bins off zero Doppler (+-1 bin): a bool mask over ``m`` bins."""
    keep = torch.ones(m, dtype=torch.bool)
    zero = m // 2
    keep[max(zero - 1, 0): zero + 2] = False
    return keep


@torch.no_grad()
def frame_stats(frames: torch.Tensor, config: RadarConfig, chunk: int = 32) -> FrameStats:
    """Reduce raw frames ``(F, rx, chirps, samples)`` (SDK floats) to :class:`FrameStats`."""
    x = frames.to(torch.float64)
    F, R, M, N = x.shape
    full = float(config.adc_full_scale_counts)
    rd = RangeDoppler()
    power = torch.zeros(R, N // 2, M, dtype=torch.float64)
    static = torch.zeros(R, N // 2, dtype=torch.complex128)
    dbs = []
    per_cell_db = []
    for s in range(0, F, chunk):
        X = rd(x[s: s + chunk])  # (f, rx, range, doppler) complex
        p = X.real.square() + X.imag.square()
        power += p.sum(dim=0)
        static += X[..., M // 2].sum(dim=0)
        d = _db(p)
        dbs.append(d.flatten()[:: max(1, d.numel() // 200_000)])
        per_cell_db.append(d)
    power /= F
    static /= F
    q = torch.quantile(torch.cat(dbs), torch.tensor(RD_QUANTILES, dtype=torch.float64))
    cells = torch.cat(per_cell_db)  # (F, rx, range, doppler) dB
    keep = _guard_slice(M)
    off = cells[..., keep] if M > 4 else cells
    floor = 10 ** (off.permute(1, 2, 0, 3).reshape(R, N // 2, -1).median(dim=-1).values / 10)
    counts = (x + 1) * (full / 2)
    sub = counts.transpose(0, 1).reshape(R, -1)
    if sub.shape[1] > 400_000:
        sub = sub[:, :: sub.shape[1] // 400_000]
    code_q = torch.quantile(sub, torch.tensor(ADC_QUANTILES, dtype=torch.float64), dim=1).T
    clipped = ((counts <= 0) | (counts >= full)).double().mean(dim=(0, 2, 3))
    centred = x - x.mean(dim=-1, keepdim=True)
    fpow = _db(centred.square().mean(dim=(1, 2, 3)))
    # Chirp power after removing the static part (mean over chirps): bursts (interference) show
    # as a heavy upper tail.
    moving = centred - centred.mean(dim=2, keepdim=True)
    cpow = _db(moving.square().mean(dim=(1, 3))).flatten()
    cq = torch.quantile(cpow, torch.tensor(CHIRP_QUANTILES, dtype=torch.float64))
    burst = float((cpow > cq[0] + 3.0).double().mean())
    scale = full / 2
    chirp_noise = float((x[:, :, 1:] - x[:, :, :-1]).square().mean().sqrt() / math.sqrt(2) * scale) if M > 1 else 0.0
    frame_noise = float((x[1:] - x[:-1]).square().mean().sqrt() / math.sqrt(2) * scale) if F > 1 else None
    return FrameStats(power, q, floor, static, code_q, clipped, fpow, chirp_noise, frame_noise, cq, burst, F)


@dataclass
class Views:
    """The view vectors of one set of frames, name -> tensor (``docs/diagnosis.md``, "Residual views")."""

    values: dict[str, torch.Tensor]
    stats: FrameStats

    def __getitem__(self, name: str) -> torch.Tensor:
        return self.values[name]


def _lines(power: torch.Tensor) -> torch.Tensor:
    """Peak-over-median (dB) per range row (off zero Doppler) and per Doppler column."""
    p = power.mean(dim=0)  # (range, doppler)
    M = p.shape[-1]
    keep = _guard_slice(M)
    rows = p[:, keep] if M > 4 else p
    row = _db(rows.amax(dim=-1) / rows.median(dim=-1).values.clamp_min(_TINY))
    body = p[2:] if p.shape[0] > 4 else p
    col = _db(body.amax(dim=0) / body.median(dim=0).values.clamp_min(_TINY))
    return torch.cat([row, col])


def compute_views(frames: torch.Tensor | FrameStats, config: RadarConfig) -> Views:
    """All views of raw frames ``(F, rx, chirps, samples)`` (or of precomputed stats)."""
    st = frames if isinstance(frames, FrameStats) else frame_stats(frames, config)
    R, nr, M = st.power.shape
    zero_p = st.power[..., M // 2]  # (rx, range)
    body = st.power[:, 2:] if nr > 4 else st.power
    floor_rx = _db(st.floor_rx_range.mean(dim=1))
    # Static level per RX beyond range bin 1, so that the TX->RX leakage (its own per-RX stage)
    # does not dominate the balance of the scene's returns.
    static_rx = _db((zero_p[:, 2:] if nr > 4 else zero_p).mean(dim=1))
    fp = st.frame_power_db
    frame_power = torch.stack([
        fp.median(),
        fp.std() if fp.numel() > 1 else torch.zeros((), dtype=torch.float64),
        _db(torch.tensor(st.chirp_noise**2, dtype=torch.float64)),
        _db(torch.tensor((st.frame_noise if st.frame_noise is not None else st.chirp_noise) ** 2,
                         dtype=torch.float64)),
        *(st.chirp_power_q[1:] - st.chirp_power_q[0]),
    ])
    values = {
        "rd_histogram": st.db_quantiles,
        "noise_floor": _db(st.floor_rx_range.mean(dim=0)),
        "range_profile": _db(zero_p.mean(dim=0)),
        "doppler_profile": _db(body.mean(dim=(0, 1))),
        "lines": _lines(st.power),
        "rx_balance": torch.cat([floor_rx - floor_rx.mean(), static_rx - static_rx.mean()]),
        "rx_phase": torch.angle(st.static_cplx),  # (rx, range)
        "adc_histogram": torch.cat([st.code_quantiles, st.clipped[:, None]], dim=1),
        "frame_power": frame_power,
        "static_ratio": _db(zero_p.mean(dim=0) / st.power.mean(dim=0).sum(dim=-1).clamp_min(_TINY) * M),
    }
    return Views(values, st)


def _rms(d: torch.Tensor) -> float:
    return float(d.square().mean().sqrt()) if d.numel() else 0.0


def view_errors(twin: Views, capture: Views) -> dict[str, float]:
    """One error per view (dB, ``docs/diagnosis.md``, "Residual views") between twin and capture views."""
    out: dict[str, float] = {}
    for name in ("rd_histogram", "noise_floor", "range_profile", "doppler_profile", "lines", "static_ratio"):
        out[name] = _rms(twin[name] - capture[name])
    # Frame-power spread over frames is only meaningful as a level: compare it as dB of the spread.
    fpt, fpc = twin["frame_power"], capture["frame_power"]
    d = fpt - fpc
    d[1] = 20 * torch.log10((fpt[1] + 0.05) / (fpc[1] + 0.05))
    out["frame_power"] = _rms(d)
    # Per-RX balance; phase of the strongest static return where the capture has one 10 dB over
    # its floor (in both RX it is compared in).
    bal = twin["rx_balance"] - capture["rx_balance"]
    R = capture.stats.power.shape[0]
    parts = [bal]
    if R > 1:
        zp = capture.stats.power[..., capture.stats.power.shape[-1] // 2].mean(dim=0)
        fl = capture.stats.floor_rx_range.mean(dim=0)
        # Past the leakage bins (0..2), where leakage, near returns and the high-pass mix.
        first = 3 if zp.numel() > 6 else 1
        snr = zp[first:] / fl[first:].clamp_min(_TINY)
        k = int(snr.argmax()) + first
        if float(snr[k - first]) > 10.0:
            pc = capture["rx_phase"][:, k] - capture["rx_phase"][0, k]
            pt = twin["rx_phase"][:, k] - twin["rx_phase"][0, k]
            dphi = torch.remainder(pt - pc + math.pi, 2 * math.pi) - math.pi
            parts.append(20 * torch.log10(1 + 2 * torch.sin(dphi[1:] / 2).abs()))
    out["rx_balance"] = _rms(torch.cat(parts))
    # ADC codes: quantile differences relative to the capture's spread, as dB of a relative error.
    qa, qc = twin["adc_histogram"][:, :-1], capture["adc_histogram"][:, :-1]
    spread = ((qc[:, 5] - qc[:, 3]) / 1.349).clamp_min(0.5)
    rel = (qa - qc).square().mean(dim=1).sqrt() / spread
    clip = (twin["adc_histogram"][:, -1] - capture["adc_histogram"][:, -1]).abs() * 100
    out["adc_histogram"] = _rms(20 * torch.log10(1 + rel + clip))
    return out


def overall_error(errors: dict[str, float]) -> float:
    """Mean of the view errors (dB)."""
    return float(sum(errors[k] for k in VIEW_NAMES) / len(VIEW_NAMES))


VIEW_UNITS = {
    **{k: "dB" for k in VIEW_NAMES},
    "overall": "dB (mean of the view errors)",
}
