"""People's level against a real capture: the signal side of the twin, as the noise side was fitted.

Empty-room floors pin the noise, not the signal gain. :func:`fit_people_level` compares a moving
person's MTI range-Doppler peak in a capture with the twin's walkers crossing the same ranges, at
matched range bin (the IF high-pass and ``R^-4`` both depend on range). Method and numbers for the
public recordings: ``docs/receiver.md``, "The signal side".
"""

from __future__ import annotations

import math
import os
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.views import rd_noise_floor_db
from radaraug.errors import CalibrationError
from radaraug.transforms import RangeDoppler, ToDecibels
from radaraug.units import DB_CONVENTION

WALK_SPEEDS_M_S = (0.6, 1.0, 1.4)
"""Walking speeds of the twin's walkers (slow indoor walk to normal pace)."""
WALK_OFFSETS_M = (0.0, 0.3)
"""Lateral offsets of the walks from the boresight (a person near the axis, not exactly on it)."""


@dataclass(frozen=True)
class PeopleLevelFit:
    """Capture-minus-twin level of a moving person at matched range (dB), with what it rests on.

    Attributes:
        offset_dB: median over the capture's moving frames of (frame peak - twin's median peak in the
            same range bin). Positive: the real person is stronger than the twin's walker.
        spread_dB: half the interquartile range of those differences.
        ranges_m: centres of the range bins used (both sides have frames there).
        capture_dBFS, twin_dBFS: per range bin, the capture's and the twin's median MTI peak.
        capture_frames: capture frames used (moving target in a shared range bin).
        twin_frames: twin frames simulated.
        capture_floor_dBFS, twin_floor_dBFS: RD noise floors (no MTI) at the same config.
        rcs_scale_dB: the people RCS scale the twin was simulated with.
        db_convention: :data:`radaraug.units.DB_CONVENTION`.
    """

    offset_dB: float
    spread_dB: float
    ranges_m: tuple[float, ...]
    capture_dBFS: tuple[float, ...]
    twin_dBFS: tuple[float, ...]
    capture_frames: int
    twin_frames: int
    capture_floor_dBFS: float
    twin_floor_dBFS: float
    rcs_scale_dB: float = 0.0
    db_convention: str = DB_CONVENTION

    def to_dict(self) -> dict[str, Any]:
        """JSON-able dict (numbers rounded to 0.01 dB / 1 mm)."""
        d = asdict(self)
        for k, v in d.items():
            if isinstance(v, float):
                d[k] = round(v, 2)
            elif isinstance(v, tuple):
                d[k] = [round(x, 3 if k == "ranges_m" else 2) for x in v]
        return d


@torch.no_grad()
def mti_peaks(frames: torch.Tensor, min_range_bin: int = 2) -> tuple[np.ndarray, np.ndarray, float]:
    """Per frame, the strongest MTI range-Doppler cell of the first RX, and the RD noise floor.

    Args:
        frames: raw frames ``(F, rx, chirps, samples)`` in SDK floats.
        min_range_bin: range bins below it are left out (the TX->RX leakage's residue).

    Returns:
        (peak dBFS ``(F,)``, its range bin ``(F,)``, noise floor dBFS of the maps without MTI).
    """
    if frames.ndim != 4:
        raise CalibrationError(f"people level: need frames (F, rx, chirps, samples), got shape {tuple(frames.shape)}")
    mti = ToDecibels()(RangeDoppler(static_clutter=True)(frames))[:, 0, min_range_bin:]  # (F, range, doppler)
    floor = rd_noise_floor_db(frames, "people level: ")
    flat = mti.flatten(1).max(dim=1)
    bins = flat.indices.div(mti.shape[-1], rounding_mode="floor") + min_range_bin
    return flat.values.double().numpy(), bins.numpy(), float(floor)


@torch.no_grad()
def twin_walks(
    config: RadarConfig,
    ranges_m: tuple[float, float],
    *,
    scene: Any = "corridor",
    rcs_scale_dB: float = 0.0,
    seed: int = 0,
) -> torch.Tensor:
    """Twin frames ``(F, rx, chirps, samples)`` of single walkers crossing ``ranges_m`` at ``config``.

    One walk per speed (:data:`WALK_SPEEDS_M_S`), direction and lateral offset (:data:`WALK_OFFSETS_M`)
    along the boresight in ``scene`` (a scene, a scene file or a built-in name), frames about one range
    bin apart; ``rcs_scale_dB`` scales the walker's paths by ``10**(dB/20)``.
    """
    from radaraug.scene.people import Walker
    from radaraug.scene.scene import Scene
    from radaraug.sim.randomization import ItemDraw
    from radaraug.sim.twin import DigitalTwin

    scene = Scene.load(scene)
    twin = DigitalTwin(scene, config=config)
    pos = scene.radar.position.double()
    axis = scene.radar.rotation.double()[:, 2].clone()
    axis[2] = 0.0
    if float(axis.norm()) < 1e-6:
        raise CalibrationError("people level: the scene's radar looks straight up or down (no horizontal walk)")
    axis = axis / axis.norm()
    side = torch.stack([-axis[1], axis[0], axis.new_zeros(())])
    heading = math.atan2(float(axis[1]), float(axis[0]))
    lo, hi = float(ranges_m[0]), float(ranges_m[1])
    length = hi - lo + 0.6  # start a little outside the span so the walker is in stride inside it
    n = max(4, math.ceil(length / config.range_resolution_m) + 1)
    draw = None if rcs_scale_dB == 0 else ItemDraw(
        variant=0, system_gain_offset_dB=0.0, noise_figure_offset_dB=0.0, rcs_scale_dB=(float(rcs_scale_dB),))
    g = torch.Generator().manual_seed(seed)
    out = []
    for speed in WALK_SPEEDS_M_S:
        for toward in (True, False):
            for offset in WALK_OFFSETS_M:
                r0 = hi + 0.4 if toward else lo - 0.2
                start = pos + axis * r0 + side * offset
                walker = Walker(speed_m_s=speed, start=(float(start[0]), float(start[1])),
                                heading_rad=heading + (math.pi if toward else 0.0),
                                phase=float(torch.rand((), generator=g)))
                times = torch.linspace(0.0, length / speed, n, dtype=torch.float64)
                out.append(twin.simulate([walker], times, generators=g, draw=draw))
    return torch.cat(out)


