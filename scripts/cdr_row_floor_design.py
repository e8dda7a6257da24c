"""A test of the CDR account's prediction: a floor calibrated row by row does what RT does, no better.

docs/training.md ("CDR's floor once the map is floor-relative") measured that the floor-relative map keeps
only a floor's spread within each range row, that the twin's noise already has the capture's, and that the
paper's pooled fit adds spread. If that is the whole story, a CDR whose clamp draws each cell from the
calibration capture's own values *in that range row* (per RX; off zero Doppler, outside the excised
persistent cells) gives the networks what the noisy twin gives them: the prediction is that it scores like
RT on held-out worlds, and above the paper's CDR. This script runs RT and that row-wise CDR (on the quiet
twin, as the recipes' CDR) on the design suite (validation) through ``reproduce`` with the ``cdr`` recipe's
method swapped; score it with ``scripts/design_errors.py --method``.

    python scripts/cdr_row_floor_design.py -o RUN
    python scripts/design_errors.py RUN --method cdr -o row_cdr.json
    python scripts/design_errors.py RUN --method rt -o rt.json
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
from typing import Any

import torch
from torch import nn

import radaraug.training.reproduce as R
from radaraug.diagnosis.record import persistent_cells_of
from radaraug.io import open_capture
from radaraug.training.methods import Method
from radaraug.training.pipeline import rd_db_chain
from radaraug.transforms.functional._floor import zero_doppler_bins

QUANTILES = 256  # points of each (RX, range row) quantile function
INTERFERENCE_DB = 6.0  # the recipes' interference excision (ImageSpec.excise_interference_db)
PERSISTENT_DB = 3.0  # the recipes' persistent-line threshold (ImageSpec.excise_persistent_db)


class RowFloor(nn.Module):
    """``max(S, N)``, ``N`` drawn per cell from the calibration's values in the same RX and range row."""

    floor = "row"

    def __init__(self, quantiles_db: torch.Tensor, seed: int) -> None:
        super().__init__()
        self.register_buffer("quantiles_db", quantiles_db.float())  # (rx, range, QUANTILES)
        self.generator = torch.Generator().manual_seed(int(seed))

    @classmethod
    def fit(cls, capture: str, seed: int, blank: int = 2) -> RowFloor:
        """Quantiles of each (RX, row)'s dB values over the capture's frames, off zero Doppler +-``blank``."""
        chain = rd_db_chain(INTERFERENCE_DB)
        with open_capture(capture) as cap:
            maps = chain(cap.read()).double()  # (F, rx, range, doppler)
        keep = torch.ones(maps.shape[-2:], dtype=torch.bool)
        keep[:, zero_doppler_bins(maps.shape[-1], blank)] = False
        kept = keep & ~persistent_cells_of(capture, PERSISTENT_DB, chain)
        probs = torch.linspace(0, 1, QUANTILES, dtype=torch.float64)
        q = torch.empty(maps.shape[1], maps.shape[2], QUANTILES, dtype=torch.float64)
        for r in range(maps.shape[2]):
            cells = kept[r] if kept[r].any() else keep[r]  # a row whose cells are all lines: its plain cells
            values = maps[:, :, r, cells].transpose(0, 1).reshape(maps.shape[1], -1)  # (rx, frames x cells)
            q[:, r] = torch.quantile(values, probs, dim=1).T
        return cls(q, seed)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        """Per-RX dB maps ``(B, rx, range, doppler)`` with each cell clamped from below by a draw."""
        u = torch.rand(x.shape, generator=self.generator, dtype=torch.float64)
        idx = (u * (QUANTILES - 1)).round().long().to(x.device)
        q = self.quantiles_db.to(x.device)[None].expand(x.shape[0], -1, -1, -1)  # (B, rx, range, K)
        return torch.maximum(x, torch.gather(q, -1, idx).to(x.dtype))


class RowCDR(Method):
    """CDR with :class:`RowFloor` on the quiet twin (the recipes' CDR twin)."""

    name = "cdr"
    needs_calibration = True

    def __init__(self, twin_noise_offset_db: float | None = -15.0, test_dr: bool = False) -> None:
        super().__init__(test_dr)
        self.twin_noise_offset_db = twin_noise_offset_db

    def dr(self, calibration: Any, seed: int) -> nn.Module:
        """The row-wise floor of the calibration capture."""
        return RowFloor.fit(str(calibration), seed)


def main() -> None:
    """Run RT and the row-wise CDR on the design suite."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", type=Path, required=True)
    ap.add_argument("--worlds", type=int, default=8)
    ap.add_argument("--seeds", type=int, default=3)
    args = ap.parse_args()
    original = R.run_recipe

    def run_recipe(task: str, method: str, settings: Any, ablation: str | None = None) -> dict[str, Any]:
        cfg = original(task, method, settings, ablation)
        if method == "cdr":
            cfg["data"]["method"] = {"class_path": f"{__name__}.RowCDR", "init_args": {"twin_noise_offset_db": -15.0}}
        return cfg

    R.run_recipe = run_recipe
    settings = R.ReproduceSettings.quick()
    rep = R.reproduce(args.output, quick=True, seeds=args.seeds, methods=["rt", "cdr"], test_sets=("design",),
                      worlds=args.worlds, ablation=False, progress=True,
                      settings=replace(settings, keep_classifiers=False))
    print("done", rep["wall_seconds"])


if __name__ == "__main__":
    main()
