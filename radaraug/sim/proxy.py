"""The held-out proxy test set: labelled captures from a twin that training was *not* made with.

No labelled real corridor recording ships with radaraug, so the default test side of the
recipes is this proxy: radaraug HDF5 captures of 0, 1 and 2 walking people (per-frame ``count``
and ``occupancy`` labels) plus an empty-room calibration capture (to fit
:class:`~radaraug.transforms.CalibratedDR`), simulated from a deliberately **different**
configuration. It shows whether training survives a twin it was not made with. It is a
sim-to-proxy test, **not** a sim-to-real one, and its settings were fixed before any training
result was seen: do not tune them to make a method look good.

What is the same as training: the radar configuration (:meth:`RadarConfig.bgt60tr13c`, so that
CalibratedDR's chain and map shape match), the ray tracer, the IF synthesis and the 16-segment
body model. What differs (also written into ``proxy.json`` and ``docs/proxy.md``):

* **Room**: 14 m x 2.6 m x 3.0 m instead of 20 m x 2 m x 2.7 m; concrete floor, 12.5 mm
  plasterboard ceiling (slab), a glass left wall, concrete right and near walls, a 4 cm wooden
  far wall (slab); plus clutter the training corridor lacks: a metal cabinet, a wooden bench and
  a concrete pillar (:func:`proxy_room`).
* **Radar pose**: 1.5 m high (training 1.2 m), 0.55 m off the corridor axis, 0.3 m from the near
  wall, boresight tilted 6 degrees down and turned toward the axis (training: on the axis,
  horizontal).
* **Motion source**: :class:`~radaraug.scene.people.BVHPerson` playing clips of
  :class:`~radaraug.scene.people.sine_gait.SineGait` (a sinusoidal gait with a linear cadence law
  and a larger arm swing) that the generator writes into ``motion/``; training uses the
  Boulic-Thalmann :class:`~radaraug.scene.people.Walker`. No motion capture is used.
* **Body surface**: an effective "clothed body" permittivity ``4.5 - j4.0`` (normal-incidence
  reflectivity -6.8 dB) instead of dry skin ``7.98 - j10.90`` (-4.2 dB): an assumption, inside
  the ~4 dB spread of human RCS.
* **Walks**: several short walks per file (1.6-3.2 s each), 0.5-1.6 m/s toward or away from the
  radar, heights 1.5-1.95 m, from anywhere that keeps the whole walk inside the room and at
  least 1 m in front of the radar; training draws 0.6-1.8 m/s, 1.55-1.95 m, 1-12 m.
* **Receiver** (:func:`proxy_effects`, hardware order): other TX->RX leakage (level, range and
  phase), 3x the RMS LO frequency noise with a wider corner, carried by 16 paths including the 8
  strongest *static room returns* (the training twin puts phase noise on leakage and people
  only), noise figure 9 dB (12), system gain -4 dB (0), an RX gain/phase mismatch (none), a
  233 kHz spur tone at the ADC input (none) and other DC offsets.

Labels: a person counts in a frame when :func:`radaraug.sim.offline.people_inside` puts the body
centre inside the room and it is at least ``MIN_RANGE_M`` in front of the radar along its
horizontal boresight. Walks are drawn so that every frame of a file has the file's count (a walk
that would break this is drawn again), so files work both as ``PATH:COUNT`` and per frame.

Determinism: the walks and noise of count ``c`` depend only on ``(seed, c, frames_per_count,
tracer settings)`` and the device type, so the file of one count is bit-identical whichever
other counts are generated with it. Re-running with the same arguments on a complete output
folder reuses the files (``proxy.json`` is written last and checked).
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import
from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.io.atomic import atomic_write_json
from radaraug.io.blocks import BLOCK_FRAMES, BlockWriter, frame_times
from radaraug.io.generated_set import GeneratedTestSet, check_count_arg, test_file_name
from radaraug.safe_read import load_json
from radaraug.scene.geometry import RadarPose, SceneGeometry
from radaraug.scene.materials import MATERIALS, Material, register_material
from radaraug.scene.room import box, corridor, merge
from radaraug.scene.scene import Scene
from radaraug.sensor.effects import (
    ADCClipping,
    ADCNoise,
    ADCQuantization,
    AntiAliasLowPass,
    DCOffset,
    Effect,
    IFGain,
    IFHighPass,
    PhaseNoise,
    RxGainPhaseMismatch,
    SpurTone,
    SystemGain,
    ThermalNoise,
    TxRxLeakage,
)
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.offline import people_inside
from radaraug.sim.seeding import Stream, item_generator, item_seed
from radaraug.sim.twin import DigitalTwin
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

GENERATOR_VERSION = 3
"""Bumped whenever the generator's output changes; part of the reuse check."""

