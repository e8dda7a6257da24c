"""Held-out test worlds drawn from wide priors, in two suites: one to look at, one only to report.

A world is a whole test situation (room, mounting, radar config, receiver, people, disturbances)
drawn from :data:`PRIORS` by the independent generator, with its own empty-room capture. A world
is a pure function of ``(suite, index)`` and :data:`WORLD_GENERATOR_VERSION`; ``design`` worlds may
be looked at freely, ``report`` worlds are run only to report. See docs/heldout_worlds.md.
"""

from __future__ import annotations

import json
import math
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.testsets.generated import (
    GeneratedTestSet,
    check_count_arg,
    load_generated_set,
    reusable_generated_set,
    start_generated_set,
)
from radaraug.testsets.independent import room as room_mod
from radaraug.testsets.independent import walkers
from radaraug.testsets.independent.generator import (
    MANIFEST_NAME,
    RECEIVER,
    PeoplePriors,
    finish_set,
    receiver_kwargs,
    resolve_effects,
    write_set_files,
)
from radaraug.testsets.independent.receiver import C_LIGHT

WORLD_GENERATOR_VERSION = 1
"""Bumped whenever a world's draw or output changes; part of the reuse check."""
WORLD_MANIFEST_FORMAT = "radaraug-heldout-world"
SUITES: dict[str, int] = {"design": 340_117, "report": 138_531, "report-1": 902_551, "report-2": 611_873,
                          "report-3": 258_449}
"""Entropy of each suite's seed sequence: world ``i`` of suite ``s`` is drawn from
``SeedSequence(SUITES[s], spawn_key=(i, 1))``, its seed from ``spawn_key=(i, 0)``. The spent suites
(:data:`SPENT_SUITES`) stay drawable so that their records can be rerun; ``report`` draws from seeds
nobody has run."""
SPENT_SUITES: tuple[str, ...] = ("report-1", "report-2", "report-3")
"""Report suites that have been looked at: their numbers are validation numbers now."""
DEFAULT_WORLDS: dict[str, int] = {"design": 6, "report": 4, "report-1": 4, "report-2": 4, "report-3": 4}
"""Worlds per suite that ``reproduce --test-sets design|report`` uses unless told otherwise."""
MAX_WORLDS = 1000

PRIORS: dict[str, str] = {
    "config": "samples {128, 256}; sample rate {1, 2} MHz; chirps {32, 64}; max range U(10, 24) m (sets the "
              "bandwidth, kept within 58-63.5 GHz); chirp repetition time = ADC time + ADC delay + U(30, 150) us; "
              "frame period {50, 100} ms; IF gain {23, 28, 33, 38, 43, 48} dB; high-pass {20, 45, 70, 80} kHz; "
              "TX power level U{20..31}",
    "room": "length U(5, min(12, 0.7 max range)) m, width U(2.6, 7) m, height U(2.4, 3.8) m; wall reflectivity "
            "U(-16, -5) dB per surface; diffuse backscatter U(0.01, 0.08) per surface; 3-10 fixtures (cabinet, "
            "shelf, desk, chair, pillar, radiator, plant, lamp, door frame) by the side walls or on the ceiling, "
            "RCS per type; far-wall edges U(-2, 6) dBsm",
    "mount": "one of: table (height U(0.7, 1.2) m, tilt U(-3, 5) deg), wall (U(1.2, 2.0) m, U(3, 15) deg), high "
             "(U(2.0, ceiling - 0.2) m, U(15, 35) deg); across the near wall U(0.35, 0.65) of the width; yaw "
             "U(-12, 12) deg",
    "receiver": "noise figure U(10, 16) dB; ADC noise U(1.2, 2.2) counts RMS; leakage U(-4, 4) dB around the "
                "independent set's; DC levels +-U(0, 150) counts",
    "people": "RCS range (lo, lo + U(4, 10)) dBsm with lo U(-14, 0); speed (lo, lo + U(0.4, 1.0)) m/s with lo "
              "U(0.2, 0.9); standing probability U(0, 0.4); crossing probability U(0, 0.7)",
    "disturbances": "each with probability 0.5: spur (U(0.03, 0.47) fs, log-U(0.3, 4) counts), fan (housing "
                    "0.1-0.5 mm at 12-25 Hz, 3-5 blades 3-10 cm radial), interference (U(0.02, 0.2) of the chirps, "
                    "log-U(20, 300) counts, U(5, 30) us), frame drift (U(0.05, 0.5) dB, U(0.3, 3) counts), RX "
                    "mismatch (+-U(0.3, 3) dB, +-U(0.1, 1) rad), phase noise (log-U(10, 150) kHz RMS, corner "
                    "log-U(100, 500) kHz), clipping (a metal object where its beat is U(2, 3) times the high-pass cutoff, U(1.0, 1.15) "
                    "times over the ADC's headroom)",
}
"""The priors, as written in every world's manifest."""

