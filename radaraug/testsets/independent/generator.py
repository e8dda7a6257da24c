"""The ``independent`` held-out set: labelled captures made without any of the twin's code.

:func:`make_independent_set` writes captures of 0, 1 and 2 people and an empty-room calibration
capture of one fixed office, like :func:`radaraug.testsets.proxy.make_proxy`, from the independent room,
people and receiver; its undeclared effects act on every capture, the calibration one included.
Receiver constants, effects and seeding: docs/heldout_worlds.md ("Inside the generator").
"""

from __future__ import annotations

import itertools
import json
import math
import os
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.files import atomic_write_json
from radaraug.testsets.generated import (
    GeneratedTestSet,
    check_count_arg,
    check_people_counts,
    load_generated_set,
    reusable_generated_set,
    start_generated_set,
    test_file_name,
)
from radaraug.testsets.independent import room as room_mod
from radaraug.testsets.independent import walkers
from radaraug.testsets.independent.receiver import _check_effects, _chirp_times, generate

GENERATOR_VERSION = 1
"""Bumped whenever the output changes; part of the reuse check."""
MANIFEST_NAME = "manifest.json"
MANIFEST_FORMAT = "radaraug-heldout-independent"
CALIBRATION_NAME = "calibration_empty.h5"
BLOCK_FRAMES = 10
"""Frames per receiver call (bounded memory, progress-bar steps, one noise stream each)."""
EPISODE_FRAMES = (20, 40)
"""Each test file is a sequence of episodes of this many frames, each with newly drawn people."""
MIN_EPISODE_FRAMES = 12
EPISODE_GAP_S = 2.0
FILE_TIME_ORIGIN_S = 1000.0
MIN_SEPARATION_M = 0.5
"""Two people's body centres stay at least this far apart during an episode."""
_STREAM_PEOPLE, _STREAM_RECEIVER = 1, 2

RECEIVER: dict[str, Any] = {
    "noise_figure_dB": 13.0,
    "front_end_gain_dB": 26.0,
    "tx_power_dBm_at_level_31": 5.0,
    "leakage_coupling_dB": (-33.5, -41.0, -42.0),
    "leak_range_m": 0.05,
    "leak_phase_rad": (0.3, -0.9, 1.7),
    "dc_counts_12bit": (1640.0, 1930.0, 2075.0),
    "filter_method": "analog",
    "phase_noise_min_level_dB": -110.0,
    "adc_noise_rms_counts_12bit": 1.6,
}
"""The receiver's base constants (per-RX values by antenna number 1, 2, 3), fixed before any
training result was seen; why each has its value: docs/heldout_worlds.md ("The independent set's receiver")."""

UNDECLARED_EFFECTS: tuple[dict[str, Any], ...] = (
    {"name": "phase_noise", "freq_noise_rms_Hz": 25e3, "corner_Hz": 300e3},
    {"name": "spur_tone", "freq_Hz": 156.25e3, "amplitude_counts": (0.6, 0.5, 0.7), "phase_rad": 1.1},
    {"name": "frame_drift", "gain_rms_dB": 0.1, "dc_rms_counts": 1.0},
    {"name": "rx_gain_phase_mismatch", "gain_dB": (0.0, -0.6, 0.4), "phase_rad": (0.0, 0.2, -0.3)},
)
"""The default undeclared effects besides the desk fan (:func:`default_effects` adds it; per-RX
values by antenna number 1, 2, 3): LO phase noise, a spur tone, frame drift and an RX gain/phase
mismatch, in every capture (docs/heldout_worlds.md, "The independent set's receiver")."""


# ------------------------------------------------------------------------------------ receiver
def _by_antenna(values: Sequence[float], config: RadarConfig) -> list[float]:
    """Per-RX values for the config's antennas from a table for antennas 1, 2, 3 (cycled beyond)."""
    return [float(values[(a - 1) % len(values)]) for a in config.rx_antennas]


def tx_power_dBm(config: RadarConfig) -> float:
    """TX power at the config's power level (amplitude linear in the level, assumed)."""
    level = config.tx_power_level
    if level <= 0:
        return -math.inf
    return float(RECEIVER["tx_power_dBm_at_level_31"]) + 20.0 * math.log10(level / 31.0)