MANIFEST_NAME = "proxy.json"
MANIFEST_FORMAT = "radaraug-heldout-proxy"
CALIBRATION_NAME = "calibration_empty.h5"
ROOM_SCENE_NAME = "room.json"
MOTION_DIR = "motion"

# ------------------------------------------------------------------------------------- the room
ROOM_SIZE_M = (14.0, 2.6, 3.0)
"""Length (x), width (y), height (z) of the proxy room."""

ROOM_MATERIALS: dict[str, str] = {
    "floor": "concrete",
    "ceiling": "plasterboard",
    "left_wall": "glass",
    "right_wall": "concrete",
    "near_wall": "concrete",
    "far_wall": "wood",
}
ROOM_THICKNESS_M: dict[str, float] = {"ceiling": 0.0125, "far_wall": 0.04}

CLUTTER: tuple[dict[str, Any], ...] = (
    {"name": "metal_cabinet", "material": "metal", "min": (4.5, -1.3, 0.0), "max": (5.0, -0.8, 1.9)},
    {"name": "wooden_bench", "material": "wood", "min": (8.0, 0.9, 0.0), "max": (9.6, 1.3, 0.45)},
    {"name": "concrete_pillar", "material": "concrete", "min": (10.8, -1.3, 0.0), "max": (11.15, -0.95, 3.0)},
)
"""Objects the training corridor lacks: axis-aligned boxes ``min``/``max`` corners in metres."""

RADAR_POSITION_M = (0.3, 0.55, 1.5)
RADAR_TILT_DOWN_DEG = 6.0
RADAR_AIM_XY = (14.0, 0.0)
"""The boresight points at the far wall's centre line, tilted ``RADAR_TILT_DOWN_DEG`` down."""

# ---------------------------------------------------------------------------------------- people
BODY_MATERIAL = Material("proxy_clothed_body", 4.5, 0.0, 0.0, 0.0, eps_complex_override=complex(4.5, -4.0))
"""Effective permittivity of a clothed body (assumed; normal-incidence |Gamma|^2 = -6.8 dB, against
-4.2 dB for the training twin's dry skin)."""

WALK_SPEED_M_S = (0.5, 1.6)
HEIGHT_M = (1.5, 1.95)
LATERAL_M = (-0.5, 0.5)
LATERAL_LIMIT_M = 0.65  # the clutter leaves |y| < 0.75 free
HEADING_JITTER_DEG = 4.0
ARM_SWING = (0.8, 1.2)
WALK_FRAMES = (16, 32)
MIN_WALK_FRAMES = 12
MIN_RANGE_M = 1.0
"""A person counts when at least this far in front of the radar (horizontal boresight)."""
FAR_MARGIN_M = 0.6
MIN_SEPARATION_M = 0.6
WALK_GAP_S = 1.5
FILE_TIME_ORIGIN_S = 1000.0
BVH_FPS = 100.0

# -------------------------------------------------------------------------------------- receiver
STATIC_PHASE_NOISE_PATHS = 8
"""The strongest static room returns that carry phase noise (re-synthesized per frame)."""


def _register_body_material() -> None:
    known = MATERIALS.get(BODY_MATERIAL.name)
    if known is None:
        register_material(BODY_MATERIAL)
    elif known != BODY_MATERIAL:
        raise ConfigError(f"material {BODY_MATERIAL.name!r} is registered with other values")


def proxy_room(max_edge_m: float = 0.5) -> SceneGeometry:
    """The proxy room: the corridor plus the :data:`CLUTTER` boxes, merged.

    The corridor is :data:`ROOM_SIZE_M` / :data:`ROOM_MATERIALS`; object id 0 = walls, 1.. = the objects.
    """
    length, width, height = ROOM_SIZE_M
    walls = corridor(length, width, height, materials=ROOM_MATERIALS, thickness_m=ROOM_THICKNESS_M,
                     max_edge_m=max_edge_m)
    objects = [box(c["min"], c["max"], c["material"], max_edge_m=max_edge_m) for c in CLUTTER]
    return merge([walls, *objects])


