"""Floor-relative RD maps: a network input that does not key on absolute levels (docs/transforms.md)."""

from __future__ import annotations

from typing import Any

import torch

from radaraug.transforms import functional as F
from radaraug.transforms.base import Params, RadarTransform
from radaraug.transforms.functional._floor import check_blank_bins


class FloorRelative(RadarTransform):
    """Each range row of a dB RD map minus its median over Doppler; zero Doppler ± ``bins`` set to 0 dB.

    Deterministic; dB maps ``(..., range, doppler)`` with a centred Doppler axis in and out.

    Args:
        blank_zero_doppler: bins on each side of zero Doppler set to 0 dB; 0 keeps the static returns.
        excise: optional bool ``(range, doppler)`` mask of cells also set to 0 dB (an empty room's
            persistent lines: :func:`~radaraug.transforms.functional.persistent_cells`).
    """

    event_ndim = 2
    input_layout = "dB RD maps (..., range, doppler)"

    def __init__(self, blank_zero_doppler: int = 1, excise: torch.Tensor | None = None) -> None:
        super().__init__()
        self.blank_zero_doppler = check_blank_bins(blank_zero_doppler)
        self.excise: torch.Tensor | None
        self.register_buffer("excise", None if excise is None else torch.as_tensor(excise, dtype=torch.bool))

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        """The row-referenced, zero-Doppler-blanked (and excised) map."""
        return F.floor_relative(x, self.blank_zero_doppler, self.excise)

    def extra_spec(self) -> dict[str, Any]:
        """The blanked bins on each side of zero Doppler (and the number of excised cells)."""
        spec: dict[str, Any] = {"blank_zero_doppler": self.blank_zero_doppler}
        if self.excise is not None:
            spec["excised_cells"] = int(self.excise.sum())
        return spec