DISTURBANCES = ("spur_tone", "fan", "interference", "frame_drift", "rx_gain_phase_mismatch", "phase_noise",
                "clipping")
"""The disturbances a world may carry (each drawn with probability 0.5)."""
_FIXTURES: dict[str, tuple[tuple[float, float], tuple[float, float], str]] = {
    # type: (RCS range dBsm, height range m, where)
    "cabinet": ((3.0, 10.0), (0.6, 1.6), "wall"),
    "shelf": ((0.0, 6.0), (0.4, 1.8), "wall"),
    "desk": ((-6.0, 0.0), (0.5, 0.8), "wall"),
    "chair": ((-8.0, -2.0), (0.2, 0.9), "wall"),
    "pillar": ((2.0, 6.0), (0.5, 2.0), "wall"),
    "radiator": ((-1.0, 4.0), (0.3, 0.7), "wall"),
    "plant": ((-12.0, -5.0), (0.3, 1.2), "wall"),
    "lamp": ((-9.0, -3.0), (0.0, 0.0), "ceiling"),
    "door_frame": ((-4.0, 1.0), (0.8, 1.2), "far_wall"),
}
_SURFACES = ("far_wall", "left_wall", "right_wall", "floor", "ceiling")
_MARGIN_M = 0.75
"""Walkable floor: this far from the side walls (the fixtures stand within 0.6 m of them)."""


