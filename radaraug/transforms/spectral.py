"""Range-Doppler processing: mean removal, MTI, range/Doppler FFTs, dB conversion, RX combination.

Layouts, the dBFS convention and the Doppler sign: docs/transforms.md, "Layouts and units".
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
    """Subtract each chirp's mean over fast time (the per-RX ADC DC offset)."""

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.remove_mean)


class StaticClutterRemoval(RadarTransform):
    """Moving-target indication: subtract the mean over chirps of each sample (or range bin).

    On a raw cube or complex range profiles (the same RD map either way): whatever does not change
    within a frame (walls, leakage, DC) is removed.
    """

    input_layout = "(..., rx, chirps, samples or range)"
    accepts_complex = True
    kernel = staticmethod(F.static_clutter_removal)


class InterferenceExcision(RadarTransform):
    """Replace the chirps an interferer's burst hit by the mean of the frame's other chirps (before the RD FFTs).

    Deterministic; raw cubes ``(..., rx, chirps, samples)`` in and out. See
    :func:`~radaraug.transforms.functional.interference_excision` and docs/transforms.md.

    Args:
        threshold_db: how far a chirp's moving power must stand over the frame's median chirp.
    """

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.interference_excision)
    spec_fields = ("threshold_db",)

    def __init__(self, threshold_db: float = 6.0) -> None:
        super().__init__()
        if not threshold_db > 0:
            raise InputTensorError(f"InterferenceExcision threshold_db must be > 0, got {threshold_db}")
        self.threshold_db = float(threshold_db)


class RangeFFT(_WindowedFFT):
    """Range FFT: real ``(..., rx, chirps, samples)`` -> complex ``(..., rx, chirps, N // 2)``, dBFS scaled.

    Args:
        window: ``rect``, ``hann``, ``hamming``, ``blackman`` or ``blackmanharris`` (symmetric).
    """

    input_layout = RAW_LAYOUT
    kernel = staticmethod(F.range_fft)


class DopplerFFT(_WindowedFFT):
    """Doppler FFT: complex ``(..., rx, chirps, range)`` -> ``(..., rx, range, doppler)``, zero Doppler centred.

    Args:
        window: as for :class:`RangeFFT`.
    """

    input_layout = PROFILE_LAYOUT
    accepts_complex = True
    kernel = staticmethod(F.doppler_fft)


class RangeDoppler(_FFTTransform):
    """Raw cube -> complex RD map: [mean removal] -> [MTI] -> range FFT -> Doppler FFT, in one pass.

    Chain checks compare it as ``RemoveMean -> [StaticClutterRemoval] -> RangeFFT -> DopplerFFT``.

    Args:
        range_window, doppler_window: windows over samples and over chirps.
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
    """``20 * log10(max(|X|, floor))``: complex or magnitude map -> dB (dBFS with radaraug's chain).

    Args:
        floor: smallest magnitude before the log (-240 dB by default, keeping exact zeros finite).
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
    """Combine the RX channels of an RD map into one, keeping an rx dim of size 1.

    Args:
        mode: ``"mean_power"`` ``sqrt(mean |X|**2)`` (with ``db``: the mean of ``10**(dB/10)``, in dB),
            ``"coherent"`` ``mean X`` (not with ``db``: dB has no phase), ``"max"`` or ``"select"``.
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
