"""Twin randomization: per-item draws of what one empty-room calibration cannot pin down.

:class:`TwinRandomization` draws per item each person's RCS, the people, the room and mounting (from
a pool of room variants), receiver offsets, static scatterers, phase noise and an effect catalog, from
generators seeded by ``(seed, index)``; the order of the draws is part of the contract. See
docs/simulation.md ("Twin randomization").
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, SceneError
from radaraug.scene.materials import get_material
from radaraug.scene.room import CORRIDOR_SURFACES, box, merge
from radaraug.scene.scene import Scene
from radaraug.scene.scene_file import _yaw_pitch_roll
from radaraug.sensor.effects import (
    Effect,
    FrameDrift,
    Interference,
    RxGainPhaseMismatch,
    SpurTone,
    VibratingClutter,
)
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.item_signal import (
    SCATTERER_ANTENNA_GAIN_DBI,
    item_receiver,
    people_paths,
    room_quadrature,
    scale_people_paths,
    static_scatterer_paths,
    strongest_room_paths,
)
from radaraug.sim.scenarios import ScenarioSampler, _uniform
from radaraug.sim.seeding import Stream, item_generator

ITEM_STREAM = Stream.ITEM_DRAWS
"""Generator stream of the per-item draws (room variant, gain, noise figure, RCS per person)."""
ROOM_STREAM = Stream.ROOM_POOL
"""Generator stream of the room pool (``index`` = variant number)."""
SCATTERER_STREAM = Stream.SCATTERERS
"""Generator stream of the per-item static scatterers."""
EFFECTS_STREAM = Stream.EFFECTS
"""Generator stream of the per-item effect catalog (spur, interference, fan, mismatch, drift, levels)."""
MISMATCH_ANTENNAS = 16
"""RX gain/phase mismatch is drawn for antenna numbers 1..16 (``radaraug.config.MAX_ANTENNAS``), whatever
the config, so that the draws do not depend on it; a config's RX channels take their antennas' values."""

RADAR_CEILING_MARGIN_M = 0.15
"""The radar's drawn height is clipped to at most the drawn room height minus this."""

# ITU-R P.2040-3 materials valid at 60 GHz (brick is defined only up to 40 GHz: left out).
DEFAULT_MATERIALS: dict[str, tuple[str, ...]] = {
    "floor": ("floorboard", "concrete", "wood", "chipboard"),
    "ceiling": ("ceiling_board", "plasterboard", "concrete"),
    "left_wall": ("plasterboard", "concrete", "glass", "wood"),
    "right_wall": ("plasterboard", "concrete", "glass", "wood"),
    "near_wall": ("concrete", "plasterboard", "wood", "metal"),
    "far_wall": ("concrete", "plasterboard", "wood", "glass", "metal"),
}
"""Default material choices per corridor surface (drawn uniformly and independently)."""

DEFAULT_CLUTTER_MATERIALS: tuple[str, ...] = ("metal", "wood", "chipboard", "concrete", "glass", "plasterboard")
"""Materials of clutter objects (cabinets, shelves, benches, bins, radiators, glass cases)."""
CLUTTER_LENGTH_M = (0.3, 1.5)
"""Clutter object size along the wall it stands against."""
CLUTTER_DEPTH_M = (0.25, 0.7)
"""Clutter object depth out of the wall."""
CLUTTER_HEIGHT_M = (0.4, 2.0)
"""Clutter object height (bin to tall cabinet)."""
CLUTTER_START_M = 1.0
"""Clutter stands at least this far along the corridor from its near end (the radar's side)."""

# Every field is checked by its annotation (:data:`_FIELD_CHECKS`); these add the bounds of some.
_POSITIVE_RANGES = ("length_m", "width_m", "height_m", "radar_height_m", "person_height_m", "speed_m_s", "range_m",
                    "static_scatterer_range_m", "vibrating_clutter_range_m",
                    # drawn log-uniformly
                    "spur_tone_amplitude_counts", "interference_amplitude_counts", "interference_duration_s",
                    "vibrating_clutter_displacement_m", "vibrating_clutter_Hz")
_BOUNDED_RANGES = {"spur_tone_freq_nyquist": (0.0, 1.0), "interference_chirp_probability": (0.0, 1.0),
                   "rx_mismatch_phase_deg": (-180.0, 180.0), "frame_drift_gain_rms_dB": (0.0, math.inf),
                   "frame_drift_dc_rms_counts": (0.0, math.inf), "phase_noise_rms_Hz": (0.0, math.inf)}


def _materials_default() -> dict[str, tuple[str, ...]]:
    return dict(DEFAULT_MATERIALS)


