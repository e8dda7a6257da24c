"""A classifier's test chain as plain matrix products, for export.

:class:`MatmulChain` computes the images of a :class:`~radaraug.training.classifier_file.ChainSpec` (what a
classifier file records; its ``eager()`` is the library's transforms) with matrix products, a sort and
a table lookup only, so that TorchScript and ONNX export it (the FFTs as DFT matrices, the
anti-aliased resize as the two matrices it applies). docs/predict.md.
"""

from __future__ import annotations

import math
from typing import Any

import torch
from torch import nn
from torch.nn import functional as nnf

from radaraug.errors import CheckpointError
from radaraug.training.classifier_file import ChainSpec
from radaraug.transforms import ToDecibels
from radaraug.transforms.functional._floor import kept_cells
from radaraug.transforms.functional._image import colormap_lut, max_windows, windows_max
from radaraug.transforms.windows import normalized_window, shifted_doppler_window

#: ToDecibels' default magnitude floor (the eager chain's): its dB maps stay finite on exact zeros.
_MAG_FLOOR = ToDecibels().floor


def _dft_matrices(n: int, m: int, rd: dict[str, Any]) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
    """Real and imaginary parts of the range ``(n // 2, n)`` and Doppler ``(m, m)`` operators (float64).

    The range operator folds in the mean removal and the normalized window, the Doppler operator the
    window and the fftshift, exactly as :func:`~radaraug.transforms.functional.range_doppler` applies them.
    """
    if rd.get("static_clutter", False):
        raise CheckpointError("export: static-clutter removal (MTI) is not in the matrix chain; export the network alone")
    f64 = torch.float64
    t = torch.arange(n, dtype=f64)
    r = torch.arange(n // 2, dtype=f64)
    wr = normalized_window(rd.get("range_window", "hann"), n, f64, torch.device("cpu"))
    ang = -2 * math.pi * torch.outer(r, t) / n
    rng = torch.complex(torch.cos(ang), torch.sin(ang)) * wr
    if rd.get("remove_mean", True):  # x - mean(x) is the linear map I - 1/n
        rng = rng - rng.sum(dim=1, keepdim=True) / n
    c = torch.arange(m, dtype=f64)
    wd = shifted_doppler_window(rd.get("doppler_window", "hann"), m, f64, torch.device("cpu")).to(torch.complex128)
    ang = -2 * math.pi * torch.outer(c, c) / m
    dop = torch.complex(torch.cos(ang), torch.sin(ang)) * wd
    return rng.real, rng.imag, dop.real, dop.imag


def _resize_matrix(n_in: int, n_out: int) -> torch.Tensor:
    """The ``(n_out, n_in)`` matrix that the chain's anti-aliased bilinear resize applies along one axis."""
    # Two columns, not one: the anti-aliased kernel treats a width-1 image differently.
    eye = torch.eye(n_in, dtype=torch.float64).reshape(n_in, 1, n_in, 1).expand(n_in, 1, n_in, 2)
    cols = nnf.interpolate(eye, size=(n_out, 2), mode="bilinear", align_corners=False, antialias=True)
    return cols[..., 0].reshape(n_in, n_out).T.contiguous()


class MatmulChain(nn.Module):
    """:class:`ChainSpec`'s images from raw frames with matrix products, one sort and a table lookup.

    Equal to :meth:`ChainSpec.eager` within float32 rounding (tests/inference/test_chain.py states
    the tolerance); it exists so that exporters that lack complex FFTs or the anti-aliased resize
    (ONNX) still get the whole chain.

    Args:
        spec: the chain.
        samples, chirps: the radar config's samples per chirp and chirps per frame.
    """

    # buffers (registered in __init__)
    rng_re: torch.Tensor
    rng_im: torch.Tensor
    dop_re: torch.Tensor
    dop_im: torch.Tensor
    keep: torch.Tensor
    lut: torch.Tensor
    resize_h: torch.Tensor
    resize_w: torch.Tensor

    def __init__(self, spec: ChainSpec, samples: int, chirps: int) -> None:
        super().__init__()
        rr, ri, dr, di = _dft_matrices(samples, chirps, spec.range_doppler)
        for name, value in (("rng_re", rr), ("rng_im", ri), ("dop_re", dr), ("dop_im", di)):
            self.register_buffer(name, value.float().contiguous())
        self.floor_relative = spec.representation == "floor_relative"
        keep = (kept_cells(samples // 2, chirps, spec.blank_zero_doppler, spec.excise) if self.floor_relative
                else torch.ones(samples // 2, chirps, dtype=torch.bool))
        self.register_buffer("keep", keep.float())
        self.vmin, self.vmax = float(spec.clip_range_db[0]), float(spec.clip_range_db[1])
        self.register_buffer("lut", colormap_lut("viridis").float())
        size = spec.image_size or (samples // 2, chirps)
        self.max_resize = spec.resample == "max"
        if self.max_resize:  # each pixel the max of its cells' levels, before the colour table (gathers)
            self.register_buffer("resize_h", max_windows(samples // 2, int(size[0])))
            self.register_buffer("resize_w", max_windows(chirps, int(size[1])))
        else:
            self.register_buffer("resize_h", _resize_matrix(samples // 2, int(size[0])).float())
            self.register_buffer("resize_w", _resize_matrix(chirps, int(size[1])).float())
        self.median_index = (chirps - 1) // 2  # torch's lower median
        self.excises_interference = spec.interference_db is not None
        self.interference_ratio = 10.0 ** (float(spec.interference_db or 0.0) / 10.0)

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        """Raw frames ``(B, rx, chirps, samples)`` float32 -> viridis images ``(B, 3, H, W)`` in [0, 1]."""
        x = frames.float()
        if self.excises_interference:
            x = self._excise_interference(x)
        a_re = x @ self.rng_re.T  # (B, rx, chirps, range)
        a_im = x @ self.rng_im.T
        o_re = self.dop_re @ a_re - self.dop_im @ a_im  # (B, rx, doppler, range)
        o_im = self.dop_re @ a_im + self.dop_im @ a_re
        power = (o_re * o_re + o_im * o_im).clamp_min(_MAG_FLOOR * _MAG_FLOOR)
        level = 10.0 * torch.log10(power.mean(dim=1)).transpose(-1, -2)  # RX mean power in dB: (B, range, doppler)
        if self.floor_relative:
            median = torch.sort(level, dim=-1).values[..., self.median_index:self.median_index + 1]
            level = (level - median) * self.keep
        u = (level.clamp(self.vmin, self.vmax) - self.vmin) * (1.0 / (self.vmax - self.vmin))
        if self.max_resize:
            u = windows_max(u, self.resize_h, self.resize_w)
        n = self.lut.shape[0]
        idx = (u * n).long().clamp(0, n - 1)
        img = self.lut[idx].permute(0, 3, 1, 2)  # (B, 3, range, doppler)
        return img if self.max_resize else self.resize_h @ img @ self.resize_w.T

    def _excise_interference(self, x: torch.Tensor) -> torch.Tensor:
        """:func:`~radaraug.transforms.functional.interference_excision` with a sort for the median (ONNX has no median)."""
        moving = x - x.mean(dim=-2, keepdim=True)
        power = (moving * moving).mean(dim=(1, 3))  # (B, chirps)
        median = torch.sort(power, dim=-1).values[:, self.median_index:self.median_index + 1]
        hit = (power > median * self.interference_ratio)[:, None, :, None]  # (B, 1, chirps, 1)
        keep = (~hit).float()
        clean_mean = (x * keep).sum(dim=-2, keepdim=True) / keep.sum(dim=-2, keepdim=True).clamp_min(1.0)
        return torch.where(hit, clean_mean, x)
