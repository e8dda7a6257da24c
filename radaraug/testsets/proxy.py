"""The held-out proxy test set: labelled captures from a twin configuration training was *not* made with.

:func:`make_proxy` writes captures of 0, 1 and 2 walking people (per-frame ``count`` and ``occupancy``
labels) and an empty-room calibration capture, simulated by the shared twin from the data file
:data:`SPEC_PATH` (another room, radar pose, motion source, body surface and receiver). Numbers on it
are sim-to-proxy, not sim-to-real, and its settings are not to be tuned. See docs/proxy.md.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import os
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch
import yaml

from radaraug._optional import lazy_import
from radaraug._torch import parse_device, torch_threads
from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.files import atomic_write_json
from radaraug.io.blocks import BLOCK_FRAMES, BlockWriter
from radaraug.scene.geometry import RadarPose, SceneGeometry
from radaraug.scene.materials import Material
from radaraug.scene.room import box, merge
from radaraug.scene.scene import Scene
from radaraug.sensor.effects import Effect, effect_from_dict
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.offline import people_inside, simulate_frames
from radaraug.sim.randomization import ItemDraw
from radaraug.sim.scenarios import ScenarioSampler, _uniform
from radaraug.sim.seeding import Stream, item_seed
from radaraug.sim.twin import DigitalTwin
from radaraug.testsets.generated import (
    GeneratedTestSet,
    check_count_arg,
    check_people_counts,
    load_generated_set,
    reusable_generated_set,
    start_generated_set,
    test_file_name,
)
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

SPEC_PATH = Path(__file__).resolve().parents[1] / "data" / "proxy.yaml"
"""What the proxy simulates (shipped with the package)."""


def _load_spec(path: Path) -> dict[str, Any]:
    try:
        spec = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, yaml.YAMLError) as err:
        raise ConfigError(f"{path}: cannot read the proxy description ({err})") from None
    keys = set(spec) if isinstance(spec, dict) else set()
    missing = {"generator_version", "scene", "aim", "clutter", "people", "walks", "receiver"} - keys
    if missing:
        raise ConfigError(f"{path}: the proxy description lacks {sorted(missing)}")
    return spec


SPEC = _load_spec(SPEC_PATH)
GENERATOR_VERSION: int = SPEC["generator_version"]
"""Bumped (in the data file) whenever the generator's output changes; part of the reuse check."""

MANIFEST_NAME = "proxy.json"
MANIFEST_FORMAT = "radaraug-heldout-proxy"
CALIBRATION_NAME = "calibration_empty.h5"
ROOM_SCENE_NAME = "room.json"
MOTION_DIR = "motion"

CLUTTER: tuple[dict[str, Any], ...] = tuple(SPEC["clutter"])
"""Objects the training corridor lacks: axis-aligned boxes ``min``/``max`` corners in metres."""
_PEOPLE, _WALKS = SPEC["people"], SPEC["walks"]
_BODY_EPS = SPEC["scene"]["materials"][_PEOPLE["material"]]["eps"]
BODY_MATERIAL = Material(_PEOPLE["material"], _BODY_EPS[0], 0.0, 0.0, 0.0,
                         eps_complex_override=complex(*_BODY_EPS))
"""Effective permittivity of a clothed body (assumed; the scene registers it when loaded)."""


def proxy_room(max_edge_m: float = 0.5) -> SceneGeometry:
    """The proxy room: the scene's corridor plus the :data:`CLUTTER` boxes, merged (object id 0: walls)."""
    return proxy_scene(max_edge_m=max_edge_m).room


def proxy_pose() -> RadarPose:
    """The proxy radar pose (the data file's ``scene.radar`` and ``aim``)."""
    return proxy_scene().radar


def proxy_scene(config: RadarConfig | None = None, *, max_edge_m: float | None = None) -> Scene:
    """The empty proxy room with the radar (``config`` default: the data file's); registers the body material."""
    spec = copy.deepcopy(SPEC["scene"])
    if max_edge_m is not None:
        spec["room"]["max_edge"] = max_edge_m
    radar, aim = spec["radar"], SPEC["aim"]
    x, y, z = radar["position"]
    (ax, ay), tilt = aim["at_xy_m"], aim["tilt_down_deg"]
    radar["look_at"] = [ax, ay, z - math.hypot(ax - x, ay - y) * math.tan(math.radians(tilt))]
    scene = Scene.from_dict(spec, source=SPEC_PATH)
    edge = spec["room"]["max_edge"]
    room = merge([scene.room, *(box(c["min"], c["max"], c["material"], max_edge_m=edge) for c in CLUTTER)])
    return dataclasses.replace(scene, room=room, room_spec=None, config=config or scene.config)