@dataclass
class TwinRandomization:
    """What the twin draws per item, and from which ranges (``(lo, hi)``: uniform; "log": in the logarithm).

    Every field is a plain type (bool, int, float, a pair, lists of material names), so a YAML/JSON
    mapping of the same keys configures it (:meth:`from_dict`; lists are accepted for pairs). Why
    each default: docs/simulation.md ("Twin randomization"), which also lists every prior.

    Args:
        enabled: False gives the twin without randomization (see :meth:`off`).
        rcs_scale_dB: per-person RCS scale, dB (amplitude x ``10**(dB/20)``, direct and multipath paths).
        room_variants: size of the room pool (one room trace each, by ``prepare()``, cached on disk).
        length_m, width_m, height_m: corridor size, m.
        materials: per corridor surface, the P.2040 material names drawn from; surfaces not named
            keep :data:`DEFAULT_MATERIALS`.
        radar_height_m: radar height above the floor, m (at most the drawn ceiling minus 0.15 m).
        radar_pitch_deg, radar_yaw_deg: added to the scene's radar pose, degrees.
        person_height_m, speed_m_s: people's body height (m) and walking speed (m/s).
        range_m: start distance along the corridor, m (at most the drawn length minus ``wall_margin_m``).
        heading_jitter_deg: heading spread around straight toward/away, degrees.
        crossing_probability, standing_probability: chance that a walker crosses the room, and that a
            person stands (they count), passed to the :class:`ScenarioSampler` (0 draws nothing extra).
        wall_margin_m: lateral positions are drawn within +-(width / 2 - margin), m.
        system_gain_offset_dB, noise_figure_offset_dB: added to the receiver's ``system_gain`` and
            ``thermal_noise`` noise figure, dB.
        clutter_objects: clutter boxes per room variant, ``[lo, hi]`` inclusive, against a side wall
            (:data:`CLUTTER_LENGTH_M` x :data:`CLUTTER_DEPTH_M` x :data:`CLUTTER_HEIGHT_M`).
        clutter_materials: materials drawn for each clutter box.
        static_scatterers: static point scatterers per item, ``[lo, hi]`` inclusive (no tracing cost;
            they reach the receiver with the people, so the strongest get its phase noise).
        static_scatterer_range_m, static_scatterer_rcs_dBsm: a scatterer's range (m) and RCS (dBsm).
        static_scatterer_azimuth_deg: its azimuth off boresight, deg (elevation: +-20 deg).
        phase_noise_rms_Hz: RMS LO frequency noise of the ``phase_noise`` stage, Hz.
        phase_noise_paths: how many of the strongest per-item paths (by amplitude x delay) get it.
        effects_probability: factor on every catalog probability below (0: the catalog off).
        spur_tone_probability, spur_tone_freq_nyquist, spur_tone_amplitude_counts: chance of a
            :class:`~radaraug.sensor.effects.SpurTone`, its frequency (fraction of Nyquist) and
            peak amplitude at the ADC (counts, log).
        interference_probability, interference_chirp_probability: chance of another radar's
            :class:`~radaraug.sensor.effects.Interference` and the fraction of chirps it hits.
        interference_amplitude_counts, interference_duration_s: peak burst amplitude after the IF
            gain (counts, log) and burst length (s, log).
        vibrating_clutter_probability, vibrating_clutter_range_m: chance of a
            :class:`~radaraug.sensor.effects.VibratingClutter` (a fan, a pump) and its range (m).
        vibrating_clutter_rcs_dBsm, vibrating_clutter_displacement_m, vibrating_clutter_Hz: its RCS
            (dBsm, radar equation with 6 dBi antennas), peak displacement (m, log) and frequency (Hz, log).
        rx_mismatch_probability, rx_mismatch_gain_dB, rx_mismatch_phase_deg: chance of an
            :class:`~radaraug.sensor.effects.RxGainPhaseMismatch` on top of the receiver's own, and
            its per-RX gain (dB) and phase (deg).
        frame_drift_probability, frame_drift_gain_rms_dB, frame_drift_dc_rms_counts: chance of a
            :class:`~radaraug.sensor.effects.FrameDrift`, its per-frame gain RMS (dB) and per-RX DC
            shift RMS (counts).
        wide_levels_probability: chance that the item's gain and noise come from the wide ranges below
            instead of ``system_gain_offset_dB`` / ``noise_figure_offset_dB``.
        wide_system_gain_offset_dB, wide_noise_figure_offset_dB: the wide ranges, dB.
        adc_noise_offset_dB: offset on the ``adc_noise`` stage's RMS, drawn with the wide levels, dB.
        static_phase_noise_probability, static_phase_noise_paths: chance that the room's strongest
            returns get the item's phase noise (passed to the receiver as paths), and how many.
    """

    enabled: bool = True
    rcs_scale_dB: tuple[float, float] = (-20.0, 10.0)
    room_variants: int = 8
    length_m: tuple[float, float] = (8.0, 25.0)
    width_m: tuple[float, float] = (1.5, 3.5)
    height_m: tuple[float, float] = (2.4, 3.5)
    materials: dict[str, tuple[str, ...]] = field(default_factory=_materials_default)
    radar_height_m: tuple[float, float] = (0.8, 2.0)
    radar_pitch_deg: tuple[float, float] = (-10.0, 10.0)
    radar_yaw_deg: tuple[float, float] = (-5.0, 5.0)
    person_height_m: tuple[float, float] = (1.45, 2.0)
    speed_m_s: tuple[float, float] = (0.4, 2.0)
    range_m: tuple[float, float] = (0.8, 15.0)
    heading_jitter_deg: float = 30.0
    crossing_probability: float = 0.0
    wall_margin_m: float = 0.35
    standing_probability: float = 0.0
    system_gain_offset_dB: tuple[float, float] = (-6.0, 6.0)
    noise_figure_offset_dB: tuple[float, float] = (-3.0, 3.0)
    clutter_objects: tuple[int, int] = (0, 6)
    clutter_materials: tuple[str, ...] = DEFAULT_CLUTTER_MATERIALS
    static_scatterers: tuple[int, int] = (0, 8)
    static_scatterer_range_m: tuple[float, float] = (0.5, 20.0)
    static_scatterer_rcs_dBsm: tuple[float, float] = (-20.0, 10.0)
    static_scatterer_azimuth_deg: tuple[float, float] = (-45.0, 45.0)
    phase_noise_rms_Hz: tuple[float, float] = (30e3, 400e3)
    phase_noise_paths: int = 16
    # ---- the effect catalog (per-item probabilities; the ranges' sources: docs/simulation.md)
    effects_probability: float = 1.0
    spur_tone_probability: float = 0.3
    spur_tone_freq_nyquist: tuple[float, float] = (0.01, 0.99)
    spur_tone_amplitude_counts: tuple[float, float] = (0.3, 5.0)
    interference_probability: float = 0.3
    interference_chirp_probability: tuple[float, float] = (0.01, 0.3)
    interference_amplitude_counts: tuple[float, float] = (5.0, 1000.0)
    interference_duration_s: tuple[float, float] = (0.5e-6, 20e-6)
    vibrating_clutter_probability: float = 0.3
    vibrating_clutter_range_m: tuple[float, float] = (0.5, 10.0)
    vibrating_clutter_rcs_dBsm: tuple[float, float] = (-20.0, 5.0)
    vibrating_clutter_displacement_m: tuple[float, float] = (0.1e-3, 3e-3)
    vibrating_clutter_Hz: tuple[float, float] = (5.0, 60.0)
    rx_mismatch_probability: float = 0.3
    rx_mismatch_gain_dB: tuple[float, float] = (-1.5, 1.5)
    rx_mismatch_phase_deg: tuple[float, float] = (-30.0, 30.0)
    frame_drift_probability: float = 0.3
    frame_drift_gain_rms_dB: tuple[float, float] = (0.1, 1.0)
    frame_drift_dc_rms_counts: tuple[float, float] = (0.2, 4.0)
    wide_levels_probability: float = 0.3
    wide_system_gain_offset_dB: tuple[float, float] = (-12.0, 12.0)
    wide_noise_figure_offset_dB: tuple[float, float] = (-4.0, 8.0)
    adc_noise_offset_dB: tuple[float, float] = (-3.0, 3.0)
    static_phase_noise_probability: float = 0.5
    static_phase_noise_paths: int = 4

    def __post_init__(self) -> None:
        # Normalise YAML-ish input (lists, ints) and fail early, naming the field.
        for f in dataclasses.fields(self):
            setattr(self, f.name, _FIELD_CHECKS[str(f.type)](getattr(self, f.name), f.name))

    @classmethod
    def off(cls) -> TwinRandomization:
        """The non-randomized twin: a dataset gives exactly the items it gives without randomization."""
        return cls(enabled=False)

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON/YAML types (pairs and material choices as lists)."""
        return json.loads(json.dumps(dataclasses.asdict(self)))  # tuples -> lists; floats round-trip exactly

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> TwinRandomization:
        """Inverse of :meth:`to_dict`; missing keys take the defaults.

        Raises:
            ConfigError: not a mapping, an unknown key (named), or a bad value.
        """
        if not isinstance(data, Mapping):
            raise ConfigError(f"twin randomization must be a mapping, got {type(data).__name__}")
        known = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(str(k) for k in data if k not in known)
        if unknown:
            raise ConfigError(f"twin randomization: unknown key(s) {unknown}; known: {sorted(known)}")
        return cls(**dict(data))

    # ------------------------------------------------------------------ draws
    def room(self, seed: int, k: int) -> RoomDraw:
        """Room variant ``k`` of the pool of a dataset seeded ``seed`` (a pure function of both)."""
        if not 0 <= k < self.room_variants:
            raise ConfigError(f"room variant {k} out of range: the pool has {self.room_variants}")
        g = item_generator(seed, k, stream=Stream.ROOM_POOL)
        length = _uniform(self.length_m, g)
        width = _uniform(self.width_m, g)
        height = _uniform(self.height_m, g)
        # Every surface draws (in CORRIDOR_SURFACES order), even ones a room without end walls
        # lacks, so the other draws do not depend on that setting.
        mats = {s: self.materials[s][int(torch.randint(len(self.materials[s]), (), generator=g))]
                for s in CORRIDOR_SURFACES}
        radar_height = min(_uniform(self.radar_height_m, g), height - RADAR_CEILING_MARGIN_M)
        pitch = _uniform(self.radar_pitch_deg, g)
        yaw = _uniform(self.radar_yaw_deg, g)
        lo_n, hi_n = self.clutter_objects
        clutter = []
        for _ in range(int(torch.randint(lo_n, hi_n + 1, (), generator=g))):
            along = _uniform(CLUTTER_LENGTH_M, g)
            depth = min(_uniform(CLUTTER_DEPTH_M, g), width / 3)
            tall = min(_uniform(CLUTTER_HEIGHT_M, g), height - 0.1)
            x0 = _uniform((CLUTTER_START_M, max(CLUTTER_START_M, length - 0.2 - along)), g)
            side = 1.0 if bool(torch.rand((), generator=g) < 0.5) else -1.0
            mat = self.clutter_materials[int(torch.randint(len(self.clutter_materials), (), generator=g))]
            y_wall, y_in = side * width / 2, side * (width / 2 - depth)
            clutter.append({"min": [x0, min(y_wall, y_in), 0.0], "max": [x0 + along, max(y_wall, y_in), tall],
                            "material": mat})
        return RoomDraw(k, length, width, height, mats, radar_height, pitch, yaw, tuple(clutter))

    def variant_of(self, seed: int, index: int) -> int:
        """Which room variant item ``index`` uses (the first draw of its stream)."""
        g = item_generator(seed, index, stream=Stream.ITEM_DRAWS)
        return int(torch.randint(self.room_variants, (), generator=g))

    def item(self, seed: int, index: int, num_people: int) -> ItemDraw:
        """The per-item draws of item ``index`` with ``num_people`` people.

        Person ``j``'s RCS scale does not depend on how many people follow it.
        """
        g = item_generator(seed, index, stream=Stream.ITEM_DRAWS)
        variant = int(torch.randint(self.room_variants, (), generator=g))
        gain = _uniform(self.system_gain_offset_dB, g)
        nf = _uniform(self.noise_figure_offset_dB, g)
        rcs = tuple(_uniform(self.rcs_scale_dB, g) for _ in range(num_people))
        # Own stream: the scatterers do not depend on the number of people (or vice versa).
        gs = item_generator(seed, index, stream=Stream.SCATTERERS)
        lo_n, hi_n = self.static_scatterers
        scatterers = tuple(
            (_uniform(self.static_scatterer_range_m, gs), _uniform(self.static_scatterer_azimuth_deg, gs),
             _uniform((-20.0, 20.0), gs), _uniform(self.static_scatterer_rcs_dBsm, gs))
            for _ in range(int(torch.randint(lo_n, hi_n + 1, (), generator=gs)))
        )
        phase_noise = _uniform(self.phase_noise_rms_Hz, gs)
        catalog = self.effects(seed, index)
        if catalog.pop("wide_levels"):
            gain, nf = catalog.pop("wide_system_gain_offset_dB"), catalog.pop("wide_noise_figure_offset_dB")
            catalog["wide_levels"] = True
        else:
            for key in ("wide_system_gain_offset_dB", "wide_noise_figure_offset_dB", "adc_noise_offset_dB"):
                catalog.pop(key)
        return ItemDraw(variant, gain, nf, rcs, scatterers, phase_noise, **catalog,
                        phase_noise_paths=self.phase_noise_paths)

    def effects(self, seed: int, index: int) -> dict[str, Any]:
        """The effect-catalog draws of item ``index`` (its own stream, :data:`EFFECTS_STREAM`).

        Every effect draws all its values whether it hits or not (one probability shifts no other draw).
        Returns the :class:`ItemDraw` fields plus ``wide_levels`` (bool) and the wide levels' values.
        """
        g = item_generator(seed, index, stream=Stream.EFFECTS)
        scale = self.effects_probability

        def hit(p: float) -> bool:
            return bool(torch.rand((), generator=g, dtype=torch.float64) < scale * p)

        out: dict[str, Any] = {}
        on = hit(self.spur_tone_probability)
        spur = (_uniform(self.spur_tone_freq_nyquist, g), _log_uniform(self.spur_tone_amplitude_counts, g),
                _uniform((-math.pi, math.pi), g))
        out["spur_tone"] = spur if on else None
        on = hit(self.interference_probability)
        inter = (_uniform(self.interference_chirp_probability, g), _log_uniform(self.interference_amplitude_counts, g),
                 _log_uniform(self.interference_duration_s, g))
        out["interference"] = inter if on else None
        on = hit(self.vibrating_clutter_probability)
        vib = (_uniform(self.vibrating_clutter_range_m, g), _uniform(self.vibrating_clutter_rcs_dBsm, g),
               _log_uniform(self.vibrating_clutter_displacement_m, g), _log_uniform(self.vibrating_clutter_Hz, g),
               _uniform((-math.pi, math.pi), g))
        out["vibrating_clutter"] = vib if on else None
        on = hit(self.rx_mismatch_probability)
        gains = tuple(_uniform(self.rx_mismatch_gain_dB, g) for _ in range(MISMATCH_ANTENNAS))
        phases = tuple(_uniform(self.rx_mismatch_phase_deg, g) for _ in range(MISMATCH_ANTENNAS))
        out["rx_mismatch"] = (gains, phases) if on else None
        on = hit(self.frame_drift_probability)
        drift = (_uniform(self.frame_drift_gain_rms_dB, g), _uniform(self.frame_drift_dc_rms_counts, g))
        out["frame_drift"] = drift if on else None
        out["wide_levels"] = hit(self.wide_levels_probability)
        out["wide_system_gain_offset_dB"] = _uniform(self.wide_system_gain_offset_dB, g)
        out["wide_noise_figure_offset_dB"] = _uniform(self.wide_noise_figure_offset_dB, g)
        out["adc_noise_offset_dB"] = _uniform(self.adc_noise_offset_dB, g)
        out["static_phase_noise_paths"] = self.static_phase_noise_paths if hit(self.static_phase_noise_probability) else 0
        return out

    def sampler(self, base: ScenarioSampler, room: RoomDraw, radar_x_m: float) -> ScenarioSampler:
        """``base`` with this randomization's people ranges, fitted inside ``room``.

        Counts and their weights, toward/away and speed spacing are kept; the radar is at
        ``x = radar_x_m``.
        """
        lateral = max(0.0, room.width_m / 2 - self.wall_margin_m)
        far = max(0.0, room.length_m - radar_x_m - self.wall_margin_m)
        hi = min(self.range_m[1], far)
        lo = min(self.range_m[0], hi)
        return dataclasses.replace(
            base, speed_m_s=self.speed_m_s, height_m=self.person_height_m, range_m=(lo, hi),
            lateral_m=(-lateral, lateral), heading_jitter_deg=self.heading_jitter_deg,
            crossing_probability=max(base.crossing_probability, self.crossing_probability),
            standing_probability=max(base.standing_probability, self.standing_probability),
        )


@dataclass(frozen=True)
class RoomDraw:
    """One room of the pool: a corridor and the radar's mounting in it.

    Attributes:
        index: variant number ``k``.
        length_m, width_m, height_m: corridor size.
        materials: P.2040 material name per corridor surface.
        radar_height_m: radar height above the floor.
        radar_pitch_deg, radar_yaw_deg: added to the base scene's pose.
        clutter: boxes in the room, ``{"min": [x, y, z], "max": [x, y, z], "material": name}`` (corridor frame).
    """

    index: int
    length_m: float
    width_m: float
    height_m: float
    materials: dict[str, str]
    radar_height_m: float
    radar_pitch_deg: float
    radar_yaw_deg: float
    clutter: tuple[dict[str, Any], ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-able description."""
        return {**dataclasses.asdict(self), "materials": dict(self.materials), "clutter": [dict(c) for c in self.clutter]}

    def scene(self, base: Scene, config: RadarConfig | None = None) -> Scene:
        """This room as a :class:`Scene`, with ``base``'s radar in the drawn corridor.

        The radar's x, y position, pose and mounting and the corridor's ``max_edge`` and end walls
        come from ``base``.

        Raises:
            ConfigError: ``base`` is not a corridor scene, or its radar is outside the drawn room.
        """
        spec = base.room_spec
        if spec is None or spec.get("type") != "corridor":
            kind = "a room built in Python" if spec is None else f"a {spec.get('type')!r} room"
            raise ConfigError(f"twin randomization draws corridor rooms; scene {base.name!r} has {kind} "
                              "(use a corridor scene, or TwinRandomization.off())")
        x, y = (float(v) for v in base.radar.position[:2])
        if not (0.0 < x < self.length_m and abs(y) < self.width_m / 2):
            raise ConfigError(f"room variant {self.index}: the scene's radar at x={x:.2f}, y={y:.2f} m is "
                              f"outside the drawn {self.length_m:.2f} x {self.width_m:.2f} m corridor")
        room = {"type": "corridor", "length": self.length_m, "width": self.width_m, "height": self.height_m,
                "max_edge": spec.get("max_edge", 0.5), "end_walls": spec.get("end_walls", True),
                "materials": dict(self.materials)}
        data = {"name": f"{base.name}-variant-{self.index}",
                "radar": {"position": [x, y, self.radar_height_m], "rotation": self._rotation(base).tolist()},
                "room": room}
        try:
            scene = Scene.from_dict(data)
        except SceneError as err:
            raise ConfigError(f"room variant {self.index}: {err}") from None
        scene.config = config or base.config
        if self.clutter:
            max_edge = float(spec.get("max_edge", 0.5))
            scene.room = merge([scene.room, *(box(c["min"], c["max"], c["material"], max_edge_m=max_edge)
                                              for c in self.clutter)])
            scene.room_spec = None  # no longer a plain corridor: written inline by Scene.to_dict
        return scene

    def _rotation(self, base: Scene) -> torch.Tensor:
        """The base pose turned by the drawn yaw (about world z) and pitch (boresight up), mounting kept.

        ``yaw_pitch_roll(yaw0, pitch0, 0) @ M`` (``M``: roll, mounting) becomes ``yaw_pitch_roll(yaw0 + yaw,
        pitch0 + pitch, 0) @ M``.
        """
        rot = base.radar.rotation.detach().cpu().to(torch.float64)
        b = rot[:, 2]
        yaw0 = math.degrees(math.atan2(float(b[1]), float(b[0])))
        pitch0 = math.degrees(math.asin(max(-1.0, min(1.0, float(b[2])))))
        mount = _yaw_pitch_roll(yaw0, pitch0, 0.0).T @ rot
        return _yaw_pitch_roll(yaw0 + self.radar_yaw_deg, pitch0 + self.radar_pitch_deg, 0.0) @ mount