def proxy_pose() -> RadarPose:
    """The proxy radar pose (see :data:`RADAR_POSITION_M`)."""
    x, y, z = RADAR_POSITION_M
    dist = math.hypot(RADAR_AIM_XY[0] - x, RADAR_AIM_XY[1] - y)
    target = (RADAR_AIM_XY[0], RADAR_AIM_XY[1], z - dist * math.tan(math.radians(RADAR_TILT_DOWN_DEG)))
    return RadarPose.look_at(RADAR_POSITION_M, target)


def proxy_scene(config: RadarConfig | None = None) -> Scene:
    """The empty proxy room with the radar (``config`` default :meth:`RadarConfig.bgt60tr13c`)."""
    return Scene(room=proxy_room(), radar=proxy_pose(), config=config or RadarConfig.bgt60tr13c(),
                 name="heldout-proxy-room")


def proxy_effects(config: RadarConfig) -> list[Effect]:
    """The proxy receiver's effect chain, in hardware order.

    leakage -> phase noise -> thermal noise -> system gain -> RX gain/phase mismatch -> IF
    high-pass -> IF gain -> ADC-side noise -> anti-alias low-pass -> spur tone -> DC offset -> ADC
    quantization -> ADC clipping. Values are fixed, not fitted to anything (see the module doc).
    Generator version 2: the leakage couplings moved with the library's front-end gain (-20.5 dB)
    so the proxy's leakage keeps its level at the ADC, and the proxy's own ADC-side noise
    (2.2 counts, the default's is 1.75) was added with it.
    """
    return [
        TxRxLeakage(coupling_dB=[-31.5, -40.5, -42.0], range_m=0.07, phase_rad=[0.4, -1.2, 2.0]),
        PhaseNoise(freq_noise_rms_Hz=300e3, corner_Hz=400e3, num_paths=16),
        ThermalNoise(noise_figure_dB=9.0),
        SystemGain(gain_dB=-4.0),
        RxGainPhaseMismatch(gain_dB=[0.0, -1.2, 0.7], phase_rad=[0.0, 0.35, -0.25]),
        IFHighPass(cutoff_Hz=config.effective_hp_cutoff_Hz),
        IFGain(gain_dB=float(config.if_gain_dB)),
        ADCNoise(rms_counts=2.2 * (2**config.adc_bits - 1) / 4095),
        AntiAliasLowPass(cutoff_Hz=config.effective_aaf_cutoff_Hz),
        SpurTone(freq_Hz=233e3, amplitude_counts=[0.4, 0.4, 0.4], phase_rad=0.7),
        DCOffset(level_counts=[1585.0, 1990.0, 2040.0]),
        ADCQuantization(),
        ADCClipping(),
    ]


def proxy_receiver(config: RadarConfig | None = None) -> FMCWReceiver:
    """:class:`FMCWReceiver` with :func:`proxy_effects`."""
    config = config or RadarConfig.bgt60tr13c()
    return FMCWReceiver(config, effects=proxy_effects(config))


# ------------------------------------------------------------------------------------ labelling
def people_in_view(twin: DigitalTwin, people: list[Any], times: torch.Tensor,
                   min_range_m: float = MIN_RANGE_M) -> np.ndarray:
    """Per frame, the people inside the room and at least ``min_range_m`` in front of the radar.

    Inside: the body centre, :func:`people_inside`; in front: along the radar's horizontal boresight.
    """
    counts = np.zeros(len(times), dtype=np.int64)
    pose = twin.scene.radar
    axis = pose.rotation[:, 2].to(torch.float64).clone()
    axis[2] = 0.0
    axis = axis / axis.norm()
    origin = pose.position.to(torch.float64)
    for p in people:
        inside = people_inside(twin, [p], times).astype(bool)
        centre = p.ellipsoids(times.to(torch.float64)).centers.mean(dim=-2)
        ahead = ((centre - origin)[:, :2] @ axis[:2]).numpy() >= min_range_m
        counts += (inside & ahead).astype(np.int64)
    return counts


# ---------------------------------------------------------------------------------------- walks
def _u(g: torch.Generator, lo: float, hi: float) -> float:
    return lo + (hi - lo) * float(torch.rand((), generator=g, dtype=torch.float64))


def _split_frames(g: torch.Generator, total: int) -> list[int]:
    """Walk lengths (frames) adding up to ``total``."""
    out, left = [], total
    while left > 0:
        n = int(torch.randint(WALK_FRAMES[0], WALK_FRAMES[1] + 1, (), generator=g))
        if left - n < MIN_WALK_FRAMES:
            n = left
        out.append(n)
        left -= n
    return out


