"""What an empty-room capture calibrates, fitted in one place and cached in tagged, versioned files.

The recipes calibrate the training twin on the user's empty-room capture in three ways, each a fit
that belongs to the calibration layer, not to the Lightning DataModule that asks for it:

* :func:`cached_noise_fit`: the twin's noise figure (and ADC-side noise, moved together) whose
  empty-room floor equals the capture's (:func:`radaraug.sim.noise_fit.fit_noise_figure`);
* :func:`cached_profile_fit`: the twin profile ``radaraug diagnose`` fits on the capture without a
  scene (``cdr_profile``, ``catalog_priors: calibration``);
* :func:`persistent_cells_of`: the cells of the capture's range-Doppler maps that stand above their
  row in every frame (spur and fan lines), excised from every training and test map.

The cached files carry ``{"format", "version"}`` and are read through
:func:`radaraug.safe_read.load_json`; a file of another format or version, or one that cannot be
read, is fitted again and replaced (never trusted). Keys cover what the fit depends on, so a cache
shared by runs is safe.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import torch

from radaraug._cache_key import cache_key
from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError, RadarAugError
from radaraug.io.atomic import atomic_write_json
from radaraug.sensor.profile import TwinProfile

NOISE_FIT_FORMAT = "radaraug-noise-fit"
NOISE_FIT_VERSION = 2
"""2: the fit moves thermal and ADC-side noise together (version 1 moved the noise figure alone)."""

#: Frames of the calibration capture read for the excision mask.
PERSISTENT_FRAMES = 64


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
        :func:`~radaraug.sim.noise_fit.fit_noise_figure`'s dict plus ``calibration``, ``format`` and
        ``version``.
    """
    from radaraug.safe_read import load_json
    from radaraug.scene.scene import Scene
    from radaraug.sim.noise_fit import capture_noise_floor_db, fit_noise_figure

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
    opts = {"method": "sbr", "rays": int(tracer_rays)} if tracer_rays is not None else None
    fit = fit_noise_figure(Scene.load(scene), config, target, tracer_options=opts)
    fit.update(calibration=str(calibration), format=NOISE_FIT_FORMAT, version=NOISE_FIT_VERSION)
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_json(path, fit, newline=False, indent=2)
    return fit


def cached_profile_fit(calibration: str, path: str | Path, *, max_frames: int,
                       progress: bool = False) -> TwinProfile:
    """The twin profile ``diagnose`` fits on ``calibration`` (no scene), from ``path`` when fitted before.

    ``path`` is the caller's cache file (its key must cover the capture's content and ``max_frames``);
    a file that does not load as a profile is fitted again and replaced.
    """
    from radaraug import calibration as cal_mod

    path = Path(path)
    if path.is_file():
        try:
            return TwinProfile.load(path)
        except CalibrationError:
            pass  # unreadable (e.g. written by another radaraug): fit again and replace it
    diag = cal_mod.diagnose(str(calibration), scene=None, max_frames=int(max_frames), progress=progress)
    path.parent.mkdir(parents=True, exist_ok=True)
    diag.profile.save(path)
    return diag.profile


def persistent_cells_of(calibration: str, threshold_db: float, rd_db: Callable[[torch.Tensor], torch.Tensor],
                        frames: int = PERSISTENT_FRAMES) -> torch.Tensor:
    """The calibration capture's persistent lines as a ``(range, doppler)`` mask of its RD maps.

    Cells that stand more than ``threshold_db`` above their row's floor in every one of the first
    ``frames`` frames (``rd_db``'s per-RX dB maps, RX power-combined): what every frame of the empty
    room shows (a spur's line, a fan's Doppler lines). ``rd_db`` is the caller's map chain (the
    recipes': :func:`radaraug.training.pipeline.rd_db_chain`), so the mask lines up with its maps.

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
                              "(record longer, or set data.excise_persistent_db: null)")
        maps = CombineRx("mean_power", db=True)(rd_db(cap.read(0, n))).squeeze(-3)
    return persistent_cells(maps, float(threshold_db))


__all__ = ["NOISE_FIT_FORMAT", "NOISE_FIT_VERSION", "cached_noise_fit", "cached_profile_fit", "noise_fit_path",
           "persistent_cells_of"]