_FROM_CONFIG = {"if_highpass": lambda c: c.effective_hp_cutoff_Hz, "if_gain": lambda c: float(c.if_gain_dB),
                "anti_alias_lowpass": lambda c: c.effective_aaf_cutoff_Hz}


def proxy_effects(config: RadarConfig) -> list[Effect]:
    """The proxy receiver's effect chain, in hardware order (the data file's ``receiver.effects``).

    Values are fixed, not fitted; a ``"config"`` parameter comes from ``config``, and the ADC-side
    noise (12-bit counts) is scaled to its ADC.
    """
    out = []
    for e in SPEC["receiver"]["effects"]:
        params = {k: _FROM_CONFIG[e["name"]](config) if v == "config" else v for k, v in e.get("params", {}).items()}
        if e["name"] == "adc_noise":
            params["rms_counts"] = params["rms_counts"] * (2**config.adc_bits - 1) / 4095
        out.append(effect_from_dict({"name": e["name"], "params": params}))
    return out


def proxy_receiver(config: RadarConfig | None = None) -> FMCWReceiver:
    """:class:`FMCWReceiver` with :func:`proxy_effects`."""
    config = config or RadarConfig.bgt60tr13c()
    return FMCWReceiver(config, effects=proxy_effects(config))


def proxy_draw() -> ItemDraw:
    """What the proxy changes in :meth:`DigitalTwin.simulate`: phase noise on the room's strongest returns."""
    return ItemDraw(variant=0, system_gain_offset_dB=0.0, noise_figure_offset_dB=0.0, rcs_scale_dB=(),
                    catalog={"static_phase_noise": {"paths": int(SPEC["receiver"]["static_phase_noise_paths"])}})


# ------------------------------------------------------------------------------------ labelling
def people_in_view(twin: DigitalTwin, people: list[Any], times: torch.Tensor,
                   min_range_m: float = _PEOPLE["min_range_m"]) -> np.ndarray:
    """Per frame, the people inside the room (:func:`people_inside`) and ``min_range_m`` in front of the radar."""
    return people_inside(twin, people, times, min_range_m=min_range_m)


# ---------------------------------------------------------------------------------------- walks
def _split_frames(g: torch.Generator, total: int) -> list[int]:
    """Walk lengths (frames) adding up to ``total``."""
    out, left = [], total
    while left > 0:
        n = int(torch.randint(_WALKS["frames"][0], _WALKS["frames"][1] + 1, (), generator=g))
        if left - n < _WALKS["min_frames"]:
            n = left
        out.append(n)
        left -= n
    return out


def _draw_person(g: torch.Generator, duration_s: float, x_lo: float, x_hi: float) -> dict[str, float]:
    """One walker's parameters; its straight path stays in ``[x_lo, x_hi]`` and ``|y| <= lateral_limit_m``."""
    p = _PEOPLE
    for _ in range(200):
        speed = _uniform(p["speed_m_s"], g)
        toward = bool(torch.rand((), generator=g) < 0.5)
        jitter = math.radians(_uniform((-p["heading_jitter_deg"], p["heading_jitter_deg"]), g))
        heading = (math.pi if toward else 0.0) + jitter
        lateral = _uniform(p["lateral_m"], g)
        dx, dy = speed * duration_s * math.cos(heading), speed * duration_s * math.sin(heading)
        lo, hi = max(x_lo, x_lo - dx), min(x_hi, x_hi - dx)
        x0 = _uniform((lo, hi), g) if hi > lo else float("nan")
        params = {
            "speed_m_s": speed, "toward_radar": float(toward), "heading_rad": heading, "start_x_m": x0,
            "start_y_m": lateral, "height_m": _uniform(p["height_m"], g), "phase": _uniform((0.0, 1.0), g),
            "arm_swing": _uniform(p["arm_swing"], g),
        }
        if hi > lo and abs(lateral + dy) <= p["lateral_limit_m"]:
            return params
    raise RuntimeError("proxy: could not place a walk inside the room")  # pragma: no cover