def receiver_kwargs(config: RadarConfig) -> dict[str, Any]:
    """Keyword arguments of :func:`radaraug.testsets.independent.receiver.generate` for the base chain."""
    scale = config.adc_full_scale_counts / 4095.0
    mid = config.adc_full_scale_counts / 2.0
    dc = _by_antenna(RECEIVER["dc_counts_12bit"], config)
    return {
        "noise_figure_dB": RECEIVER["noise_figure_dB"],
        "front_end_gain_dB": RECEIVER["front_end_gain_dB"],
        "tx_power_dBm": tx_power_dBm(config),
        "leakage_coupling_dB": _by_antenna(RECEIVER["leakage_coupling_dB"], config),
        "leak_range_m": RECEIVER["leak_range_m"],
        "leak_phase_rad": _by_antenna(RECEIVER["leak_phase_rad"], config),
        # DC levels move with the ADC's mid-scale for other resolutions.
        "dc_counts": dc if config.adc_bits == 12 else [mid + (v - 2047.5) * scale for v in dc],
        "filter_method": RECEIVER["filter_method"],
        "phase_noise_min_level_dB": RECEIVER["phase_noise_min_level_dB"],
    }


def default_effects(config: RadarConfig) -> list[dict[str, Any]]:
    """The default undeclared effects for ``config``: :data:`UNDECLARED_EFFECTS` plus the desk fan."""
    out = [{k: _by_antenna(v, config) if isinstance(v, tuple) else v for k, v in e.items()}
           for e in UNDECLARED_EFFECTS]
    return out + room_mod.fan_effects(config)


def resolve_effects(effects: str | Sequence[Mapping[str, Any]] | None, config: RadarConfig) -> list[dict[str, Any]]:
    """Every effect the receiver applies: the base ADC-side noise plus ``effects``.

    Args:
        effects: ``"default"`` (:func:`default_effects`), ``"none"`` or None (the base chain
            only), or a list of receiver effects ``{"name": ..., **params}``
            (:data:`radaraug.testsets.independent.receiver.EFFECT_PARAMS`) applied on top of the base chain.
        config: the radar configuration.

    Raises:
        ConfigError: an unknown value or effect.
    """
    base = [{"name": "adc_noise",
             "rms_counts": RECEIVER["adc_noise_rms_counts_12bit"] * config.adc_full_scale_counts / 4095.0}]
    if effects is None or (isinstance(effects, str) and effects == "none"):
        extra: list[dict[str, Any]] = []
    elif isinstance(effects, str):
        if effects != "default":
            raise ConfigError(f"make_independent_set: effects must be 'default', 'none' or a list, got {effects!r}")
        extra = default_effects(config)
    else:
        extra = [dict(e) for e in effects]
    try:
        _check_effects(base + extra)
    except ValueError as err:
        raise ConfigError(f"make_independent_set: {err}") from None
    return json.loads(json.dumps(base + extra))


# -------------------------------------------------------------------------------------- people
def person_tracks(person: walkers.Person, rcs_m2: np.ndarray, t: np.ndarray, config: RadarConfig,
                  mount: room_mod.Mount = room_mod.OFFICE.mount) -> list[dict[str, Any]]:
    """The receiver's ``tracks`` of ``person``'s scatterers at chirp times ``t`` ``(F, M)``.

    Args:
        person: the person.
        rcs_m2: ``(NUM_POINTS, F)`` linear RCS per point and frame (:func:`walkers.rcs_per_frame`).
        t: the person's time (s) of each chirp's first ADC sample.
        config: the radar configuration.
        mount: where the radar hangs and looks.
    """
    dt = walkers.DERIVATIVE_STEP_S
    r, u = room_mod.look(walkers.positions(person, t), mount)  # (P, F, M), (P, F, M, 3)
    r_plus, _ = room_mod.look(walkers.positions(person, t + dt), mount)
    r_minus, _ = room_mod.look(walkers.positions(person, t - dt), mount)
    rate = (r_plus - r_minus) / (2.0 * dt)
    level = room_mod.level_dB(rcs_m2[:, :, None], r, u, config.wavelength_m)
    rx_phase = np.moveaxis(room_mod.rx_phase_rad(u, config), -1, -2)  # (P, F, RX, M)
    return [{"range_m": r[i], "rate_m_s": rate[i], "level_dB": level[i], "phase_rad": person.point_phase_rad[i],
             "rx_phase_rad": rx_phase[i]} for i in range(walkers.NUM_POINTS)]


