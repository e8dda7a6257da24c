"""What an empty-room capture calibrates: every fit on it, and the one record that holds them.

:func:`fit_record` fits a :class:`~radaraug.transforms.record_file.CalibrationRecord` (CalibratedDR's
floor and, on request, the twin profile, the noise fit and the persistent cells); :func:`load_record`
reads it back. The recipes' cached fits (:func:`cached_noise_fit`, :func:`cached_profile_fit`,
:func:`persistent_cells_of`) are refitted whenever a cache file is unreadable or of another format or
version. See ``docs/diagnosis.md``, "The calibration record".
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import torch

from radaraug._cache_key import cache_key
from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError, RadarAugError
from radaraug.files import atomic_write_json
from radaraug.sensor.profile import TwinProfile
from radaraug.transforms._motion import DEFAULT_THRESHOLD_DB
from radaraug.transforms.record_file import (
    NOISE_FIT_FORMAT,
    RECORD_FORMAT,
    RECORD_VERSION,
    CalibrationRecord,
    content_digest,
    load_record,
)

NOISE_FIT_VERSION = 2
"""The version :func:`cached_noise_fit` writes and reuses (2: thermal and ADC-side noise moved together)."""

#: Frames of the calibration capture read for the excision mask.
PERSISTENT_FRAMES = 64
#: dB over the row's floor at which a cell is persistent: the recipes' excision threshold, and what
#: ``radaraug fit-cdr`` / ``calibrate`` record, so that a record serves the excision without the capture.
PERSISTENT_THRESHOLD_DB = 3.0
#: dB over the frame's median chirp at which a chirp is another radar's burst: the recipes' interference
#: excision (``ImageSpec.excise_interference_db``), and the chain ``radaraug fit-cdr`` / ``calibrate`` fit on.
INTERFERENCE_THRESHOLD_DB = 6.0


def recipes_map_chain(interference_db: float | None = INTERFERENCE_THRESHOLD_DB) -> Any:
    """Raw frames -> per-RX dB maps as the recipes make them (interference excision, RD FFTs, dB)."""
    from radaraug.transforms.compose import RadarCompose
    from radaraug.transforms.spectral import InterferenceExcision, RangeDoppler, ToDecibels

    steps: list[Any] = [RangeDoppler(), ToDecibels()]
    if interference_db is not None:
        steps.insert(0, InterferenceExcision(float(interference_db)))
    return RadarCompose(steps)


def noise_fit_path(cache_dir: str | Path, scene: str, config: RadarConfig, target_db: float,
                   tracer_rays: int | None) -> Path:
    """``cache_dir/noise_fit-<key>.json`` of a noise fit (the key covers everything the fit reads)."""
    key = cache_key([NOISE_FIT_FORMAT, NOISE_FIT_VERSION, str(scene), config.to_dict(), round(float(target_db), 4),
                      tracer_rays])
    return Path(cache_dir) / f"noise_fit-{key}.json"


def cached_noise_fit(calibration: str, *, scene: str, config: RadarConfig, cache_dir: str | Path,
                     tracer_rays: int | None = None) -> dict[str, Any]:
    """The twin's noise fitted to ``calibration``'s floor, from ``cache_dir`` when fitted before.

    Args:
        calibration: the empty-room capture.
        scene: the training scene (built-in name or file).
        config: the radar config simulated (the capture's).
        cache_dir: where fits are cached.
        tracer_rays: SBR rays of the room trace (None: the tracer's default method).

    Returns:
        :func:`~radaraug.diagnosis.noise_fit.fit_noise_figure`'s dict plus ``calibration``,
        ``format`` and ``version``.
    """
    from radaraug.diagnosis.noise_fit import capture_noise_floor_db
    from radaraug.files import load_json

    target = capture_noise_floor_db(calibration)
    path = noise_fit_path(cache_dir, scene, config, target, tracer_rays)
    if path.is_file():
        try:
            fit = load_json(path, error=CalibrationError, what="noise fit")
            if isinstance(fit, dict) and fit.get("format") == NOISE_FIT_FORMAT and fit.get("version") == \
                    NOISE_FIT_VERSION and "noise_figure_dB" in fit:
                return fit
        except RadarAugError:
            pass  # unreadable or another writer's: fit again and replace it
    fit = _noise_fit(scene, config, target, tracer_rays)
    fit.update(calibration=str(calibration), format=NOISE_FIT_FORMAT, version=NOISE_FIT_VERSION)
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_json(path, fit, newline=False, indent=2)
    return fit


def cached_profile_fit(calibration: str, path: str | Path, *, max_frames: int,
                       progress: bool = False) -> TwinProfile:
    """The twin profile ``diagnose`` fits on ``calibration`` (no scene), from ``path`` when fitted before.

    ``path``'s key must cover the capture's content and ``max_frames``; a file that does not load as a
    profile is fitted again.
    """
    path = Path(path)
    if path.is_file():
        try:
            return TwinProfile.load(path)
        except CalibrationError:
            pass  # unreadable (e.g. written by another radaraug): fit again and replace it
    profile = _profile_fit(calibration, max_frames, progress)
    path.parent.mkdir(parents=True, exist_ok=True)
    profile.save(path)
    return profile


def persistent_cells_of(calibration: str, threshold_db: float, rd_db: Callable[[torch.Tensor], torch.Tensor],
                        frames: int = PERSISTENT_FRAMES) -> torch.Tensor:
    """The calibration capture's persistent lines as a ``(range, doppler)`` mask of its RD maps.

    Cells more than ``threshold_db`` above their row's floor in every one of the first ``frames`` frames
    of ``rd_db``'s maps (RX power-combined): a spur's line, a fan's Doppler lines. ``rd_db`` is the
    caller's map chain (the recipes': :func:`radaraug.training.pipeline.rd_db_chain`), so the mask lines
    up with its maps.

    Raises:
        ConfigError: fewer than 3 frames.
    """
    from radaraug.io import open_capture
    from radaraug.transforms import CombineRx
    from radaraug.transforms.functional import persistent_cells

    with open_capture(calibration) as cap:
        n = min(cap.num_frames, int(frames))
        if n < 3:
            raise ConfigError(f"calibration {calibration}: {n} frames; excising its persistent lines needs >= 3 "
                              "(record longer, or set data.image.excise_persistent_db: null)")
        maps = CombineRx("mean_power", db=True)(rd_db(cap.read(0, n))).squeeze(-3)
    return persistent_cells(maps, float(threshold_db))


def fit_record(
    capture: str | os.PathLike,
    *,
    floor: str = "normal",
    pipeline: Any = None,
    max_frames: int | None = None,
    motion_threshold_db: float = DEFAULT_THRESHOLD_DB,
    profile_frames: int | None = None,
    noise_scene: str | None = None,
    tracer_rays: int | None = None,
    persistent_db: float | None = None,
    progress: bool = False,
) -> CalibrationRecord:
    """Fit the calibration record of an empty-room capture: CalibratedDR's floor and, on request, the rest.

    Args:
        capture: the empty-room capture (radaraug ``.h5`` or Infineon recording folder).
        floor: CalibratedDR's floor distribution, ``"normal"`` or ``"empirical"``.
        pipeline: raw cube -> dB map chain of the floor and the persistent cells; default
            ``RangeDoppler() -> ToDecibels()`` (``fit-cdr`` and ``calibrate`` pass the recipes':
            :func:`recipes_map_chain`).
        max_frames: frames the floor is fitted on (default: all).
        motion_threshold_db: threshold of the motion check (warns ``MotionWarning``).
        profile_frames: also fit the twin profile (``diagnose`` without a scene) on this many frames.
        noise_scene: also fit the twin's noise to the capture's floor, simulating this scene.
        tracer_rays: SBR rays of the noise fit's room trace (None: the tracer's default method).
        persistent_db: also record the persistent cells at this threshold (:func:`persistent_cells_of`).
        progress: progress bars.

    Returns:
        The record (``file`` None until saved and read back), with the capture's name, content digest
        and frame count.

    Raises:
        CalibrationError, CaptureError: as the fits they come from.
    """
    from radaraug.transforms.dr import FLOORS
    from radaraug.transforms.floor_fit import floor_statistics

    if floor not in FLOORS:
        raise CalibrationError(f"fit_record: floor must be one of {FLOORS}, got {floor!r}")
    stats = floor_statistics(capture, pipeline=pipeline, max_frames=max_frames, motion_threshold_db=motion_threshold_db,
                             progress=progress)
    config = stats.pop("config")
    stats["quantiles_db"] = stats["quantiles_db"].tolist()  # float64 -> float -> float64 is exact: the same floor
    record = CalibrationRecord(cdr={**stats, "floor": floor}, config=config,
                               capture={"name": Path(capture).name, "sha256": content_digest(capture),
                                        "frames": stats["num_frames"]})
    if profile_frames is not None:
        record.profile = _profile_fit(capture, profile_frames, progress)
    if noise_scene is not None:
        from radaraug.diagnosis.noise_fit import capture_noise_floor_db

        if config is None:
            raise CalibrationError(f"{capture}: no radar config to simulate the noise fit with")
        record.noise_fit = _noise_fit(noise_scene, config, capture_noise_floor_db(capture), tracer_rays)
    if persistent_db is not None:
        chain = pipeline if pipeline is not None else recipes_map_chain(None)
        mask = persistent_cells_of(str(capture), persistent_db, chain)
        record.persistent_cells = {"threshold_db": float(persistent_db), "shape": list(mask.shape),
                                   "cells": mask.nonzero().tolist()}
    return record


def _noise_fit(scene: str, config: RadarConfig, target_db: float, tracer_rays: int | None) -> dict[str, Any]:
    from radaraug.diagnosis.noise_fit import fit_noise_figure
    from radaraug.scene.scene import Scene

    opts = {"method": "sbr", "rays": int(tracer_rays)} if tracer_rays is not None else None
    return fit_noise_figure(Scene.load(scene), config, target_db, tracer_options=opts)


def _profile_fit(capture: str | os.PathLike, max_frames: int, progress: bool) -> TwinProfile:
    from radaraug import diagnosis as cal_mod  # through the package, where tests replace diagnose

    return cal_mod.diagnose(str(capture), scene=None, max_frames=int(max_frames), progress=progress).profile


__all__ = ["NOISE_FIT_FORMAT", "NOISE_FIT_VERSION", "RECORD_FORMAT", "RECORD_VERSION", "CalibrationRecord",
           "cached_noise_fit", "cached_profile_fit", "fit_record", "load_record", "noise_fit_path",
           "persistent_cells_of"]