def _frames_and_config(capture: Any, config: RadarConfig | None, max_frames: int | None,
                       what: str) -> tuple[torch.Tensor, RadarConfig, str]:
    if isinstance(capture, torch.Tensor):
        if config is None:
            raise CalibrationError(f"people level: {what} is a tensor; give its config")
        return capture, config, what
    from radaraug.io import open_capture

    if isinstance(capture, (str, os.PathLike)):
        with open_capture(capture) as reader:
            return _frames_and_config(reader, config, max_frames, what)
    if not (hasattr(capture, "read") and hasattr(capture, "config")):
        raise CalibrationError(f"people level: {what} must be a path, a capture reader or a tensor, "
                               f"got {type(capture).__name__}")
    n = capture.num_frames if max_frames is None else min(int(max_frames), capture.num_frames)
    name = os.path.basename(str(getattr(capture, "path", what)))
    return capture.read(0, n), capture.config, name


def fit_people_level(
    capture: Any,
    *,
    config: RadarConfig | None = None,
    empty: Any = None,
    scene: Any = "corridor",
    rcs_scale_dB: float = 0.0,
    min_snr_dB: float = 20.0,
    min_range_m: float = 0.6,
    min_frames: int = 8,
    max_frames: int | None = None,
    seed: int = 0,
) -> PeopleLevelFit:
    """Fit the level of a moving person in ``capture`` against the twin's walker, at matched range.

    Args:
        capture: a capture path, an open reader, or raw frames ``(F, rx, chirps, samples)`` in SDK
            floats (then give ``config``).
        config: the config of a tensor ``capture``.
        empty: optionally the same sensor's empty-room capture: a frame then counts as moving when its
            peak beats the empty room's strongest MTI cell in that range bin by ``min_snr_dB``.
        scene: the twin's scene for the walks (:func:`twin_walks`).
        rcs_scale_dB: people RCS scale of the twin (0: its default).
        min_snr_dB: how far above the floor (or the empty room) a frame's MTI peak must be.
        min_range_m: peaks nearer than this are left out (rarely a walking person).
        min_frames: fewest moving frames (in range bins the twin also covers) the fit accepts.
        max_frames: read at most this many frames of a capture.
        seed: seed of the twin's walks (phases and noise).

    Raises:
        CalibrationError: fewer than ``min_frames`` moving frames, a bad source, or a tensor without a config.
    """
    frames, cfg, name = _frames_and_config(capture, config, max_frames, "capture")
    peaks, bins, floor = mti_peaks(frames)
    axis = np.asarray(cfg.range_axis_m())
    moving = (peaks > floor + min_snr_dB) & (axis[bins] >= min_range_m)
    if empty is not None:
        e_frames, e_cfg, e_name = _frames_and_config(empty, cfg if isinstance(empty, torch.Tensor) else None,
                                                     max_frames, "empty capture")
        if e_cfg != cfg:
            raise CalibrationError(f"people level: empty capture {e_name} has another config than {name}")
        with torch.no_grad():
            e_mti = ToDecibels()(RangeDoppler(static_clutter=True)(e_frames))[:, 0].amax(dim=(0, 2))
        moving &= peaks > e_mti.double().numpy()[bins] + min_snr_dB
    if int(moving.sum()) < min_frames:
        raise CalibrationError(
            f"people level: {name} shows no moving target: {int(moving.sum())} of {len(peaks)} frames have an "
            f"MTI peak {min_snr_dB:g} dB above the {'empty room' if empty is not None else 'noise floor'} "
            f"beyond {min_range_m:g} m (need {min_frames})")
    peaks, bins = peaks[moving], bins[moving]
    span = (float(axis[bins.min()]), float(axis[bins.max()]))
    sim = twin_walks(cfg, span, scene=scene, rcs_scale_dB=rcs_scale_dB, seed=seed)
    t_peaks, t_bins, t_floor = mti_peaks(sim)
    diffs, ranges, cap_db, twin_db = [], [], [], []
    for k in np.unique(bins):
        t = t_peaks[t_bins == k]
        if len(t) < 2:  # one twin frame is no level
            continue
        c = peaks[bins == k]
        ref = float(np.median(t))
        diffs.append(c - ref)
        ranges.append(float(axis[k]))
        cap_db.append(float(np.median(c)))
        twin_db.append(ref)
    d = np.concatenate(diffs) if diffs else np.zeros(0)
    if len(d) < min_frames:
        raise CalibrationError(f"people level: {name}: only {len(d)} moving frames fall in range bins the twin's "
                               f"walkers reach (need {min_frames})")
    q1, q3 = np.percentile(d, [25, 75])
    return PeopleLevelFit(
        offset_dB=float(np.median(d)), spread_dB=float(q3 - q1) / 2, ranges_m=tuple(ranges),
        capture_dBFS=tuple(cap_db), twin_dBFS=tuple(twin_db), capture_frames=len(d), twin_frames=len(t_peaks),
        capture_floor_dBFS=floor, twin_floor_dBFS=t_floor, rcs_scale_dB=float(rcs_scale_dB),
    )