def _too_close(a: dict[str, float], b: dict[str, float], duration_s: float) -> bool:
    t = np.linspace(0.0, duration_s, 32)

    def track(p: dict[str, float]) -> np.ndarray:
        v = p["speed_m_s"]
        return np.stack([p["start_x_m"] + v * t * math.cos(p["heading_rad"]),
                         p["start_y_m"] + v * t * math.sin(p["heading_rad"])], axis=1)

    return bool(np.linalg.norm(track(a) - track(b), axis=1).min() < _PEOPLE["min_separation_m"])


def _make_people(params: list[dict[str, float]], motion_dir: Path, stem: str) -> tuple[list[Any], list[str]]:
    from radaraug.scene.people import BVHPerson
    from radaraug.scene.people.sine_gait import SineGait, write_sine_gait_bvh

    people, files = [], []
    for k, p in enumerate(params):
        gait = SineGait(height_m=p["height_m"], speed_m_s=p["speed_m_s"], phase=p["phase"], arm_swing=p["arm_swing"])
        clip = write_sine_gait_bvh(gait, motion_dir / f"{stem}_p{k}.bvh", fps=_PEOPLE["bvh_fps"])
        person = BVHPerson(clip, start=(p["start_x_m"], p["start_y_m"]), heading_rad=p["heading_rad"], scale=0.01)
        person.material = _PEOPLE["material"]
        people.append(person)
        files.append(clip.name)
    return people, files


# ---------------------------------------------------------------------------------- the result
#: The generated set (:class:`radaraug.testsets.generated.GeneratedTestSet`, shared by both generators).
ProxySet = GeneratedTestSet


def _training_twin_summary() -> dict[str, Any]:
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
    return [{"effect": name, "training": train.get(name), "proxy": proxy.get(name)}
            for name in dict.fromkeys([*proxy, *train]) if train.get(name) != proxy.get(name)]


def differences(config: RadarConfig | None = None) -> dict[str, Any]:
    """What the proxy changes against the training twin (the ``differences`` of ``proxy.json``)."""
    config = config or RadarConfig.bgt60tr13c()
    room = SPEC["scene"]["room"]
    return {
        "room": {"training": "20 m x 2 m x 2.7 m corridor, floorboard / ceiling_board / plasterboard / concrete, "
                             "no clutter",
                 "proxy": {"size_m": [room["length"], room["width"], room["height"]], "materials": room["materials"],
                           "slab_thickness_m": room["thickness"],
                           "clutter": [{**c, "min": list(c["min"]), "max": list(c["max"])} for c in CLUTTER]}},
        "radar_pose": {"training": {"position_m": [0.1, 0.0, 1.2], "boresight": "horizontal, along the axis"},
                       "proxy": {"position_m": SPEC["scene"]["radar"]["position"],
                                 "tilt_down_deg": SPEC["aim"]["tilt_down_deg"], "aimed_at_xy_m": SPEC["aim"]["at_xy_m"]}},
        "motion_source": {"training": "Walker (Boulic-Thalmann)",
                          "proxy": "BVHPerson playing SineGait clips written by radaraug (see motion/)"},
        "body_surface": {"training": "skin, eps 7.98 - j10.90, |Gamma|^2 -4.2 dB",
                         "proxy": f"{BODY_MATERIAL.name}, eps 4.5 - j4.0, |Gamma|^2 -6.8 dB (assumed)"},
        "walks": {"training": "ScenarioSampler: 0.6-1.8 m/s, 1.55-1.95 m, start 1-12 m, lateral +-0.6 m, "
                              "jitter +-5 deg",
                  "proxy": {**{k: _PEOPLE[k] for k in ("speed_m_s", "height_m", "lateral_m", "heading_jitter_deg")},
                            "walk_frames": _WALKS["frames"], "min_range_m": _PEOPLE["min_range_m"],
                            "min_separation_m": _PEOPLE["min_separation_m"]}},
        "phase_noise_on_static_clutter": {"training": 0, "proxy": SPEC["receiver"]["static_phase_noise_paths"]},
        "receiver_effects": _effect_differences(config),
    }


