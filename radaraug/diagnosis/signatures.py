"""Effect signatures: one detector per catalog effect, testing what sets that effect apart.

The search finds *a* chain that explains the capture, not necessarily the one that is there (a spur
taken for a vibrating object); each detector reads the capture's raw frames ``(F, rx, chirps,
samples)`` (SDK floats) and its config, without a twin or a scene, and returns a :class:`Signature`.
Work is in float64 ADC counts on the frames' device. What each detector tests, its thresholds,
conventions and limits: ``docs/diagnosis.md``, "Signatures".
"""

from __future__ import annotations

import inspect
import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cached_property, lru_cache, wraps
from typing import Concatenate, ParamSpec

import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.declip import normal_cdf

_TINY = 1e-30

@dataclass(frozen=True)
class Signature:
    """What a detector found.

    Attributes:
        effect: catalog name of the effect (:data:`SIGNATURE_EFFECTS`).
        score: evidence for the effect (a dB excess or a test statistic; its unit is in
            ``detail``); 0 when there is no evidence at all.
        present: whether the signature is there.
        params: rough estimates of the effect's parameters (and the detector's statistics).
        detail: one line saying what was measured.
    """

    effect: str
    score: float
    present: bool
    params: dict[str, float] = field(default_factory=dict)
    detail: str = ""


# --------------------------------------------------------------------------- windows, spectra
def _window(kind: str, n: int, device: torch.device) -> torch.Tensor:
    """Periodic window of length ``n`` (float64): ``hann`` (the RD window) or ``bh4`` (4-term Blackman-Harris).

    ``bh4``'s -92 dB sidelobes keep a strong line out of bins far from it (floor shape, skirts, near DC).
    """
    t = 2 * math.pi * torch.arange(n, dtype=torch.float64, device=device) / n
    if kind == "hann":
        return 0.5 - 0.5 * torch.cos(t)
    if kind == "bh4":
        return 0.35875 - 0.48829 * torch.cos(t) + 0.14128 * torch.cos(2 * t) - 0.01168 * torch.cos(3 * t)
    raise ValueError(f"unknown window {kind!r}")


def _enbw(w: torch.Tensor) -> float:
    """Equivalent noise bandwidth of a window, in bins: ``N sum w^2 / (sum w)^2``."""
    return float(w.numel() * w.square().sum() / w.sum().square())


