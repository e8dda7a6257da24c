"""Range-Doppler processing: mean removal, MTI, range/Doppler FFTs, dB conversion.

Layouts: raw cube ``(..., rx, chirps, samples)`` (SDK floats in [-1, 1], or any real float);
range profiles ``(..., rx, chirps, range)``; RD map ``(..., rx, range, doppler)``.

Conventions (``radaraug.units.DB_CONVENTION``): each FFT is divided by its window sum, so a
tone's amplitude is read directly ("dBFS"). The chirp is real-sampled: only the ``N // 2``
positive range bins are kept, and a real tone of amplitude ``A`` reads ``|X| = A / 2`` in its
bin -- a full-scale tone (``A = 1``) reads -6.02 dBFS. The Doppler axis is centred (fftshift):
zero velocity at index ``M // 2``, bin ``M // 2 + k`` is ``k`` velocity resolutions, and positive
indices are targets moving *away* (range increasing), matching
``RadarConfig.velocity_axis_m_s()``. Why: the beat signal of a target at ``R(t)`` is
``cos(2 pi (f_b t + f_c tau))`` with ``tau = 2 R / c``; its positive-frequency part (the range bin
kept) carries the phase ``+2 pi f_c tau``, which grows by ``4 pi v T_c / lambda`` per chirp
when the target moves away (``v > 0``): a positive slow-time frequency ``+2 v / lambda``.
"""

from __future__ import annotations

import math
from typing import Any

import torch

from radaraug.errors import InputTensorError
from radaraug.transforms.base import Params, RadarTransform
from radaraug.transforms.windows import check_window_name, normalized_window, shifted_doppler_window

RAW_LAYOUT = "a raw cube (..., rx, chirps, samples)"
PROFILE_LAYOUT = "range profiles (..., rx, chirps, range)"
RD_LAYOUT = "an RD map (..., rx, range, doppler)"


FFT_DTYPES = (torch.float32, torch.float64, torch.complex64, torch.complex128)


class _FFTTransform(RadarTransform):
    """A transform that runs an FFT: float32/float64 (or complex64/128) input only."""

    def check_input(self, x: Any) -> torch.Tensor:
        x = super().check_input(x)
        if x.dtype not in FFT_DTYPES:
            # torch's FFTs refuse half precision on the CPU (and on CUDA for most sizes).
            raise InputTensorError(
                f"{type(self).__name__} expects {self.input_layout} of float32 or float64, got {x.dtype} "
                "(convert with .float())"
            )
        return x

    def forward(self, x: torch.Tensor, *rest: Any) -> Any:
        x = self.check_input(x)
        event = x.shape[x.ndim - self.event_ndim:]
        if x.numel() == 0 and all(d > 0 for d in event):
            # Some torch builds (MKL FFT in torch 2.14 on CPU) raise on a zero-size batch instead
            # of returning an empty result: transform one zero event and keep none of it.
            probe = self.transform(x.new_zeros(event), {})
            out = probe.expand(*x.shape[: x.ndim - self.event_ndim], *probe.shape).clone()
        else:
            out = self.transform(x, {})
        return (out, *rest) if rest else out


class RemoveMean(RadarTransform):
    """Subtract each chirp's mean over fast time (removes the per-RX ADC DC offset)."""

    input_layout = RAW_LAYOUT

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        return x - x.mean(dim=-1, keepdim=True)


class StaticClutterRemoval(RadarTransform):
    """Moving-target indication: subtract the mean over chirps of each sample (or range bin).

    Works on a raw cube or on complex range profiles (``(..., rx, chirps, *)``): the operation is
    linear and acts on the chirp axis only, so both give the same RD map. Everything that does not
    change within a frame -- walls, leakage, DC -- ends up exactly in the zero-Doppler bin
    and is removed.
    """

    input_layout = "(..., rx, chirps, samples or range)"
    accepts_complex = True

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        return x - x.mean(dim=-2, keepdim=True)


