"""Range-Doppler kernels, with the conventions of :mod:`radaraug.transforms.spectral`."""

from __future__ import annotations

import math
from collections.abc import Callable

import torch

from radaraug.errors import InputTensorError
from radaraug.transforms._checks import check_tensor
from radaraug.transforms.windows import check_window_name, normalized_window, shifted_doppler_window

RAW_LAYOUT = "a raw cube (..., rx, chirps, samples)"
PROFILE_LAYOUT = "range profiles (..., rx, chirps, range)"
FFT_DTYPES = (torch.float32, torch.float64, torch.complex64, torch.complex128)
COMBINE_MODES = ("mean_power", "coherent", "max", "select")


def check_fft_input(x: object, what: str, layout: str, *, allow_complex: bool) -> torch.Tensor:
    """``x`` if it passes ``check_tensor`` (no value test) and is float32/64 (or complex64/128).

    A raw cube (``layout`` :data:`RAW_LAYOUT`) also needs 2 samples per chirp; messages name ``what`` and ``layout``.
    """
    x = check_tensor(x, f"{what} expects {layout}", allow_complex=allow_complex, finite=False)
    if x.dtype not in FFT_DTYPES:
        # torch's FFTs refuse half precision on the CPU (and on CUDA for most sizes).
        raise InputTensorError(f"{what} expects {layout} of float32 or float64, got {x.dtype} (convert with .float())")
    if layout == RAW_LAYOUT and x.shape[-1] < 2:
        raise InputTensorError(f"{what} needs at least 2 samples per chirp, got {x.shape[-1]}")
    return x


def _event_wise(kernel: Callable[[torch.Tensor], torch.Tensor], x: torch.Tensor) -> torch.Tensor:
    """``kernel(x)``, also for an empty batch of non-empty events (some CPU FFT builds raise on one)."""
    event = x.shape[x.ndim - 3 :]
    if x.numel() == 0 and all(d > 0 for d in event):
        probe = kernel(x.new_zeros(event))
        return probe.expand(*x.shape[: x.ndim - 3], *probe.shape).clone()
    return kernel(x)


def remove_mean(x: torch.Tensor) -> torch.Tensor:
    """Subtract each chirp's mean over fast time (the per-RX ADC DC offset).

    Args:
        x: raw cube ``(..., rx, chirps, samples)``, real floating.

    Examples:
        >>> remove_mean(torch.tensor([[[0.25, 0.75]]])).tolist()
        [[[-0.25, 0.25]]]
    """
    x = check_tensor(x, f"remove_mean expects {RAW_LAYOUT}", finite=False)
    return x - x.mean(dim=-1, keepdim=True)


def static_clutter_removal(x: torch.Tensor) -> torch.Tensor:
    """Moving-target indication: subtract the mean over chirps of each sample (or range bin).

    Args:
        x: raw cube or complex range profiles ``(..., rx, chirps, samples or range)``.

    Examples:
        >>> static_clutter_removal(torch.tensor([[[1.0, 2.0], [3.0, 2.0]]])).tolist()
        [[[-1.0, 0.0], [1.0, 0.0]]]
    """
    x = check_tensor(x, "static_clutter_removal expects (..., rx, chirps, samples or range)",
                     allow_complex=True, finite=False)
    return x - x.mean(dim=-2, keepdim=True)


def interference_excision(x: torch.Tensor, threshold_db: float = 6.0) -> torch.Tensor:
    """Chirps hit by an interferer's burst replaced by the mean of the frame's other chirps.

    A crossing FMCW interferer sweeps the IF band within a few chirps and raises every range bin there;
    the Doppler FFT then smears it over the whole row. A chirp is flagged when its power after the
    frame's mean chirp is removed (RX and samples averaged) exceeds the frame's median chirp by
    ``threshold_db``: people and the room change slowly from chirp to chirp, a burst does not.

    Args:
        x: raw cube ``(..., rx, chirps, samples)``, real floating.
        threshold_db: how far over the median chirp a chirp must stand to be replaced.

    Examples:
        >>> x = torch.ones(1, 4, 2); x[0, 1] = 5.0
        >>> interference_excision(x)[0].tolist()
        [[1.0, 1.0], [1.0, 1.0], [1.0, 1.0], [1.0, 1.0]]
    """
    x = check_tensor(x, f"interference_excision expects {RAW_LAYOUT}", finite=False)
    # What changes from chirp to chirp (the frame's mean chirp removed), its power per chirp over RX and samples
    power = static_clutter_removal(x).square_().mean(dim=(-3, -1))  # (..., chirps)
    median = power.median(dim=-1, keepdim=True).values
    hit = (power > median * 10 ** (float(threshold_db) / 10))[..., None, :, None]  # (..., 1, chirps, 1)
    if x.device.type == "cpu" and not bool(hit.any()):  # the usual case: nothing to replace (a CUDA or meta
        return x                                           # tensor is not read back to the host)
    # The replacement: the mean of the chirps not hit (the bursts would leave their share in the plain mean).
    keep = (~hit).to(x.dtype)
    clean_mean = (x * keep).sum(dim=-2, keepdim=True) / keep.sum(dim=-2, keepdim=True).clamp_min(1)
    return torch.where(hit, clean_mean, x)  # other chirps exactly as they came


