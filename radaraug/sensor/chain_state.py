"""`ChainState`: the signal down the receiver chain, as path coefficients and spectra until samples are needed.

A linear stage then only multiplies each by its response; :meth:`ChainState.materialize` synthesizes the
samples once (``docs/receiver.md``, "How it is computed").
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import KW_ONLY, dataclass, field

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.errors import InputTensorError
from radaraug.sensor.synthesis import ChirpTiming, beat_frequency_Hz, synthesize


@dataclass
class ModulatedPaths:
    """Paths whose contribution is multiplied sample by sample by a real process.

    ``x += multiplier * sum_p Re{coef_p exp(j Phi_p)}``; ``multiplier`` is ``(…, 1 or RX, M, N)``;
    ``chirp_delay`` / ``chirp_gain`` (``(…, 1, P, M)`` or None) as in :class:`ChainState`.
    """

    coef: torch.Tensor
    delay_s: torch.Tensor
    delay_rate: torch.Tensor
    multiplier: torch.Tensor
    chirp_delay: torch.Tensor | None = None
    chirp_gain: torch.Tensor | None = None


@dataclass
class StartupTransient:
    """A high-pass start-up transient: ``Re sum_k weights_k f_k(t)`` with ``f_k = (a t)^(k-1) e^(-a t) / (k-1)!``.

    ``weights`` ``(order, …, RX, M)`` complex; ``lowpass``: the ``(2 pi cutoff, order)`` of the low-pass
    sections it passed after (applied when rendered).
    """

    weights: torch.Tensor
    a: float
    order: int
    lowpass: list[tuple[float, int]] = field(default_factory=list)


@dataclass(eq=False)
class ChainState:
    """Working state of one receiver call (not user-facing; effects mutate it in order).

    Attributes:
        config: the radar configuration.
        timing: chirp constants of ``config``.
        dtype: real output dtype; ``device``: where everything lives.
        generator: the ``torch.Generator`` for every random draw (None: global RNG).
        frame_start_s: absolute time of the frame's first ramp start: a float, or a float64 tensor
            broadcastable to :attr:`batch_shape` (one start per frame).
        tx_power_W: transmit power.
        front_end_gain: ADC float units per sqrt(W) at the RX port (0 dB IF gain).
        batch_shape: leading dims of the paths.
        chirp_delay: ``(…, 1, P, M)`` extra delay per path and chirp (shared by the RX) or None (zero).
        chirp_gain: ``(…, 1, P, M)`` real per-chirp amplitude factor or None (one).
    """

    config: RadarConfig
    coef: torch.Tensor
    delay_s: torch.Tensor
    delay_rate: torch.Tensor
    _: KW_ONLY
    dtype: torch.dtype
    generator: torch.Generator | None
    frame_start_s: float | torch.Tensor
    tx_power_W: float
    front_end_gain: float
    method: str
    taylor_tol: float
    noise_tol: float | None = None
    chirp_delay: torch.Tensor | None = None
    chirp_gain: torch.Tensor | None = None
    modulated: list[ModulatedPaths] = field(default_factory=list, init=False)
    transients: list[StartupTransient] = field(default_factory=list, init=False)
    spectrum: torch.Tensor | None = field(default=None, init=False)
    samples: torch.Tensor | None = field(default=None, init=False)

    def __post_init__(self) -> None:
        self.timing = ChirpTiming.from_config(self.config)
        self.device = self.coef.device
        self.batch_shape = tuple(self.coef.shape[:-2])
        if not isinstance(self.frame_start_s, torch.Tensor):
            self.frame_start_s = float(self.frame_start_s)

    # ------------------------------------------------------------------ helpers
    @property
    def num_rx(self) -> int:
        """Receive channels."""
        return self.config.num_rx

    @property
    def complex_dtype(self) -> torch.dtype:
        """Complex dtype matching :attr:`dtype`."""
        return torch.complex64 if self.dtype == torch.float32 else torch.complex128

    @property
    def sample_shape(self) -> tuple[int, ...]:
        """``(…, RX, M, N)``."""
        return (*self.batch_shape, self.num_rx, self.timing.num_chirps, self.timing.num_samples)

    @property
    def float_per_count(self) -> float:
        """One ADC count in SDK floats (``2 / (2**bits - 1)``): converts parameters given in counts."""
        return 2.0 / self.config.adc_full_scale_counts

    def param(self, value: torch.Tensor) -> torch.Tensor:
        """An effect parameter on this call's device and dtype (keeps the autograd graph)."""
        return value.to(device=self.device, dtype=self.dtype)

    def fft_freqs_Hz(self) -> torch.Tensor:
        """Frequencies of the real-FFT bins over fast time (float64)."""
        return torch.fft.rfftfreq(self.timing.num_samples, d=1 / self.timing.fs, dtype=torch.float64,
                                  device=self.device)

    def sample_times_s(self) -> torch.Tensor:
        """Absolute time ``frame_start_s + m PRT + adc_delay + n / fs`` of every sample, float64.

        ``(…, 1, M, N)``, or ``(M, N)`` when :attr:`frame_start_s` is a float; for time-locked effects.
        """
        tm = self.timing
        m = torch.arange(tm.num_chirps, device=self.device, dtype=torch.float64)
        n = torch.arange(tm.num_samples, device=self.device, dtype=torch.float64)
        start = self.frame_start_s
        if isinstance(start, torch.Tensor):  # one start per frame of the batch: (…, 1, 1, 1)
            start = start.to(device=self.device, dtype=torch.float64)[..., None, None, None]
        return start + (m * tm.prt + tm.adc_delay)[:, None] + (n / tm.fs)[None, :]

    def cycle_phase(self, cycles: torch.Tensor) -> torch.Tensor:
        """``2 pi cycles`` in :attr:`dtype`; the (possibly huge) float64 count is reduced mod 1 before the cast."""
        return 2 * math.pi * (cycles - torch.round(cycles)).to(self.dtype)

    def randn(self, shape: tuple[int, ...]) -> torch.Tensor:
        """Standard normal draws from :attr:`generator` (or the global RNG)."""
        return self._draw(torch.randn, shape)

    def rand(self, shape: tuple[int, ...]) -> torch.Tensor:
        """Uniform draws in [0, 1) from :attr:`generator` (or the global RNG)."""
        return self._draw(torch.rand, shape)

    def _draw(self, fn: Callable[..., torch.Tensor], shape: tuple[int, ...]) -> torch.Tensor:
        try:
            return fn(shape, generator=self.generator, device=self.device, dtype=self.dtype)
        except RuntimeError as e:
            gdev = self.generator.device if self.generator is not None else "cpu"
            raise InputTensorError(
                f"receiver: the generator is on {gdev} but the paths are on {self.device}; "
                "pass a torch.Generator(device=...) on the paths' device"
            ) from e

    # ------------------------------------------------------------------ building the signal
    def add_paths(
        self, coef: torch.Tensor, delay_s: torch.Tensor, delay_rate: torch.Tensor,
        chirp_delay: torch.Tensor | None = None, chirp_gain: torch.Tensor | None = None,
    ) -> None:
        """Append paths ``(…, RX, P')``, optionally with per-chirp delays / gains ``(…, 1, P', M)`` (default 0 / 1)."""
        if self.samples is not None:
            raise RuntimeError("paths cannot be added after the samples were synthesized")
        shape = (*self.batch_shape, self.num_rx, coef.shape[-1])
        per_chirp = (*self.batch_shape, 1, coef.shape[-1], self.timing.num_chirps)
        old_shape = (*self.batch_shape, 1, self.coef.shape[-1], self.timing.num_chirps)
        # A missing per-chirp term is its neutral value (zero extra delay, unit gain) for every chirp.
        for name, new, fill, dt in (("chirp_delay", chirp_delay, 0.0, self.delay_s.dtype),
                                    ("chirp_gain", chirp_gain, 1.0, self.dtype)):
            old = getattr(self, name)
            if old is None and new is None:
                continue
            old = torch.full(old_shape, fill, dtype=dt, device=self.device) if old is None else old
            new = torch.full((), fill, dtype=dt, device=self.device) if new is None else new
            setattr(self, name, torch.cat([old.expand(old_shape), new.to(old.dtype).expand(per_chirp)], dim=-2))
        self.coef = torch.cat([self.coef, coef.to(self.coef.dtype).expand(shape)], dim=-1)
        self.delay_s = torch.cat([self.delay_s, delay_s.to(self.delay_s.dtype).expand(shape)], dim=-1)
        self.delay_rate = torch.cat([self.delay_rate, delay_rate.to(self.delay_rate.dtype).expand(shape)], dim=-1)

    def add_samples(self, x: torch.Tensor) -> None:
        """Add a real signal broadcastable to ``(…, RX, M, N)`` (e.g. noise) at this point of the chain."""
        if self.samples is not None:
            self.samples = self.samples + x
            return
        spec = torch.fft.rfft(x.expand(self.sample_shape), dim=-1)
        self.spectrum = spec if self.spectrum is None else self.spectrum + spec

    def add_samples_after_synthesis(self, x: torch.Tensor) -> None:
        """Add a signal broadcastable to ``(…, RX, M, N)`` to the synthesized samples.

        Unlike :meth:`add_samples`, later linear stages do not filter it.
        """
        self.samples = self.materialize() + x.to(device=self.device, dtype=self.dtype)

    def add_constant(self, per_rx: torch.Tensor) -> None:
        """Add a per-RX constant ``(RX,)`` (a DC offset) at this point of the chain."""
        value = per_rx[:, None, None]
        if self.samples is not None:
            self.samples = self.samples + value
            return
        # A constant is N at the DC bin of the (unnormalised) real FFT and zero elsewhere.
        F = self.timing.num_samples // 2 + 1
        unit = torch.zeros(F, dtype=self.dtype, device=self.device)
        unit[0] = self.timing.num_samples
        spec = (value * unit).to(self.complex_dtype).expand((*self.sample_shape[:-1], F))
        self.spectrum = spec if self.spectrum is None else self.spectrum + spec

    def apply_linear(
        self,
        rx_gain: torch.Tensor | None = None,
        response: Callable[[torch.Tensor], torch.Tensor] | None = None,
    ) -> None:
        """Apply an LTI stage: a complex gain per RX ``(RX,)`` and/or a frequency response.

        ``response(freq_Hz)`` maps float64 frequencies (negative for a path with a negative IF) to the complex,
        Hermitian response; paths take it at their mean beat frequency.
        """
        cd = self.complex_dtype
        g = None if rx_gain is None else rx_gain.to(cd)
        if g is not None:
            for tr in self.transients:  # a gain per RX turns their analytic signal as it turns the paths'
                tr.weights = tr.weights * g.to(torch.complex128)[:, None]
        if self.samples is None:
            targets: list[ChainState | ModulatedPaths] = [self, *self.modulated]
            for target in targets:
                h = g[:, None] if g is not None else 1.0
                if response is not None:
                    h = h * response(beat_frequency_Hz(target.delay_s, target.delay_rate, self.timing)).to(cd)
                target.coef = target.coef * h
            if self.spectrum is not None:
                self.spectrum = self.spectrum * self._bin_response(g, response)
            return
        spec = torch.fft.rfft(self.samples, dim=-1) * self._bin_response(g, response)
        self.samples = torch.fft.irfft(spec, n=self.timing.num_samples, dim=-1)

    def _bin_response(self, g: torch.Tensor | None, response: Callable | None) -> torch.Tensor:
        h = torch.ones((), dtype=self.complex_dtype, device=self.device)
        if response is not None:
            h = response(self.fft_freqs_Hz()).to(self.complex_dtype)
        if g is not None:
            h = g[:, None, None] * h
        return h

    def add_startup_transient(self, cutoff_Hz: torch.Tensor, order: int) -> None:
        """Add what ``order`` first-order high-pass sections, at rest at each ramp start, add to the paths' steady state.

        Call it with the coefficients before the sections' response. Each path's beat tone runs from the
        ramp start (``adc_delay`` before the first sample); the sections answer ``z e^{j w t}`` with
        ``H(jw) z e^{j w t}`` plus ``z sum_k A_k (a t)^(k-1) e^(-a t) / (k-1)!`` (``a = 2 pi cutoff``,
        :func:`startup_coefficients`). Kept as per-chirp weights of those ``order`` functions: later gains
        scale them, later anti-alias sections filter them exactly (:meth:`lowpass_transients`), and
        :meth:`materialize` adds them. Signals added as samples and modulated copies get none.
        """
        tm = self.timing
        if cutoff_Hz.numel() != 1:
            raise InputTensorError(f"the high-pass start-up needs one cutoff for every RX, got {tuple(cutoff_Hz.shape)}")
        a = 2 * math.pi * float(cutoff_Hz.reshape(-1)[0])
        delay, rate = self.delay_s.double(), self.delay_rate.double()  # (…, RX, P)
        m = torch.arange(tm.num_chirps, device=self.device, dtype=torch.float64) * tm.prt
        tau = (delay + rate * tm.adc_delay)[..., None] + rate[..., None] * m  # (…, RX, P, M) at each first sample
        if self.chirp_delay is not None:
            tau = tau + self.chirp_delay.double()
        beat = beat_frequency_Hz(delay, rate, tm)  # (…, RX, P)
        # The tone's phase at the ramp start: at the first sample, less adc_delay of the beat.
        cycles = tau * (tm.f0 - 0.5 * tm.slope * tau) - (beat * tm.adc_delay)[..., None]
        z = self.coef.to(torch.complex128)[..., None] * torch.polar(torch.ones_like(cycles),
                                                                      2 * math.pi * (cycles - torch.round(cycles)))
        if self.chirp_gain is not None:
            z = z * self.chirp_gain.double()
        coefs = startup_coefficients(1j * 2 * math.pi * beat / a, order)  # (order, …, RX, P)
        weights = torch.einsum("k...p,...pm->k...m", coefs, z)  # (order, …, RX, M)
        self.transients.append(StartupTransient(weights, a, order))

    def lowpass_transients(self, cutoff_Hz: float, order: int) -> None:
        """Pass the start-up transients added so far through ``order`` first-order low-pass sections (exactly)."""
        for tr in self.transients:
            tr.lowpass.append((2 * math.pi * float(cutoff_Hz), int(order)))

    def _render_transients(self) -> torch.Tensor | None:
        """``(…, RX, M, N)`` the sum of the start-up transients at the samples (None: none)."""
        out = None
        tm = self.timing
        for tr in self.transients:
            basis = torch.as_tensor(_transient_basis(tr.a, tr.order, tuple(tr.lowpass), tm.adc_delay, tm.fs,
                                                     tm.num_samples), device=self.device)  # (order, N)
            w = tr.weights[..., :tm.num_chirps]  # a one-chirp synthesis of static paths takes the first
            x = torch.einsum("k...m,kn->...mn", w, basis.to(torch.complex128)).real.to(self.dtype)
            out = x if out is None else out + x
        return out

    def chirp_terms(self, idx: torch.Tensor) -> tuple[torch.Tensor | None, torch.Tensor | None]:
        """The per-chirp delay and gain ``(…, 1, k, M)`` of the paths ``idx`` ``(…, RX, k)`` (the same on every RX)."""
        def pick(t: torch.Tensor | None) -> torch.Tensor | None:
            if t is None:
                return None
            i = idx[..., :1, :, None].expand(*idx.shape[:-2], 1, idx.shape[-1], t.shape[-1])
            return t.expand(*self.batch_shape, 1, *t.shape[-2:]).gather(-2, i)
        return pick(self.chirp_delay), pick(self.chirp_gain)

    # ------------------------------------------------------------------ samples
    def _noise_abs_tol(self) -> float | None:
        """``noise_tol`` times the RMS per sample of the noise added so far (None: orders relative to the strongest path).

        The noise is read from the added signals' spectrum at this point of the chain (filtered like the
        paths): the median bin power over the non-DC bins, so that a DC offset or a spur does not count.
        """
        if self.noise_tol is None or self.spectrum is None or self.spectrum.shape[-1] < 2:
            return None
        power = self.spectrum[..., 1:].detach().abs().square().double()
        sigma = math.sqrt(float(power.median()) / self.timing.num_samples)
        return None if sigma <= 0 else self.noise_tol * sigma

    def materialize(self) -> torch.Tensor:
        """Synthesize the samples ``(…, RX, M, N)`` (idempotent)."""
        if self.samples is not None:
            return self.samples
        def synth(p: ChainState | ModulatedPaths, abs_tol: float | None = None) -> torch.Tensor:
            return synthesize(p.coef, p.delay_s, p.delay_rate, self.timing, dtype=self.dtype, method=self.method,
                              taylor_tol=self.taylor_tol, chirp_delay=p.chirp_delay, chirp_gain=p.chirp_gain,
                              abs_tol=abs_tol)

        x = synth(self, self._noise_abs_tol())
        for mod in self.modulated:
            x = x + mod.multiplier * synth(mod)
        if self.spectrum is not None:
            x = x + torch.fft.irfft(self.spectrum, n=self.timing.num_samples, dim=-1)
        transients = self._render_transients()
        if transients is not None:
            x = x + transients
        self.samples = x
        return x


