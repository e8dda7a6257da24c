"""Calibrate the twin's noise level on an empty-room capture: one offset on both noise sources.

The fit moves the noise figure by ``d`` dB and the ADC-side RMS by ``10**(d/20)``, so the floor
follows ``d`` at any IF gain, and iterates on ``d`` until the empty twin's RD noise floor
(:func:`radaraug.io.summary.noise_floor_db`) equals the capture's. Why it matters for training:
``docs/diagnosis.md``, "The calibration record".
"""

from __future__ import annotations

import math
import os
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.views import rd_noise_floor_db
from radaraug.errors import CalibrationError
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS, DEFAULT_NOISE_FIGURE_DB
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.seeding import Stream, item_generator
from radaraug.sim.twin import DigitalTwin

NOISE_FIGURE_LIMITS_DB = (0.0, 45.0)
"""Fitted noise figures are kept in this range (a floor beyond it is not thermal noise)."""


def capture_noise_floor_db(capture: Any, max_frames: int = 64) -> float:
    """The RD noise floor (dBFS) of a capture path or open reader."""
    from radaraug.io import open_capture

    if isinstance(capture, (str, os.PathLike)):
        with open_capture(capture) as reader:
            return capture_noise_floor_db(reader, max_frames)
    n = min(capture.num_frames, max_frames)
    return rd_noise_floor_db(capture.read(0, n), f"{capture.path}: ")


@torch.no_grad()
def fit_noise_figure(
    scene: Scene,
    config: RadarConfig,
    target_floor_db: float,
    *,
    frames: int = 8,
    iterations: int = 3,
    tol_db: float = 0.1,
    seed: int = 0,
    tracer_options: dict[str, Any] | None = None,
    twin: DigitalTwin | None = None,
) -> dict[str, Any]:
    """The noise offset that puts the empty twin's RD noise floor at ``target_floor_db``.

    Args:
        scene: the (empty) training scene; its people are ignored.
        config: the radar config to simulate (the capture's).
        target_floor_db: the capture's floor (:func:`capture_noise_floor_db`).
        frames: empty frames simulated per iteration.
        iterations: most fixed-point steps.
        tol_db: stop when the floors agree this well.
        seed: noise seed.
        tracer_options: the room trace's options (e.g. ``{"method": "sbr", "rays": 128}``).
        twin: an existing twin of ``scene`` and ``config`` whose room trace to reuse.

    Returns:
        ``{"noise_figure_dB", "adc_noise_rms_counts", "noise_offset_dB", "target_floor_db",
        "twin_floor_db", "history"}`` (``history``: ``(noise_figure_dB, floor_db)`` per step); build the
        receiver with :func:`noise_fit_receiver`.

    Raises:
        CalibrationError: the floor does not move with the noise figure, or the fit leaves
            :data:`NOISE_FIGURE_LIMITS_DB`.
    """
    if twin is None:
        twin = DigitalTwin(scene, config=config, tracer_options=tracer_options)
    static = twin.static_signal()
    times = twin.frame_times(range(frames))
    nf = DEFAULT_NOISE_FIGURE_DB
    history: list[tuple[float, float]] = []
    for step in range(iterations):
        rx = FMCWReceiver(config, noise_figure_dB=nf,
                          adc_noise_rms_counts=_adc_rms(config, nf)).to(twin.device)
        gens = [item_generator(seed, k, stream=Stream.NOISE_FIT, device=twin.device) for k in range(frames)]
        paths = twin.paths([], times)
        x = torch.stack([rx(paths.select(k), generator=g, frame_start_s=float(times[k]),
                            static_signal=static) for k, g in enumerate(gens)])
        floor = rd_noise_floor_db(x)
        history.append((nf, floor))
        diff = target_floor_db - floor
        if abs(diff) <= tol_db:
            break
        if step > 0:
            (nf0, f0), (nf1, f1) = history[-2], history[-1]
            slope = (f1 - f0) / (nf1 - nf0) if nf1 != nf0 else 0.0
            if slope < 0.3:
                raise CalibrationError(
                    f"the twin's noise floor hardly moves with the noise figure ({f0:.1f} -> {f1:.1f} dB for "
                    f"NF {nf0:.1f} -> {nf1:.1f} dB): quantization or another stage dominates")
            diff /= slope
        nf = nf + diff
        if not NOISE_FIGURE_LIMITS_DB[0] <= nf <= NOISE_FIGURE_LIMITS_DB[1] or not math.isfinite(nf):
            raise CalibrationError(
                f"fitting the noise floor {target_floor_db:.1f} dB needs a noise figure of {nf:.1f} dB, outside "
                f"{list(NOISE_FIGURE_LIMITS_DB)}: the capture's floor is not the twin's thermal noise")
    best_nf, best_floor = min(history, key=lambda h: abs(h[1] - target_floor_db))
    return {"noise_figure_dB": round(best_nf, 3), "adc_noise_rms_counts": round(_adc_rms(config, best_nf), 4),
            "noise_offset_dB": round(best_nf - DEFAULT_NOISE_FIGURE_DB, 3),
            "target_floor_db": round(target_floor_db, 3),
            "twin_floor_db": round(best_floor, 3), "history": [[round(a, 3), round(b, 3)] for a, b in history]}


def _adc_rms(config: RadarConfig, noise_figure_dB: float) -> float:
    """ADC-side noise RMS that goes with ``noise_figure_dB`` (both moved by the same offset)."""
    scale = (2**config.adc_bits - 1) / 4095
    return ADC_NOISE_RMS_COUNTS * scale * 10 ** ((noise_figure_dB - DEFAULT_NOISE_FIGURE_DB) / 20)


def noise_fit_receiver(config: RadarConfig, fit: dict[str, Any]) -> FMCWReceiver:
    """The default receiver with the noise levels of a :func:`fit_noise_figure` result."""
    adc = fit.get("adc_noise_rms_counts")
    return FMCWReceiver(config, noise_figure_dB=float(fit["noise_figure_dB"]),
                        adc_noise_rms_counts=None if adc is None else float(adc))


__all__ = ["NOISE_FIGURE_LIMITS_DB", "capture_noise_floor_db", "fit_noise_figure", "noise_fit_receiver"]