def _split_frames(rng: np.random.Generator, total: int) -> list[int]:
    out, left = [], total
    while left > 0:
        n = int(rng.integers(EPISODE_FRAMES[0], EPISODE_FRAMES[1] + 1))
        if left - n < MIN_EPISODE_FRAMES:
            n = left
        out.append(n)
        left -= n
    return out


def _too_close(people: list[walkers.Person], duration_s: float) -> bool:
    t = np.linspace(0.0, duration_s, 64)
    centres = [walkers.positions(p, t)[0, :, :2] for p in people]  # pelvis
    pairs = itertools.combinations(centres, 2)
    return any(float(np.linalg.norm(a - b, axis=-1).min()) < MIN_SEPARATION_M for a, b in pairs)


@dataclass(frozen=True)
class PeoplePriors:
    """What the people of a set are drawn from (the defaults: the ``independent`` set's).

    Attributes:
        rcs_dBsm: range of a person's mean whole-body RCS (uniform).
        speed_m_s: range of a walker's speed (uniform).
        standing_probability: chance that a drawn person stands (breathing, swaying) instead of walking.
        crossing_probability: chance that a walker's racetrack runs across the radar's beam (along
            ``y``) instead of toward and away from it.
    """

    rcs_dBsm: tuple[float, float] = walkers.RCS_DBSM
    speed_m_s: tuple[float, float] = walkers.SPEED_M_S
    standing_probability: float = 0.0
    crossing_probability: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly description."""
        return {"rcs_dBsm": list(self.rcs_dBsm), "speed_m_s": list(self.speed_m_s),
                "standing_probability": self.standing_probability,
                "crossing_probability": self.crossing_probability}


def _draw_person(rng: np.random.Generator, room: room_mod.Room, people: PeoplePriors) -> walkers.Person:
    """One person on ``room``'s walkable floor (a crossing walker's racetrack runs along ``y``)."""
    tr = walkers.TURN_RADIUS_M
    (x0, x1), (y0, y1) = room.walk_x_m, room.walk_y_m
    standing = bool(rng.random() < people.standing_probability)
    # Drawn only when crossing walkers are possible, so the other sets' streams are unchanged.
    crossing = not standing and people.crossing_probability > 0 and bool(rng.random() < people.crossing_probability)
    if crossing:
        # The racetrack's frame turned +90 degrees: its x runs along the room's y, its lane centre
        # is minus the room's x.
        return walkers.draw_person(rng, x_range_m=(y0, y1), lane_range_m=(-(x1 - tr), -(x0 + tr)),
                                   standing=False, rcs_dBsm=people.rcs_dBsm, speed_m_s=people.speed_m_s,
                                   track_yaw_rad=math.pi / 2, min_straight_m=0.5 * (y1 - y0 - 2 * tr))
    return walkers.draw_person(rng, x_range_m=(x0, x1), lane_range_m=(y0 + tr, y1 - tr), standing=standing,
                               rcs_dBsm=people.rcs_dBsm, speed_m_s=people.speed_m_s)


def plan_episodes(count: int, frames: int, seed: int, config: RadarConfig,
                  standing_probability: float = 0.0, *, room: room_mod.Room = room_mod.OFFICE,
                  people: PeoplePriors | None = None) -> list[dict[str, Any]]:
    """The episodes of the file of ``count`` people: frames, start time, people.

    Each episode draws new people (:func:`walkers.draw_person`) on ``room``'s walkable floor from
    ``people`` (default: :class:`PeoplePriors` with ``standing_probability``); two people are
    redrawn until their body centres stay :data:`MIN_SEPARATION_M` apart for the whole episode.
    """
    people = PeoplePriors(standing_probability=standing_probability) if people is None else people
    split_rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(_STREAM_PEOPLE, count, 10_000)))
    episodes = []
    t0 = FILE_TIME_ORIGIN_S * (count + 1)
    for j, n in enumerate(_split_frames(split_rng, frames)):
        rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(_STREAM_PEOPLE, count, j)))
        duration = n * config.frame_repetition_time_s
        for _attempt in range(200):
            drawn = [_draw_person(rng, room, people) for _ in range(count)]
            if count < 2 or not _too_close(drawn, duration):
                break
        else:  # pragma: no cover - the lanes leave room for two people
            raise RuntimeError(f"heldout: could not place {count} people apart")
        rcs = [walkers.rcs_per_frame(p, rng, n) for p in drawn]
        episodes.append({"frames": n, "t0": t0, "people": drawn, "rcs": rcs})
        t0 += duration + EPISODE_GAP_S
    return episodes


# ---------------------------------------------------------------------------------- generation
def _block_seed(seed: int, file_key: int, block: int) -> int:
    state = np.random.SeedSequence(seed, spawn_key=(_STREAM_RECEIVER, file_key, block)).generate_state(1)
    return int(state[0])


def _write_file(path: Path, config: RadarConfig, episodes: list[dict[str, Any]], count: int, file_key: int,
                seed: int, effects: list[dict[str, Any]], scene: list[dict[str, Any]], attrs: dict[str, Any],
                bar: Any, kwargs: dict[str, Any], mount: room_mod.Mount) -> None:
    from radaraug.io import CaptureWriter

    total = sum(e["frames"] for e in episodes)
    block = 0
    period = config.frame_repetition_time_s
    with CaptureWriter(path, config, labels_schema={"count": "int64", "occupancy": "int64"}, attrs=attrs,
                       expected_frames=total) as writer:
        for ep in episodes:
            for a in range(0, ep["frames"], BLOCK_FRAMES):
                b = min(a + BLOCK_FRAMES, ep["frames"])
                local = np.arange(a, b, dtype=np.float64) * period  # frame starts, episode time
                t_chirp = _chirp_times(config, local)
                tracks: list[dict[str, Any]] = []
                for person, rcs in zip(ep["people"], ep["rcs"]):
                    tracks += person_tracks(person, rcs[:, a:b], t_chirp, config, mount)
                counts = generate(config, b - a, seed=_block_seed(seed, file_key, block), effects=effects,
                                  scene=scene, tracks=tracks, start_time_s=ep["t0"] + local[0], **kwargs)
                labels = np.full(b - a, count, dtype=np.int64)
                writer.append(counts, timestamp=ep["t0"] + local,
                              labels={"count": labels, "occupancy": (labels > 0).astype(np.int64)})
                block += 1
                bar.update(b - a)


def load_independent_set(out_dir: str | os.PathLike) -> GeneratedTestSet:
    """The set described by ``out_dir/manifest.json`` (files checked to exist).

    Raises:
        ConfigError: no readable manifest, or a file it lists is missing.
    """
    return load_generated_set(out_dir, MANIFEST_NAME, MANIFEST_FORMAT, "independent held-out manifest")[0]


def make_independent_set(
    out_dir: str | os.PathLike,
    *,
    config: RadarConfig | None = None,
    frames_per_count: int = 60,
    calibration_frames: int = 40,
    seed: int = 2024,
    effects: str | Sequence[Mapping[str, Any]] | None = "default",
    counts: Sequence[int] = (0, 1, 2),
    standing_probability: float = 0.0,
    progress: bool = True,
) -> GeneratedTestSet:
    """Generate (or reuse) the independent held-out set in ``out_dir``.

    Args:
        out_dir: output folder (created); the generator owns the names it writes there
            (``calibration_empty.h5``, ``test_count<c>.h5``, ``manifest.json``).
        config: radar configuration of every file (default :meth:`RadarConfig.bgt60tr13c`).
        frames_per_count: frames of each test file (episodes of 20-40 frames with new people).
        calibration_frames: frames of the empty-room capture.
        seed: seed of the people and of the receiver noise (the room is fixed).
        effects: undeclared receiver effects: ``"default"`` (phase noise, spur, frame drift, RX
            mismatch, desk fan), ``"none"`` (the base chain only) or a list of receiver effects
            (see :func:`resolve_effects`). They act on every capture, the calibration one included.
        counts: people counts to generate, one test file each (0, 1 and/or 2).
        standing_probability: chance that a drawn person stands (breathing, swaying) for their
            episode instead of walking; they still count.
        progress: show a tqdm progress bar (frames).

    Returns:
        The :class:`GeneratedTestSet` (``calibration``, ``tests``, ``config``, ``manifest``,
        ``reused``, ``to_dict()``, ``test_specs()``).

    Raises:
        ConfigError: bad sizes, counts, seed, config, effects or probability.
    """
    config = RadarConfig.bgt60tr13c() if config is None else config
    if not isinstance(config, RadarConfig):
        raise ConfigError(f"make_independent_set: config must be a RadarConfig, got {type(config).__name__}")
    frames_per_count = check_count_arg("make_independent_set", "frames_per_count", frames_per_count, 1)
    calibration_frames = check_count_arg("make_independent_set", "calibration_frames", calibration_frames, 1)
    seed = check_count_arg("make_independent_set", "seed", seed, 0)
    counts = check_people_counts("make_independent_set", counts)
    if isinstance(standing_probability, bool) or not isinstance(standing_probability, (int, float)) \
            or not 0.0 <= float(standing_probability) <= 1.0:
        raise ConfigError(f"make_independent_set: standing_probability must be in [0, 1], got {standing_probability!r}")
    resolved = resolve_effects(effects, config)
    settings = json.loads(json.dumps({
        "generator_version": GENERATOR_VERSION, "frames_per_count": frames_per_count,
        "calibration_frames": calibration_frames, "seed": seed, "counts": list(counts),
        "config": config.to_dict(), "effects": resolved, "standing_probability": float(standing_probability),
    }))
    out = Path(out_dir)
    reused = reusable_generated_set(out, MANIFEST_NAME, MANIFEST_FORMAT, settings, config)
    if reused is not None:
        return reused[0]
    return _generate(out, settings, config, resolved, progress)


def write_set_files(out: Path, config: RadarConfig, *, seed: int, counts: Sequence[int], frames_per_count: int,
                    calibration_frames: int, effects: list[dict[str, Any]], common: dict[str, Any],
                    room: room_mod.Room = room_mod.OFFICE, people: PeoplePriors | None = None,
                    receiver: dict[str, Any] | None = None, progress: bool = True,
                    desc: str = "heldout") -> dict[str, Any]:
    """Write the calibration capture and one test capture per count of a room; the manifest's ``files``.

    Args:
        out: the set's folder.
        config: the radar configuration.
        seed: seed of the people and of the receiver noise.
        counts: people counts, one test file each.
        frames_per_count: frames of each test file.
        calibration_frames: frames of the calibration file.
        effects: every receiver effect (:func:`resolve_effects`).
        common: attributes written into every file.
        room: the room, its fixtures and the radar's mount.
        people: what the people are drawn from.
        receiver: :func:`radaraug.testsets.independent.receiver.generate` keyword arguments (default
            :func:`receiver_kwargs`).
        progress: show a tqdm progress bar (frames).
        desc: the progress bar's label.
    """
    from radaraug._optional import lazy_import

    scene = room_mod.room_scene(config, room=room)
    kwargs = receiver_kwargs(config) if receiver is None else receiver
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm
    total = calibration_frames + frames_per_count * len(counts)
    files: dict[str, Any] = {}
    with tqdm(total=total, desc=desc, unit="frame", disable=not progress) as bar:
        cal = [{"frames": calibration_frames, "t0": 0.0, "people": [], "rcs": []}]
        _write_file(out / CALIBRATION_NAME, config, cal, 0, 0, seed, effects, scene,
                    {**common, "description": "empty room, for CalibratedDR.fit",
                     "role": "calibration", "labels": {"count": 0}}, bar, kwargs, room.mount)
        files["calibration"] = {"path": CALIBRATION_NAME, "frames": calibration_frames, "count": 0}
        files["tests"] = []
        for c in counts:
            episodes = plan_episodes(c, frames_per_count, seed, config, room=room, people=people)
            described = [{"frames": e["frames"], "t0_s": round(e["t0"], 6),
                          "people": [p.to_dict() for p in e["people"]]} for e in episodes]
            path = out / test_file_name(c)
            _write_file(path, config, episodes, c, c + 1, seed, effects, scene,
                        {**common, "description": f"{c} people in every frame",
                         "role": "test", "labels": {"count": c}, "episodes": described}, bar, kwargs, room.mount)
            files["tests"].append({"path": path.name, "frames": frames_per_count, "count": c,
                                   "episodes": described})
    return files


def _generate(out: Path, settings: dict[str, Any], config: RadarConfig, effects: list[dict[str, Any]],
              progress: bool) -> GeneratedTestSet:
    started = time.perf_counter()
    manifest_path = start_generated_set(out, MANIFEST_NAME)
    seed = settings["seed"]
    common = {"source": "radaraug independent held-out generator (radaraug.testsets.independent)",
              "generator_version": GENERATOR_VERSION, "seed": seed,
              "note": "simulated without the training twin's code: numbers on it are sim-to-sim, not sim-to-real"}
    files = write_set_files(out, config, seed=seed, counts=settings["counts"],
                            frames_per_count=settings["frames_per_count"],
                            calibration_frames=settings["calibration_frames"], effects=effects, common=common,
                            people=PeoplePriors(standing_probability=settings["standing_probability"]),
                            progress=progress)
    elapsed = time.perf_counter() - started
    manifest = {
        "format": MANIFEST_FORMAT,
        "generator_version": GENERATOR_VERSION,
        "settings": settings,
        "statement": "An independent held-out set: room, people and receiver simulated by radaraug.testsets.independent, which "
                     "shares no simulation code with the training twin. It is still simulation (sim-to-sim, not "
                     "sim-to-real). Its settings were fixed before any training result was seen; do not tune them "
                     "to make a method look good.",
        "config": config.to_dict(),
        "seed": seed,
        "files": files,
        "label_rule": "count = people in the room, walking or standing (every person is inside the walkable "
                      f"floor x {list(room_mod.WALK_X_M)} m, y {list(room_mod.WALK_Y_M)} m, at least 1 m in front "
                      "of the radar, in every frame); every frame of a test file has the file's count",
        "room": room_mod.describe(),
        "people_model": {
            "points": list(walkers.POINT_NAMES), "rcs_fractions": walkers.RCS_FRACTIONS,
            "height_m": list(walkers.HEIGHT_M), "speed_m_s": list(walkers.SPEED_M_S),
            "rcs_dBsm": list(walkers.RCS_DBSM), "fluctuation_dB": list(walkers.FLUCTUATION_DB),
            "fluctuation_frame_correlation": walkers.FLUCTUATION_CORRELATION,
            "turn_radius_m": walkers.TURN_RADIUS_M, "swing_fraction": list(walkers.SWING_FRACTION),
            "episode_frames": list(EPISODE_FRAMES), "min_separation_m": MIN_SEPARATION_M,
            "standing_probability": settings["standing_probability"],
        },
        "receiver": {"model": "radaraug.testsets.independent.receiver.generate (NumPy, per-sample float64 phases, analog "
                              "first-order IF filters with the high-pass start-up transient)",
                     "constants": {k: list(v) if isinstance(v, tuple) else v for k, v in RECEIVER.items()},
                     "generate_kwargs": json.loads(json.dumps(receiver_kwargs(config))),
                     "effects": effects},
    }
    return finish_set(out, manifest_path, manifest, files, config, elapsed)


def finish_set(out: Path, manifest_path: Path, manifest: dict[str, Any], files: dict[str, Any], config: RadarConfig,
               elapsed: float) -> GeneratedTestSet:
    """Write ``manifest`` (with the keys every held-out set shares) last, atomically; the set it describes."""
    manifest = manifest | {
        "dsp_chain_expected": "RangeDoppler() -> ToDecibels() (the chain CalibratedDR is fitted with)",
        "shares_with_training_twin": "RadarConfig numbers and the capture writer only",
        "licence": "generated by radaraug, MIT",
        "generation_s": round(elapsed, 2),
    }
    atomic_write_json(manifest_path, manifest, indent=2)
    tests = [(out / f["path"], f["count"]) for f in files["tests"]]
    return GeneratedTestSet(out / files["calibration"]["path"], tests, config, manifest=manifest_path, reused=False,
                            generation_s=elapsed)


__all__ = [
    "GENERATOR_VERSION", "PeoplePriors", "RECEIVER", "UNDECLARED_EFFECTS", "default_effects",
    "load_independent_set", "make_independent_set", "person_tracks", "plan_episodes", "receiver_kwargs",
    "finish_set", "resolve_effects", "write_set_files",
]
