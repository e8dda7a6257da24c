"""From dB maps to network images: clip and normalize, colormap lookup, resize (bilinear or by the max)."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np
import torch
import torch.nn.functional as nnf

from radaraug._optional import lazy_import
from radaraug.errors import ConfigError, InputTensorError, RadarAugError
from radaraug.transforms._checks import check_tensor
from radaraug.transforms._viridis import viridis_rgb


def clip_normalize(x: torch.Tensor, vmin: float, vmax: float) -> torch.Tensor:
    """``(clip(x, vmin, vmax) - vmin) / (vmax - vmin)``: dB map -> [0, 1].

    Args:
        x: a dB map ``(..., H, W)``, real floating.
        vmin: dB value mapped to 0 (and everything below).
        vmax: dB value mapped to 1 (and everything above), > ``vmin``.

    Examples:
        >>> clip_normalize(torch.tensor([[-130.0, -75.0, 0.0]]), -110.0, -40.0).tolist()
        [[0.0, 0.5, 1.0]]
    """
    vmin, vmax = check_clip_range(vmin, vmax)
    x = check_tensor(x, "clip_normalize expects a dB map (..., H, W)", min_ndim=2, finite=False)
    return (x.clamp(vmin, vmax) - vmin) * (1.0 / (vmax - vmin))


def check_clip_range(vmin: float, vmax: float) -> tuple[float, float]:
    """``(vmin, vmax)`` as floats if finite with ``vmin < vmax``, else :class:`RadarAugError`."""
    vmin, vmax = float(vmin), float(vmax)
    if not (math.isfinite(vmin) and math.isfinite(vmax)) or vmax <= vmin:
        raise RadarAugError(f"ClipNormalize: need finite vmin < vmax, got {vmin}, {vmax}")
    return vmin, vmax


@functools.lru_cache(maxsize=16)
def _lut_f64(name: str) -> torch.Tensor:
    if name == "viridis":
        return torch.tensor(viridis_rgb(), dtype=torch.float64)
    matplotlib = lazy_import("matplotlib", feature=f"the {name!r} colormap (viridis needs no matplotlib)")
    try:
        cmap = matplotlib.colormaps[name]
    except KeyError:
        raise RadarAugError(f"Colormap: unknown colormap {name!r}") from None
    return torch.from_numpy(cmap.resampled(256)(np.arange(256))[:, :3].astype(np.float64))


def colormap_lut(name: str = "viridis") -> torch.Tensor:
    """The ``(256, 3)`` float64 RGB table of a colormap (``viridis`` built in, others from matplotlib).

    Raises:
        RadarAugError: an unknown name.

    Examples:
        >>> colormap_lut("viridis").shape
        torch.Size([256, 3])
    """
    return _lut_f64(str(name)).clone()


def check_one_channel(x: torch.Tensor) -> torch.Tensor:
    """``x`` if it holds one channel ``(..., 1, H, W)``, else :class:`InputTensorError`."""
    if x.shape[-3] != 1:
        raise InputTensorError(
            f"Colormap expects one channel (..., 1, H, W), got {x.shape[-3]} in shape {tuple(x.shape)}; "
            "combine the RX channels first (CombineRx)"
        )
    return x


def colormap(x: torch.Tensor, cmap: str | torch.Tensor = "viridis") -> torch.Tensor:
    """One-channel map in [0, 1] ``(..., 1, H, W)`` -> RGB ``(..., 3, H, W)`` through a lookup table.

    As ``matplotlib.colormaps[name](x)[..., :3]``: entry ``floor(K x)`` of a ``K``-entry table, x = 1 the
    last entry; values outside [0, 1] are clipped.

    Args:
        x: ``(..., 1, H, W)``, real floating (combine RX channels first).
        cmap: a colormap name (see :func:`colormap_lut`) or a ``(K, 3)`` table.

    Examples:
        >>> colormap(torch.tensor([[[0.0, 1.0]]])).shape
        torch.Size([3, 1, 2])
    """
    x = check_one_channel(check_tensor(x, "colormap expects a one-channel map (..., 1, H, W) in [0, 1]", finite=False))
    lut = colormap_lut(cmap) if isinstance(cmap, str) else cmap
    if not (isinstance(lut, torch.Tensor) and lut.ndim == 2 and lut.shape[1] == 3 and lut.shape[0] >= 1):
        raise InputTensorError(f"colormap: cmap must be a name or a (K, 3) tensor, got {cmap!r}")
    n = lut.shape[0]
    idx = (x.squeeze(-3).clamp(0.0, 1.0) * n).to(torch.long).clamp_(max=n - 1)
    return nnf.embedding(idx, lut.to(dtype=x.dtype, device=x.device)).movedim(-1, -3)


def check_size(size: object, what: str = "Resize") -> tuple[int, int]:
    """``(height, width)`` as ints, else :class:`ConfigError` (also for one int, torchvision's short side)."""
    if isinstance(size, (int, np.integer)) and not isinstance(size, bool):
        raise ConfigError(
            f"{what}: size must be (height, width), got the int {size}; write ({size}, {size}) for a square "
            "output (torchvision would read an int as the short side, keeping the aspect ratio)"
        )
    if not isinstance(size, Sequence) or isinstance(size, str) or len(size) != 2:
        raise ConfigError(f"{what}: size must be (height, width), got {size!r}")
    h, w = size
    if any(isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1 for v in (h, w)):
        raise ConfigError(f"{what}: size must be two positive ints (height, width), got {size!r}")
    return int(h), int(w)


def resize(x: torch.Tensor, size: Sequence[int], antialias: bool = True) -> torch.Tensor:
    """Resample the last two dims to ``size = (height, width)`` (bilinear, antialiased when shrinking).

    The values of torchvision v2's ``resize(x, [height, width])`` on float tensors, to float rounding.

    Args:
        x: an image or map ``(..., H, W)``, real floating.
        size: ``(height, width)``.
        antialias: low-pass before shrinking (torchvision v2's default).

    Raises:
        ConfigError: ``size`` is not two positive ints.

    Examples:
        >>> resize(torch.full((3, 64, 32), 0.25), (224, 224)).shape
        torch.Size([3, 224, 224])
    """
    size = check_size(size, "resize")
    x = check_tensor(x, "resize expects an image or map (..., H, W)", min_ndim=2, finite=False)
    lead = x.shape[:-2]
    flat = x.reshape(-1, 1, *x.shape[-2:])
    out = nnf.interpolate(flat, size=size, mode="bilinear", align_corners=False, antialias=bool(antialias))
    return out.reshape(*lead, *size)


def max_windows(n_in: int, n_out: int) -> torch.Tensor:
    """``(n_out, k)`` input indices of each output cell's window (adaptive pooling's), short windows repeated.

    Window ``i`` covers ``floor(i * n_in / n_out) .. ceil((i + 1) * n_in / n_out) - 1``; a window shorter
    than the longest repeats its last index, which leaves a max unchanged.
    """
    starts = [(i * n_in) // n_out for i in range(n_out)]
    ends = [-(-(i + 1) * n_in // n_out) for i in range(n_out)]
    k = max(e - s for s, e in zip(starts, ends))
    return torch.tensor([[min(s + j, e - 1) for j in range(k)] for s, e in zip(starts, ends)], dtype=torch.long)


def max_resize(x: torch.Tensor, size: Sequence[int]) -> torch.Tensor:
    """Resample the last two dims to ``size`` keeping each output cell's largest input value.

    Each output cell is the max over the input cells it covers (the windows of adaptive max pooling),
    so a target one range bin wide keeps its peak where a bilinear shrink averages it with the floor
    around it. Gathers and maxima only, so exporters (ONNX) take it as it is.

    Args:
        x: an image or map ``(..., H, W)``, real floating.
        size: ``(height, width)``.

    Raises:
        ConfigError: ``size`` is not two positive ints.

    Examples:
        >>> max_resize(torch.tensor([[0.0, 0.0, 9.0, 0.0]]), (1, 2)).tolist()
        [[0.0, 9.0]]
    """
    size = check_size(size, "max_resize")
    x = check_tensor(x, "max_resize expects an image or map (..., H, W)", min_ndim=2, finite=False)
    h, w = x.shape[-2:]
    return windows_max(x, max_windows(h, size[0]).to(x.device), max_windows(w, size[1]).to(x.device))


def windows_max(x: torch.Tensor, rows: torch.Tensor, cols: torch.Tensor) -> torch.Tensor:
    """``(..., H, W)`` -> ``(..., len(rows), len(cols))``: the max over each cell's window (:func:`max_windows`)."""
    lead, w = x.shape[:-2], x.shape[-1]
    y = x.index_select(-2, rows.flatten()).reshape(*lead, rows.shape[0], rows.shape[1], w).amax(dim=-2)
    return y.index_select(-1, cols.flatten()).reshape(*lead, rows.shape[0], cols.shape[0], cols.shape[1]).amax(dim=-1)
