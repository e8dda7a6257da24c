"""From dB RD maps to network images: clip and normalize to [0, 1], colormap to RGB, resize (docs/transforms.md)."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
import torch

from radaraug.errors import InputTensorError, RadarAugError
from radaraug.transforms import functional as F
from radaraug.transforms.base import Params, RadarTransform
from radaraug.transforms.functional._image import check_clip_range, check_one_channel, check_size


class ClipNormalize(RadarTransform):
    """``(clip(x, vmin, vmax) - vmin) / (vmax - vmin)``: dB map -> [0, 1].

    Args:
        vmin, vmax: the dB values mapped to 0 and 1 (and everything beyond them).
    """

    event_ndim = 2
    input_layout = "a dB map (..., H, W)"
    kernel = staticmethod(F.clip_normalize)
    spec_fields = ("vmin", "vmax")

    def __init__(self, vmin: float, vmax: float) -> None:
        super().__init__()
        self.vmin, self.vmax = check_clip_range(vmin, vmax)

    @classmethod
    def estimate(
        cls,
        data: torch.Tensor | Iterable[Any],
        low: float = 1.0,
        high: float = 99.9,
        max_items: int | None = None,
    ) -> ClipNormalize:
        """Choose ``[vmin, vmax]`` as percentiles of all dB values in ``data``.

        The defaults clip the deep lower tail of the noise and let a few leakage peaks saturate. As in the
        paper, estimate once on the training maps and use the same range for real maps.

        Args:
            data: a tensor of dB maps, or a Dataset / iterable of them (or of ``(map, label)``).
            low: lower percentile (0..100).
            high: upper percentile (0..100), > ``low``.
            max_items: read at most this many items of an iterable / Dataset.
        """
        if not 0 <= low < high <= 100:
            raise RadarAugError(f"ClipNormalize.estimate: need 0 <= low < high <= 100, got {low}, {high}")
        chunks: list[np.ndarray] = []
        items = [data] if isinstance(data, torch.Tensor) else _iterate(data, max_items)
        for k, item in enumerate(items):
            if isinstance(item, (tuple, list)):
                item = item[0]
            t = torch.as_tensor(item)
            if t.is_complex() or not t.is_floating_point():
                raise InputTensorError(
                    f"ClipNormalize.estimate: item {k} is not a real float dB map ({t.dtype})"
                )
            chunks.append(t.detach().reshape(-1).to("cpu", torch.float64).numpy())
        values = np.concatenate(chunks) if chunks else np.empty(0)
        if values.size == 0:
            raise InputTensorError("ClipNormalize.estimate: no data")
        if not np.isfinite(values).all():
            raise InputTensorError("ClipNormalize.estimate: data holds NaN or Inf")
        vmin, vmax = np.percentile(values, [low, high])
        if vmax <= vmin:
            raise RadarAugError(
                f"ClipNormalize.estimate: the data is constant ({vmin} dB); cannot pick a range"
            )
        return cls(float(vmin), float(vmax))


def _iterate(data: Any, max_items: int | None) -> Iterable[Any]:
    if hasattr(data, "__getitem__") and hasattr(data, "__len__") and not isinstance(data, (list, tuple)):
        n = len(data) if max_items is None else min(max_items, len(data))
        return (data[i] for i in range(n))
    return itertools.islice(data, None if max_items is None else max(max_items, 0))


class Colormap(RadarTransform):
    """One-channel map in [0, 1] ``(..., 1, H, W)`` -> RGB ``(..., 3, H, W)`` through a 256-entry table.

    matplotlib's lookup; ``viridis`` ships with radaraug, other names need matplotlib. Combine RX
    channels first (:class:`~radaraug.transforms.spectral.CombineRx`).

    Args:
        name: colormap name.
    """

    input_layout = "a one-channel map (..., 1, H, W) in [0, 1]"
    lut: torch.Tensor  # (256, 3) colour table, a buffer

    def __init__(self, name: str = "viridis") -> None:
        super().__init__()
        self.name = name
        self.register_buffer("lut", F.colormap_lut(name), persistent=False)

    def check_input(self, x: Any) -> torch.Tensor:
        """As :meth:`RadarTransform.check_input`; more than one channel raises InputTensorError."""
        return check_one_channel(super().check_input(x))

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        """Look every value up in the colour table."""
        return F.colormap(x, self.lut)

    def extra_spec(self) -> dict[str, Any]:
        """The colormap's name."""
        return {"cmap": self.name}


class Resize(RadarTransform):
    """Resample the last two dims to ``size = (height, width)`` (bilinear, antialiased when shrinking).

    The values of torchvision v2's ``Resize((height, width))`` on float tensors, to float rounding.

    Args:
        size: ``(height, width)``; a single int raises :class:`~radaraug.errors.ConfigError` (torchvision
            reads it as the short side).
        antialias: low-pass before shrinking (torchvision v2's default).
    """

    event_ndim = 2
    input_layout = "an image or map (..., H, W)"
    kernel = staticmethod(F.resize)

    def __init__(self, size: Sequence[int], antialias: bool = True) -> None:
        super().__init__()
        self.size = check_size(size)
        self.antialias = bool(antialias)

    def extra_spec(self) -> dict[str, Any]:
        """``size`` and ``antialias``."""
        return {"size": list(self.size), "antialias": self.antialias}


class MaxResize(RadarTransform):
    """Resample the last two dims to ``size = (height, width)``, each output cell the max of the cells it covers.

    Put it before :class:`Colormap` (on levels or [0, 1] values): a person one range bin wide keeps their
    peak where :class:`Resize` averages it with the floor (docs/transforms.md).

    Args:
        size: ``(height, width)``; a single int raises :class:`~radaraug.errors.ConfigError`.
    """

    event_ndim = 2
    input_layout = "an image or map (..., H, W)"
    kernel = staticmethod(F.max_resize)

    def __init__(self, size: Sequence[int]) -> None:
        super().__init__()
        self.size = check_size(size, "MaxResize")

    def extra_spec(self) -> dict[str, Any]:
        """``size``."""
        return {"size": list(self.size)}
