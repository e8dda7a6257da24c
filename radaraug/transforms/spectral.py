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

from typing import Any

import torch

from radaraug.errors import InputTensorError
from radaraug.transforms import functional as F
from radaraug.transforms.base import RadarTransform
from radaraug.transforms.functional._spectral import (
    COMBINE_MODES,
    PROFILE_LAYOUT,
    RAW_LAYOUT,
    check_combine_args,
    check_fft_input,
)
from radaraug.transforms.windows import check_window_name


class _FFTTransform(RadarTransform):
    """A transform that runs an FFT: float32/float64 (or complex64/128) input only."""

    def check_input(self, x: Any) -> torch.Tensor:
        return check_fft_input(
            super().check_input(x), type(self).__name__, self.input_layout, allow_complex=self.accepts_complex
        )


class _WindowedFFT(_FFTTransform):
    """An FFT along one axis with a named window (:class:`RangeFFT`, :class:`DopplerFFT`)."""

    spec_fields = ("window",)

    def __init__(self, window: str = "hann") -> None:
        super().__init__()
        self.window = check_window_name(window)


class RemoveMean(RadarTransform):
    """Subtract each chirp's mean over fast time (removes the per-RX ADC DC offset).

    Kernel: :func:`radaraug.transforms.functional.remove_mean`.
    """

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.remove_mean)


class StaticClutterRemoval(RadarTransform):
    """Moving-target indication: subtract the mean over chirps of each sample (or range bin).

    Works on a raw cube or on complex range profiles (``(..., rx, chirps, *)``): the operation is
    linear and acts on the chirp axis only, so both give the same RD map. Everything that does not
    change within a frame -- walls, leakage, DC -- ends up exactly in the zero-Doppler bin
    and is removed. Kernel: :func:`radaraug.transforms.functional.static_clutter_removal`.
    """

    input_layout = "(..., rx, chirps, samples or range)"
    accepts_complex = True
    kernel = staticmethod(F.static_clutter_removal)


class RangeFFT(_WindowedFFT):
    """Window over samples, real FFT, keep the ``N // 2`` positive bins, divide by the window sum.

    Input ``(..., rx, chirps, samples)`` real; output complex ``(..., rx, chirps, N // 2)``
    (complex64 for float32 input, complex128 for float64).
    Kernel: :func:`radaraug.transforms.functional.range_fft`.

    Args:
        window: ``rect``, ``hann``, ``hamming``, ``blackman`` or ``blackmanharris`` (symmetric).
    """

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.range_fft)


class DopplerFFT(_WindowedFFT):
    """Window over chirps, FFT, divide by the window sum, centre zero Doppler (fftshift).

    Input complex range profiles ``(..., rx, chirps, range)``; output ``(..., rx, range,
    doppler)``, zero velocity at index ``M // 2``, positive index = moving away.
    Kernel: :func:`radaraug.transforms.functional.doppler_fft`.

    Args:
        window: as for :class:`RangeFFT`.
    """

    input_layout = PROFILE_LAYOUT
    accepts_complex = True
    kernel = staticmethod(F.doppler_fft)


class RangeDoppler(_FFTTransform):
    """Raw cube -> complex RD map: [mean removal] -> [MTI] -> range FFT -> Doppler FFT.

    Equivalent to ``RemoveMean -> StaticClutterRemoval -> RangeFFT -> DopplerFFT`` (the optional
    steps only when enabled) and recorded as that chain in :meth:`chain_spec` comparisons.
    Kernel: :func:`radaraug.transforms.functional.range_doppler`.

    Args:
        range_window: window over samples.
        doppler_window: window over chirps.
        remove_mean: subtract each chirp's mean (DC offset) first.
        static_clutter: subtract the mean over chirps (MTI).
    """

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.range_doppler)
    spec_fields = ("range_window", "doppler_window", "remove_mean", "static_clutter")

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


class ToDecibels(RadarTransform):
    """``20 * log10(max(|X|, floor))``: complex or magnitude map -> dB (dBFS with this chain).

    A real input is taken as a magnitude (its absolute value is used).
    Kernel: :func:`radaraug.transforms.functional.to_decibels`.

    Args:
        floor: smallest magnitude before the log (keeps exact zeros finite: -240 dB by default).
    """

    accepts_complex = True
    input_layout = "a complex or magnitude map (..., rx, range, doppler)"
    kernel = staticmethod(F.to_decibels)
    spec_fields = ("floor",)

    def __init__(self, floor: float = 1e-12) -> None:
        super().__init__()
        if not floor > 0:
            raise InputTensorError(f"ToDecibels floor must be > 0, got {floor}")
        self.floor = float(floor)


class CombineRx(RadarTransform):
    """Combine the RX channels of a (linear) RD map into one, keeping an rx dim of size 1.

    Modes (linear maps, complex or magnitude):

    * ``"mean_power"``: ``sqrt(mean_rx |X|**2)`` (real magnitude; dB of it = mean power in dB);
    * ``"coherent"``: ``mean_rx X`` (complex sum / n_rx: a broadside target keeps its level);
    * ``"max"``: ``max_rx |X|``;
    * ``"select"``: channel ``index`` only.

    With ``db=True`` the input is a dB map: ``mean_power`` averages ``10**(dB/10)`` and returns
    dB, ``max`` and ``select`` work as is, ``coherent`` is refused (dB has no phase).
    Kernel: :func:`radaraug.transforms.functional.combine_rx`.

    Args:
        mode: one of the modes above.
        index: the channel for ``"select"``.
        db: the input is in dB.
    """

    accepts_complex = True
    MODES = COMBINE_MODES
    kernel = staticmethod(F.combine_rx)

    def __init__(self, mode: str = "mean_power", index: int | None = None, db: bool = False) -> None:
        super().__init__()
        check_combine_args(mode, index, db)
        self.mode, self.index, self.db = mode, index, bool(db)

    def extra_spec(self) -> dict[str, Any]:
        """``mode`` and ``db`` (and ``index`` when set)."""
        spec: dict[str, Any] = {"mode": self.mode, "db": self.db}
        if self.index is not None:
            spec["index"] = self.index
        return spec
