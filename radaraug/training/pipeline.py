"""The paper's processing chain, split where the simulate-once cache sits.

:func:`rd_db_chain` (raw frames to per-RX dB maps, cached), the method's DR (training only) and
:func:`image_chain` (every split; captures skip the DR). The chain is drawn in docs/training.md.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import torch
from torch import nn

from radaraug.diagnosis.record import recipes_map_chain
from radaraug.errors import ConfigError
from radaraug.transforms import (
    ClipNormalize,
    Colormap,
    CombineRx,
    FloorRelative,
    MaxResize,
    RadarCompose,
    Resize,
)
from radaraug.transforms.functional._floor import floor_relative, kept_cells

#: Network input representations: the paper's clipped dBFS map, or each range row referenced to
#: its own Doppler median with zero Doppler blanked (docs/training.md, "Representations").
REPRESENTATIONS = ("paper", "floor_relative")
#: How a map shrinks to the network's size: the paper's bilinear resize of the colour image, or the max of
#: the cells each pixel covers, taken on the levels before the colour map (docs/training.md, "Representations").
RESAMPLES = ("bilinear", "max")


def is_calibration_json(calibration: str | os.PathLike) -> bool:
    """True when ``calibration`` names a saved CalibratedDR (``.json``), False for a capture."""
    return str(calibration).lower().endswith(".json")


def rd_db_chain(interference_db: float | None = None) -> RadarCompose:
    """Raw frames ``(..., rx, chirps, samples)`` -> per-RX RD dB maps ``(..., rx, range, doppler)``.

    Args:
        interference_db: replace the chirps another radar's burst hit first
            (:class:`~radaraug.transforms.InterferenceExcision` at this threshold); None: no excision.
    """
    return recipes_map_chain(interference_db)


def check_resample(resample: str) -> str:
    """``resample`` if it is one of :data:`RESAMPLES` (ConfigError otherwise)."""
    if resample not in RESAMPLES:
        raise ConfigError(f"resample must be one of {RESAMPLES}, got {resample!r}")
    return resample


def check_representation(representation: str) -> str:
    """``representation`` if it is one of :data:`REPRESENTATIONS` (ConfigError otherwise)."""
    if representation not in REPRESENTATIONS:
        raise ConfigError(f"representation must be one of {REPRESENTATIONS}, got {representation!r}")
    return representation


def level_chain(representation: str = "paper", excise: torch.Tensor | None = None,
                blank_zero_doppler: int = 1) -> nn.Sequential:
    """Per-RX dB maps -> the one-channel dB map that is clipped: RX combination (+ floor referencing).

    ``"floor_relative"`` adds :class:`~radaraug.transforms.FloorRelative` with ``blank_zero_doppler`` and ``excise``.
    """
    steps: list[nn.Module] = [CombineRx("mean_power", db=True)]
    if check_representation(representation) == "floor_relative":
        steps.append(FloorRelative(blank_zero_doppler=blank_zero_doppler, excise=excise))
    return nn.Sequential(*steps)


def noise_texture_db(rx: int) -> float:
    """Std (dB) of a noise-only cell of a floor-relative map: ``10 log10`` of a chi-square of ``2 rx`` dof.

    The mean power over ``rx`` receivers of complex-Gaussian noise is Gamma(``rx``) distributed at any level,
    so its dB spread, ``10 / ln 10 * sqrt(trigamma(rx))``, is the same for every floor (5.57 dB for one
    receiver, 2.73 dB for three): what a floor-relative map shows of a floor, whatever its level.
    """
    if rx < 1:
        raise ConfigError(f"noise_texture_db needs rx >= 1, got {rx}")
    trigamma = math.pi ** 2 / 6 - sum(1.0 / j ** 2 for j in range(1, rx))
    return 10 / math.log(10) * math.sqrt(trigamma)


@torch.no_grad()
def floor_texture(db_maps: torch.Tensor, excise: torch.Tensor | None = None,
                  blank_zero_doppler: int = 1) -> dict[str, torch.Tensor]:
    """Per frame of per-RX dB maps ``(N, rx, range, doppler)``, what the floor looks like before and after referencing.

    Over the cells off the blanked zero Doppler and outside ``excise``: ``level_db``, the RX-combined map's
    median (the absolute floor a calibration sets); ``texture_std_db``, the floor-relative cells' spread (for
    noise alone :func:`noise_texture_db`); ``peak_db``, the largest floor-relative cell (what a person adds
    over its row's floor); ``row_spread_db``, the std over range rows of their medians (how the floor varies
    along range). Each ``(N,)``. docs/training.md ("CDR's floor once the map is floor-relative") uses them.
    """
    absolute = level_chain("paper")(db_maps.float()).squeeze(-3)
    relative = floor_relative(absolute, blank_zero_doppler, excise)  # the floor-relative level chain, RX combined once
    rows, cols = absolute.shape[-2:]
    keep = kept_cells(rows, cols, blank_zero_doppler, excise, device=absolute.device)
    a, r = absolute[:, keep], relative[:, keep]
    return {"level_db": a.median(dim=1).values, "texture_std_db": r.std(dim=1), "peak_db": r.max(dim=1).values,
            "row_spread_db": absolute.median(dim=-1).values.std(dim=-1)}


def image_chain(vmin: float, vmax: float, size: Sequence[int] | None = None,
                representation: str = "paper", excise: torch.Tensor | None = None,
                blank_zero_doppler: int = 1, resample: str = "bilinear") -> nn.Sequential:
    """Per-RX dB maps -> ``(3, H, W)`` viridis images in [0, 1] (the network input; levels: :func:`level_chain`).

    ``resample``: ``"bilinear"`` resizes the colour image (the paper's), ``"max"`` shrinks the clipped levels
    to ``size`` by the max of each pixel's cells before the colour map (:class:`~radaraug.transforms.MaxResize`).
    """
    check_resample(resample)
    if size is not None and len(size) != 2:
        raise ConfigError(f"image size must be [H, W], got {list(size)}")
    steps: list[nn.Module] = [*level_chain(representation, excise, blank_zero_doppler), ClipNormalize(vmin, vmax)]
    if size is not None and resample == "max":
        steps.append(MaxResize((int(size[0]), int(size[1]))))
    steps.append(Colormap("viridis"))
    if size is not None and resample == "bilinear":
        steps.append(Resize((int(size[0]), int(size[1]))))
    return nn.Sequential(*steps)


@torch.no_grad()
def estimate_clip_range(
    db_maps: torch.Tensor, dr: nn.Module | None = None, *, percentiles: tuple[float, float] = (1.0, 99.9),
    representation: str = "paper", excise: torch.Tensor | None = None, blank_zero_doppler: int = 1,
) -> tuple[float, float]:
    """``[vmin, vmax]``: percentiles of simulated per-RX dB maps ``(N, rx, range, doppler)``.

    Taken after ``dr`` and :func:`level_chain`, so that the clip covers what the network sees.
    """
    x = db_maps.float()
    if dr is not None:
        x = dr(x)
    x = level_chain(representation, excise, blank_zero_doppler)(x).flatten()
    if x.numel() > 2_000_000:  # quantile() refuses very large inputs; a strided subsample is enough
        x = x[:: math.ceil(x.numel() / 2_000_000)]
    lo, hi = torch.quantile(x.double(), torch.tensor([percentiles[0] / 100, percentiles[1] / 100], dtype=torch.float64))
    vmin, vmax = float(lo), float(hi)
    if not vmax > vmin:
        vmax = vmin + 1.0
    return round(vmin, 2), round(vmax, 2)