# --------------------------------------------------------------------------------- generation
def load_proxy(out_dir: str | os.PathLike) -> ProxySet:
    """The :class:`ProxySet` described by ``out_dir/proxy.json`` (files checked to exist).

    Raises:
        ConfigError: no readable manifest, or a file it lists is missing.
    """
    return load_generated_set(out_dir, MANIFEST_NAME, MANIFEST_FORMAT, "proxy manifest")[0]


def _reusable(out: Path, settings: dict[str, Any]) -> ProxySet | None:
    """The existing set when ``out`` holds a complete one made with ``settings`` (its motion files too)."""
    reused = reusable_generated_set(out, MANIFEST_NAME, MANIFEST_FORMAT, settings, RadarConfig.bgt60tr13c())
    if reused is None:
        return None
    found, data = reused
    motion = data["files"].get("motion", [])
    return found if isinstance(motion, list) and all((out / MOTION_DIR / str(n)).is_file() for n in motion) else None


def _write_file(twin: DigitalTwin, path: Path, walks: list[dict[str, Any]], noise_base: int, attrs: dict[str, Any],
                device: str, bar: Any) -> None:
    """Simulate ``walks`` (each ``{"people", "frames", "t0", "labels"}``) into ``path``, :data:`BLOCK_FRAMES` at a time.

    Each walk's people move from its time 0, the recording's time is ``t0`` later. The file appears
    under its name only complete (``publish="close"``; docs/proxy.md, "Crash safety").
    """
    path.with_name(path.stem + ".partial.h5").unlink(missing_ok=True)  # the temporary name of older versions
    draw, block = proxy_draw(), 0
    with BlockWriter.create(path, twin.config, attrs=attrs, publish="close") as writer:
        for walk in walks:
            for a in range(0, walk["frames"], BLOCK_FRAMES):
                b = min(a + BLOCK_FRAMES, walk["frames"])
                local, x = simulate_frames(twin, walk["people"], a, b, noise_base, block, device, draw=draw,
                                           t0=walk["t0"])
                writer.write(twin.receiver.to_counts(x).cpu().numpy(), walk["t0"] + local, walk["labels"][a:b])
                block += 1
                bar.update(b - a)


def _plan_walks(twin: DigitalTwin, count: int, frames: int, seed: int, motion_dir: Path) -> list[dict[str, Any]]:
    """Draw the walks of the file of ``count`` people (labels checked against ``count``)."""
    g = torch.Generator().manual_seed(item_seed(seed, count + 1, stream=Stream.PROXY_WALKS))
    period = twin.config.frame_repetition_time_s
    x_lo = SPEC["scene"]["radar"]["position"][0] + _PEOPLE["min_range_m"] + _PEOPLE["near_margin_m"]
    x_hi = SPEC["scene"]["room"]["length"] - _PEOPLE["far_margin_m"]
    walks, t_start = [], _WALKS["file_time_origin_s"] * (count + 1)
    for j, n in enumerate(_split_frames(g, frames)):
        duration = n * period
        local = torch.arange(n, dtype=torch.float64) * period
        for _attempt in range(100):
            params: list[dict[str, float]] = []
            while len(params) < count:
                p = _draw_person(g, duration, x_lo, x_hi)
                if all(not _too_close(p, q, duration) for q in params):
                    params.append(p)
            people, files = _make_people(params, motion_dir, f"count{count}_walk{j:02d}")
            labels = people_in_view(twin, people, local)
            if bool((labels == count).all()):
                break
        else:  # pragma: no cover - the draw keeps walks in view by construction
            raise RuntimeError(f"proxy: could not draw a walk with {count} people in view")
        walks.append({"people": people, "frames": n, "t0": t_start, "labels": labels,
                      "params": params, "motion": files})
        t_start += duration + _WALKS["gap_s"]
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
        out_dir: output folder (created); the generator owns the names it writes there (docs/proxy.md).
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
    counts = check_people_counts("make_proxy", counts)
    device_type = parse_device(device, "make_proxy: device").type
    tracer_options = dict(tracer_options or {})
    settings = json.loads(json.dumps({
        "generator_version": GENERATOR_VERSION, "frames_per_count": frames_per_count,
        "calibration_frames": calibration_frames, "seed": seed, "counts": list(counts),
        "device_type": device_type, "tracer_options": tracer_options,
    }))
    out = Path(out_dir)
    found = _reusable(out, settings)
    if found is not None:
        return found

    # One intra-op thread: the per-frame kernels are small, and several threads contend (measured
    # several times slower on a loaded 2-core machine). Restored on return.
    with torch_threads(1):
        return _generate(out, settings, frames_per_count, calibration_frames, seed, counts, progress, str(device),
                         tracer_options)