@dataclass(frozen=True)
class ItemDraw:
    """The per-item draws: room variant, receiver offsets, each person's RCS scale, static scatterers.

    The scatterers are ``(range_m, azimuth_deg, elevation_deg, rcs_dBsm)``. The effect catalog's
    fields are None (0, False) where the item does not carry the effect:

    * ``spur_tone``: ``(frequency / Nyquist, amplitude_counts, phase_rad)``;
    * ``interference``: ``(chirp_probability, amplitude_counts, duration_s)``;
    * ``vibrating_clutter``: ``(range_m, rcs_dBsm, displacement_m, vibration_Hz, phase_rad)``;
    * ``rx_mismatch``: ``(gain_dB, phase_deg)``, each a value per antenna number 1..16;
    * ``frame_drift``: ``(gain_rms_dB, dc_rms_counts)``;
    * ``wide_levels``: the offsets came from the wide ranges (``adc_noise_offset_dB`` applies);
    * ``static_phase_noise_paths``: how many of the room's strongest returns carry the phase noise.

    ``phase_noise_paths`` is carried (:attr:`TwinRandomization.phase_noise_paths`), not drawn.
    """

    variant: int
    system_gain_offset_dB: float
    noise_figure_offset_dB: float
    rcs_scale_dB: tuple[float, ...]
    scatterers: tuple[tuple[float, float, float, float], ...] = ()
    phase_noise_rms_Hz: float | None = None
    spur_tone: tuple[float, float, float] | None = None
    interference: tuple[float, float, float] | None = None
    vibrating_clutter: tuple[float, float, float, float, float] | None = None
    rx_mismatch: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    frame_drift: tuple[float, float] | None = None
    wide_levels: bool = False
    adc_noise_offset_dB: float = 0.0
    static_phase_noise_paths: int = 0
    phase_noise_paths: int = 16

    def effects_dict(self, config: RadarConfig) -> dict[str, Any]:
        """The catalog effects this item carries, ``{name: {parameter: value}}`` (JSON-able)."""
        out: dict[str, Any] = {}
        if self.spur_tone is not None:
            frac, amp, phase = self.spur_tone
            out["spur_tone"] = {"freq_Hz": frac * float(config.sample_rate_Hz) / 2, "amplitude_counts": amp,
                                "phase_rad": phase}
        if self.interference is not None:
            out["interference"] = dict(zip(("probability", "amplitude_counts", "duration_s"), self.interference))
        if self.vibrating_clutter is not None:
            out["vibrating_clutter"] = dict(zip(("range_m", "rcs_dBsm", "displacement_m", "vibration_Hz", "phase_rad"),
                                                self.vibrating_clutter))
        if self.rx_mismatch is not None:
            gains, phases = self.rx_mismatch
            out["rx_gain_phase_mismatch"] = {"gain_dB": [gains[a - 1] for a in config.rx_antennas],
                                             "phase_deg": [phases[a - 1] for a in config.rx_antennas]}
        if self.frame_drift is not None:
            out["frame_drift"] = dict(zip(("gain_rms_dB", "dc_rms_counts"), self.frame_drift))
        if self.wide_levels:
            out["wide_levels"] = {"system_gain_offset_dB": self.system_gain_offset_dB,
                                  "noise_figure_offset_dB": self.noise_figure_offset_dB,
                                  "adc_noise_offset_dB": self.adc_noise_offset_dB}
        if self.static_phase_noise_paths:
            out["static_phase_noise"] = {"paths": self.static_phase_noise_paths}
        return out

    def catalog_effects(self, config: RadarConfig) -> list[Effect]:
        """The receiver stages of the catalog effects this item carries (to insert at their place)."""
        drawn = self.effects_dict(config)
        effects: list[Effect] = []
        if "vibrating_clutter" in drawn:
            vib = dict(drawn["vibrating_clutter"])
            level = _radar_equation_dB(config, vib["range_m"], vib.pop("rcs_dBsm"))
            effects.append(VibratingClutter(level_dB=level, **vib))
        if "rx_gain_phase_mismatch" in drawn:
            mismatch = drawn["rx_gain_phase_mismatch"]
            effects.append(RxGainPhaseMismatch(gain_dB=mismatch["gain_dB"],
                                               phase_rad=[math.radians(p) for p in mismatch["phase_deg"]]))
        # The others take the parameters effects_dict names.
        for name, stage in (("interference", Interference), ("frame_drift", FrameDrift), ("spur_tone", SpurTone)):
            if name in drawn:
                effects.append(stage(**drawn[name]))
        return effects