def _rspec(x: torch.Tensor, w: torch.Tensor) -> torch.Tensor:
    """Range spectrum over the last axis, divided by the window sum; bins ``0 .. N//2 - 1``."""
    n = x.shape[-1]
    return torch.fft.rfft(x * w, dim=-1)[..., : n // 2] / w.sum()


def _remove_dc(x: torch.Tensor, w: torch.Tensor) -> torch.Tensor:
    """``x`` minus its window-weighted mean, so bin 0 of the windowed spectrum is exactly 0.

    A plain mean would leave a constant (from every return that is not a whole number of cycles) in
    the window's main lobe around DC, where the leakage is looked for.
    """
    return x - (x * w).sum(dim=-1, keepdim=True) / w.sum()


def _db(p: float | torch.Tensor) -> float:
    return 10 * math.log10(max(float(p), _TINY))


class Prepared:
    """Raw frames in ADC counts and the spectra several detectors share, computed once.

    Args:
        frames: ``(F, rx, chirps, samples)`` SDK floats.
        config: the capture's radar config.
    """

    def __init__(self, frames: torch.Tensor, config: RadarConfig) -> None:
        if frames.ndim != 4:
            raise ValueError(f"frames must be (F, rx, chirps, samples), got shape {tuple(frames.shape)}")
        F, R, M, N = frames.shape
        if R != config.num_rx or M != config.num_chirps_per_frame or N != config.num_samples_per_chirp:
            raise ValueError(f"frames {tuple(frames.shape)} do not match the config ({config.num_rx} RX, "
                             f"{config.num_chirps_per_frame} chirps, {config.num_samples_per_chirp} samples)")
        self.config = config
        self.full = float(config.adc_full_scale_counts)
        # float64 counts: the ADC's own unit, where rails and quantization are plain numbers.
        self.counts = (frames.detach().to(torch.float64) + 1.0) * (self.full / 2)
        self.shape = (F, R, M, N)
        self.device = frames.device
        self.hann = _window("hann", N, self.device)
        self.bh4 = _window("bh4", N, self.device)

    @cached_property
    def static(self) -> torch.Tensor:
        """Mean chirp of each frame and RX ``(F, R, N)`` (the static scene, DC included)."""
        return self.counts.mean(dim=2)

    @cached_property
    def moving(self) -> torch.Tensor:
        """Samples minus their frame's mean chirp ``(F, R, M, N)``: static returns, DC and leakage gone."""
        return self.counts - self.static[:, :, None]

    @cached_property
    def moving_hann(self) -> torch.Tensor:
        """Hann range spectra of :attr:`moving`, ``(F, R, M, K)``."""
        return _rspec(self.moving, self.hann)

    @cached_property
    def moving_bh4(self) -> torch.Tensor:
        """Blackman-Harris range spectra of :attr:`moving`, ``(F, R, M, K)``."""
        return _rspec(self.moving, self.bh4)

    @cached_property
    def static_hann(self) -> torch.Tensor:
        """Hann range spectra of each frame's mean chirp (its DC removed), ``(F, R, K)``."""
        return _rspec(_remove_dc(self.static, self.hann), self.hann)

    @cached_property
    def static_bh4(self) -> torch.Tensor:
        """Blackman-Harris range spectra of each frame's mean chirp (its DC removed), ``(F, R, K)``."""
        return _rspec(_remove_dc(self.static, self.bh4), self.bh4)

    @cached_property
    def doppler(self) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Range-Doppler spectra ``(F, R, M, K)`` of :attr:`moving_hann`, their power ``(K, M)``, its floor ``(K, 1)``.

        Hann over chirps, zero Doppler at ``M // 2``; the power is averaged over frames and RX, the floor is
        its median per range bin.
        """
        wd = _window("hann", self.shape[2], self.device)
        X = torch.fft.fftshift(torch.fft.fft(self.moving_hann * wd[:, None], dim=2), dim=2) / wd.sum()
        Pm = X.abs().square().mean(dim=(0, 1)).T
        return X, Pm, Pm.median(dim=1, keepdim=True).values.clamp_min(_TINY)

    @cached_property
    def doppler_rows(self) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Each range bin's Doppler row off zero Doppler, and what it stands on.

        Returns the mask of Doppler bins off zero Doppler (+-1 left out) ``(M,)``, each range bin's median
        power over them ``(K,)`` and its reference ``(K,)``, the median of that median over the bins 3..10
        away (a ridge or band raises a bin's own median, not its neighbours').
        """
        _, pm, _ = self.doppler
        K, M = pm.shape
        keep = torch.ones(M, dtype=torch.bool, device=self.device)
        keep[max(M // 2 - 1, 0): M // 2 + 2] = False
        rowmed = pm[:, keep].median(dim=1).values.clamp_min(_TINY)
        ref = torch.stack([torch.cat([rowmed[max(k - 10, 0): max(k - 2, 0)], rowmed[k + 3: k + 11]]).median()
                           for k in range(K)]).clamp_min(_TINY)
        return keep, rowmed, ref

    @cached_property
    def chirp_power(self) -> torch.Tensor:
        """Power of each chirp's moving part, all RX and samples, ``(F, M)`` (counts^2)."""
        return self.moving.square().mean(dim=(1, 3))

    @cached_property
    def chirp_excess(self) -> torch.Tensor:
        """Each chirp's power per range bin over its frame's median chirp, all RX, ``(F, M, K)``.

        No window: a Hann window would hide a burst near the chirp's ends (38 % of 5 us bursts missed).
        """
        pw = torch.fft.rfft(self.moving, dim=-1)[..., : self.shape[3] // 2].abs().square().sum(dim=1)  # (F, M, K)
        return pw / pw.median(dim=1, keepdim=True).values.clamp_min(_TINY)

    @cached_property
    def chirp_wideband(self) -> torch.Tensor:
        """Each chirp's median over range bins of :attr:`chirp_excess`, ``(F, M)``.

        A burst raises most range bins of its chirp; a moving object raises a few bins, which the median ignores.
        """
        return self.chirp_excess.median(dim=-1).values

    @cached_property
    def burst_mask(self) -> torch.Tensor:
        """``(F, M)`` True for chirps hit by a burst (see :func:`detect_interference`)."""
        return _burst_flags(self.chirp_wideband)[0]

    @cached_property
    def rails(self) -> torch.Tensor:
        """Samples on an ADC rail ``(F, R, M, N)`` (bool)."""
        c = torch.round(self.counts)
        return (c <= 0) | (c >= self.full)

    @cached_property
    def clipped_fraction(self) -> float:
        """Share of samples on an ADC rail."""
        return float(self.rails.double().mean())

    @cached_property
    def clipped_at_chirp_start(self) -> bool:
        """Every clipped sample lies in the first 1/32 of its chirp (at least 4 samples).

        That is a strong near-DC path ringing through the IF high-pass's start-up, not the ADC's range
        (which clips all through the chirp).
        """
        n = self.shape[-1]
        edge = max(4, n // 32)
        return bool(self.rails.any()) and not bool(self.rails[..., edge:].any())

    @cached_property
    def floor_hann(self) -> torch.Tensor:
        """Per-RX noise power per range bin ``(R, K)``: median over frames and chirps of ``|X|^2``, over ``ln 2``.

        The median (``ln 2`` times an exponential variable's mean) ignores the few chirps a burst hits.
        """
        p = self.moving_hann.abs().square()
        F, R, M, K = p.shape
        return p.permute(1, 3, 0, 2).reshape(R, K, F * M).median(dim=-1).values / math.log(2) * M / max(M - 1, 1)


DETECTORS: dict[str, Callable[..., Signature]] = {}
"""Effect name -> detector ``(frames, config) -> Signature``, in the order they are defined here."""

_P = ParamSpec("_P")


def _detector(effect: str, min_rx: int = 1, min_chirps: int = 1, min_frames: int = 1) -> Callable[
    [Callable[Concatenate[Prepared, RadarConfig, _P], Signature]],
    Callable[Concatenate[torch.Tensor | Prepared, RadarConfig, _P], Signature],
]:
    """Make ``measure(p, config, ...)`` the detector of ``effect`` and register it in :data:`DETECTORS`.

    The detector takes raw frames (SDK floats) or a :class:`Prepared` of them; on a capture with
    fewer RX, chirps or frames than ``measure`` needs it reports the effect absent, unmeasured.
    """
    mins = ((min_rx, "RX"), (min_chirps, "chirps"), (min_frames, "frames"))
    needs = "needs at least " + " and ".join(f"{n} {what}" for n, what in mins if n > 1)

    def register(measure: Callable[Concatenate[Prepared, RadarConfig, _P], Signature]
                 ) -> Callable[Concatenate[torch.Tensor | Prepared, RadarConfig, _P], Signature]:
        @wraps(measure)
        def detect(frames: torch.Tensor | Prepared, config: RadarConfig, *args: _P.args,
                   **kwargs: _P.kwargs) -> Signature:
            p = frames if isinstance(frames, Prepared) else Prepared(frames, config)
            F, R, M, N = p.shape
            if R < min_rx or M < min_chirps or F < min_frames:
                return Signature(effect, 0.0, False, {}, needs)
            return measure(p, config, *args, **kwargs)

        # help() and inspect show what callers pass: ``frames`` (raw frames or a Prepared), not ``p``.
        signature = inspect.signature(measure)
        first, *rest = signature.parameters.values()
        frames = first.replace(name="frames", annotation="torch.Tensor | Prepared")
        detect.__signature__ = signature.replace(parameters=[frames, *rest])  # type: ignore[attr-defined]
        DETECTORS[effect] = detect
        return detect

    return register


def _burst_flags(r: torch.Tensor, min_db: float = 3.0, n_sigma: float = 8.0) -> tuple[torch.Tensor, torch.Tensor, float]:
    """Chirps far above their frame's other chirps, from ``r`` ``(F, M)`` (:attr:`Prepared.chirp_wideband`).

    A chirp is a burst when it stands ``max(min_db, n_sigma * spread)`` dB above its frame's median,
    ``spread`` the robust (MAD) spread of all chirps in dB. Returns the flags, the excess (dB) and the spread.
    """
    ratio_db = 10 * torch.log10(r.clamp_min(_TINY) / r.median(dim=1, keepdim=True).values.clamp_min(_TINY))
    mad = float((ratio_db - ratio_db.median()).abs().median()) * 1.4826
    thr = max(min_db, n_sigma * mad)
    return ratio_db > thr, ratio_db, mad


def _per_rx(name: str, values: Sequence[float] | torch.Tensor) -> dict[str, float]:
    """A per-RX value as signature parameters, ``{name_rx1: ..., name_rx2: ...}``."""
    return {f"{name}_rx{i + 1}": float(v) for i, v in enumerate(values)}


def _peaks(v: torch.Tensor, lo: int = 0, above: float = -math.inf) -> list[int]:
    """Flat indices of the local maxima (each at least its neighbours) of a 1-D or 2-D ``v``, strongest first.

    Only those over ``above`` and from row ``lo`` on count.
    """
    v2 = v.reshape(v.shape[0], -1)  # a 1-D v as one column
    pool = torch.nn.functional.max_pool2d(v2[None, None], 3, stride=1, padding=1)[0, 0]
    rows = torch.arange(v2.shape[0], device=v.device)[:, None]
    idx = torch.nonzero(((v2 >= pool) & (v2 > above) & (rows >= lo)).flatten()).flatten()
    return [int(i) for i in idx[torch.argsort(v2.flatten()[idx], descending=True)]]


# --------------------------------------------------------------------------- ADC clipping
@_detector("adc_clipping")
def detect_adc_clipping(p: Prepared, config: RadarConfig,
                        min_fraction: float = 1e-4, min_pileup: float = 4.0) -> Signature:
    """Samples piled up on the ADC rails.

    A clipped ADC maps the whole tail beyond a rail onto the rail code, so that code holds far more
    samples than the codes just inside it; an unclipped histogram is smooth there.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_fraction: smallest clipped fraction reported as present.
        min_pileup: smallest ratio of rail-code count to the mean count of the 4 codes inside it.

    Returns:
        A :class:`Signature`; ``score`` is the clipped fraction in percent; ``params``: ``fraction``,
        ``fraction_low``, ``fraction_high``, ``gaussian_fraction`` (what a Gaussian of each RX's robust
        spread would clip), ``pileup`` (larger rail), ``at_chirp_start`` (1: every clipped sample is at
        the chirp start, a near-DC path's start-up transient; then not present).
    """
    c = torch.round(p.counts).clamp(0, p.full).transpose(0, 1).reshape(p.shape[1], -1)  # (R, n)
    n = c.shape[1]
    lo = (c <= 0).double().sum(dim=1)
    hi = (c >= p.full).double().sum(dim=1)
    lo_nb = ((c >= 1) & (c <= 4)).double().sum(dim=1) / 4
    hi_nb = ((c >= p.full - 4) & (c <= p.full - 1)).double().sum(dim=1) / 4
    q = torch.quantile(c[:, :: max(1, n // 200_000)], torch.tensor([0.25, 0.5, 0.75], dtype=torch.float64,
                                                                  device=c.device), dim=1)
    mu, sigma = q[1], ((q[2] - q[0]) / 1.349).clamp_min(0.5)
    gauss = normal_cdf((0.5 - mu) / sigma) + normal_cdf((mu - (p.full - 0.5)) / sigma)
    frac = float((lo + hi).sum() / c.numel())
    # A rail without samples gives 0 (the counts are >= 0).
    pileup = float(torch.maximum(lo / (lo_nb + 1), hi / (hi_nb + 1)).max())
    present = frac >= min_fraction and pileup >= min_pileup and float((lo + hi).sum()) >= 10
    params = {"fraction": frac, "fraction_low": float(lo.sum() / c.numel()), "fraction_high": float(hi.sum() / c.numel()),
              "gaussian_fraction": float(gauss.mean()), "pileup": pileup,
              "at_chirp_start": float(p.clipped_at_chirp_start)}
    detail = (f"{100 * frac:.3g} % of samples on the rails (Gaussian of the measured spread: "
              f"{100 * float(gauss.mean()):.3g} %), rail code {pileup:.1f}x its neighbours")
    if present and p.clipped_at_chirp_start:
        # The ADC's range is not what clips: a near-DC path's high-pass start-up transient is
        # (``detect_tx_rx_leakage`` measures that path); a smaller ADC range would clip the whole chirp.
        return Signature("adc_clipping", 0.0, False, params,
                         detail + ", all in the first samples of the chirps: a near-DC path's start-up transient")
    return Signature("adc_clipping", 100 * frac, present, params, detail + "; score: % clipped")


# --------------------------------------------------------------------------- phase noise
@_detector("phase_noise", min_rx=2, min_chirps=8)
def detect_phase_noise(p: Prepared, config: RadarConfig, guard: int = 5,
                       width: int = 40, min_z: float = 8.0, min_snr_db: float = 12.0,
                       line_db: float = 10.0, min_alignment: float = 0.9,
                       min_excess_db: float | None = 3.0) -> Signature:
    """A noise skirt around the strongest static return, common to all RX (one LO).

    Residual LO phase noise puts a skirt around a return, white over Doppler and identical in every
    RX up to the return's inter-RX phase; thermal noise is independent between RX. So the cross-RX
    range-Doppler spectrum of the moving part, projected on the carrier's inter-RX phase and summed
    ``guard .. width`` range bins from it, measures the skirt without the thermal floor.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        guard: nearest range-bin offset from the carrier counted in the skirt.
        width: farthest range-bin offset counted.
        min_z: smallest significance (skirt over its thermal-noise standard deviation).
        min_snr_db: smallest static-return power over the per-chirp noise floor (dB) to test.
        line_db: RD cells this far over their range bin's median Doppler power are lines, left out.
        min_alignment: smallest cosine between the skirt's inter-RX phase and the carrier's.
        min_excess_db: report the skirt only this far (dB) over the declared LO noise's
            (:func:`declared_skirt_dBc`); None: any significant skirt.

    Returns:
        A :class:`Signature`; ``score`` is ``z``; ``params``: ``skirt_dBc`` (over the carrier's power),
        ``range_m``, ``range_bin``, ``carrier_snr_dB``, ``whiteness`` (~1 for noise new every chirp),
        ``alignment``, ``freq_noise_rms_Hz_lower`` (a lower bound), ``declared_skirt_dBc``, ``excess_dB``,
        ``freq_noise_rms_Hz`` (the declared stage's Lorentzian, at its corner, scaled to the measured skirt).
    """
    F, R, M, N = p.shape
    keep = (~p.burst_mask).to(torch.float64)  # (F, M)
    n_keep = float(keep.sum())
    C = p.static_bh4.mean(dim=0)  # (R, K) coherent static spectrum
    K = C.shape[-1]
    pc = C.abs().square().mean(dim=0)
    Dm = p.moving_bh4
    if n_keep < F * M:
        # Each frame's static part from its clean chirps only: a burst would otherwise leave 1/M of
        # itself, common to all RX, in every chirp of its frame.
        w_k = keep[:, None, :, None]
        clean = (p.counts * w_k).sum(dim=2, keepdim=True) / w_k.sum(dim=2, keepdim=True).clamp_min(1.0)
        Dm = _rspec(p.counts - clean, p.bh4)
    floor = (Dm.abs().square() * keep[:, None, :, None]).sum(dim=(0, 2)) / max(n_keep, 1.0)  # (R, K)
    # Strongest static return past the near-DC bins (leakage, DC) with room for the skirt band.
    peaks = _peaks(pc, lo=3)
    k0 = next((k for k in peaks if k + guard < K), None)
    if k0 is None:
        return Signature("phase_noise", 0.0, False, {}, "no static return")
    fl = floor.mean(dim=0).median().clamp_min(_TINY)  # the per-chirp floor of one cell
    snr = _db(pc[k0] / fl)
    if snr < min_snr_db:
        return Signature("phase_noise", 0.0, False, {"carrier_snr_dB": snr},
                         f"strongest static return only {snr:.1f} dB over the floor")
    # Range-Doppler spectra, burst chirps zeroed (and the loss of chirps scaled back below).
    wd = _window("hann", M, p.device)
    X = torch.fft.fft(Dm * (keep[:, None, :, None] * wd[:, None]), dim=2) / wd.sum()  # (F, R, M, K)
    enbw_d = _enbw(wd) * n_keep / (F * M)
    Pd = X.abs().square().mean(dim=(0, 1))  # (M, K)
    line = Pd > 10 ** (line_db / 10) * Pd.median(dim=0, keepdim=True).values
    # A line's Hann main lobe covers +-2 Doppler cells.
    line = torch.nn.functional.max_pool1d(line.double().T[:, None], 5, stride=1, padding=2)[:, 0].T > 0
    use = (~line).double()
    scale = M / use.sum(dim=0).clamp_min(1.0)  # (K,) back to the full Doppler band
    outer = (torch.fft.fftfreq(M, device=p.device).abs() >= 0.25).double()  # outer half of the Doppler band
    offs = torch.arange(K, device=p.device) - k0
    band0 = (offs.abs() >= guard) & (offs.abs() <= width) & (torch.arange(K, device=p.device) >= 2)
    n_band = int(band0.sum())
    # Range bins with a strong line (and the window's main lobe around them) are left out: zeroing
    # the burst chirps spreads a line over the whole Doppler band there.
    strong = (Pd > 100 * Pd.median(dim=0, keepdim=True).values).any(dim=0).double()
    strong = torch.nn.functional.max_pool1d(strong[None, None], 9, stride=1, padding=4)[0, 0] > 0
    band = band0 & ~strong
    band_scale = n_band / max(int(band.sum()), 1)
    core = offs.abs() <= 4
    i, j = torch.triu_indices(R, R, 1, device=p.device)  # every RX pair (P of them), summed below
    # Carrier's inter-RX phase: the skirt of a common LO carries it too.
    cij = (C[i][:, core] * C[j][:, core].conj()).sum(dim=-1)  # (P,)
    u = cij / cij.abs().clamp_min(_TINY)
    xij = (X[:, i] * X[:, j].conj()).mean(dim=0) * use  # (P, M, K) complex
    zij = (xij.sum(dim=1) * scale)[:, band].sum(dim=-1) / enbw_d
    zij_outer = ((xij * outer[:, None]).sum(dim=1) * scale)[:, band].sum(dim=-1) / enbw_d
    num = (zij * u.conj()).real.sum()
    num_o = (zij_outer * u.conj()).real.sum()
    mag = zij.abs().sum()
    den = cij.abs().sum()
    var = ((floor[i][:, band] * floor[j][:, band]).sum(dim=-1) / (2 * max(n_keep, 1.0))).sum()
    # Something common to the RX but arriving from elsewhere (an interferer) has another phase.
    alignment = float(num / mag.clamp_min(_TINY))
    z = float(num / var.sqrt().clamp_min(_TINY))
    ratio = float(num / den.clamp_min(_TINY)) * band_scale
    whiteness = float(2 * num_o / num) if float(num) > 0 else 0.0
    tau = 2 * k0 * config.range_resolution_m / 299_792_458.0
    pn_rms = math.sqrt(max(ratio, 0.0)) / (2 * math.pi * tau)
    present = z >= min_z and 0.6 < whiteness < 1.5 and alignment >= min_alignment
    # The declared skirt over the same band (before the strong-line bins were left out: the sum
    # was scaled back to the band's full width), from every static return 10 dB over the floor:
    # a farther return's skirt (larger delay) reaches into this carrier's band.
    bins = torch.nonzero(band0).flatten().cpu()
    decl_lin = 0.0
    for kj in (k for k in peaks if float(pc[k]) > 10 * float(fl)):
        off = (bins - kj).abs()
        tau_j = 2 * kj * config.range_resolution_m / 299_792_458.0
        decl_lin += float(pc[kj] / pc[k0]) * 10 ** (declared_skirt_dBc(config, tau_j, off[off > 0].double()) / 10)
    decl = _db(decl_lin)
    excess = _db(ratio) - decl
    params = {"skirt_dBc": _db(ratio), "range_bin": float(k0), "range_m": k0 * config.range_resolution_m,
              "carrier_snr_dB": snr, "whiteness": whiteness, "alignment": alignment, "z": z,
              "freq_noise_rms_Hz_lower": pn_rms, "declared_skirt_dBc": decl, "excess_dB": excess,
              # the skirt grows as the LO noise's square: the declared stage's RMS scaled to the measured skirt
              "freq_noise_rms_Hz": _declared_lo_noise()[0] * 10 ** (excess / 20)}
    note = ""
    if min_excess_db is not None and present and excess < min_excess_db:
        present = False
        note = f"; within {min_excess_db:g} dB of the declared skirt ({decl:.1f} dBc): declared"
    return Signature(
        "phase_noise", max(z, 0.0), present, params,
        f"cross-RX skirt {_db(ratio):.1f} dBc over bins {guard}..{width} around bin {k0} "
        f"(z = {z:.1f}, whiteness {whiteness:.2f}, alignment with the carrier {alignment:.2f}, "
        f"{excess:+.1f} dB over the declared){note}; score: z",
    )


def _declared_lo_noise() -> tuple[float, float]:
    """The declared (default) :class:`~radaraug.sensor.effects.PhaseNoise`'s RMS frequency noise and corner, Hz."""
    from radaraug.sensor.effects import PhaseNoise

    pn = PhaseNoise()
    return float(pn.freq_noise_rms_Hz), float(pn.corner_Hz)


def declared_skirt_dBc(config: RadarConfig, tau_s: float, offsets: torch.Tensor) -> float:
    """Skirt (dBc) of the declared LO phase noise over range-bin ``offsets`` from a carrier of delay ``tau_s``.

    The default :class:`~radaraug.sensor.effects.PhaseNoise` in closed form (``docs/diagnosis.md``,
    "Signatures").
    """
    sigma, fc = _declared_lo_noise()
    fs, N = config.sample_rate_Hz, config.num_samples_per_chirp
    s0 = sigma**2 / (fc * math.atan(fs / 2 / fc))
    f = offsets.to(torch.float64) * fs / N
    band = (s0 / (1 + (f / fc) ** 2)).sum() * (fs / N) / 2
    return _db(float(band) * (2 * math.pi * tau_s) ** 2)


# --------------------------------------------------------------------------- spur tone
def _fine_dft(p: Prepared, k: int) -> tuple[torch.Tensor, torch.Tensor, int]:
    """A fine DFT over fast time around range bin ``k`` (1/40 bin steps, no scalloping loss).

    Returns the grid of fractional bins ``(G,)``, the moving part's Hann-weighted DFT on it
    ``(F, R, M, G)`` and the grid index of the largest mean power.
    """
    N = p.shape[3]
    n = torch.arange(N, dtype=torch.float64, device=p.device)
    grid = k + torch.linspace(-1, 1, 81, dtype=torch.float64, device=p.device)
    basis = torch.exp(-2j * math.pi * grid[:, None] * n[None, :] / N) * (p.hann / p.hann.sum())  # (G, N)
    a = torch.einsum("frmn,gn->frmg", p.moving.to(torch.complex128), basis)
    return grid, a, int(a.abs().square().mean(dim=(0, 1, 2)).argmax())


@_detector("spur_tone", min_chirps=4)
def detect_spur_tone(p: Prepared, config: RadarConfig, min_db: float = 15.0,
                     min_frames: float = 0.9, max_cv: float = 0.25, mirror_db: float = 10.0,
                     max_migration_bins: float = 0.3, min_ridge_db: float = 8.0) -> Signature:
    """A single persistent line off zero Doppler with a constant amplitude, or an unlocked spur's ridge.

    A spur locked to absolute time advances by ``2 pi f PRT`` per chirp: one Doppler line at
    ``frac(f PRT)``, steady in every frame and RX. A moving target's line migrates, a vibration makes
    a mirrored pair, noise-like effects make no line. The frequency comes from a fine DFT over fast
    time, its alias fixed by the Doppler bin.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_db: smallest line height over its range bin's median Doppler power (frame average).
        min_frames: share of frames in which the line must stand 6 dB over the floor.
        max_cv: largest coefficient of variation of the per-frame amplitude.
        mirror_db: a line at the mirrored Doppler bin within this many dB makes a pair (not a spur).
        max_migration_bins: largest spread (10th..90th percentile, range bins) of the line's per-frame
            frequency.
        min_ridge_db: without a line, smallest height of an unlocked spur's ridge (:func:`_spur_ridge`).

    Returns:
        A :class:`Signature`; ``score`` is the line height in dB; ``params``: ``freq_Hz``,
        ``amplitude_counts`` (RX mean), ``level_dBFS``, ``range_bin``, ``doppler_bin`` (centred),
        ``frames_fraction``, ``cv``, ``mirror_dB``, ``rx_spread_dB``, ``migration_bins``.
    """
    F, R, M, N = p.shape
    X, Pm, floor = p.doppler
    c = M // 2
    E = Pm / floor
    E[:, max(c - 1, 0): c + 2] = 0  # zero Doppler: static returns' residue, not a spur
    E[:1] = 0
    # Candidates: 2-D local maxima (a strong line fills its neighbour cells too).
    flat = _peaks(E, above=0.0)[:8]
    K = E.shape[0]
    first: Signature | None = None
    for idx in flat:
        k, d = divmod(idx, M)
        h = _db(E[k, d])
        if h < min_db:
            break
        dm = 2 * c - d
        mir = max((_db(E[k, j]) for j in range(dm - 1, dm + 2) if 0 <= j < M), default=-300.0)
        ok = float((X[:, :, d, k].abs().square().mean(dim=1) / floor[k, 0] > 10 ** 0.6).double().mean())
        pre = mir < h - mirror_db and ok >= min_frames and 2 <= k < K - 1
        if first is not None and not pre:
            continue
        grid, a, g = _fine_dft(p, k)
        # A spur's frequency is fixed; a moving target's beat frequency follows its range (range
        # migration over the capture): the line's fine frequency per frame, spread in range bins.
        g_fr = grid[a.abs().square().mean(dim=(1, 2)).argmax(dim=-1)]  # (F,)
        migration = float(torch.quantile(g_fr, 0.9) - torch.quantile(g_fr, 0.1)) if F > 1 else 0.0
        amp_fr = 2 * a[..., g].abs().square().mean(dim=2).sqrt()  # (F, R): per-frame RMS amplitude
        amp = float(amp_fr.square().mean().sqrt())
        cv = float(amp_fr.mean(dim=1).std() / amp_fr.mean().clamp_min(_TINY)) if F > 1 else 0.0
        rx_amp = amp_fr.square().mean(dim=0)
        rx_spread = _db(rx_amp.max() / rx_amp.min().clamp_min(_TINY))
        f_est = float(grid[g]) * config.sample_rate_Hz / N
        # The line's Doppler bin gives frac(f PRT): pick the alias 1/PRT apart nearest the estimate.
        prt = config.chirp_repetition_time_s
        frac = (d - c) / M
        f = (round(f_est * prt - frac) + frac) / prt
        if abs(f - f_est) > config.sample_rate_Hz / N:
            f = f_est
        present = pre and cv <= max_cv and migration <= max_migration_bins
        sig = Signature(
            "spur_tone", h, present,
            {"freq_Hz": f, "amplitude_counts": amp, "level_dBFS": 20 * math.log10(max(amp / p.full, _TINY)),
             "range_bin": float(k), "doppler_bin": float(d - c), "frames_fraction": ok, "cv": cv,
             "mirror_dB": mir, "rx_spread_dB": rx_spread, "migration_bins": migration},
            f"line {h:.1f} dB over the floor at range bin {k}, Doppler bin {d - c:+d}: {amp:.2f} counts at "
            f"{f / 1e3:.3f} kHz, in {100 * ok:.0f} % of frames, cv {cv:.2f}, mirror {mir:.1f} dB, "
            f"frequency spread over frames {migration:.2f} bin; "
            "score: dB over the floor",
        )
        if present:
            return sig
        first = first or sig
    ridge = _spur_ridge(p, config, min_db=min_ridge_db)
    if ridge.present:
        return ridge
    line = first or Signature("spur_tone", 0.0, False, {}, "no line off zero Doppler")
    return Signature(line.effect, line.score, False, line.params, f"{line.detail}; {ridge.detail}")


def _spur_ridge(p: Prepared, config: RadarConfig, min_db: float = 8.0, max_flat_db: float = 4.0,
                neighbour_db: float = 6.0, min_frames: float = 0.9, max_cv: float = 0.25) -> Signature:
    """An unlocked spur: one range bin raised evenly over every Doppler bin, in every frame.

    A tone with a new phase every chirp spreads over Doppler: its row is raised over the rows 3..10
    bins away, flat over Doppler, narrow in range and steady over frames.
    """
    F, N = p.shape[0], p.shape[3]
    X, Pm, _ = p.doppler
    K = Pm.shape[0]
    if K < 8:
        return Signature("spur_tone", 0.0, False, {}, "no ridge: too few range bins")
    keep, rowmed, ref = p.doppler_rows
    h = 10 * torch.log10(rowmed / ref)
    k = int(h[2: K - 1].argmax()) + 2
    height = float(h[k])
    row = Pm[k, keep]
    flat = _db(row.quantile(0.9) / row.quantile(0.1).clamp_min(_TINY))
    side = max(float(h[j]) for j in (k - 3, k + 3) if 0 <= j < K)  # the bins 3 away that exist
    per_frame = X[:, :, keep, k].abs().square().mean(dim=(1, 2))  # (F,)
    frames_ok = float((per_frame / ref[k] > 10 ** 0.3).double().mean())
    cv = float(per_frame.std() / per_frame.mean().clamp_min(_TINY)) if F > 1 else 0.0
    grid, a, g = _fine_dft(p, k)  # the tone's fast-time frequency (its Doppler says nothing here)
    amp = float(2 * a[..., g].abs().square().mean().sqrt())
    # what is left of a line: a jitter of RMS s keeps exp(-s^2) of the power in it
    line = float(row.max() / row.sum())
    jitter = math.sqrt(max(-math.log(max(line, 1e-12)), 0.0))
    present = (height >= min_db and flat <= max_flat_db and height - side >= neighbour_db
               and frames_ok >= min_frames and cv <= max_cv)
    f = float(grid[g]) * config.sample_rate_Hz / N
    params = {"freq_Hz": f, "amplitude_counts": amp, "level_dBFS": 20 * math.log10(max(amp / p.full, _TINY)),
              "range_bin": float(k), "ridge_dB": height, "flatness_dB": flat, "neighbour_dB": side,
              "frames_fraction": frames_ok, "cv": cv, "phase_jitter_rad": jitter, "locked": 0.0}
    if not present:
        return Signature("spur_tone", 0.0, False, params,
                         f"no ridge (best: range bin {k}, {height:.1f} dB over its neighbours, flat within "
                         f"{flat:.1f} dB, bins 3 away {side:.1f} dB)")
    return Signature("spur_tone", height, True, params,
                     f"ridge {height:.1f} dB over its neighbours at range bin {k}, flat within {flat:.1f} dB over "
                     f"Doppler, bins 3 away {side:.1f} dB, in {100 * frames_ok:.0f} % of frames, cv {cv:.2f}: an "
                     f"unlocked spur of {amp:.2f} counts at {f / 1e3:.3f} kHz; score: ridge dB")


# --------------------------------------------------------------------------- IF high-pass
def butterworth_highpass_power(f: torch.Tensor, cutoff_Hz: float | torch.Tensor,
                               order: float | torch.Tensor) -> torch.Tensor:
    """``|H|^2 = (f/fc)^2n / (1 + (f/fc)^2n)`` of an order-``n`` Butterworth high-pass."""
    x = (f / cutoff_Hz) ** (2 * order)
    return x / (1 + x)


def _hp_fit(f: torch.Tensor, psd: torch.Tensor, fcs: torch.Tensor, orders: torch.Tensor, fs: float
            ) -> tuple[torch.Tensor, torch.Tensor]:
    """Weighted least squares of ``psd ~ H(f; fc, n) (a + c f/fs) + b`` for every ``(fc, n)``.

    Returns the misfits (RMS dB, ``(len(fcs), len(orders))``) and the coefficients ``(a, c, b)``.
    ``b`` is the floor that bypasses the high-pass, ``c`` a tilt for the anti-alias filter.
    """
    h = butterworth_highpass_power(f[None, None], fcs[:, None, None], orders[None, :, None])  # (G, O, B)
    x = f / fs
    A = torch.stack([h, h * x, torch.ones_like(h)], dim=-1) / psd[:, None]  # (G, O, B, 3)
    y = torch.ones_like(psd).expand_as(h)[..., None]
    sol = torch.linalg.lstsq(A, y).solution  # (G, O, 3, 1)
    coef = sol[..., 0]
    model = (A @ sol)[..., 0] * psd
    err = 10 * torch.log10(model.clamp_min(psd.min() * 1e-3) / psd)
    return err.square().mean(dim=-1).sqrt(), coef


@_detector("if_highpass", min_chirps=2)
def detect_if_highpass(p: Prepared, config: RadarConfig, min_gain_db: float = 0.3,
                       max_fit_Hz: float | None = None, min_misfit_ratio: float = 2.0,
                       min_small_gain_db: float = 0.1) -> Signature:
    """The IF high-pass's cutoff and order, from the shape of the noise floor.

    Chirp-to-chirp differences cancel everything static; the thermal part of the noise left went
    through the high-pass, the ADC-side part did not. A Butterworth ``|H|^2`` plus a flat floor is
    fitted to the floor's spectrum and compared with the nominal first-order high-pass at
    ``config.effective_hp_cutoff_Hz``. Where the high-passed floor stands only a few dB over the
    ADC-side floor, another filter moves a few bins by a few tenths of a dB: the fit then counts when
    the nominal misfit is ``min_misfit_ratio`` times the free one (which sits at the spectrum's own
    estimation noise, ~0.08 dB).

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_gain_db: RMS improvement (dB) of the free fit over the nominal one that suffices alone.
        max_fit_Hz: top of the fitted band (default ``min(0.3 fs, 6 x nominal cutoff)``).
        min_misfit_ratio: nominal over free misfit that makes a smaller improvement count.
        min_small_gain_db: the smallest improvement (dB) that counts with that ratio.

    Returns:
        A :class:`Signature`; ``score`` is the RMS improvement (dB); ``params``: ``cutoff_Hz``,
        ``order``, ``misfit_dB``, ``nominal_misfit_dB``, ``hp_over_floor_dB`` (high-passed noise over
        the flat floor at the top of the band: the high-pass is only visible when > 0).
    """
    F, R, M, N = p.shape
    keep = ~p.burst_mask
    sel = (keep[:, 1:] & keep[:, :-1]).flatten()  # chirp pairs without a burst, (F (M-1),)
    dd = _rspec(p.counts.diff(dim=2), p.bh4)  # (F, R, M-1, K)
    K = dd.shape[-1]
    ddk = dd.permute(1, 3, 0, 2).reshape(R, K, -1)[:, :, sel]  # (R, K, kept pairs)
    pw_sel = ddk.abs().square()
    psd = pw_sel.median(dim=-1).values.mean(dim=0) / math.log(2)  # (K,)
    if R > 1:
        # Remove what is common to the RX (the thermal floor is independent between them).
        pairs = list(itertools.combinations(range(R), 2))
        coh = sum((ddk[i] * ddk[j].conj()).mean(dim=-1).abs() for i, j in pairs)
        # The mean power (not the median) is what the cross spectrum compares with.
        psd_mean = pw_sel.mean(dim=(0, 2))
        psd = psd * (1 - (coh / len(pairs) / psd_mean.clamp_min(_TINY)).clamp(0, 0.9))
    fs = config.sample_rate_Hz
    nom = config.effective_hp_cutoff_Hz
    fmax = max_fit_Hz if max_fit_Hz is not None else min(0.3 * fs, 6 * nom)
    f_all = torch.arange(K, dtype=torch.float64, device=p.device) * fs / N
    band = (torch.arange(K, device=p.device) >= 2) & (f_all <= fmax)
    f, y = f_all[band], psd[band].clamp_min(_TINY)
    if f.numel() < 6:
        return Signature("if_highpass", 0.0, False, {}, "too few low-frequency bins")
    orders = torch.tensor([1.0, 2.0, 3.0, 4.0], dtype=torch.float64, device=p.device)
    lo_fc, hi_fc = max(fs / N, 2e3), min(0.45 * fs, 3 * fmax)
    fcs = torch.logspace(math.log10(lo_fc), math.log10(hi_fc), 80, dtype=torch.float64, device=p.device)
    err, coef = _hp_fit(f, y, fcs, orders, fs)
    gi, oi = divmod(int(err.argmin()), len(orders))
    # Refine the cutoff around the best grid point.
    fine = fcs[gi] * torch.logspace(-0.06, 0.06, 25, dtype=torch.float64, device=p.device)
    err_f, coef_f = _hp_fit(f, y, fine, orders[oi: oi + 1], fs)
    fi = int(err_f.argmin())
    fc_best, n_best, mis = float(fine[fi]), float(orders[oi]), float(err_f[fi, 0])
    a, c, b = (float(v) for v in coef_f[fi, 0])
    err_n, coef_n = _hp_fit(f, y, torch.tensor([nom], dtype=torch.float64, device=p.device), orders[:1], fs)
    mis_n = float(err_n[0, 0])
    hp_over = _db(max(a * (1 + c * fmax / fs), _TINY) / max(b, _TINY)) if b > 0 else 99.0
    gain = mis_n - mis
    differs = n_best >= 2 or abs(math.log(fc_best / nom)) > math.log(1.3)
    clear = gain >= min_gain_db or (gain >= min_small_gain_db and mis_n >= min_misfit_ratio * mis)
    present = clear and differs and hp_over > 0
    return Signature(
        "if_highpass", max(gain, 0.0), present,
        {"cutoff_Hz": fc_best, "order": n_best, "misfit_dB": mis, "nominal_misfit_dB": mis_n,
         "hp_over_floor_dB": hp_over},
        f"noise floor fits a Butterworth high-pass of order {n_best:g} at {fc_best / 1e3:.1f} kHz "
        f"({mis:.2f} dB RMS) vs nominal order 1 at {nom / 1e3:.1f} kHz ({mis_n:.2f} dB RMS); "
        "score: RMS dB gained",
    )


# --------------------------------------------------------------------------- RX mismatch
def _mismatch_in_noise(floor: torch.Tensor, g_noise: torch.Tensor, params: dict[str, float],
                       min_gain_db: float, max_spread_db: float = 0.5) -> Signature:
    """Without a static return: a receiver several dB off in its noise, evenly over range.

    A channel gain scales its thermal noise at every range alike; a local feature raises a few bins.
    """
    ratio = 10 * torch.log10(floor / floor[:1])  # (R, bins)
    spread = float(((ratio - g_noise[:, None]).abs().median(dim=1).values * 1.4826).max())
    worst = float(g_noise[1:].abs().max()) if g_noise.numel() > 1 else 0.0
    present = worst >= min_gain_db and spread <= max_spread_db
    gains = ", ".join(f"{float(g):+.2f}" for g in g_noise[1:])
    return Signature(
        "rx_gain_phase_mismatch", worst if present else 0.0, present,
        {**params, **_per_rx("gain_dB", g_noise), "spread_dB": spread},
        f"no static return to compare; noise gain re RX1 {gains} dB, steady over range within {spread:.2f} dB"
        + ("" if present else f" (needs >= {min_gain_db:.1f} dB on some RX)")
        + "; score: largest |noise gain| dB",
    )


def _mid_band(k: int) -> slice:
    """The middle half of ``k`` range bins, where the RX mismatch detector reads the noise floor."""
    return slice(max(k // 4, 2), max(3 * k // 4, 3))


@lru_cache(maxsize=32)
def declared_noise_floor(config: RadarConfig, frames: int = 4) -> tuple[float, float]:
    """The declared chain's mid-band noise floor, as the RX mismatch detector reads it, and its thermal share.

    The rest of the floor is ADC-side noise and rounding, added after the RX channels' gains: a channel
    gain ``g`` moves the floor by only ``10 log10(share g + 1 - share)``. Measured on the default
    receiver's empty frames with and without the ADC-side stages.

    Returns:
        ``(floor, thermal share)``: the floor in :attr:`Prepared.floor_hann` units, the share in [0, 1].
    """
    from radaraug.sensor import FMCWReceiver, Paths
    from radaraug.sensor.defaults import default_effects

    R = config.num_rx
    z = torch.zeros(frames, 0, R, dtype=torch.float64)
    empty = Paths(z, z.clone(), z.to(torch.complex128))
    floors = []
    for after_gain in ((), ("adc_noise", "adc_quantization")):  # everything; the thermal part alone
        rx = FMCWReceiver(config, effects=[e for e in default_effects(config) if e.name not in after_gain])
        fl = Prepared(rx(empty, generator=torch.Generator().manual_seed(0)), config).floor_hann
        floors.append(float(fl[:, _mid_band(fl.shape[1])].median()))
    return floors[0], min(max(floors[1] / max(floors[0], _TINY), 0.0), 1.0)


def thermal_share(floor: float, config: RadarConfig) -> float:
    """Share of a capture's mid-band floor ``floor`` that entered before the RX gains.

    What the capture's floor holds over the declared ADC-side floor counts as thermal; at least the
    declared share (a quieter floor than declared is not read as a missing thermal part).
    """
    declared, share = declared_noise_floor(config)
    return min(max(share, 1 - (1 - share) * declared / max(floor, _TINY)), 1.0)


NOISE_GAIN_RESOLUTION_DB = 0.3
"""Smallest noise-floor ratio between RX the mismatch detector reads as a gain (dB)."""


@_detector("rx_gain_phase_mismatch", min_rx=2)
def detect_rx_gain_phase_mismatch(p: Prepared, config: RadarConfig,
                                  min_gain_db: float = 0.5, max_spread_db: float = 1.0,
                                  min_noise_share: float = 0.4, min_snr_db: float = 20.0,
                                  min_noise_gain_db: float = 1.5, share: float | None = None) -> Signature:
    """A per-RX gain that scales the static returns and the noise alike (or, with no return, the noise).

    A gain in the RX channel gives the same ratio to RX1 at every static return and in the noise
    floor's thermal part; the ADC-side part, added after the gain, dilutes it. Where the dilution
    leaves less than :data:`NOISE_GAIN_RESOLUTION_DB` in the floor, the static returns decide alone
    (at least three, with the spread bound). Phases are reported, not tested: without a scene they
    cannot be told from the angle of arrival.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_gain_db: smallest |gain| (static returns) reported as a mismatch.
        max_spread_db: largest spread of the ratio over the static returns (MAD x 1.48).
        min_noise_share: the noise's ratio must carry at least this share of what the returns' gain
            predicts for the floor (same sign).
        min_snr_db: static returns used must stand this far over the per-chirp floor (dB).
        min_noise_gain_db: with no such return, the smallest |gain| of the noise alone.
        share: the floor's thermal share (default: :func:`thermal_share` of RX1's floor).

    Returns:
        A :class:`Signature`; ``score`` is the largest |gain| (dB) when the two agree, else 0;
        ``params``: ``gain_dB_rx{i}`` (static returns, else noise), ``static_gain_dB_rx{i}``,
        ``noise_gain_dB_rx{i}``, ``phase_rad_rx{i}``, ``spread_dB``, ``num_returns``, ``thermal_share``.
    """
    F, R, M, N = p.shape
    floor = p.floor_hann  # (R, K)
    K = floor.shape[1]
    mid = _mid_band(K)
    g_noise = 10 * torch.log10((floor[:, mid] / floor[:1, mid]).median(dim=1).values)
    C = p.static_hann.mean(dim=0)  # (R, K)
    pc = C.abs().square()
    pcm = pc.mean(dim=0)
    fl = floor.mean(dim=0)
    peaks = [k for k in _peaks(pcm, lo=3) if float(pcm[k] / fl[k]) > 10 ** (min_snr_db / 10)]
    peaks = [k for k in peaks if float(pcm[k]) > float(pcm[peaks[0]]) * 1e-3][:12] if peaks else []
    params = {"num_returns": float(len(peaks)), **_per_rx("noise_gain_dB", g_noise)}
    if not peaks:
        return _mismatch_in_noise(floor[:, mid], g_noise, params, min_noise_gain_db)
    ks = torch.tensor(peaks, device=p.device)
    g_k = 10 * torch.log10(pc[:, ks] / pc[:1, ks])  # (R, P)
    g_static = g_k.median(dim=1).values
    spread = float(((g_k - g_static[:, None]).abs().median(dim=1).values * 1.4826).max()) if len(peaks) > 2 else 0.0
    k0 = peaks[0]
    ph = torch.angle(C[:, k0] * C[0, k0].conj())
    if share is None:
        share = thermal_share(float(floor[0, mid].median()), config)
    worst, agree = 0.0, True
    for i in range(1, R):
        gs, gn = float(g_static[i]), float(g_noise[i])
        if abs(gs) >= min_gain_db:
            expect = 10 * math.log10(share * 10 ** (gs / 10) + 1 - share)  # the floor's ratio, diluted
            if abs(expect) >= NOISE_GAIN_RESOLUTION_DB:
                agree = agree and gs * gn > 0 and abs(gn) >= min_noise_share * abs(expect) and abs(gn) <= abs(gs) + 0.5
            else:  # the floor cannot show it: it must not contradict it, and the returns decide
                agree = agree and len(peaks) >= 3 and abs(gn) < NOISE_GAIN_RESOLUTION_DB + abs(expect)
            worst = max(worst, abs(gs))
    # RX1's static gain is 0 (the reference).
    params |= {**_per_rx("static_gain_dB", g_static), **_per_rx("gain_dB", g_static), **_per_rx("phase_rad", ph),
               "spread_dB": spread, "thermal_share": share}
    present = worst >= min_gain_db and agree and spread <= max_spread_db
    gains = ", ".join(f"{float(g_static[i]):+.2f}/{float(g_noise[i]):+.2f}" for i in range(1, R))
    return Signature(
        "rx_gain_phase_mismatch", worst if (agree and spread <= max_spread_db) else 0.0, present, params,
        f"gain re RX1 (static returns / noise) {gains} dB over {len(peaks)} returns, spread {spread:.2f} dB; "
        "score: largest |gain| dB when both agree",
    )


# --------------------------------------------------------------------------- TX->RX leakage
_DECLARED_LEAKAGE_STAGES = ("tx_rx_leakage", "system_gain", "if_highpass", "if_gain", "anti_alias_lowpass")


@lru_cache(maxsize=32)
def declared_leakage_dBFS(config: RadarConfig, bins: int = 3) -> tuple[float, ...]:
    """Near-DC level (dBFS per RX, as :func:`detect_tx_rx_leakage` measures it) of the declared leakage.

    One noiseless chirp of the default receiver's deterministic stages on an empty scene: the level
    after the IF high-pass depends on the chirp and the IF gain.
    """
    from radaraug.sensor import FMCWReceiver, Paths
    from radaraug.sensor.defaults import default_effects

    effects = [e for e in default_effects(config) if e.name in _DECLARED_LEAKAGE_STAGES]
    R = config.num_rx
    paths = Paths(delay_s=torch.full((1, 1, R), 1e-8, dtype=torch.float64),
                  delay_rate=torch.zeros(1, 1, R, dtype=torch.float64),
                  amplitude=torch.zeros(1, 1, R, dtype=torch.complex128))
    x = FMCWReceiver(config, effects=effects)(paths, generator=torch.Generator().manual_seed(0))
    x = x.reshape(R, -1, config.num_samples_per_chirp).to(torch.float64).mean(dim=1)  # (R, N) mean chirp
    w = _window("bh4", config.num_samples_per_chirp, torch.device("cpu"))
    pw = _rspec(_remove_dc(x, w), w)[..., 1:bins].abs().square().sum(dim=-1)  # SDK float units
    return tuple(_db(v) for v in pw)


@_detector("tx_rx_leakage")
def detect_tx_rx_leakage(p: Prepared, config: RadarConfig, bins: int = 3,
                         min_chirp_snr_db: float = 0.0, min_coherence: float = 0.9,
                         max_clipped: float = 1e-3, max_declared_db: float | None = 15.0) -> Signature:
    """A coherent return at near-zero beat frequency: the on-chip/in-package TX->RX coupling.

    The leakage path is millimetres to centimetres long: after the IF high-pass it is a slow curve,
    the same in every chirp and frame. The capture's mean chirp (window-weighted DC removed,
    Blackman-Harris) must hold power in range bins ``1 .. bins - 1`` visible in a single chirp, with
    the same phase in every frame.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        bins: near-DC range bins counted.
        min_chirp_snr_db: smallest near-DC power over the per-chirp noise in those bins (dB).
        min_coherence: smallest frame-to-frame phase coherence.
        max_clipped: above this clipped share the test is not made (clipping intermodulation lands near
            DC too), unless the clipping is at the chirp start (:attr:`Prepared.clipped_at_chirp_start`).
        max_declared_db: report the leakage only when it differs from the declared one
            (:func:`declared_leakage_dBFS`) by more than this (dB) on some RX; None: any visible leakage.

    Returns:
        A :class:`Signature`; ``score`` is the near-DC power over the per-chirp noise (dB, best RX);
        ``params``: ``level_dBFS_rx{i}``, ``declared_dBFS_rx{i}``, ``excess_dB`` (largest
        |level - declared| where visible), ``chirp_snr_dB``, ``coherence``, ``clipped_fraction``,
        ``clipped_at_chirp_start``; ``within_declared`` 1 when it matches the declared leakage.
    """
    F, R, M, N = p.shape
    S = p.static_bh4[..., 1:bins]  # (F, R, bins - 1); bin 0 is the DC, removed
    mean_s = S.mean(dim=0)  # (R, bins)
    pl = mean_s.abs().square().sum(dim=-1)  # (R,)
    noise = p.moving_bh4[..., 1:bins].abs().square().mean(dim=(0, 2)).sum(dim=-1) * M / max(M - 1, 1)  # (R,)
    snr = 10 * torch.log10(pl.clamp_min(_TINY) / noise.clamp_min(_TINY))
    # Phase coherence over frames, per RX: |sum_f <S_f, mean>| / sum_f |<S_f, mean>|.
    dot = (S * mean_s.conj()[None]).sum(dim=-1)  # (F, R)
    coh = dot.sum(dim=0).abs() / dot.abs().sum(dim=0).clamp_min(_TINY)
    i = int(snr.argmax())
    params = {"chirp_snr_dB": float(snr[i]), "coherence": float(coh[i])}
    params.update(_per_rx("level_dBFS", [_db(pl[r] * (2 / p.full) ** 2) for r in range(R)]))
    params["clipped_fraction"] = p.clipped_fraction
    present = float(snr[i]) >= min_chirp_snr_db and float(coh[i]) >= min_coherence
    # Clipping confined to the chirp start is the leakage's own start-up transient: the
    # Blackman-Harris window is ~0 on those samples, so no intermodulation reaches bins 1..2.
    own_clipping = p.clipped_at_chirp_start
    params["clipped_at_chirp_start"] = float(own_clipping)
    declared_note = ""
    if max_declared_db is not None:
        decl = declared_leakage_dBFS(config, bins)
        dev = [params[f"level_dBFS_rx{r + 1}"] - decl[r] for r in range(R) if float(snr[r]) >= min_chirp_snr_db]
        excess = max(dev, key=abs) if dev else 0.0
        params |= {**_per_rx("declared_dBFS", decl), "excess_dB": excess}
        declared_note = f", {excess:+.1f} dB from the declared leakage"
    if present and p.clipped_fraction > max_clipped and not own_clipping:
        # The rails distort every chirp the same way: intermodulation of the static returns lands
        # near DC, coherent in every chirp, and cannot be told from a leakage path (declared or not).
        return Signature("tx_rx_leakage", 0.0, False, params,
                         f"near-DC coherent content {float(snr[i]):.1f} dB over the noise, but "
                         f"{100 * p.clipped_fraction:.2g} % of samples clip: clipping intermodulation")
    if present and max_declared_db is not None and abs(params["excess_dB"]) <= max_declared_db:
        # the declared leakage, perhaps at another level: ``within_declared`` lets the loop refit it
        return Signature("tx_rx_leakage", 0.0, False, params | {"within_declared": 1.0},
                         f"near-DC coherent return {float(snr[i]):.1f} dB over the per-chirp noise, "
                         f"{params['excess_dB']:+.1f} dB from the declared (default receiver's) leakage: declared")
    return Signature(
        "tx_rx_leakage", max(float(snr[i]), 0.0), present, params,
        f"near-DC coherent return (range bins 1..{bins - 1}) {float(snr[i]):.1f} dB over the per-chirp noise, "
        f"frame coherence {float(coh[i]):.3f}{declared_note}"
        + (f", clipping {100 * p.clipped_fraction:.2g} % of samples at the chirp start" if own_clipping else "")
        + "; score: dB over the per-chirp noise",
    )


# --------------------------------------------------------------------------- interference
@_detector("interference")
def detect_interference(p: Prepared, config: RadarConfig, min_bursts: int = 2,
                        min_wideband: float = 0.2) -> Signature:
    """Bursts: a few chirps whose power (static part removed) stands far above their frame's other chirps.

    A crossing FMCW interferer sweeps the IF band in the chirps it hits, raising most range bins; a
    moving object raises a few bins in many chirps, a drifting gain whole frames.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_bursts: fewest flagged chirps to report the effect.
        min_wideband: smallest median share of range bins raised by 3 dB in flagged chirps.

    Returns:
        A :class:`Signature`; ``score`` is the median excess (dB) of the flagged chirps; ``params``:
        ``probability`` (share of chirps hit), ``num_bursts``, ``excess_dB``, ``wideband``,
        ``amplitude_counts`` and ``duration_s`` (Hann-burst equivalents: energy
        ``A^2 / 2 * 3/8 * duration * fs``).
    """
    F, R, M, N = p.shape
    flags, ex_db, mad = _burst_flags(p.chirp_wideband)
    nb = int(flags.sum())
    params = {"probability": nb / (F * M), "num_bursts": float(nb), "spread_dB": mad}
    if nb == 0:
        return Signature("interference", 0.0, False, params, f"no chirp above its frame (spread {mad:.2f} dB)")
    fi, mi = torch.nonzero(flags, as_tuple=True)
    wide = (p.chirp_excess[fi, mi] > 2).double().mean(dim=-1)  # (nb,)
    wideband = float(wide.median())
    excess = float(ex_db[flags].median())
    # Energy and extent of the bursts, per flagged chirp (RX mean).
    med = p.chirp_power.median(dim=1).values[fi]  # (nb,)
    energy = ((p.chirp_power[fi, mi] - med).clamp_min(0) * N)  # counts^2 x samples
    env = p.moving[fi, :, mi].square().mean(dim=1)  # (nb, N)
    dur = (env > 9 * med[:, None]).double().sum(dim=-1) / config.sample_rate_Hz
    dur_s = max(float(dur.median()), 1.0 / config.sample_rate_Hz)
    amp = math.sqrt(max(float(energy.median()), 0.0) * 2 / (0.375 * dur_s * config.sample_rate_Hz))
    params.update({"excess_dB": excess, "wideband": wideband, "amplitude_counts": amp, "duration_s": dur_s})
    present = nb >= min_bursts and wideband >= min_wideband
    return Signature(
        "interference", excess, present, params,
        f"{nb} of {F * M} chirps ({100 * nb / (F * M):.2g} %) stand {excess:.1f} dB over their frame, "
        f"{100 * wideband:.0f} % of range bins raised; score: median excess dB",
    )


# --------------------------------------------------------------------------- vibrating clutter
_BETA = torch.linspace(1e-4, 2.3, 4000, dtype=torch.float64)
_J_RATIO = (torch.special.bessel_j1(_BETA) / torch.special.bessel_j0(_BETA)) ** 2


def _beta_from_ratio(r: float) -> float:
    """``beta`` with ``(J1(beta) / J0(beta))^2 = r`` (monotone on (0, 2.3))."""
    i = int(torch.searchsorted(_J_RATIO, torch.tensor([r], dtype=torch.float64)).clamp(0, len(_BETA) - 1))
    return float(_BETA[i])


def doppler_band_widths(hot: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Per range bin, how many Doppler bins in a row are ``hot`` from the zero-Doppler guard (+-1) outwards.

    ``hot`` is ``(K, M)`` with zero Doppler at ``M // 2``; returns the widths ``(K,)`` towards positive
    and towards negative Doppler.
    """
    c = hot.shape[1] // 2
    up = torch.cumprod(hot[:, c + 2:].int(), dim=1).sum(dim=1)
    down = torch.cumprod(hot[:, : c - 1].flip(1).int(), dim=1).sum(dim=1)
    return up, down


def _vibration_band(p: Prepared, config: RadarConfig, min_db: float = 10.0, min_bins: int = 3,
                    max_asym_bins: int = 2) -> Signature | None:
    """A large vibration: a Doppler band, symmetric about zero, at one range bin (None: no band).

    With ``beta >> 1`` the Bessel lines reach ``+-v_max = +-2 pi f_v d``; only that product is
    measurable (frames sample the motion too slowly to separate ``f_v`` and ``d``).
    """
    F, R, M, N = p.shape
    X, Pm, _ = p.doppler
    K, c = Pm.shape[0], M // 2
    if K < 8 or c < 6:
        return None
    keep, _, ref = p.doppler_rows
    w_up, w_dn = doppler_band_widths(Pm / ref[:, None] > 10 ** (min_db / 10))
    rows = torch.nonzero((torch.minimum(w_up, w_dn) >= min_bins) & (torch.arange(K, device=p.device) >= 2))
    if rows.numel() == 0:
        return None
    k = int(rows[(Pm[rows[:, 0]][:, keep]).max(dim=1).values.argmax()])  # the strongest banded row
    up, dn = int(w_up[k]), int(w_dn[k])
    if max(up, dn) >= c - 3 or abs(up - dn) > max_asym_bins:  # no edge (a ridge), or one-sided
        return None
    cells = torch.cat([torch.arange(c + 2, c + 2 + up), torch.arange(c - 1 - dn, c - 1)]).to(p.device)
    level = Pm[k, cells].mean()
    side = max(float(Pm[j, cells].mean()) for j in (k - 3, k + 3) if 0 <= j < K)
    if _db(level / max(side, _TINY)) < 10.0:  # a band in a whole range span: not one object
        return None
    # The band's edge: where it falls 6 dB under its peak, interpolated in dB between bins.
    row_db = 10 * torch.log10(Pm[k].clamp_min(_TINY))
    edge_db = float(row_db[cells].max()) - 6.0

    def edge(step: int, width: int) -> float:
        start = c + 2 * step if step > 0 else c - 1 + step  # first band bin on that side
        offs = [start + step * i for i in range(width + 1) if 0 <= start + step * i < M]
        last = max((i for i, d in enumerate(offs) if float(row_db[d]) >= edge_db), default=0)
        d0 = offs[last]
        if last + 1 < len(offs):
            a, b = float(row_db[d0]), float(row_db[offs[last + 1]])
            return abs(d0 - c) + (a - edge_db) / max(a - b, 1e-9)
        return float(abs(d0 - c))

    dv = config.wavelength_m / (2 * M * config.chirp_repetition_time_s)
    v_max = 0.5 * (edge(1, up) + edge(-1, dn)) * dv
    height = _db(Pm[k, cells].median() / ref[k])
    return Signature(
        "vibrating_clutter", height, True,
        {"range_bin": float(k), "range_m": k * config.range_resolution_m, "v_max_m_s": v_max,
         "velocity_displacement_m_Hz": v_max / (2 * math.pi), "band_bins_up": float(up),
         "band_bins_down": float(dn), "band_dB": height, "variant": 1.0},
        f"Doppler band +{up}/-{dn} bins (edge +-{v_max:.2f} m/s) at range bin {k}, {height:.1f} dB over the "
        f"floor: a vibration of f_v x d = {1e3 * v_max / (2 * math.pi):.1f} mm Hz (beta >> 1); score: band dB",
    )


@_detector("vibrating_clutter", min_chirps=8)
def detect_vibrating_clutter(p: Prepared, config: RadarConfig, min_db: float = 10.0,
                             max_asym_db: float = 3.0, min_carrier_db: float = 20.0,
                             min_lock: float = 0.5) -> Signature:
    """A symmetric pair of Doppler lines around a static return, or a Doppler band: a vibrating object.

    A return at ``R + d sin(2 pi f_v t)`` is phase-modulated with ``beta = 4 pi d / lambda``: lines
    ``J_k(beta)`` at Doppler ``k f_v``, a pair ``J1`` at ``+-f_v`` of equal height, phase-locked to the
    carrier ``J0``. A spur or a moving target makes one line. The sidebands over the carrier give
    ``(J1/J0)^2`` and hence ``beta``.

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_db: both lines this far over their range bin's median Doppler power.
        max_asym_db: largest level difference of the two lines.
        min_carrier_db: the static return at that range this far over the per-chirp floor.
        min_lock: smallest frame-to-frame coherence of ``X+ X- / C^2`` (1 for a vibration).

    Returns:
        A :class:`Signature`; ``score`` is the weaker line's height (dB); ``params``: ``vibration_Hz``,
        ``displacement_m``, ``beta``, ``sideband_dBc``, ``range_m``, ``range_bin``, ``doppler_bin``,
        ``asymmetry_dB``, ``phase_lock``. A band (:func:`_vibration_band`, tried first) gives
        ``v_max_m_s`` and ``velocity_displacement_m_Hz`` instead, with ``variant`` 1.
    """
    band = _vibration_band(p, config, min_db=min_db)
    if band is not None:
        return band
    F, R, M, N = p.shape
    X, Pm, floor = p.doppler
    K = Pm.shape[0]
    c = M // 2
    E = Pm / floor
    pc = p.static_hann.abs().square().mean(dim=(0, 1))  # (K,)
    # The noise level over all range bins: the vibrating bin's own floor holds the modulation.
    fl = p.floor_hann.mean(dim=0).median()
    j = torch.arange(2, c - 1, device=p.device)  # not empty: M >= 8
    up, dn = E[:, c + j], E[:, c - j]  # (K, J)
    weak = torch.minimum(up, dn)
    asym = (10 * torch.log10(up / dn)).abs()
    carrier_ok = (pc / fl.clamp_min(_TINY) > 10 ** (min_carrier_db / 10))[:, None]
    score = torch.where((asym <= max_asym_db) & carrier_ok, weak, torch.zeros_like(weak))
    score[:2] = 0
    k, ji = divmod(int(score.argmax()), j.numel())
    h = _db(score[k, ji])
    if h < min_db:
        # Report the strongest pair anyway (not present).
        return Signature("vibrating_clutter", max(h, 0.0), False, {"range_bin": float(k)},
                         f"no symmetric Doppler pair {min_db:.0f} dB over the floor (best {h:.1f} dB)")
    jj = int(j[ji])
    ks = slice(max(k - 2, 0), min(k + 3, K))

    def line(d: int) -> tuple[float, float]:
        ds = slice(max(d - 2, 0), min(d + 3, M))
        blk = Pm[ks, ds]
        pw = float((blk - floor[ks]).clamp_min(0).sum()) / (1.5 * 1.5)
        # Sub-bin Doppler: power-weighted centre of the 3 cells around the line.
        w3 = Pm[k, max(d - 1, 0): d + 2]
        pos = float((w3 * torch.arange(-1, w3.numel() - 1, device=p.device, dtype=torch.float64)).sum() / w3.sum())
        return pw, d + pos

    # Phase lock: a phase-modulated return's lines are C J1 e^{j phi} and -C J1 e^{-j phi}, so
    # X+ X- / C^2 = -(J1/J0)^2 in every frame whatever the vibration's phase; two unrelated lines
    # (e.g. intermodulation of a spur with a static return on a clipping ADC) wander from frame
    # to frame.
    q = X[:, :, c + jj, k] * X[:, :, c - jj, k] / p.static_hann[:, :, k].square()  # (F, R)
    lock = float(q.sum().abs() / q.abs().sum().clamp_min(_TINY))
    p_up, d_up = line(c + jj)
    p_dn, d_dn = line(c - jj)
    carrier = float(pc[ks].sum()) / 1.5
    ratio = 0.5 * (p_up + p_dn) / max(carrier, _TINY)
    beta = _beta_from_ratio(ratio)
    f_v = 0.5 * ((d_up - c) + (c - d_dn)) / (M * config.chirp_repetition_time_s)
    disp = beta * config.wavelength_m / (4 * math.pi)
    return Signature(
        "vibrating_clutter", h, lock >= min_lock,
        {"vibration_Hz": f_v, "displacement_m": disp, "beta": beta, "sideband_dBc": _db(ratio),
         "range_bin": float(k), "range_m": k * config.range_resolution_m, "doppler_bin": float(jj),
         "asymmetry_dB": float(asym[k, ji]), "phase_lock": lock},
        f"Doppler pair +-{jj} bins ({f_v:.2f} Hz) at range bin {k}, {_db(ratio):.1f} dBc each "
        f"(beta {beta:.3f}, {disp * 1e3:.3f} mm), phase lock to the carrier {lock:.2f}; "
        "score: weaker line dB over the floor",
    )


# --------------------------------------------------------------------------- frame drift
@_detector("frame_drift", min_frames=4)
def detect_frame_drift(p: Prepared, config: RadarConfig, min_dc_counts: float = 0.5,
                       min_gain_db: float = 0.15, min_f: float = 4.0, min_snr_db: float = 20.0,
                       max_returns: int = 4, min_gain_z: float = 3.0) -> Signature:
    """The DC level (per RX) or the gain (common to the RX) wandering from frame to frame.

    Frame means scatter by the within-frame noise over ``sqrt(M)``; a drift adds to that variance.
    The gain is read from the strongest static returns' levels per frame: a common gain moves them
    all alike, so its variance is their mutual covariance (a moving person moves only their own return).

    Args:
        p: ``frames`` as called: the capture's raw frames (SDK floats) or a :class:`Prepared` of them.
        config: the capture's config.
        min_dc_counts: smallest DC drift RMS (counts) reported.
        min_gain_db: smallest gain drift RMS (dB) reported.
        min_f: smallest ratio of observed to noise-explained frame-mean variance.
        min_snr_db: static returns used for the gain stand this far over the per-chirp floor.
        max_returns: strongest static returns used for the gain.
        min_gain_z: with two or more returns, the gain variance must stand this many standard errors
            above zero.

    Returns:
        A :class:`Signature`; ``score`` is the larger variance ratio; ``params``: ``dc_rms_counts``
        (the largest RX), ``dc_rms_mean_counts`` (RMS over the RX), ``gain_rms_dB``, ``dc_f``, ``gain_f``,
        ``gain_z``, ``num_returns``.
    """
    F, R, M, N = p.shape
    # Chirp DC: Blackman-Harris-weighted mean, blind to every return beyond ~4 range bins (a
    # plain mean picks up each return that is not a whole number of cycles: a breathing chest at
    # 0.3 m moved the plain frame means by 1.9 counts RMS on a BGT60 recording, 0.06 here).
    cm = (p.counts * p.bh4).sum(dim=-1) / p.bh4.sum()  # (F, R, M) chirp means
    fm = cm.mean(dim=-1)  # (F, R)
    expect = (cm.var(dim=-1) / M).mean(dim=0)  # (R,)
    obs = fm.var(dim=0)
    dc_f = float((obs / expect.clamp_min(1e-12)).max())
    dc_rms = float((obs - expect).clamp_min(0).sqrt().max())
    dc_rms_mean = float((obs - expect).clamp_min(0).mean().sqrt())  # the RMS over RX: what one stage draws
    # Gain: log-amplitude of each strong static return per frame (RX mean). A drifting gain moves
    # *every* static return alike, the near-DC leakage included (it goes through the same chain);
    # a person breathing or moving in front of the radar moves one return (on a BGT60 recording:
    # 3.7 dB RMS on a breathing chest at 0.3 m, 0.01 dB on the leakage).
    pcf = p.static_hann.abs().square()  # (F, R, K)
    pm = pcf.mean(dim=(0, 1))
    fl = p.floor_hann.mean(dim=0)
    ks = [k for k in _peaks(pm, lo=1) if float(pm[k] / fl[k].clamp_min(_TINY)) > 10 ** (min_snr_db / 10)]
    ks = ks[:max_returns]
    g_rms, g_f, g_z = 0.0, 0.0, 0.0
    # Each return's level per frame, dB, RX mean: one row per return.
    levels = (10 * torch.log10(pcf[:, :, ks].clamp_min(_TINY))).mean(dim=1).T.contiguous()  # (returns, F)
    # Noise-explained spread of a return's level: sigma_dB ~ 4.34 * sqrt(2 noise / P) (small noise),
    # noise = the per-frame mean's noise power.
    sig_n = 4.343 * torch.sqrt(2 * (p.floor_hann[:, ks] / M) / pcf[:, :, ks].mean(dim=0).clamp_min(_TINY))
    var_exp = [float(v) / R for v in sig_n.square().mean(dim=0)]  # per return
    if len(levels) == 1:
        var_obs = float(levels[0].var())
        g_f = var_obs / max(var_exp[0], 1e-12)
        g_rms = math.sqrt(max(var_obs - var_exp[0], 0.0))  # 10 log10 |S|^2 is the amplitude in dB
        g_z = math.inf
    elif len(levels) > 1:
        # The common gain's variance is the returns' mutual covariance (their noise is independent,
        # and so is the motion of one return); its standard error sqrt(var_i var_j / (F - 1)).
        cov = torch.cov(levels)
        n_ret = len(levels)
        off = ~torch.eye(n_ret, dtype=torch.bool, device=cov.device)
        g_var = float(cov[off].mean())
        se = float(torch.sqrt(torch.outer(cov.diagonal(), cov.diagonal())[off] / (F - 1)).mean())
        v_e = sum(var_exp) / n_ret
        g_f = 1 + max(g_var, 0.0) / max(v_e, 1e-12)
        g_rms = math.sqrt(max(g_var, 0.0))
        g_z = g_var / max(se, 1e-12)
    gain_ok = g_f >= min_f and g_rms >= min_gain_db and g_z >= min_gain_z
    present = (dc_f >= min_f and dc_rms >= min_dc_counts) or gain_ok
    return Signature(
        "frame_drift", max(dc_f, g_f) if present else 0.0, present,
        {"dc_rms_counts": dc_rms, "dc_rms_mean_counts": dc_rms_mean, "gain_rms_dB": g_rms, "dc_f": dc_f, "gain_f": g_f,
         "gain_z": g_z if math.isfinite(g_z) else 99.0, "num_returns": float(len(levels))},
        f"frame-to-frame DC {dc_rms:.2f} counts RMS (variance ratio {dc_f:.1f}), gain {g_rms:.2f} dB RMS "
        f"(ratio {g_f:.1f}); score: variance ratio",
    )


# --------------------------------------------------------------------------- all
SIGNATURE_EFFECTS = tuple(DETECTORS)
"""The catalog effects that have a detector, in the order :func:`detect_all` reports them."""


@torch.no_grad()
def detect_all(frames: torch.Tensor, config: RadarConfig) -> list[Signature]:
    """Every detector on raw frames ``(F, rx, chirps, samples)`` (SDK floats), shared work done once.

    Returns one :class:`Signature` per effect of :data:`SIGNATURE_EFFECTS`, in that order. On a clipping
    capture with a spur, a Doppler pair at the spur's Doppler offset is intermodulation, not a vibration.
    """
    p = Prepared(frames, config)
    sigs = {name: DETECTORS[name](p, config) for name in SIGNATURE_EFFECTS}
    vib, spur, clip = sigs["vibrating_clutter"], sigs["spur_tone"], sigs["adc_clipping"]
    if vib.present and spur.present and clip.present and \
            abs(vib.params["doppler_bin"] - abs(spur.params["doppler_bin"])) <= 1:
        # A clipping ADC mixes the spur with every static return: lines at f_spur +- f_return with
        # the spur's Doppler +-d, a phase-locked pair around a static return's bin, like a vibration.
        sigs["vibrating_clutter"] = Signature(
            "vibrating_clutter", 0.0, False, dict(vib.params),
            f"Doppler pair at the spur's Doppler offset on a clipping capture: intermodulation ({vib.detail})")
    return [sigs[name] for name in SIGNATURE_EFFECTS]


__all__ = [
    "DETECTORS",
    "SIGNATURE_EFFECTS",
    "Prepared",
    "Signature",
    "butterworth_highpass_power",
    "detect_adc_clipping",
    "NOISE_GAIN_RESOLUTION_DB",
    "declared_leakage_dBFS",
    "declared_noise_floor",
    "declared_skirt_dBc",
    "detect_all",
    "detect_frame_drift",
    "detect_if_highpass",
    "detect_interference",
    "detect_phase_noise",
    "detect_rx_gain_phase_mismatch",
    "thermal_share",
    "detect_spur_tone",
    "detect_tx_rx_leakage",
    "detect_vibrating_clutter",
    "doppler_band_widths",
]