def _generate(out: Path, settings: dict[str, Any], frames_per_count: int, calibration_frames: int, seed: int,
              counts: tuple[int, ...], progress: bool, device: str, tracer_options: dict[str, Any]) -> ProxySet:
    started = time.perf_counter()
    manifest_path = start_generated_set(out, MANIFEST_NAME)
    motion_dir = out / MOTION_DIR
    motion_dir.mkdir(exist_ok=True)

    scene = proxy_scene()
    # One twin for every file (the room is traced once).
    twin = DigitalTwin(scene, receiver=proxy_receiver(scene.config), tracer_options=tracer_options,
                       device=torch.device(device))
    config = twin.config
    scene.save(out / ROOM_SCENE_NAME)
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

    total = calibration_frames + frames_per_count * len(counts)
    common = {"source": "radaraug held-out proxy generator (radaraug.testsets.proxy)",
              "generator_version": GENERATOR_VERSION, "seed": seed,
              "note": "simulated held-out proxy: numbers on it are sim-to-proxy, not sim-to-real"}
    files: dict[str, Any] = {"motion": []}
    with tqdm(total=total, desc="proxy", unit="frame", disable=not progress) as bar:
        # Empty-room calibration capture: consecutive frames from t = 0.
        cal_walk = {"people": [], "frames": calibration_frames, "t0": 0.0,
                    "labels": np.zeros(calibration_frames, dtype=np.int64)}
        cal_path = out / CALIBRATION_NAME
        _write_file(twin, cal_path, [cal_walk], item_seed(seed, 0, stream=Stream.PROXY_NOISE),
                    {**common, "description": "held-out proxy: empty room, for CalibratedDR.fit", "role": "calibration",
                     "labels": {"count": 0}}, device, bar)
        files["calibration"] = {"path": CALIBRATION_NAME, "frames": calibration_frames, "count": 0}
        files["tests"] = []
        for c in counts:
            walks = _plan_walks(twin, c, frames_per_count, seed, motion_dir)
            desc = [{"frames": w["frames"], "t0_s": round(w["t0"], 6), "people": _rounded(w["params"], 5),
                     "motion": w["motion"]} for w in walks]
            path = out / test_file_name(c)
            _write_file(twin, path, walks, item_seed(seed, c + 1, stream=Stream.PROXY_NOISE),
                        {**common, "description": f"held-out proxy: {c} walking people in every frame",
                         "role": "test", "labels": {"count": c}, "walks": desc}, device, bar)
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
        "label_rule": f"count = people whose body centre is inside the room and >= {_PEOPLE['min_range_m']} m in front "
                      "of the radar; every frame of a test file has the file's count",
        "dsp_chain_expected": "RangeDoppler() -> ToDecibels() (the chain CalibratedDR is fitted with)",
        "receiver": _rounded(twin.receiver.to_dict()),
        "differences": differences(config),
        "training_twin": _training_twin_summary(),
        "float_convention": FLOAT_CONVENTION,
        "db_convention": DB_CONVENTION,
        "licence": "generated by radaraug, MIT",
        "generation_s": round(elapsed, 2),
    }
    atomic_write_json(manifest_path, manifest, indent=2)
    tests = [(out / t["path"], t["count"]) for t in files["tests"]]
    return ProxySet(cal_path, tests, config, manifest=manifest_path, generation_s=elapsed)


__all__ = [
    "BODY_MATERIAL", "CLUTTER", "ProxySet", "differences", "load_proxy", "make_proxy", "people_in_view",
    "proxy_draw", "proxy_effects", "proxy_pose", "proxy_receiver", "proxy_room", "proxy_scene",
]