def _radar_equation_dB(config: RadarConfig, range_m: float, rcs_dBsm: float) -> float:
    """Received over transmitted power of a point scatterer, dB: ``G^2 lambda^2 sigma / ((4 pi)^3 R^4)``.

    With the static scatterers' antenna gain (:data:`SCATTERER_ANTENNA_GAIN_DBI`), as
    :func:`~radaraug.sensor.point_target.point_target_paths` gives them.
    """
    lam = float(config.wavelength_m)
    return (2 * SCATTERER_ANTENNA_GAIN_DBI + rcs_dBsm + 20 * math.log10(lam) - 30 * math.log10(4 * math.pi)
            - 40 * math.log10(range_m))


def check_receiver(receiver: FMCWReceiver, randomization: TwinRandomization) -> None:
    """Raise ConfigError when ``receiver`` cannot take the randomization's gain / noise offsets."""
    names = [e.name for e in receiver.effects]
    first_nonlinear = next((i for i, e in enumerate(receiver.effects) if e.kind == "nonlinear"), len(names))
    r = randomization
    wide = r.effects_probability * r.wide_levels_probability > 0
    zero = (0.0, 0.0)
    if r.system_gain_offset_dB != zero or (wide and r.wide_system_gain_offset_dB != zero):
        if "system_gain" not in names:
            raise ConfigError("twin randomization: the receiver has no system_gain stage; add one or set "
                              "system_gain_offset_dB (and wide_system_gain_offset_dB) to [0, 0]")
        # The room's cached signal went through the linear stages before the first non-linear
        # one; only there does scaling it by the gain equal applying the gain.
        if names.index("system_gain") > first_nonlinear:
            raise ConfigError("twin randomization: the receiver's system_gain comes after a non-linear stage")
    nf_used = r.noise_figure_offset_dB != zero or (wide and r.wide_noise_figure_offset_dB != zero)
    if nf_used and "thermal_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no thermal_noise stage; add one or set "
                          "noise_figure_offset_dB (and wide_noise_figure_offset_dB) to [0, 0]")
    if wide and r.adc_noise_offset_dB != zero and "adc_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no adc_noise stage; add one or set "
                          "adc_noise_offset_dB to [0, 0] (or wide_levels_probability to 0)")
    if r.phase_noise_rms_Hz != zero and "phase_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no phase_noise stage; add one or set "
                          "phase_noise_rms_Hz to [0, 0]")
    if r.effects_probability * r.static_phase_noise_probability > 0 and "phase_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no phase_noise stage for the room's strongest "
                          "returns; add one or set static_phase_noise_probability to 0")


