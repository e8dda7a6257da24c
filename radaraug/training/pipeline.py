"""The paper's processing chain, split where the simulate-once cache sits.

:func:`rd_db_chain` (raw frames to per-RX dB maps, cached), :func:`make_dr` (training only) and
:func:`image_chain` (every split; captures skip the DR). The chain is drawn in docs/training.md.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import Any

import torch
from torch import nn

from radaraug.errors import ConfigError
from radaraug.transforms import (
    CalibratedDR,
    ClipNormalize,
    Colormap,
    CombineRx,
    FloorRelative,
    RadarCompose,
    RandomDR,
    RangeDoppler,
    Resize,
    ToDecibels,
)

#: Class names per task; the label of a simulated item is its people count.
TASKS: dict[str, tuple[str, ...]] = {"occupancy": ("empty", "occupied"), "counting": ("0", "1", "2")}
#: Noise-floor randomization methods: the paper's three, and CDR on a twin whose receiver carries
#: the twin profile fitted (``radaraug diagnose``) on the same empty-room calibration capture.
METHODS = ("rt", "randomdr", "cdr", "cdr_profile")
#: Network input representations: the paper's clipped dBFS map, or each range row referenced to
#: its own Doppler median with zero Doppler blanked (docs/training.md, "Representations").
REPRESENTATIONS = ("paper", "floor_relative")
#: CalibratedDR floors a run can ask for: CalibratedDR's own (``normal``: the paper's, ``empirical``:
#: the capture's measured distribution) and ``matched``: the empirical clamp distribution
#: deconvolved against the twin's own empty-room floor, so that ``max(S, N)`` has the capture's
#: (:func:`radaraug.transforms.floor_fit.matched_floor_quantiles`).
CDR_FLOORS = ("normal", "empirical", "matched")
#: Methods whose DR is CalibratedDR (they need a calibration).
CDR_METHODS = ("cdr", "cdr_profile")
#: Methods whose twin receiver is the twin profile fitted on the calibration capture.
PROFILE_METHODS = ("cdr_profile",)


def check_task(task: str) -> tuple[str, ...]:
    """The class names of ``task`` (ConfigError for an unknown task)."""
    if task not in TASKS:
        raise ConfigError(f"task must be one of {sorted(TASKS)}, got {task!r}")
    return TASKS[task]


def label_of(count: int | torch.Tensor, task: str) -> Any:
    """The class label of a people count for ``task`` (occupancy: count > 0)."""
    if task == "occupancy":
        return (count > 0).long() if isinstance(count, torch.Tensor) else int(count > 0)
    return count


def is_calibration_json(calibration: str | os.PathLike) -> bool:
    """True when ``calibration`` names a saved CalibratedDR (``.json``), False for a capture."""
    return str(calibration).lower().endswith(".json")


def rd_db_chain() -> RadarCompose:
    """Raw frames ``(..., rx, chirps, samples)`` -> per-RX RD dB maps ``(..., rx, range, doppler)``."""
    return RadarCompose([RangeDoppler(), ToDecibels()])


def make_dr(
    method: str,
    *,
    calibration: str | os.PathLike | CalibratedDR | None = None,
    seed: int | None = None,
    randomdr_mean_db: Sequence[float] | None = None,
    randomdr_std_db: Sequence[float] | None = None,
    cdr_floor: str | None = None,
) -> nn.Module | None:
    """The training-time noise-floor randomization of ``method`` (None for ``rt``).

    Args:
        method: ``rt`` (no randomization), ``randomdr``, ``cdr`` or ``cdr_profile`` (``cdr``'s DR).
        calibration: for the CDR methods: a fitted :class:`CalibratedDR`, its JSON, or an empty-room capture.
        seed: seed of the transform's own generator (per-sample draws).
        randomdr_mean_db: RandomDR's range of the floor mean in dB (None: the default, docs/transforms.md).
        randomdr_std_db: RandomDR's range of the floor standard deviation in dB (None: the default).
        cdr_floor: ``"normal"``, ``"empirical"`` or ``"matched"`` (empirical here; the data module then
            matches its quantiles to the twin's floor); None: the calibration's own.
    """
    if method not in METHODS:
        raise ConfigError(f"method must be one of {METHODS}, got {method!r}")
    if method == "rt":
        return None
    if method == "randomdr":
        ranges = {"mean_db": randomdr_mean_db, "std_db": randomdr_std_db}
        kw: dict[str, Any] = {k: tuple(v) for k, v in ranges.items() if v is not None}
        return RandomDR(seed=seed, **kw)
    if calibration is None:
        raise ConfigError(f"method {method!r} needs a calibration: an empty-room capture or a CalibratedDR JSON")
    if isinstance(calibration, CalibratedDR):
        fitted = calibration
    elif is_calibration_json(calibration):
        fitted = CalibratedDR.load(calibration)
    else:
        fitted = CalibratedDR.fit(calibration, progress=False)
    return fitted.replace(floor=("empirical" if cdr_floor == "matched" else cdr_floor) or fitted.floor, seed=seed)


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


def image_chain(vmin: float, vmax: float, size: Sequence[int] | None = None,
                representation: str = "paper", excise: torch.Tensor | None = None,
                blank_zero_doppler: int = 1) -> nn.Sequential:
    """Per-RX dB maps -> ``(3, H, W)`` viridis images in [0, 1] (the network input; levels: :func:`level_chain`)."""
    steps: list[nn.Module] = [*level_chain(representation, excise, blank_zero_doppler), ClipNormalize(vmin, vmax),
                              Colormap("viridis")]
    if size is not None:
        if len(size) != 2:
            raise ConfigError(f"image size must be [H, W], got {list(size)}")
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
