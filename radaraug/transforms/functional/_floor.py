"""Floor-relative RD maps: each range row referenced to its own Doppler median, zero Doppler blanked.

Why: a network trained on absolute dB levels keys on what moves between domains -- the receiver's
noise floor, the system gain, the skirt that phase noise spreads across Doppler around strong static
returns. Referencing each range row to its median over Doppler (a CFAR-like normalization: the
median of a row is its floor, or its skirt where a strong static return spreads one) leaves what
stands out of its own row, and blanking the zero-Doppler bins removes the static room itself. What
is left is motion above the local floor, in dB.
"""

from __future__ import annotations

import torch

from radaraug.errors import ConfigError
from radaraug.transforms._checks import check_tensor


def check_blank_bins(bins: int) -> int:
    """``bins`` as an int >= 0 (ConfigError otherwise)."""
    if isinstance(bins, bool) or not isinstance(bins, int) or bins < 0:
        raise ConfigError(f"zero-Doppler blanking takes a number of bins >= 0 on each side, got {bins!r}")
    return bins


def floor_relative(x: torch.Tensor, blank_zero_doppler: int = 1, excise: torch.Tensor | None = None) -> torch.Tensor:
    """Each range row of a dB RD map minus its median over Doppler; zero Doppler ± ``bins`` set to 0 dB.

    Args:
        x: dB RD maps ``(..., range, doppler)`` with the Doppler axis centred (zero velocity at
            index ``doppler // 2``, radaraug's layout), real floating.
        blank_zero_doppler: bins on each side of zero Doppler set to 0 dB (the row's floor) after
            referencing; 0 keeps them.
        excise: optional boolean ``(range, doppler)`` mask of cells also set to 0 dB: persistent lines of
            the empty room (a spur, a fan), found on a calibration capture by :func:`persistent_cells`.

    Returns:
        A map of the same shape, dtype and device, in dB relative to each row's median.

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> x = torch.full((1, 4, 8), -100.0)
        >>> x[0, 2, 6] = -70.0          # a mover, 30 dB above its row's floor
        >>> x[0, 1, 4] = -40.0          # a static return at zero Doppler
        >>> y = F.floor_relative(x)
        >>> float(y[0, 2, 6]), float(y[0, 1, 4]), float(y.abs().sum() - 30)
        (30.0, 0.0, 0.0)
    """
    bins = check_blank_bins(blank_zero_doppler)
    x = check_tensor(x, "floor_relative expects dB RD maps (..., range, doppler)", min_ndim=2, finite=False)
    # Lower median (torch's): for an even Doppler count it is the lower of the two middle values.
    out = x - x.median(dim=-1, keepdim=True).values
    if bins:
        centre = x.shape[-1] // 2
        lo, hi = max(centre - bins, 0), min(centre + bins + 1, x.shape[-1])
        out[..., lo:hi] = 0.0
    if excise is not None:
        if excise.shape != x.shape[-2:] or excise.dtype != torch.bool:
            raise ConfigError(f"floor_relative: excise must be a bool mask of shape {tuple(x.shape[-2:])}, got "
                              f"{excise.dtype} {tuple(excise.shape)}")
        out = out.masked_fill(excise.to(out.device), 0.0)
    return out


def persistent_cells(maps_db: torch.Tensor, threshold_db: float = 3.0, blank_zero_doppler: int = 1) -> torch.Tensor:
    """Cells of an empty room's RD maps that stand persistently above their row's floor.

    The median over frames of :func:`floor_relative` maps: noise alone gives ~0 dB in every cell (its
    per-frame values scatter, their median over frames does not), so a cell whose median exceeds
    ``threshold_db`` carries something that is there in every frame -- a spur tone's line, a fan's
    Doppler lines, a phase-noise skirt's shoulder. Like a CFAR clutter map, these cells are then left
    out of every map (:func:`floor_relative`'s ``excise``), simulated and captured alike.

    Args:
        maps_db: ``(frames, range, doppler)`` dB maps of the empty room (RX combined), >= 3 frames.
        threshold_db: excess of the median over the row's floor that marks a cell.
        blank_zero_doppler: as :func:`floor_relative` (those cells are blanked anyway, not marked).

    Returns:
        A ``(range, doppler)`` bool mask.

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> g = torch.Generator().manual_seed(0)
        >>> maps = -100 + 10 * torch.log10(torch.empty(40, 16, 8).exponential_(generator=g))
        >>> maps[:, 5, 1] += 20.0   # a spur's line in every frame
        >>> F.persistent_cells(maps).nonzero().tolist()
        [[5, 1]]
    """
    x = check_tensor(maps_db, "persistent_cells expects dB maps (frames, range, doppler)", min_ndim=3, finite=False)
    if x.ndim != 3 or x.shape[0] < 3:
        raise ConfigError(f"persistent_cells needs (frames >= 3, range, doppler) maps, got {tuple(x.shape)}")
    med = floor_relative(x, blank_zero_doppler).median(dim=0).values
    return med > float(threshold_db)
