"""From dB RD maps to network images: clip + normalize, colormap, resize.

``ClipNormalize`` maps ``[vmin, vmax]`` dB to ``[0, 1]`` (values outside are clipped first);
``Colormap`` turns a one-channel ``(..., 1, H, W)`` map in [0, 1] into ``(..., 3, H, W)`` RGB with
matplotlib's lookup semantics (256 entries, nearest entry: index ``floor(256 x)`` clipped to 255);
``Resize`` resamples the last two dims (bilinear, antialiased).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from radaraug.errors import InputTensorError, RadarAugError
from radaraug.transforms._viridis import VIRIDIS_RGB
from radaraug.transforms.base import Params, RadarTransform


class ClipNormalize(RadarTransform):
    """``(clip(x, vmin, vmax) - vmin) / (vmax - vmin)``: dB map -> [0, 1].

    Args:
        vmin: dB value mapped to 0 (everything below too).
        vmax: dB value mapped to 1 (everything above too).
    """

    event_ndim = 2
    input_layout = "a dB map (..., H, W)"

    def __init__(self, vmin: float, vmax: float) -> None:
        super().__init__()
        vmin, vmax = float(vmin), float(vmax)
        if not (math.isfinite(vmin) and math.isfinite(vmax)) or vmax <= vmin:
            raise RadarAugError(f"ClipNormalize: need finite vmin < vmax, got {vmin}, {vmax}")
        self.vmin, self.vmax = vmin, vmax

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        return (x.clamp(self.vmin, self.vmax) - self.vmin) * (1.0 / (self.vmax - self.vmin))

    def extra_spec(self) -> dict[str, Any]:
        return {"vmin": self.vmin, "vmax": self.vmax}

    @classmethod
    def estimate(
        cls,
        data: torch.Tensor | Iterable[Any],
        low: float = 1.0,
        high: float = 99.9,
        max_items: int | None = None,
    ) -> ClipNormalize:
        """Choose ``[vmin, vmax]`` as percentiles of all dB values in ``data``.

        The defaults keep the noise floor's body (its log-Rayleigh lower tail, which reaches
        tens of dB below the floor, is clipped at the 1st percentile) and the strongest returns
        up to the 99.9th percentile, so a handful of leakage peaks does not squeeze the rest of
        the scale. The paper estimates the range once, from simulation, and uses it for
        simulated and real maps alike: do the same (estimate on the training maps).

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
    it = iter(data)
    if max_items is None:
        return it
    return (item for _, item in zip(range(max_items), it))


class Colormap(RadarTransform):
    """One-channel map in [0, 1] ``(..., 1, H, W)`` -> RGB ``(..., 3, H, W)`` through a 256-entry LUT.

    Matches ``matplotlib.colormaps[name](x)[..., :3]`` for x in [0, 1]: entry ``floor(256 x)``,
    with x = 1 mapped to the last entry; inputs outside [0, 1] are clipped first. ``viridis``
    ships with radaraug; any other matplotlib colormap name is read from matplotlib.
    An rx dim > 1 is an error: combine the channels first (:class:`~radaraug.transforms.spectral.CombineRx`).

    Args:
        name: colormap name.
    """

    input_layout = "a one-channel map (..., 1, H, W) in [0, 1]"

    def __init__(self, name: str = "viridis") -> None:
        super().__init__()
        self.name = name
        if name == "viridis":
            table = torch.tensor(VIRIDIS_RGB, dtype=torch.float64)
        else:
            import matplotlib

            try:
                cmap = matplotlib.colormaps[name]
            except KeyError:
                raise RadarAugError(f"Colormap: unknown colormap {name!r}") from None
            table = torch.from_numpy(cmap.resampled(256)(np.arange(256))[:, :3].astype(np.float64))
        self.register_buffer("lut", table, persistent=False)

    def check_input(self, x: Any) -> torch.Tensor:
        x = super().check_input(x)
        if x.shape[-3] != 1:
            raise InputTensorError(
                f"Colormap expects one channel (..., 1, H, W), got {x.shape[-3]} in shape {tuple(x.shape)}; "
                "combine the RX channels first (CombineRx)"
            )
        return x

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        n = self.lut.shape[0]
        idx = (x.squeeze(-3).clamp(0.0, 1.0) * n).to(torch.long).clamp_(max=n - 1)
        lut = self.lut.to(dtype=x.dtype, device=x.device)
        return F.embedding(idx, lut).movedim(-1, -3)

    def extra_spec(self) -> dict[str, Any]:
        return {"cmap": self.name}


class Resize(RadarTransform):
    """Resample the last two dims to ``size`` (bilinear, antialiased when shrinking).

    Args:
        size: ``(height, width)``, or one int for a square output (unlike torchvision, an int
            does not keep the aspect ratio).
        antialias: low-pass before shrinking (as torchvision v2 does by default).
    """

    event_ndim = 2
    input_layout = "an image or map (..., H, W)"

    def __init__(self, size: int | tuple[int, int], antialias: bool = True) -> None:
        super().__init__()
        h, w = (size, size) if isinstance(size, int) else tuple(size)
        if int(h) < 1 or int(w) < 1:
            raise RadarAugError(f"Resize: size must be positive, got {size}")
        self.size = (int(h), int(w))
        self.antialias = bool(antialias)

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        lead = x.shape[:-2]
        flat = x.reshape(-1, 1, *x.shape[-2:])
        out = F.interpolate(
            flat, size=self.size, mode="bilinear", align_corners=False, antialias=self.antialias
        )
        return out.reshape(*lead, *self.size)

    def extra_spec(self) -> dict[str, Any]:
        return {"size": list(self.size), "antialias": self.antialias}