def _draw_person(g: torch.Generator, duration_s: float, x_lo: float, x_hi: float) -> dict[str, float]:
    """One walker's parameters; its straight path stays in ``[x_lo, x_hi]`` and ``|y| <= LATERAL_LIMIT_M``."""
    for _ in range(200):
        speed = _u(g, *WALK_SPEED_M_S)
        toward = bool(torch.rand((), generator=g) < 0.5)
        jitter = math.radians(_u(g, -HEADING_JITTER_DEG, HEADING_JITTER_DEG))
        heading = (math.pi if toward else 0.0) + jitter
        lateral = _u(g, *LATERAL_M)
        dx, dy = speed * duration_s * math.cos(heading), speed * duration_s * math.sin(heading)
        lo, hi = max(x_lo, x_lo - dx), min(x_hi, x_hi - dx)
        x0 = _u(g, lo, hi) if hi > lo else float("nan")
        params = {
            "speed_m_s": speed, "toward_radar": float(toward), "heading_rad": heading, "start_x_m": x0,
            "start_y_m": lateral, "height_m": _u(g, *HEIGHT_M), "phase": _u(g, 0.0, 1.0),
            "arm_swing": _u(g, *ARM_SWING),
        }
        if hi > lo and abs(lateral + dy) <= LATERAL_LIMIT_M:
            return params
    raise RuntimeError("proxy: could not place a walk inside the room")  # pragma: no cover


def _too_close(a: dict[str, float], b: dict[str, float], duration_s: float) -> bool:
    t = np.linspace(0.0, duration_s, 32)

    def track(p: dict[str, float]) -> np.ndarray:
        v = p["speed_m_s"]
        return np.stack([p["start_x_m"] + v * t * math.cos(p["heading_rad"]),
                         p["start_y_m"] + v * t * math.sin(p["heading_rad"])], axis=1)

    return bool(np.linalg.norm(track(a) - track(b), axis=1).min() < MIN_SEPARATION_M)


def _make_people(params: list[dict[str, float]], motion_dir: Path, stem: str) -> tuple[list[Any], list[str]]:
    from radaraug.scene.people import BVHPerson
    from radaraug.scene.people.sine_gait import SineGait, write_sine_gait_bvh

    people, files = [], []
    for k, p in enumerate(params):
        gait = SineGait(height_m=p["height_m"], speed_m_s=p["speed_m_s"], phase=p["phase"], arm_swing=p["arm_swing"])
        clip = write_sine_gait_bvh(gait, motion_dir / f"{stem}_p{k}.bvh", fps=BVH_FPS)
        person = BVHPerson(clip, start=(p["start_x_m"], p["start_y_m"]), heading_rad=p["heading_rad"], scale=0.01)
        person.material = BODY_MATERIAL.name
        people.append(person)
        files.append(clip.name)
    return people, files


# ---------------------------------------------------------------------------------- the result
#: The generated set (:class:`radaraug.io.generated_set.GeneratedTestSet`, shared by both generators).
ProxySet = GeneratedTestSet


def _training_twin_summary() -> dict[str, Any]:
    from radaraug.sim.scenarios import ScenarioSampler

    s = ScenarioSampler()
    return {
        "scene": "built-in 'corridor' (radaraug/data/scenes/corridor.yaml)",
        "room": "20 m x 2 m x 2.7 m box corridor: floorboard floor, ceiling_board ceiling, plasterboard side "
                "walls, concrete end walls (half-spaces); no furniture",
        "radar": "x = 0.1 m, on the corridor axis, 1.2 m high, boresight horizontal along the axis",
        "people": "Walker (Boulic-Thalmann gait, cycle 1.346 / sqrt(V / leg length) s), dry skin 7.98 - j10.90 "
                  "(|Gamma|^2 -4.2 dB at normal incidence)",
        "scenarios": {"speed_m_s": list(s.speed_m_s), "height_m": list(s.height_m), "range_m": list(s.range_m),
                      "lateral_m": list(s.lateral_m), "heading_jitter_deg": s.heading_jitter_deg},
        "receiver": "radaraug.sensor.defaults.default_effects (phase noise on leakage and people only)",
    }


