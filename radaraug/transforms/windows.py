"""Symmetric FFT windows (numpy's and scipy's ``sym=True`` values), cached per name, length, dtype and device."""

from __future__ import annotations

import functools
import math

import torch

from radaraug.errors import InputTensorError

WINDOWS = ("rect", "hann", "hamming", "blackman", "blackmanharris")
"""Names accepted wherever a window is asked for."""

BLACKMAN_HARRIS = [0.35875, 0.48829, 0.14128, 0.01168]
"""The 4-term Blackman-Harris coefficients ``a_k`` of ``sum_k (-1)**k a_k cos(2 pi k n / (N - 1))``."""

# Half-width of the main lobe in bins for a tone exactly on a bin: the neighbours that can hold
# energy of a perfectly static target. Used to keep static clutter out of motion checks.
MAIN_LOBE_HALF_WIDTH_BINS = {"rect": 0, "hann": 1, "hamming": 1, "blackman": 2, "blackmanharris": 3}

_ALIASES = {"hanning": "hann", "rectangular": "rect", "boxcar": "rect", "none": "rect"}
_TORCH_WINDOWS = {"hann": torch.hann_window, "hamming": torch.hamming_window, "blackman": torch.blackman_window}


def check_window_name(name: str) -> str:
    """Return ``name`` lower-cased if it is a known window, else raise :class:`InputTensorError`."""
    key = str(name).lower().replace("-", "").replace("_", "")
    key = _ALIASES.get(key, key)
    if key not in WINDOWS:
        raise InputTensorError(f"unknown window {name!r}; choose one of {', '.join(WINDOWS)}")
    return key


def _window_f64(name: str, n: int) -> torch.Tensor:
    """The window in float64 on the CPU (computed once, then cast and moved)."""
    if n == 1 or name == "rect":
        return torch.ones(n, dtype=torch.float64)
    if name in _TORCH_WINDOWS:
        return _TORCH_WINDOWS[name](n, periodic=False, dtype=torch.float64)
    # 4-term Blackman-Harris (-92 dB sidelobes), coefficients as in scipy.signal.windows.
    return torch.signal.windows.general_cosine(n, a=BLACKMAN_HARRIS, sym=True, dtype=torch.float64)


@functools.lru_cache(maxsize=64)
def get_window(
    name: str, n: int, dtype: torch.dtype = torch.float32, device: torch.device | str = "cpu"
) -> torch.Tensor:
    """A symmetric window of length ``n`` (cached: do not modify it in place).

    Args:
        name: one of :data:`WINDOWS`, or an alias such as ``"hanning"``.
        n: window length.
        dtype: real floating dtype of the result.
        device: device of the result.
    """
    return _window_f64(check_window_name(name), int(n)).to(dtype=dtype, device=device)


@functools.lru_cache(maxsize=64)
def normalized_window(name: str, n: int, dtype: torch.dtype, device: torch.device) -> torch.Tensor:
    """``w / sum(w)``: windowing and the dBFS scaling folded into one multiply (cached)."""
    w = _window_f64(check_window_name(name), int(n))
    return (w / w.sum()).to(dtype=dtype, device=device)


@functools.lru_cache(maxsize=64)
def shifted_doppler_window(name: str, m: int, dtype: torch.dtype, device: torch.device) -> torch.Tensor:
    """``w / sum(w)`` times ``exp(j*pi*2*(m//2)*k/m)``: the Doppler fftshift folded into the window.

    Multiplying slow time by this phase shifts every FFT bin by ``M//2``, as ``fftshift`` does, without a
    second pass; for even ``M`` it is ``(-1)**k`` and the window stays real.
    """
    w = _window_f64(check_window_name(name), int(m))
    w = w / w.sum()
    k = torch.arange(m, dtype=torch.float64)
    if m % 2 == 0:
        return (w * (1.0 - 2.0 * (k % 2))).to(dtype=dtype, device=device)
    phase = 2 * math.pi * (m // 2) * k / m
    cdtype = torch.complex128 if dtype == torch.float64 else torch.complex64
    return torch.polar(w, phase).to(dtype=cdtype, device=device)


def noise_power_gain(name: str, n: int) -> float:
    """``sum(w**2) / sum(w)**2``: the power per bin of unit-variance white noise (FFT divided by ``sum(w)``).

    Noise of variance ``sigma**2`` has ``E|X|**2 = sigma**2 * noise_power_gain``; ``1/n`` for ``rect``.
    """
    w = _window_f64(check_window_name(name), int(n))
    return float((w * w).sum() / w.sum() ** 2)