def range_fft(x: torch.Tensor, window: str = "hann") -> torch.Tensor:
    """Range FFT -> complex ``(..., rx, chirps, N // 2)``: windowed, divided by the window sum, positive bins.

    Args:
        x: raw cube ``(..., rx, chirps, samples)``, float32 or float64, at least 2 samples.
        window: one of :data:`~radaraug.transforms.windows.WINDOWS`.

    Examples:
        >>> tone = torch.cos(2 * math.pi * 8 * torch.arange(64.0) / 64).expand(1, 1, 64)   # full scale, bin 8
        >>> round(range_fft(tone, "rect")[0, 0, 8].abs().item(), 6)   # A/2: -6.02 dBFS
        0.5
    """
    window = check_window_name(window)
    x = check_fft_input(x, "range_fft", RAW_LAYOUT, allow_complex=False)
    n = x.shape[-1]

    def kernel(v: torch.Tensor) -> torch.Tensor:
        w = normalized_window(window, n, v.dtype, v.device)
        return torch.fft.rfft(v * w, dim=-1)[..., : n // 2]

    return _event_wise(kernel, x)


def doppler_fft(x: torch.Tensor, window: str = "hann") -> torch.Tensor:
    """Doppler FFT -> RD map ``(..., rx, range, doppler)``: windowed, divided by the window sum, centred.

    Args:
        x: complex range profiles ``(..., rx, chirps, range)``.
        window: as for :func:`range_fft`.

    Examples:
        >>> rd = doppler_fft(torch.ones(1, 16, 4, dtype=torch.complex64))   # a static target: bin M // 2
        >>> rd.shape, rd[0, 0].abs().argmax().item()
        (torch.Size([1, 4, 16]), 8)
    """
    window = check_window_name(window)
    x = check_fft_input(x, "doppler_fft", PROFILE_LAYOUT, allow_complex=True)

    def kernel(v: torch.Tensor) -> torch.Tensor:
        m = v.shape[-2]
        w = shifted_doppler_window(window, m, v.real.dtype, v.device)
        # The window carries the fftshift (see shifted_doppler_window): one multiply, one FFT.
        return torch.fft.fft(v * w[:, None], dim=-2).transpose(-1, -2)

    return _event_wise(kernel, x)


def range_doppler(
    x: torch.Tensor,
    range_window: str = "hann",
    doppler_window: str = "hann",
    remove_mean: bool = True,
    static_clutter: bool = False,
) -> torch.Tensor:
    """Raw cube -> complex RD map ``(..., rx, N // 2, M)``: [mean removal, MTI], range and Doppler FFTs.

    Args:
        x: raw cube ``(..., rx, chirps, samples)``, float32 or float64, at least 2 samples.
        range_window: window over samples.
        doppler_window: window over chirps.
        remove_mean: subtract each chirp's mean (DC offset) first.
        static_clutter: subtract the mean over chirps (MTI).

    Examples:
        >>> range_doppler(torch.randn(2, 3, 64, 256)).shape   # (frames, rx, chirps, samples)
        torch.Size([2, 3, 128, 64])
    """
    range_window, doppler_window = check_window_name(range_window), check_window_name(doppler_window)
    x = check_fft_input(x, "range_doppler", RAW_LAYOUT, allow_complex=False)
    n = x.shape[-1]

    def kernel(v: torch.Tensor) -> torch.Tensor:
        m = v.shape[-2]
        # In-place ops below only touch temporaries made here, never the input.
        own = False
        if remove_mean:
            v, own = v - v.mean(dim=-1, keepdim=True), True
        if static_clutter:
            v, own = v - v.mean(dim=-2, keepdim=True), True
        wr = normalized_window(range_window, n, v.dtype, v.device)
        wd = shifted_doppler_window(doppler_window, m, v.dtype, v.device)
        if not wd.is_complex():
            # Both windows real: apply them as one outer product before the 2-D transform.
            w2 = wd[:, None] * wr
            spec = torch.fft.rfft2(v.mul_(w2) if own else v * w2, dim=(-2, -1))
        else:
            spec = torch.fft.fft(torch.fft.rfft(v * wr, dim=-1) * wd[:, None], dim=-2)
        return spec[..., : n // 2].transpose(-1, -2)

    return _event_wise(kernel, x)


def to_decibels(x: torch.Tensor, floor: float = 1e-12) -> torch.Tensor:
    """``20 * log10(max(|X|, floor))``: complex or magnitude map -> dB (dBFS with radaraug's chain).

    Args:
        x: complex map, or a real map taken as a magnitude.
        floor: smallest magnitude before the log, > 0 (-240 dB by default).

    Examples:
        >>> to_decibels(torch.tensor([1.0, 0.1, 0.0], dtype=torch.float64)).tolist()
        [0.0, -20.0, -240.0]
    """
    if not floor > 0:
        raise InputTensorError(f"to_decibels: floor must be > 0, got {floor}")
    x = check_tensor(x, "to_decibels expects a complex or magnitude map", min_ndim=0,
                     allow_complex=True, finite=False)
    floor = float(floor)
    # 10*log10(|X|^2) avoids the square root of abs(); the floor is applied to the power.
    power = x.real.square().add_(x.imag.square()) if x.is_complex() else x.square()
    return power.clamp_min_(floor * floor).log10_().mul_(10.0)


def check_combine_args(mode: str, index: int | None, db: bool) -> None:
    """Raise :class:`InputTensorError` for an invalid :func:`combine_rx` setting."""
    if mode not in COMBINE_MODES:
        raise InputTensorError(f"CombineRx mode must be one of {COMBINE_MODES}, got {mode!r}")
    if (mode == "select") != (index is not None):
        raise InputTensorError("CombineRx: give index exactly when mode='select'")
    if db and mode == "coherent":
        raise InputTensorError("CombineRx: 'coherent' needs complex maps, not dB (db=True)")


def combine_rx(x: torch.Tensor, mode: str = "mean_power", index: int | None = None, db: bool = False) -> torch.Tensor:
    """Combine the RX channels of an RD map into one, keeping an rx dim of size 1.

    Args:
        x: RD map ``(..., rx, range, doppler)``, linear (complex or magnitude) or dB with ``db=True``.
        mode: ``"mean_power"`` ``sqrt(mean |X|**2)`` (with ``db``: the mean of ``10**(dB/10)``, in dB),
            ``"coherent"`` ``mean X`` (not with ``db``), ``"max"`` or ``"select"`` (channel ``index``).
        index: the channel for ``"select"`` (negative counts from the end).
        db: the input is in dB.

    Examples:
        >>> combine_rx(torch.full((3, 1, 1), -100.0, dtype=torch.float64), db=True).item()
        -100.0
    """
    check_combine_args(mode, index, db)
    x = check_tensor(x, "combine_rx expects an RD map (..., rx, range, doppler)", allow_complex=True, finite=False)
    if mode == "select":
        n_rx = x.shape[-3]
        if not -n_rx <= index < n_rx:  # type: ignore[operator]  # index is set in "select" mode
            raise InputTensorError(f"CombineRx: rx index {index} out of range for {n_rx} channels")
        i = index % n_rx  # type: ignore[operator]
        return x[..., i : i + 1, :, :]
    if mode == "coherent":
        return x.mean(dim=-3, keepdim=True)
    if db:
        if x.is_complex():
            raise InputTensorError("CombineRx(db=True) got a complex tensor; dB maps are real")
        if mode == "max":
            return x.amax(dim=-3, keepdim=True)
        # exp(x * ln(10)/10) is 10**(x/10), several times faster than torch.pow on the CPU.
        return x.mul(math.log(10.0) / 10.0).exp_().mean(dim=-3, keepdim=True).log10_().mul_(10.0)
    mag2 = x.real.square() + x.imag.square() if x.is_complex() else x.square()
    if mode == "max":
        return mag2.amax(dim=-3, keepdim=True).sqrt()
    return mag2.mean(dim=-3, keepdim=True).sqrt()