def _rounded(value: Any, digits: int = 6) -> Any:
    """``value`` with floats rounded to ``digits`` significant digits (float32 noise out of JSON)."""
    if isinstance(value, float):
        return float(f"{value:.{digits}g}")
    if isinstance(value, dict):
        return {k: _rounded(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_rounded(v, digits) for v in value]
    return value


def _effect_differences(config: RadarConfig) -> list[dict[str, Any]]:
    from radaraug.sensor.defaults import default_effects

    train = {e.name: _rounded(e.to_dict()["params"]) for e in default_effects(config)}
    proxy = {e.name: _rounded(e.to_dict()["params"]) for e in proxy_effects(config)}
    out = []
    for name in dict.fromkeys([*proxy, *train]):
        a, b = train.get(name), proxy.get(name)
        if a != b:
            out.append({"effect": name, "training": a, "proxy": b})
    return out


def differences(config: RadarConfig | None = None) -> dict[str, Any]:
    """What the proxy changes against the training twin (the ``differences`` of ``proxy.json``)."""
    config = config or RadarConfig.bgt60tr13c()
    return {
        "room": {"training": "20 m x 2 m x 2.7 m corridor, floorboard / ceiling_board / plasterboard / concrete, "
                             "no clutter",
                 "proxy": {"size_m": list(ROOM_SIZE_M), "materials": ROOM_MATERIALS,
                           "slab_thickness_m": ROOM_THICKNESS_M,
                           "clutter": [{**c, "min": list(c["min"]), "max": list(c["max"])} for c in CLUTTER]}},
        "radar_pose": {"training": {"position_m": [0.1, 0.0, 1.2], "boresight": "horizontal, along the axis"},
                       "proxy": {"position_m": list(RADAR_POSITION_M), "tilt_down_deg": RADAR_TILT_DOWN_DEG,
                                 "aimed_at_xy_m": list(RADAR_AIM_XY)}},
        "motion_source": {"training": "Walker (Boulic-Thalmann)",
                          "proxy": "BVHPerson playing SineGait clips written by radaraug (see motion/)"},
        "body_surface": {"training": "skin, eps 7.98 - j10.90, |Gamma|^2 -4.2 dB",
                         "proxy": f"{BODY_MATERIAL.name}, eps 4.5 - j4.0, |Gamma|^2 -6.8 dB (assumed)"},
        "walks": {"training": "ScenarioSampler: 0.6-1.8 m/s, 1.55-1.95 m, start 1-12 m, lateral +-0.6 m, "
                              "jitter +-5 deg",
                  "proxy": {"speed_m_s": list(WALK_SPEED_M_S), "height_m": list(HEIGHT_M),
                            "lateral_m": list(LATERAL_M), "heading_jitter_deg": HEADING_JITTER_DEG,
                            "walk_frames": list(WALK_FRAMES), "min_range_m": MIN_RANGE_M,
                            "min_separation_m": MIN_SEPARATION_M}},
        "phase_noise_on_static_clutter": {"training": 0, "proxy": STATIC_PHASE_NOISE_PATHS},
        "receiver_effects": _effect_differences(config),
    }


# --------------------------------------------------------------------------------- generation
def _settings(frames_per_count: int, calibration_frames: int, seed: int, counts: tuple[int, ...],
              device_type: str, tracer_options: dict[str, Any]) -> dict[str, Any]:
    return json.loads(json.dumps({
        "generator_version": GENERATOR_VERSION, "frames_per_count": frames_per_count,
        "calibration_frames": calibration_frames, "seed": seed, "counts": list(counts),
        "device_type": device_type, "tracer_options": tracer_options,
    }))


def load_proxy(out_dir: str | os.PathLike) -> ProxySet:
    """The :class:`ProxySet` described by ``out_dir/proxy.json`` (files checked to exist).

    Raises:
        ConfigError: no readable manifest, or a file it lists is missing.
    """
    out = Path(out_dir)
    path = out / MANIFEST_NAME
    try:
        data = load_json(path, error=ConfigError, what="proxy manifest")
    except ConfigError as err:
        raise ConfigError(f"{path}: no readable proxy manifest ({err})") from None
    if not isinstance(data, dict) or data.get("format") != MANIFEST_FORMAT:
        raise ConfigError(f"{path}: not a radaraug proxy manifest")
    files = data["files"]
    cal = out / files["calibration"]["path"]
    tests = [(out / t["path"], int(t["count"])) for t in files["tests"]]
    for p in [cal, *(p for p, _ in tests)]:
        if not p.is_file():
            raise ConfigError(f"{path}: lists {p.name}, which is missing")
    return ProxySet(cal, tests, RadarConfig.from_dict(data["config"]), manifest=path)


def _reusable(out: Path, settings: dict[str, Any]) -> ProxySet | None:
    """The existing set when ``out`` holds a complete one made with ``settings``."""
    from radaraug.io import open_capture

    try:
        data = load_json(out / MANIFEST_NAME, error=ConfigError, what="proxy manifest")
        if data.get("format") != MANIFEST_FORMAT or data.get("settings") != settings:
            return None
        found = load_proxy(out)
        expected = [(found.calibration, settings["calibration_frames"])]
        expected += [(p, settings["frames_per_count"]) for p, _ in found.tests]
        for p, n in expected:
            with open_capture(p) as cap:
                if cap.num_frames != n or cap.config != RadarConfig.bgt60tr13c():
                    return None
        for name in data["files"].get("motion", []):
            if not (out / MOTION_DIR / name).is_file():
                return None
    except Exception:  # noqa: BLE001 - anything unreadable means: generate again
        return None
    found.reused = True
    return found


class _Simulator:
    """One twin for every file: the room is traced once.

    The strongest static returns are kept apart so that phase noise modulates them (re-synthesized with
    every frame).
    """

    def __init__(self, device: str, tracer_options: dict[str, Any]) -> None:
        config = RadarConfig.bgt60tr13c()
        self.scene = proxy_scene(config)
        self.device = torch.device(device)
        receiver = proxy_receiver(config)
        self.twin = DigitalTwin(self.scene, receiver=receiver, tracer_options=tracer_options, device=self.device)
        static = self.twin.tracer.static_paths()
        k = min(STATIC_PHASE_NOISE_PATHS, static.num_paths)
        strength = (static.amplitude.abs() * static.delay_s.abs()).amax(dim=-1)
        strong = torch.topk(strength, k).indices if k else torch.zeros(0, dtype=torch.long, device=self.device)
        rest = torch.ones(static.num_paths, dtype=torch.bool, device=self.device)
        rest[strong] = False
        self.strong = static.map(lambda x: x[strong])
        self.static_signal = self.twin.receiver.static_signal(static.map(lambda x: x[rest]))
        self.period = config.frame_repetition_time_s

    def frames(self, people: list[Any], local_t: torch.Tensor, global_t: torch.Tensor,
               generator: torch.Generator) -> np.ndarray:
        """ADC counts ``(T, rx, chirps, samples)`` uint16."""
        with torch.no_grad():
            moving = self.twin.frame_paths(people, local_t)
            paths = _with_static(moving, self.strong)
            x = self.twin.receiver(paths, generator=generator, static_signal=self.static_signal,
                                   frame_start_s=global_t.to(device=self.device, dtype=torch.float64))
            return self.twin.receiver.to_counts(x).cpu().numpy()


def _with_static(moving: Paths, strong: Paths) -> Paths:
    """``moving`` ``(T, P, RX)`` with the static ``strong`` ``(K, RX)`` appended to every frame."""
    t = moving.delay_s.shape[0]
    k = strong.delay_s.shape[0]
    dev = moving.delay_s.device
    s = strong.map(lambda x: x.expand(t, *x.shape))
    kind_m = moving.kind if moving.kind is not None else torch.zeros(moving.delay_s.shape[:-1], dtype=torch.int8,
                                                                        device=dev)
    kind_s = s.kind if s.kind is not None else torch.zeros(t, k, dtype=torch.int8, device=dev)
    mask_m = moving.mask if moving.mask is not None else torch.ones(moving.delay_s.shape[:-1], dtype=torch.bool,
                                                                    device=dev)
    # Paths.cat keeps the moving paths' per-chirp delays and gains (static ones get none).
    return Paths.cat([
        Paths(moving.delay_s, moving.delay_rate, moving.amplitude, kind_m.to(torch.int8), mask_m,
              moving.chirp_delay_s, moving.chirp_gain),
        Paths(s.delay_s.to(moving.delay_s.dtype), s.delay_rate.to(moving.delay_rate.dtype),
              s.amplitude.to(moving.amplitude.dtype), kind_s.to(torch.int8),
              torch.ones(t, k, dtype=torch.bool, device=dev)),
    ])


def _write_file(sim: _Simulator, path: Path, walks: list[dict[str, Any]], noise_base: int, attrs: dict[str, Any],
                device: str, bar: Any) -> None:
    """Simulate ``walks`` (each ``{"people", "frames", "t0"}``) into ``path``.

    The file appears under its name only complete (``publish="close"``): a killed run leaves the
    hidden temporary of :class:`~radaraug.io.CaptureWriter`, which a later writer of ``path``
    removes, and a file already at ``path`` (an earlier run's) stays until the new one replaces it.
    """
    path.with_name(path.stem + ".partial.h5").unlink(missing_ok=True)  # the temporary name of older versions
    block = 0
    with BlockWriter.create(path, sim.twin.config, attrs=attrs, publish="close") as writer:
        for walk in walks:
            for a in range(0, walk["frames"], BLOCK_FRAMES):
                b = min(a + BLOCK_FRAMES, walk["frames"])
                local = frame_times(a, b, sim.period)
                glob = walk["t0"] + local
                gen = item_generator(noise_base, block, stream=Stream.BLOCK_NOISE, device=device)
                counts = sim.frames(walk["people"], local, glob, gen)
                writer.write(counts, glob, walk["labels"][a:b])
                block += 1
                bar.update(b - a)


def _plan_walks(sim: _Simulator, count: int, frames: int, seed: int, motion_dir: Path) -> list[dict[str, Any]]:
    """Draw the walks of the file of ``count`` people (labels checked against ``count``)."""
    g = torch.Generator().manual_seed(item_seed(seed, count + 1, stream=Stream.PROXY_WALKS))
    x_lo = RADAR_POSITION_M[0] + MIN_RANGE_M + 0.3
    x_hi = ROOM_SIZE_M[0] - FAR_MARGIN_M
    walks, t_start = [], FILE_TIME_ORIGIN_S * (count + 1)
    for j, n in enumerate(_split_frames(g, frames)):
        duration = n * sim.period
        local = torch.arange(n, dtype=torch.float64) * sim.period
        for _attempt in range(100):
            params: list[dict[str, float]] = []
            while len(params) < count:
                p = _draw_person(g, duration, x_lo, x_hi)
                if all(not _too_close(p, q, duration) for q in params):
                    params.append(p)
            people, files = _make_people(params, motion_dir, f"count{count}_walk{j:02d}")
            labels = people_in_view(sim.twin, people, local)
            if bool((labels == count).all()):
                break
        else:  # pragma: no cover - the draw keeps walks in view by construction
            raise RuntimeError(f"proxy: could not draw a walk with {count} people in view")
        walks.append({"people": people, "frames": n, "t0": t_start, "labels": labels,
                      "params": params, "motion": files})
        t_start += duration + WALK_GAP_S
    return walks


def make_proxy(
    out_dir: str | os.PathLike,
    *,
    frames_per_count: int = 120,
    calibration_frames: int = 100,
    seed: int = 1234,
    counts: tuple[int, ...] = (0, 1, 2),
    progress: bool = True,
    device: str | torch.device = "cpu",
    tracer_options: dict[str, Any] | None = None,
) -> ProxySet:
    """Generate (or reuse) the held-out proxy set in ``out_dir``.

    Args:
        out_dir: output folder (created); the generator owns the names it writes there
            (``calibration_empty.h5``, ``test_count<c>.h5``, ``motion/``, ``room.json``, ``proxy.json``).
        frames_per_count: frames of each test file (several short walks, 10 frames/s).
        calibration_frames: frames of the empty-room capture (100 = the paper's 10 s).
        seed: seed of the walks and of the receiver noise.
        counts: people counts to generate, one test file each (0, 1 and/or 2).
        progress: show a progress bar (tqdm, frames).
        device: where to simulate (files are reproducible per device type).
        tracer_options: keyword arguments of :class:`~radaraug.raytrace.RayTracer` for the room's
            trace (default: the image method, no options).

    Returns:
        The :class:`ProxySet`.

    Raises:
        ConfigError: bad sizes, counts, seed or device.
    """
    frames_per_count = check_count_arg("make_proxy", "frames_per_count", frames_per_count, 1)
    calibration_frames = check_count_arg("make_proxy", "calibration_frames", calibration_frames, 1)
    seed = check_count_arg("make_proxy", "seed", seed, 0)
    counts = tuple(counts)
    if not counts or len(set(counts)) != len(counts) or any(
            isinstance(c, bool) or not isinstance(c, (int, np.integer)) or c not in (0, 1, 2) for c in counts):
        raise ConfigError(f"make_proxy: counts must be distinct values among 0, 1, 2, got {counts!r}")
    counts = tuple(int(c) for c in counts)
    try:
        device_type = torch.device(device).type
    except (RuntimeError, TypeError):
        raise ConfigError(f"make_proxy: device {device!r} is not a torch device") from None
    tracer_options = dict(tracer_options or {})
    settings = _settings(frames_per_count, calibration_frames, seed, counts, device_type, tracer_options)
    out = Path(out_dir)
    found = _reusable(out, settings)
    if found is not None:
        return found

    _register_body_material()
    # One intra-op thread: the per-frame kernels are small, and several threads contend (measured
    # several times slower on a loaded 2-core machine). Restored on return.
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        return _generate(out, settings, frames_per_count, calibration_frames, seed, counts, progress, str(device),
                         tracer_options)
    finally:
        torch.set_num_threads(threads)


def _generate(out: Path, settings: dict[str, Any], frames_per_count: int, calibration_frames: int, seed: int,
              counts: tuple[int, ...], progress: bool, device: str, tracer_options: dict[str, Any]) -> ProxySet:
    started = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    manifest_path = out / MANIFEST_NAME
    if manifest_path.exists():
        manifest_path.unlink()  # the set is incomplete until a new manifest is written
    motion_dir = out / MOTION_DIR
    motion_dir.mkdir(exist_ok=True)

    sim = _Simulator(device, tracer_options)
    config = sim.twin.config
    sim.scene.save(out / ROOM_SCENE_NAME)
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

    total = calibration_frames + frames_per_count * len(counts)
    common = {"source": "radaraug held-out proxy generator (radaraug.sim.proxy)",
              "generator_version": GENERATOR_VERSION, "seed": seed,
              "note": "simulated held-out proxy: numbers on it are sim-to-proxy, not sim-to-real"}
    files: dict[str, Any] = {"motion": []}
    with tqdm(total=total, desc="proxy", unit="frame", disable=not progress) as bar:
        # Empty-room calibration capture: consecutive frames from t = 0.
        cal_walk = {"people": [], "frames": calibration_frames, "t0": 0.0,
                    "labels": np.zeros(calibration_frames, dtype=np.int64)}
        cal_path = out / CALIBRATION_NAME
        _write_file(sim, cal_path, [cal_walk], item_seed(seed, 0, stream=Stream.PROXY_NOISE),
                    {**common, "description": "held-out proxy: empty room, for CalibratedDR.fit", "role": "calibration",
                     "labels": {"count": 0}}, device, bar)
        files["calibration"] = {"path": CALIBRATION_NAME, "frames": calibration_frames, "count": 0}
        tests: list[tuple[Path, int]] = []
        files["tests"] = []
        for c in counts:
            walks = _plan_walks(sim, c, frames_per_count, seed, motion_dir)
            desc = [{"frames": w["frames"], "t0_s": round(w["t0"], 6), "people": _rounded(w["params"], 5),
                     "motion": w["motion"]} for w in walks]
            path = out / test_file_name(c)
            _write_file(sim, path, walks, item_seed(seed, c + 1, stream=Stream.PROXY_NOISE),
                        {**common, "description": f"held-out proxy: {c} walking people in every frame",
                         "role": "test", "labels": {"count": c}, "walks": desc}, device, bar)
            tests.append((path, c))
            files["tests"].append({"path": path.name, "frames": frames_per_count, "count": c, "walks": desc})
            files["motion"] += [m for w in walks for m in w["motion"]]
    elapsed = time.perf_counter() - started
    manifest = {
        "format": MANIFEST_FORMAT,
        "settings": settings,
        "statement": "A held-out proxy made by radaraug from a deliberately different twin configuration. "
                     "Accuracy on it is sim-to-proxy, not sim-to-real. Its settings are fixed; do not tune "
                     "them to make a method look good.",
        "config": config.to_dict(),
        "files": files,
        "room_scene": ROOM_SCENE_NAME,
        "label_rule": f"count = people whose body centre is inside the room and >= {MIN_RANGE_M} m in front "
                      "of the radar; every frame of a test file has the file's count",
        "dsp_chain_expected": "RangeDoppler() -> ToDecibels() (the chain CalibratedDR is fitted with)",
        "receiver": _rounded(sim.twin.receiver.to_dict()),
        "differences": differences(config),
        "training_twin": _training_twin_summary(),
        "float_convention": FLOAT_CONVENTION,
        "db_convention": DB_CONVENTION,
        "licence": "generated by radaraug, MIT",
        "generation_s": round(elapsed, 2),
    }
    atomic_write_json(manifest_path, manifest, indent=2)
    return ProxySet(cal_path, tests, config, manifest=manifest_path, generation_s=elapsed)


__all__ = [
    "BODY_MATERIAL", "CLUTTER", "ProxySet", "differences", "load_proxy", "make_proxy", "people_in_view",
    "proxy_effects", "proxy_pose", "proxy_receiver", "proxy_room", "proxy_scene",
]