class RangeFFT(_FFTTransform):
    """Window over samples, real FFT, keep the ``N // 2`` positive bins, divide by the window sum.

    Input ``(..., rx, chirps, samples)`` real; output complex ``(..., rx, chirps, N // 2)``
    (complex64 for float32 input, complex128 for float64).

    Args:
        window: ``rect``, ``hann``, ``hamming``, ``blackman`` or ``blackmanharris`` (symmetric).
    """

    input_layout = RAW_LAYOUT

    def __init__(self, window: str = "hann") -> None:
        super().__init__()
        self.window = check_window_name(window)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        n = x.shape[-1]
        if n < 2:
            raise InputTensorError(f"RangeFFT needs at least 2 samples per chirp, got {n}")
        w = normalized_window(self.window, n, x.dtype, x.device)
        return torch.fft.rfft(x * w, dim=-1)[..., : n // 2]

    def extra_spec(self) -> dict[str, Any]:
        return {"window": self.window}


class DopplerFFT(_FFTTransform):
    """Window over chirps, FFT, divide by the window sum, centre zero Doppler (fftshift).

    Input complex range profiles ``(..., rx, chirps, range)``; output ``(..., rx, range,
    doppler)``, zero velocity at index ``M // 2``, positive index = moving away.

    Args:
        window: as for :class:`RangeFFT`.
    """

    input_layout = PROFILE_LAYOUT
    accepts_complex = True

    def __init__(self, window: str = "hann") -> None:
        super().__init__()
        self.window = check_window_name(window)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        m = x.shape[-2]
        w = shifted_doppler_window(self.window, m, x.real.dtype, x.device)
        # The window carries the fftshift (see shifted_doppler_window): one multiply, one FFT.
        return torch.fft.fft(x * w[:, None], dim=-2).transpose(-1, -2)

    def extra_spec(self) -> dict[str, Any]:
        return {"window": self.window}


class RangeDoppler(_FFTTransform):
    """Raw cube -> complex RD map: [mean removal] -> [MTI] -> range FFT -> Doppler FFT.

    Equivalent to ``RemoveMean -> StaticClutterRemoval -> RangeFFT -> DopplerFFT`` (the optional
    steps only when enabled) and recorded as that chain in :meth:`chain_spec` comparisons.

    Args:
        range_window: window over samples.
        doppler_window: window over chirps.
        remove_mean: subtract each chirp's mean (DC offset) first.
        static_clutter: subtract the mean over chirps (MTI).
    """

    input_layout = RAW_LAYOUT

    def __init__(
        self,
        range_window: str = "hann",
        doppler_window: str = "hann",
        remove_mean: bool = True,
        static_clutter: bool = False,
    ) -> None:
        super().__init__()
        self.range_window = check_window_name(range_window)
        self.doppler_window = check_window_name(doppler_window)
        self.remove_mean = bool(remove_mean)
        self.static_clutter = bool(static_clutter)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        m, n = x.shape[-2], x.shape[-1]
        if n < 2:
            raise InputTensorError(f"RangeDoppler needs at least 2 samples per chirp, got {n}")
        # In-place ops below only touch temporaries made here, never the input.
        own = False
        if self.remove_mean:
            x, own = x - x.mean(dim=-1, keepdim=True), True
        if self.static_clutter:
            x, own = x - x.mean(dim=-2, keepdim=True), True
        wr = normalized_window(self.range_window, n, x.dtype, x.device)
        wd = shifted_doppler_window(self.doppler_window, m, x.dtype, x.device)
        if not wd.is_complex():
            # Both windows real: apply them as one outer product before the 2-D transform.
            w2 = wd[:, None] * wr
            spec = torch.fft.rfft2(x.mul_(w2) if own else x * w2, dim=(-2, -1))
        else:
            spec = torch.fft.fft(torch.fft.rfft(x * wr, dim=-1) * wd[:, None], dim=-2)
        return spec[..., : n // 2].transpose(-1, -2)

    def extra_spec(self) -> dict[str, Any]:
        return {
            "range_window": self.range_window,
            "doppler_window": self.doppler_window,
            "remove_mean": self.remove_mean,
            "static_clutter": self.static_clutter,
        }


class ToDecibels(RadarTransform):
    """``20 * log10(max(|X|, floor))``: complex or magnitude map -> dB (dBFS with this chain).

    A real input is taken as a magnitude (its absolute value is used).

    Args:
        floor: smallest magnitude before the log (keeps exact zeros finite: -240 dB by default).
    """

    accepts_complex = True
    input_layout = "a complex or magnitude map (..., rx, range, doppler)"

    def __init__(self, floor: float = 1e-12) -> None:
        super().__init__()
        if not floor > 0:
            raise InputTensorError(f"ToDecibels floor must be > 0, got {floor}")
        self.floor = float(floor)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        # 10*log10(|X|^2) avoids the square root of abs(); the floor is applied to the power.
        power = x.real.square().add_(x.imag.square()) if x.is_complex() else x.square()
        return power.clamp_min_(self.floor * self.floor).log10_().mul_(10.0)

    def extra_spec(self) -> dict[str, Any]:
        return {"floor": self.floor}


class CombineRx(RadarTransform):
    """Combine the RX channels of a (linear) RD map into one, keeping an rx dim of size 1.

    Modes (linear maps, complex or magnitude):

    * ``"mean_power"``: ``sqrt(mean_rx |X|**2)`` (real magnitude; dB of it = mean power in dB);
    * ``"coherent"``: ``mean_rx X`` (complex sum / n_rx: a broadside target keeps its level);
    * ``"max"``: ``max_rx |X|``;
    * ``"select"``: channel ``index`` only.

    With ``db=True`` the input is a dB map: ``mean_power`` averages ``10**(dB/10)`` and returns
    dB, ``max`` and ``select`` work as is, ``coherent`` is refused (dB has no phase).

    Args:
        mode: one of the modes above.
        index: the channel for ``"select"``.
        db: the input is in dB.
    """

    accepts_complex = True
    MODES = ("mean_power", "coherent", "max", "select")

    def __init__(self, mode: str = "mean_power", index: int | None = None, db: bool = False) -> None:
        super().__init__()
        if mode not in self.MODES:
            raise InputTensorError(f"CombineRx mode must be one of {self.MODES}, got {mode!r}")
        if (mode == "select") != (index is not None):
            raise InputTensorError("CombineRx: give index exactly when mode='select'")
        if db and mode == "coherent":
            raise InputTensorError("CombineRx: 'coherent' needs complex maps, not dB (db=True)")
        self.mode, self.index, self.db = mode, index, bool(db)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        if self.mode == "select":
            n_rx = x.shape[-3]
            if not -n_rx <= self.index < n_rx:
                raise InputTensorError(f"CombineRx: rx index {self.index} out of range for {n_rx} channels")
            i = self.index % n_rx
            return x[..., i : i + 1, :, :]
        if self.mode == "coherent":
            return x.mean(dim=-3, keepdim=True)
        if self.db:
            if x.is_complex():
                raise InputTensorError("CombineRx(db=True) got a complex tensor; dB maps are real")
            if self.mode == "max":
                return x.amax(dim=-3, keepdim=True)
            # exp(x * ln(10)/10) is 10**(x/10), several times faster than torch.pow on the CPU.
            return x.mul(math.log(10.0) / 10.0).exp_().mean(dim=-3, keepdim=True).log10_().mul_(10.0)
        mag2 = x.real.square() + x.imag.square() if x.is_complex() else x.square()
        if self.mode == "max":
            return mag2.amax(dim=-3, keepdim=True).sqrt()
        return mag2.mean(dim=-3, keepdim=True).sqrt()

    def extra_spec(self) -> dict[str, Any]:
        spec: dict[str, Any] = {"mode": self.mode, "db": self.db}
        if self.index is not None:
            spec["index"] = self.index
        return spec
