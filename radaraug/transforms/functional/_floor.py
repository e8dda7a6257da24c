"""Floor-relative RD maps: motion above each range row's own floor, in dB (docs/transforms.md)."""

from __future__ import annotations

import torch

from radaraug.errors import ConfigError
from radaraug.transforms._checks import check_tensor


def zero_doppler_bins(doppler: int, bins: int) -> slice:
    """The Doppler bins within ``bins`` of zero Doppler (centred axis, zero at ``doppler // 2``) that are blanked."""
    centre = doppler // 2
    return slice(max(centre - bins, 0), min(centre + bins + 1, doppler))


def kept_cells(range_bins: int, doppler: int, blank_zero_doppler: int, excise: torch.Tensor | None = None,
               device: torch.device | str | None = None) -> torch.Tensor:
    """Bool ``(range, doppler)``: the cells :func:`floor_relative` leaves (not blanked at zero Doppler, not excised)."""
    keep = torch.ones(range_bins, doppler, dtype=torch.bool, device=device)
    if blank_zero_doppler:
        keep[:, zero_doppler_bins(doppler, blank_zero_doppler)] = False
    if excise is not None:
        keep &= ~excise.to(keep.device)
    return keep


def check_blank_bins(bins: int) -> int:
    """``bins`` as an int >= 0 (ConfigError otherwise)."""
    if isinstance(bins, bool) or not isinstance(bins, int) or bins < 0:
        raise ConfigError(f"zero-Doppler blanking takes a number of bins >= 0 on each side, got {bins!r}")
    return bins


def floor_relative(x: torch.Tensor, blank_zero_doppler: int = 1, excise: torch.Tensor | None = None) -> torch.Tensor:
    """Each range row of a dB RD map minus its median over Doppler; zero Doppler ± ``bins`` set to 0 dB.

    Args:
        x: dB RD maps ``(..., range, doppler)``, Doppler centred (zero at ``doppler // 2``).
        blank_zero_doppler: bins on each side of zero Doppler set to 0 dB; 0 keeps them.
        excise: optional bool ``(range, doppler)`` mask of cells also set to 0 dB (see :func:`persistent_cells`).

    Examples:
        >>> x = torch.full((1, 4, 8), -100.0)
        >>> x[0, 2, 6], x[0, 1, 4] = -70.0, -40.0    # a mover and a static return
        >>> y = floor_relative(x)
        >>> float(y[0, 2, 6]), float(y[0, 1, 4]), float(y.abs().sum() - 30)
        (30.0, 0.0, 0.0)
    """
    bins = check_blank_bins(blank_zero_doppler)
    x = check_tensor(x, "floor_relative expects dB RD maps (..., range, doppler)", min_ndim=2, finite=False)
    # Lower median (torch's): for an even Doppler count it is the lower of the two middle values.
    out = x - x.median(dim=-1, keepdim=True).values
    if bins:
        out[..., zero_doppler_bins(x.shape[-1], bins)] = 0.0
    if excise is not None:
        if excise.shape != x.shape[-2:] or excise.dtype != torch.bool:
            raise ConfigError(f"floor_relative: excise must be a bool mask of shape {tuple(x.shape[-2:])}, got "
                              f"{excise.dtype} {tuple(excise.shape)}")
        out = out.masked_fill(excise.to(out.device), 0.0)
    return out


def persistent_cells(maps_db: torch.Tensor, threshold_db: float = 3.0, blank_zero_doppler: int = 1) -> torch.Tensor:
    """The ``(range, doppler)`` bool mask of empty-room cells whose median over frames stands above their row.

    Noise alone gives ~0 dB there; a spur's or a fan's lines, present in every frame, do not. Like a CFAR
    clutter map, these cells are then excised from every map (:func:`floor_relative`).

    Args:
        maps_db: ``(frames, range, doppler)`` dB maps of the empty room (RX combined), >= 3 frames.
        threshold_db: excess of the median over the row's floor that marks a cell.
        blank_zero_doppler: as :func:`floor_relative` (those cells are blanked anyway, not marked).

    Examples:
        >>> g = torch.Generator().manual_seed(0)
        >>> maps = -100 + 10 * torch.log10(torch.empty(40, 16, 8).exponential_(generator=g))   # noise
        >>> maps[:, 5, 1] += 20.0   # a spur's line in every frame
        >>> persistent_cells(maps).nonzero().tolist()
        [[5, 1]]
    """
    x = check_tensor(maps_db, "persistent_cells expects dB maps (frames, range, doppler)", min_ndim=3, finite=False)
    if x.ndim != 3 or x.shape[0] < 3:
        raise ConfigError(f"persistent_cells needs (frames >= 3, range, doppler) maps, got {tuple(x.shape)}")
    med = floor_relative(x, blank_zero_doppler).median(dim=0).values
    return med > float(threshold_db)