@functools.lru_cache(maxsize=64)
def _transient_basis(a: float, order: int, lowpass: tuple[tuple[float, int], ...], adc_delay: float, fs: float,
                     num_samples: int) -> np.ndarray:
    """``(order, N)`` the functions ``(a t)^(k-1) e^(-a t) / (k-1)!`` at the samples, through the low-pass sections.

    The sections (``y' = b (x - y)`` each, from rest at the ramp start) are run on a fine grid, exactly for an
    input linear between its points; without sections, the closed form.
    """
    t_s = adc_delay + np.arange(num_samples) / fs
    if not lowpass:
        x = a * t_s
        return np.stack([x**k * np.exp(-x) / math.factorial(k) for k in range(order)])
    fastest = max([a, *(b for b, _ in lowpass)])
    dt = min(1 / (16 * fs), 1 / (64 * fastest))
    steps = int(math.ceil(t_s[-1] / dt))
    t = np.arange(steps + 1) * dt
    at = a * t
    sig: np.ndarray = np.stack([at**k * np.exp(-at) / math.factorial(k) for k in range(order)])  # (order, grid)
    for b, n in lowpass:
        e = math.exp(-b * dt)
        for _ in range(n):
            y = np.zeros_like(sig)
            slope = np.diff(sig, axis=1) / dt
            for i in range(1, sig.shape[1]):
                y[:, i] = sig[:, i] - slope[:, i - 1] / b + (y[:, i - 1] - sig[:, i - 1] + slope[:, i - 1] / b) * e
            sig = y
    return np.stack([np.interp(t_s, t, row) for row in sig])


def startup_coefficients(beta: torch.Tensor, order: int) -> torch.Tensor:
    """``(order, …)`` the start-up terms ``A_1 .. A_n`` of ``n = order`` first-order high-pass sections.

    For ``(s / (s + a))^n`` driven from rest by ``e^{j w t}``, ``beta = j w / a``: the response is
    ``H e^{j w t} + sum_k A_k (a t)^(k-1) e^(-a t) / (k-1)!``, the partial fractions of
    ``sigma^n / ((sigma + 1)^n (sigma - beta))`` at ``sigma = -1`` (``A_1 = 1 / (1 + beta)`` for one section;
    the output starts at the input's value, ``H + sum_k A_k[k=1] = 1``).
    """
    b = beta.to(torch.complex128)
    out = []
    for k in range(1, order + 1):
        mm = order - k  # the derivative's order at sigma = -1
        poly = sum(math.comb(i, mm) * (-1) ** (i - mm) * b ** (order - 1 - i) for i in range(mm, order))
        out.append(poly + b ** order * (-1) ** mm / (-1 - b) ** (mm + 1))
    return torch.stack(out)