@dataclass(frozen=True)
class World:
    """One drawn test world (everything its captures are made from).

    Attributes:
        suite: ``"design"``, ``"report"`` or a spent report suite.
        index: the world's number in its suite.
        seed: seed of its people and receiver noise (drawn from the suite's sequence).
        config: the radar configuration of its captures.
        room: the room, fixtures, fan and mount.
        people: what its people are drawn from.
        receiver: :func:`radaraug.testsets.independent.receiver.generate` keyword arguments of its base chain.
        effects: every receiver effect (base ADC noise plus the disturbances).
        disturbances: the names of the disturbances it carries (:data:`DISTURBANCES`).
    """

    suite: str
    index: int
    seed: int
    config: RadarConfig
    room: room_mod.Room
    people: PeoplePriors
    receiver: dict[str, Any]
    effects: list[dict[str, Any]] = field(default_factory=list)
    disturbances: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """``SUITE-wNN``: the world's name in reports."""
        return f"{self.suite}-w{self.index:02d}"

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly description (the manifest's ``world``)."""
        return json.loads(json.dumps({
            "name": self.name, "suite": self.suite, "index": self.index, "seed": self.seed,
            "config": self.config.to_dict(), "people": self.people.to_dict(), "receiver": self.receiver,
            "disturbances": list(self.disturbances), "effects": self.effects,
            "room": room_mod.describe(self.room),
        }))


def world_seed(suite: str, index: int) -> int:
    """The seed of world ``index`` of ``suite`` (its people and receiver noise).

    Raises:
        ConfigError: an unknown suite or a bad index.
    """
    return int(_rng_state(suite, index, 0))


def _rng_state(suite: str, index: int, stream: int) -> int:
    if suite not in SUITES:
        raise ConfigError(f"unknown held-out suite {suite!r}; choose from {sorted(SUITES)}")
    index = check_count_arg("heldout worlds", "index", index, 0)
    return int(np.random.SeedSequence(SUITES[suite], spawn_key=(index, stream)).generate_state(1)[0])


def _choice(rng: np.random.Generator, values: Sequence[Any]) -> Any:
    return values[int(rng.integers(len(values)))]


def draw_config(rng: np.random.Generator) -> RadarConfig:
    """A radar config from :data:`PRIORS` ``["config"]`` (a BGT60TR13C's settable ranges)."""
    samples = int(_choice(rng, (128, 256)))
    fs = float(_choice(rng, (1e6, 2e6)))
    chirps = int(_choice(rng, (32, 64)))
    max_range = float(rng.uniform(10.0, 24.0))
    base = RadarConfig.bgt60tr13c()
    ramp = samples / fs + base.adc_delay_s
    # Real IF: f_beat = 2 S R / c <= fs / 2 at R = max range, so S = fs c / (4 R); bandwidth = S x ramp.
    bandwidth = min(fs * C_LIGHT / (4.0 * max_range) * ramp, 5.0e9)
    centre = min(max(60.5e9, 58.05e9 + bandwidth / 2), 63.45e9 - bandwidth / 2)
    prt = samples / fs + base.adc_delay_s + float(rng.uniform(30e-6, 150e-6))
    return base.replace(
        start_frequency_Hz=centre - bandwidth / 2, end_frequency_Hz=centre + bandwidth / 2, sample_rate_Hz=fs,
        num_samples_per_chirp=samples, num_chirps_per_frame=chirps, chirp_repetition_time_s=prt,
        frame_repetition_time_s=float(_choice(rng, (0.05, 0.1))),
        if_gain_dB=int(_choice(rng, (23, 28, 33, 38, 43, 48))),
        hp_cutoff_Hz=float(_choice(rng, (20e3, 45e3, 70e3, 80e3))),
        tx_power_level=int(rng.integers(20, 32)),
    )


def _mount(rng: np.random.Generator, width: float, height: float) -> room_mod.Mount:
    kind = _choice(rng, ("table", "wall", "high"))
    if kind == "table":
        z, tilt = rng.uniform(0.7, 1.2), rng.uniform(-3.0, 5.0)
    elif kind == "wall":
        z, tilt = rng.uniform(1.2, 2.0), rng.uniform(3.0, 15.0)
    else:
        z, tilt = rng.uniform(2.0, height - 0.2), rng.uniform(15.0, 35.0)
    y = rng.uniform(0.35, 0.65) * width
    return room_mod.Mount(position_m=(0.12, float(y), float(z)), tilt_down_deg=float(tilt),
                          yaw_deg=float(rng.uniform(-12.0, 12.0)))


def _fixtures(rng: np.random.Generator, size: tuple[float, float, float]) -> tuple[Any, ...]:
    length, width, height = size
    out: list[tuple[str, tuple[float, float, float], float]] = []
    for i in range(int(rng.integers(3, 11))):
        kind = _choice(rng, tuple(_FIXTURES))
        (r0, r1), (z0, z1), where = _FIXTURES[kind]
        rcs = float(rng.uniform(r0, r1))
        if where == "ceiling":
            pos = (rng.uniform(1.0, length - 0.3), rng.uniform(0.5, width - 0.5), height - 0.05)
        elif where == "far_wall":
            pos = (length, rng.uniform(0.3, width - 0.3), rng.uniform(z0, z1))
        else:
            side = rng.uniform(0.15, 0.6)
            pos = (rng.uniform(1.0, length - 0.3), side if rng.random() < 0.5 else width - side, rng.uniform(z0, z1))
        x, y, z = (float(v) for v in pos)
        out.append((f"{kind}_{i}", (x, y, z), rcs))
    for name, z in (("far_wall_floor_edge", 0.0), ("far_wall_ceiling_edge", height)):
        out.append((name, (length, float(rng.uniform(0.3, width - 0.3)), z), float(rng.uniform(-2.0, 6.0))))
    return tuple(out)


def _fan(rng: np.random.Generator, size: tuple[float, float, float]) -> dict[str, Any]:
    length, width, _ = size
    side = rng.uniform(0.2, 0.5)
    return {
        "position_m": (float(rng.uniform(1.5, length - 0.5)), float(side if rng.random() < 0.5 else width - side),
                       float(rng.uniform(0.4, 1.5))),
        "rcs_dBsm": float(rng.uniform(-14.0, -4.0)),
        "displacement_m": float(rng.uniform(0.1e-3, 0.5e-3)),
        "vibration_Hz": float(rng.uniform(12.0, 25.0)),
        "blades": int(rng.integers(3, 6)),
        "blade_rcs_dBsm": float(rng.uniform(-30.0, -20.0)),
        "blade_radial_m": float(rng.uniform(0.03, 0.10)),
    }


def draw_room(rng: np.random.Generator, config: RadarConfig, fan: bool) -> room_mod.Room:
    """A room from :data:`PRIORS` ``["room"]`` and ``["mount"]`` that fits ``config``'s max range."""
    length = float(rng.uniform(5.0, max(5.5, min(12.0, 0.7 * config.max_range_m))))
    width, height = float(rng.uniform(2.6, 7.0)), float(rng.uniform(2.4, 3.8))
    size = (length, width, height)
    mount = _mount(rng, width, height)
    return room_mod.Room(
        size_m=size,
        wall_reflectivity_dB={s: float(rng.uniform(-16.0, -5.0)) for s in _SURFACES},
        diffuse_mu={s: float(rng.uniform(0.01, 0.08)) for s in _SURFACES[1:]},
        objects=_fixtures(rng, size),
        walk_x_m=(mount.position_m[0] + 1.0, length - 0.5),
        walk_y_m=(_MARGIN_M, width - _MARGIN_M),
        fan=_fan(rng, size) if fan else None,
        mount=mount,
        seed=int(rng.integers(2**31)),
    )


def _receiver(rng: np.random.Generator, config: RadarConfig) -> dict[str, Any]:
    kw = receiver_kwargs(config)
    kw["noise_figure_dB"] = float(rng.uniform(10.0, 16.0))
    kw["leakage_coupling_dB"] = [float(v + rng.uniform(-4.0, 4.0)) for v in kw["leakage_coupling_dB"]]
    kw["dc_counts"] = [float(v + rng.uniform(-150.0, 150.0)) for v in kw["dc_counts"]]
    return kw


def _clipping_object(rng: np.random.Generator, config: RadarConfig, receiver: dict[str, Any]) -> dict[str, Any]:
    """A metal object whose tone exceeds the ADC's headroom U(1.0, 1.15) times.

    It stands where its beat frequency is 2-3 times the IF high-pass cutoff: nearer, the level
    needed to clip would make the high-pass start-up transient, not the tone, fill the ADC.
    """
    fh, fl = config.effective_hp_cutoff_Hz, config.effective_aaf_cutoff_Hz
    r = min(float(rng.uniform(1.0, 1.5)) * fh * C_LIGHT / config.slope_Hz_per_s, 0.6 * config.max_range_m)
    f_beat = 2.0 * config.slope_Hz_per_s * r / C_LIGHT
    h = (f_beat / fh) / math.hypot(1.0, f_beat / fh) / math.hypot(1.0, f_beat / fl)
    full = float(config.adc_full_scale_counts)
    headroom = min(min(d, full - d) for d in receiver["dc_counts"])
    peak = float(rng.uniform(1.0, 1.15)) * headroom * 2.0 / full  # float units at the ADC
    g = 10.0 ** (receiver["front_end_gain_dB"] / 20.0) * 10.0 ** (config.if_gain_dB / 20.0) * h
    p_tx = 1e-3 * 10.0 ** (receiver["tx_power_dBm"] / 10.0)
    level = 10.0 * math.log10((peak / g) ** 2 / 2.0 / p_tx)
    return {"name": "static_clutter", "range_m": r, "level_dB": level, "phase_rad": float(rng.uniform(0, 2 * math.pi))}


def _disturbance(name: str, rng: np.random.Generator, config: RadarConfig,
                 receiver: dict[str, Any]) -> list[dict[str, Any]]:
    u = rng.uniform
    n_rx = config.num_rx

    def signed(lo: float, hi: float) -> float:
        return float((1.0 if rng.random() < 0.5 else -1.0) * u(lo, hi))

    if name == "spur_tone":
        amp = math.exp(u(math.log(0.3), math.log(4.0)))
        return [{"name": name, "freq_Hz": float(u(0.03, 0.47) * config.sample_rate_Hz),
                 "amplitude_counts": [float(amp * u(0.7, 1.3)) for _ in range(n_rx)],
                 "phase_rad": float(u(0, 2 * math.pi))}]
    if name == "interference":
        return [{"name": name, "probability": float(u(0.02, 0.2)),
                 "amplitude_counts": float(math.exp(u(math.log(20.0), math.log(300.0)))),
                 "duration_s": float(u(5e-6, 30e-6))}]
    if name == "frame_drift":
        return [{"name": name, "gain_rms_dB": float(u(0.05, 0.5)), "dc_rms_counts": float(u(0.3, 3.0))}]
    if name == "rx_gain_phase_mismatch":
        return [{"name": name, "gain_dB": [0.0] + [signed(0.3, 3.0) for _ in range(n_rx - 1)],
                 "phase_rad": [0.0] + [signed(0.1, 1.0) for _ in range(n_rx - 1)]}]
    if name == "phase_noise":
        return [{"name": name, "freq_noise_rms_Hz": float(math.exp(u(math.log(10e3), math.log(150e3)))),
                 "corner_Hz": float(math.exp(u(math.log(100e3), math.log(500e3))))}]
    if name == "clipping":
        return [_clipping_object(rng, config, receiver)]
    return []  # the fan is part of the room (room_mod.fan_effects)


def draw_world(suite: str, index: int) -> World:
    """World ``index`` of ``suite``: a pure function of both (and :data:`WORLD_GENERATOR_VERSION`).

    Raises:
        ConfigError: an unknown suite or a bad index.
    """
    rng = np.random.default_rng(_rng_state(suite, index, 1))
    config = draw_config(rng)
    on = [name for name in DISTURBANCES if rng.random() < 0.5]
    room = draw_room(rng, config, fan="fan" in on)
    receiver = _receiver(rng, config)
    adc_noise = float(rng.uniform(1.2, 2.2))
    lo = float(rng.uniform(-14.0, 0.0))
    speed_lo = float(rng.uniform(0.2, 0.9))
    people = PeoplePriors(rcs_dBsm=(lo, lo + float(rng.uniform(4.0, 10.0))),
                          speed_m_s=(speed_lo, speed_lo + float(rng.uniform(0.4, 1.0))),
                          standing_probability=float(rng.uniform(0.0, 0.4)),
                          crossing_probability=float(rng.uniform(0.0, 0.7)))
    extra: list[dict[str, Any]] = []
    for name in on:
        extra += _disturbance(name, rng, config, receiver)
    extra += room_mod.fan_effects(config, room)
    effects = resolve_effects(extra, config)
    effects[0]["rms_counts"] = adc_noise * config.adc_full_scale_counts / 4095.0  # the base ADC-side noise
    return World(suite=suite, index=int(index), seed=world_seed(suite, index), config=config, room=room,
                 people=people, receiver=receiver, effects=effects, disturbances=tuple(on))


def _check_walkable(world: World) -> None:
    (x0, x1), (y0, y1) = world.room.walk_x_m, world.room.walk_y_m
    tr = walkers.TURN_RADIUS_M
    if x1 - x0 < 2 * tr + 1.5 or y1 - y0 < 2 * tr + 0.3:  # pragma: no cover - the priors keep rooms large enough
        raise ConfigError(f"{world.name}: walkable floor x {x0:.2f}..{x1:.2f}, y {y0:.2f}..{y1:.2f} m is too small")


def make_world(out_dir: str | os.PathLike, world: World, *, frames_per_count: int = 60,
               calibration_frames: int = 40, counts: Sequence[int] = (0, 1, 2),
               progress: bool = True) -> GeneratedTestSet:
    """Generate (or reuse) ``world``'s captures in ``out_dir``: an empty-room capture and one per count.

    Args:
        out_dir: the world's folder (created; ``calibration_empty.h5``, ``test_count<c>.h5``,
            ``manifest.json``).
        world: the world (:func:`draw_world`).
        frames_per_count: frames of each test file (episodes of 20-40 frames with new people).
        calibration_frames: frames of the empty-room capture.
        counts: people counts, one test file each.
        progress: show a tqdm progress bar (frames).

    Raises:
        ConfigError: bad sizes.
    """
    frames_per_count = check_count_arg("make_world", "frames_per_count", frames_per_count, 1)
    calibration_frames = check_count_arg("make_world", "calibration_frames", calibration_frames, 1)
    _check_walkable(world)
    settings = json.loads(json.dumps({
        "world_generator_version": WORLD_GENERATOR_VERSION, "suite": world.suite, "index": world.index,
        "frames_per_count": frames_per_count, "calibration_frames": calibration_frames, "counts": list(counts),
    }))
    out = Path(out_dir)
    reused = reusable_generated_set(out, MANIFEST_NAME, WORLD_MANIFEST_FORMAT, settings, world.config)
    if reused is not None:
        return reused[0]
    started = time.perf_counter()
    manifest_path = start_generated_set(out, MANIFEST_NAME)
    common = {"source": "radaraug held-out world generator (radaraug.testsets.independent.worlds)",
              "world": world.name, "world_generator_version": WORLD_GENERATOR_VERSION, "seed": world.seed,
              "note": "simulated without the training twin's code: numbers on it are sim-to-sim, not sim-to-real"}
    files = write_set_files(out, world.config, seed=world.seed, counts=counts, frames_per_count=frames_per_count,
                            calibration_frames=calibration_frames, effects=world.effects, common=common,
                            room=world.room, people=world.people, receiver=world.receiver, progress=progress,
                            desc=world.name)
    elapsed = time.perf_counter() - started
    manifest = {
        "format": WORLD_MANIFEST_FORMAT,
        "world_generator_version": WORLD_GENERATOR_VERSION,
        "settings": settings,
        "statement": (f"A held-out test world of the {world.suite!r} suite, drawn from wide priors by the independent "
                      "generator (radaraug.testsets.independent), which shares no simulation code with the training twin. "
                      + ("Report suite: run it only to report a decision already made, never to make one."
                         if world.suite == "report" else
                         "Spent report suite: it has been looked at, so its numbers are validation numbers now."
                         if world.suite in SPENT_SUITES else
                         "Design suite: numbers on it are validation numbers once they chose anything.")),
        "priors": PRIORS,
        "world": world.to_dict(),
        "config": world.config.to_dict(),
        "seed": world.seed,
        "files": files,
        "label_rule": "count = people in the room, walking, crossing or standing (every person stays on the walkable "
                      "floor, at least 1 m in front of the radar, in every frame); every frame of a test file has "
                      "the file's count",
        "receiver_constants": {k: list(v) if isinstance(v, tuple) else v for k, v in RECEIVER.items()},
    }
    return finish_set(out, manifest_path, manifest, files, world.config, elapsed)


def load_world(out_dir: str | os.PathLike) -> GeneratedTestSet:
    """The world described by ``out_dir/manifest.json`` (files checked to exist).

    Raises:
        ConfigError: no readable world manifest, or a file it lists is missing.
    """
    return load_generated_set(out_dir, MANIFEST_NAME, WORLD_MANIFEST_FORMAT, "held-out world manifest")[0]


def make_suite(out_dir: str | os.PathLike, suite: str, *, worlds: int | None = None, frames_per_count: int = 60,
               calibration_frames: int = 40, progress: bool = True) -> list[tuple[World, GeneratedTestSet]]:
    """Generate (or reuse) the first ``worlds`` worlds of ``suite`` under ``out_dir/<world name>``.

    Args:
        out_dir: parent folder.
        suite: ``"design"`` (look at it freely), ``"report"`` (run only to report) or a spent
            report suite (:data:`SPENT_SUITES`).
        worlds: how many (default :data:`DEFAULT_WORLDS`).
        frames_per_count: as :func:`make_world`.
        calibration_frames: as :func:`make_world`.
        progress: progress bars.

    Raises:
        ConfigError: an unknown suite or a bad size.
    """
    if suite not in SUITES:
        raise ConfigError(f"unknown held-out suite {suite!r}; choose from {sorted(SUITES)}")
    n = DEFAULT_WORLDS[suite] if worlds is None else check_count_arg("make_suite", "worlds", worlds, 1)
    if n > MAX_WORLDS:
        raise ConfigError(f"make_suite: at most {MAX_WORLDS} worlds, got {n}")
    out = []
    for i in range(n):
        world = draw_world(suite, i)
        out.append((world, make_world(Path(out_dir) / world.name, world, frames_per_count=frames_per_count,
                                      calibration_frames=calibration_frames, progress=progress)))
    return out


__all__ = [
    "DEFAULT_WORLDS", "DISTURBANCES", "PRIORS", "SPENT_SUITES", "SUITES", "WORLD_GENERATOR_VERSION", "World", "draw_config",
    "draw_room", "draw_world", "load_world", "make_suite", "make_world", "world_seed",
]