# ---------------------------------------------------------------------------- validation
def _flag(value: Any, name: str) -> bool:
    if not isinstance(value, bool):
        raise ConfigError(f"twin randomization: {name} must be true or false, got {value!r}")
    return value


def _number(value: Any, name: str, *, minimum: float | None = None) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ConfigError(f"twin randomization: {name} must be a finite number, got {value!r}")
    if minimum is not None and value < minimum:
        raise ConfigError(f"twin randomization: {name} must be >= {minimum}, got {value!r}")
    return float(value)


def _nonnegative(value: Any, name: str) -> float:
    """A float field: a number >= 0, and a probability in [0, 1] where the name says so."""
    value = _number(value, name, minimum=0.0)
    if name.endswith("_probability") and value > 1.0:
        raise ConfigError(f"twin randomization: {name} must be a probability in [0, 1], got {value!r}")
    return value


def _count(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise ConfigError(f"twin randomization: {name} must be an integer >= 1, got {value!r}")
    return value


def _pair(value: Any, name: str) -> tuple[float, float]:
    """A range ``(lo, hi)``, positive where :data:`_POSITIVE_RANGES` and inside :data:`_BOUNDED_RANGES`."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2:
        raise ConfigError(f"twin randomization: {name} must be a pair [lo, hi], got {value!r}")
    lo, hi = (_number(v, name) for v in value)
    if lo > hi:
        raise ConfigError(f"twin randomization: {name} must have lo <= hi, got {[lo, hi]}")
    if name in _POSITIVE_RANGES and lo <= 0:
        raise ConfigError(f"twin randomization: {name} must be positive, got {[lo, hi]}")
    bound_lo, bound_hi = _BOUNDED_RANGES.get(name, (-math.inf, math.inf))
    if lo < bound_lo or hi > bound_hi:
        raise ConfigError(f"twin randomization: {name} must lie in [{bound_lo}, {bound_hi}], got {[lo, hi]}")
    return (lo, hi)


def _log_uniform(lo_hi: tuple[float, float], g: torch.Generator) -> float:
    """Uniform in the logarithm over ``[lo, hi]`` (both > 0), one draw from ``g``."""
    lo, hi = lo_hi
    return math.exp(_uniform((math.log(lo), math.log(hi)), g))


def _count_pair(value: Any, name: str) -> tuple[int, int]:
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2 or any(
            isinstance(v, bool) or not isinstance(v, int) for v in value):
        raise ConfigError(f"twin randomization: {name} must be a pair of integers [lo, hi], got {value!r}")
    lo, hi = int(value[0]), int(value[1])
    if not 0 <= lo <= hi:
        raise ConfigError(f"twin randomization: {name} must have 0 <= lo <= hi, got {[lo, hi]}")
    return (lo, hi)


def _material_list(value: Any, name: str) -> tuple[str, ...]:
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, Sequence) or not value:
        raise ConfigError(f"twin randomization: {name} must be a non-empty list of material names, got {value!r}")
    for n in value:
        try:
            get_material(n)
        except SceneError as err:
            raise ConfigError(f"twin randomization: {name}: {err}") from None
    return tuple(str(n) for n in value)


def _materials(value: Any, name: str) -> dict[str, tuple[str, ...]]:
    if not isinstance(value, Mapping):
        raise ConfigError(f"twin randomization: {name} must be a mapping surface -> list of names, got {value!r}")
    unknown = sorted(str(k) for k in value if k not in CORRIDOR_SURFACES)
    if unknown:
        raise ConfigError(f"twin randomization: {name}: unknown surface(s) {unknown}; "
                          f"surfaces are {list(CORRIDOR_SURFACES)}")
    out = dict(DEFAULT_MATERIALS)
    for surface, names in value.items():
        out[surface] = _material_list(names, f"{name}.{surface}")
    return out


# The check (and normalisation) of a TwinRandomization field, by its annotation.
_FIELD_CHECKS: dict[str, Callable[[Any, str], Any]] = {
    "bool": _flag,
    "int": _count,
    "float": _nonnegative,
    "tuple[float, float]": _pair,
    "tuple[int, int]": _count_pair,
    "tuple[str, ...]": _material_list,
    "dict[str, tuple[str, ...]]": _materials,
}


__all__ = [
    "DEFAULT_MATERIALS", "EFFECTS_STREAM", "ITEM_STREAM", "ROOM_STREAM", "ItemDraw", "RoomDraw", "TwinRandomization",
    "SCATTERER_ANTENNA_GAIN_DBI", "check_receiver", "item_receiver", "people_paths", "room_quadrature",
    "scale_people_paths", "static_scatterer_paths", "strongest_room_paths",
]
