"""Twin randomization: per-item draws of what one empty-room calibration cannot pin down.

:class:`TwinRandomization` has four sections: the room (a pool of corridors, the radar's mounting,
static scatterers), the people, the receiver levels and the effect catalog (:mod:`radaraug.sim.catalog`).
Every draw comes from a generator seeded by ``(seed, index)``; the order of the draws is part of the
contract. See docs/simulation.md ("Twin randomization").
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, SceneError
from radaraug.scene.room import CORRIDOR_SURFACES, box, merge
from radaraug.scene.scene import Scene
from radaraug.scene.scene_file import _yaw_pitch_roll
from radaraug.sensor.effects import Effect
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.catalog import Catalog
from radaraug.sim.catalog import record as catalog_record
from radaraug.sim.catalog import stages as catalog_stages
from radaraug.sim.catalog.wide_levels import WideLevelsPrior
from radaraug.sim.priors import Section, material_list, span, uniform
from radaraug.sim.scenarios import ScenarioSampler
from radaraug.sim.seeding import Stream, item_generator

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


def _materials_default() -> dict[str, tuple[str, ...]]:
    return dict(DEFAULT_MATERIALS)


@dataclass
class RoomPriors(Section):
    """The ``room`` section: the pool of corridors, the radar's mounting in them, static scatterers.

    Args:
        variants: size of the room pool (one room trace each, by ``prepare()``, cached on disk).
        length_m, width_m, height_m: corridor size, m.
        materials: per corridor surface, the P.2040 material names drawn from; surfaces not named
            keep :data:`DEFAULT_MATERIALS`.
        radar_height_m: radar height above the floor, m (at most the drawn ceiling minus 0.15 m).
        radar_pitch_deg, radar_yaw_deg: added to the scene's radar pose, degrees.
        clutter_objects: clutter boxes per room variant, ``[lo, hi]`` inclusive, against a side wall
            (:data:`CLUTTER_LENGTH_M` x :data:`CLUTTER_DEPTH_M` x :data:`CLUTTER_HEIGHT_M`).
        clutter_materials: materials drawn for each clutter box.
        scatterers: static point scatterers per item, ``[lo, hi]`` inclusive (no tracing cost; they
            reach the receiver with the people, so the strongest get its phase noise).
        scatterer_range_m, scatterer_rcs_dBsm: a scatterer's range (m) and RCS (dBsm).
        scatterer_azimuth_deg: its azimuth off boresight, deg (elevation: +-20 deg).
    """

    where = "room"
    variants: int = 8
    length_m: tuple[float, float] = span(8.0, 25.0, positive=True)
    width_m: tuple[float, float] = span(1.5, 3.5, positive=True)
    height_m: tuple[float, float] = span(2.4, 3.5, positive=True)
    materials: dict[str, tuple[str, ...]] = field(default_factory=_materials_default)
    radar_height_m: tuple[float, float] = span(0.8, 2.0, positive=True)
    radar_pitch_deg: tuple[float, float] = span(-10.0, 10.0)
    radar_yaw_deg: tuple[float, float] = span(-5.0, 5.0)
    clutter_objects: tuple[int, int] = (0, 6)
    clutter_materials: tuple[str, ...] = DEFAULT_CLUTTER_MATERIALS
    scatterers: tuple[int, int] = (0, 8)
    scatterer_range_m: tuple[float, float] = span(0.5, 20.0, positive=True)
    scatterer_rcs_dBsm: tuple[float, float] = span(-20.0, 10.0)
    scatterer_azimuth_deg: tuple[float, float] = span(-45.0, 45.0)

    def check_field(self, f: dataclasses.Field, value: Any) -> Any:
        """``materials`` per surface (the unnamed surfaces keep their defaults); the rest as every section."""
        if f.name != "materials":
            return super().check_field(f, value)
        if not isinstance(value, Mapping):
            raise ConfigError(f"twin randomization: room.materials must be a mapping surface -> list of names, "
                              f"got {value!r}")
        unknown = sorted(str(k) for k in value if k not in CORRIDOR_SURFACES)
        if unknown:
            raise ConfigError(f"twin randomization: room.materials: unknown surface(s) {unknown}; "
                              f"surfaces are {list(CORRIDOR_SURFACES)}")
        out = dict(DEFAULT_MATERIALS)
        for surface, names in value.items():
            out[surface] = material_list(names, f"room.materials.{surface}")
        return out


@dataclass
class PeoplePriors(Section):
    """The ``people`` section: who walks, how strong, how fast, where.

    Args:
        rcs_scale_dB: per-person RCS scale, dB (amplitude x ``10**(dB/20)``, direct and multipath paths).
        height_m, speed_m_s: body height (m) and walking speed (m/s).
        range_m: start distance along the corridor, m (at most the drawn length minus ``wall_margin_m``).
        heading_jitter_deg: heading spread around straight toward/away, degrees.
        crossing_probability, standing_probability: chance that a walker crosses the room, and that a
            person stands (they count), passed to the :class:`ScenarioSampler` (0 draws nothing extra).
        wall_margin_m: lateral positions are drawn within +-(width / 2 - margin), m.
    """

    where = "people"
    rcs_scale_dB: tuple[float, float] = span(-20.0, 10.0)
    height_m: tuple[float, float] = span(1.45, 2.0, positive=True)
    speed_m_s: tuple[float, float] = span(0.4, 2.0, positive=True)
    range_m: tuple[float, float] = span(0.8, 15.0, positive=True)
    heading_jitter_deg: float = 30.0
    crossing_probability: float = 0.0
    standing_probability: float = 0.0
    wall_margin_m: float = 0.35


@dataclass
class LevelPriors(Section):
    """The ``levels`` section: receiver offsets and phase noise every item draws.

    Args:
        system_gain_offset_dB, noise_figure_offset_dB: added to the receiver's ``system_gain`` and
            ``thermal_noise`` noise figure, dB (the catalog's ``wide_levels`` replaces them in some items).
        phase_noise_rms_Hz: RMS LO frequency noise of the ``phase_noise`` stage, Hz.
        phase_noise_paths: how many of the strongest per-item paths (by amplitude x delay) get it.
    """

    where = "levels"
    system_gain_offset_dB: tuple[float, float] = span(-6.0, 6.0)
    noise_figure_offset_dB: tuple[float, float] = span(-3.0, 3.0)
    phase_noise_rms_Hz: tuple[float, float] = span(30e3, 400e3, bounds=(0.0, math.inf))
    phase_noise_paths: int = 16


_SECTIONS = ("room", "people", "levels", "catalog")


@dataclass(init=False)
class TwinRandomization:
    """What the twin draws per item, in four sections: room, people, levels and the effect catalog.

    Each section takes its object or a mapping of its fields, so a YAML/JSON mapping of the same
    keys configures it (:meth:`from_dict`; lists are accepted for pairs). Why each default:
    docs/simulation.md ("Twin randomization"), which also lists every prior.

    Args:
        enabled: False gives the twin without randomization (see :meth:`off`).
        room: :class:`RoomPriors` (None: its defaults).
        people: :class:`PeoplePriors`.
        levels: :class:`LevelPriors`.
        catalog: :class:`~radaraug.sim.catalog.Catalog`, keyed by effect name.

    Raises:
        ConfigError: a bad value or an unknown key, named with its section.
    """

    enabled: bool
    room: RoomPriors
    people: PeoplePriors
    levels: LevelPriors
    catalog: Catalog

    def __init__(self, enabled: bool = True, room: RoomPriors | Mapping[str, Any] | None = None,
                 people: PeoplePriors | Mapping[str, Any] | None = None,
                 levels: LevelPriors | Mapping[str, Any] | None = None,
                 catalog: Catalog | Mapping[str, Any] | None = None) -> None:
        if not isinstance(enabled, bool):
            raise ConfigError(f"twin randomization: enabled must be true or false, got {enabled!r}")
        self.enabled = enabled
        self.room = RoomPriors.from_dict({} if room is None else room)
        self.people = PeoplePriors.from_dict({} if people is None else people)
        self.levels = LevelPriors.from_dict({} if levels is None else levels)
        self.catalog = Catalog.from_dict({} if catalog is None else catalog)

    @classmethod
    def off(cls) -> TwinRandomization:
        """The non-randomized twin: a dataset gives exactly the items it gives without randomization."""
        return cls(enabled=False)

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON/YAML types, a mapping per section."""
        return {"enabled": self.enabled, **{name: getattr(self, name).to_dict() for name in _SECTIONS}}

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> TwinRandomization:
        """Inverse of :meth:`to_dict`; missing keys take the defaults.

        Raises:
            ConfigError: not a mapping, an unknown key (named), or a bad value.
        """
        if not isinstance(data, Mapping):
            raise ConfigError(f"twin randomization must be a mapping, got {type(data).__name__}")
        known = ["enabled", *_SECTIONS]
        unknown = sorted(str(k) for k in data if k not in known)
        if unknown:
            raise ConfigError(f"twin randomization: unknown key(s) {unknown}; known: {known} "
                              "(sections of fields: docs/simulation.md, 'Twin randomization')")
        return cls(**dict(data))

    def replace(self, **sections: Mapping[str, Any]) -> TwinRandomization:
        """A copy with some fields of some sections changed, e.g. ``replace(people={"speed_m_s": (1, 2)})``."""
        out = {name: getattr(self, name).to_dict() for name in _SECTIONS}
        for name, changes in sections.items():
            if name not in _SECTIONS:
                raise ConfigError(f"twin randomization has no section {name!r}; sections: {list(_SECTIONS)}")
            for key, value in changes.items():
                if name == "catalog" and isinstance(value, Mapping):
                    out[name][key] = {**out[name].get(key, {}), **value}
                else:
                    out[name][key] = value
        return TwinRandomization(enabled=self.enabled, **out)

    # ------------------------------------------------------------------ draws
    def room_draw(self, seed: int, k: int) -> RoomDraw:
        """Room variant ``k`` of the pool of a dataset seeded ``seed`` (a pure function of both)."""
        r = self.room
        if not 0 <= k < r.variants:
            raise ConfigError(f"room variant {k} out of range: the pool has {r.variants}")
        g = item_generator(seed, k, stream=Stream.ROOM_POOL)
        length = uniform(r.length_m, g)
        width = uniform(r.width_m, g)
        height = uniform(r.height_m, g)
        # Every surface draws (in CORRIDOR_SURFACES order), even ones a room without end walls
        # lacks, so the other draws do not depend on that setting.
        mats = {s: r.materials[s][int(torch.randint(len(r.materials[s]), (), generator=g))]
                for s in CORRIDOR_SURFACES}
        radar_height = min(uniform(r.radar_height_m, g), height - RADAR_CEILING_MARGIN_M)
        pitch = uniform(r.radar_pitch_deg, g)
        yaw = uniform(r.radar_yaw_deg, g)
        lo_n, hi_n = r.clutter_objects
        clutter = []
        for _ in range(int(torch.randint(lo_n, hi_n + 1, (), generator=g))):
            along = uniform(CLUTTER_LENGTH_M, g)
            depth = min(uniform(CLUTTER_DEPTH_M, g), width / 3)
            tall = min(uniform(CLUTTER_HEIGHT_M, g), height - 0.1)
            x0 = uniform((CLUTTER_START_M, max(CLUTTER_START_M, length - 0.2 - along)), g)
            side = 1.0 if bool(torch.rand((), generator=g) < 0.5) else -1.0
            mat = r.clutter_materials[int(torch.randint(len(r.clutter_materials), (), generator=g))]
            y_wall, y_in = side * width / 2, side * (width / 2 - depth)
            clutter.append({"min": [x0, min(y_wall, y_in), 0.0], "max": [x0 + along, max(y_wall, y_in), tall],
                            "material": mat})
        return RoomDraw(k, length, width, height, mats, radar_height, pitch, yaw, tuple(clutter))

    def variant_of(self, seed: int, index: int) -> int:
        """Which room variant item ``index`` uses (the first draw of its stream)."""
        g = item_generator(seed, index, stream=Stream.ITEM_DRAWS)
        return int(torch.randint(self.room.variants, (), generator=g))

    def item(self, seed: int, index: int, num_people: int) -> ItemDraw:
        """The per-item draws of item ``index`` with ``num_people`` people.

        Person ``j``'s RCS scale does not depend on how many people follow it.
        """
        g = item_generator(seed, index, stream=Stream.ITEM_DRAWS)
        variant = int(torch.randint(self.room.variants, (), generator=g))
        gain = uniform(self.levels.system_gain_offset_dB, g)
        nf = uniform(self.levels.noise_figure_offset_dB, g)
        rcs = tuple(uniform(self.people.rcs_scale_dB, g) for _ in range(num_people))
        # Own stream: the scatterers do not depend on the number of people (or vice versa).
        gs = item_generator(seed, index, stream=Stream.SCATTERERS)
        lo_n, hi_n = self.room.scatterers
        scatterers = tuple(
            (uniform(self.room.scatterer_range_m, gs), uniform(self.room.scatterer_azimuth_deg, gs),
             uniform((-20.0, 20.0), gs), uniform(self.room.scatterer_rcs_dBsm, gs))
            for _ in range(int(torch.randint(lo_n, hi_n + 1, (), generator=gs)))
        )
        phase_noise = uniform(self.levels.phase_noise_rms_Hz, gs)
        catalog = self.effects(seed, index)
        if "wide_levels" in catalog:
            gain = catalog["wide_levels"]["system_gain_offset_dB"]
            nf = catalog["wide_levels"]["noise_figure_offset_dB"]
        return ItemDraw(variant, gain, nf, rcs, scatterers, phase_noise, catalog,
                        phase_noise_paths=self.levels.phase_noise_paths)

    def effects(self, seed: int, index: int) -> dict[str, dict[str, Any]]:
        """The effect-catalog draws of item ``index``, ``{name: values}`` (its own stream, ``Stream.EFFECTS``)."""
        return self.catalog.draw(item_generator(seed, index, stream=Stream.EFFECTS))

    def sampler(self, base: ScenarioSampler, room: RoomDraw, radar_x_m: float) -> ScenarioSampler:
        """``base`` with this randomization's people ranges, fitted inside ``room``.

        Counts and their weights, toward/away and speed spacing are kept; the radar is at
        ``x = radar_x_m``.
        """
        p = self.people
        lateral = max(0.0, room.width_m / 2 - p.wall_margin_m)
        far = max(0.0, room.length_m - radar_x_m - p.wall_margin_m)
        hi = min(p.range_m[1], far)
        lo = min(p.range_m[0], hi)
        return dataclasses.replace(
            base, speed_m_s=p.speed_m_s, height_m=p.height_m, range_m=(lo, hi),
            lateral_m=(-lateral, lateral), heading_jitter_deg=p.heading_jitter_deg,
            crossing_probability=max(base.crossing_probability, p.crossing_probability),
            standing_probability=max(base.standing_probability, p.standing_probability),
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
    """The per-item draws: room variant, receiver offsets, each person's RCS scale, static scatterers, effects.

    The scatterers are ``(range_m, azimuth_deg, elevation_deg, rcs_dBsm)``. ``catalog`` holds the
    effects the item carries, ``{name: values}`` as each :class:`~radaraug.sim.catalog.CatalogEffect`
    drew them; ``phase_noise_paths`` is carried (:attr:`LevelPriors.phase_noise_paths`), not drawn.
    """

    variant: int
    system_gain_offset_dB: float
    noise_figure_offset_dB: float
    rcs_scale_dB: tuple[float, ...]
    scatterers: tuple[tuple[float, float, float, float], ...] = ()
    phase_noise_rms_Hz: float | None = None
    catalog: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    phase_noise_paths: int = 16

    @property
    def adc_noise_offset_dB(self) -> float:
        """Offset on the ``adc_noise`` stage's RMS (the catalog's ``wide_levels``; else 0), dB."""
        return float(self.catalog.get("wide_levels", {}).get("adc_noise_offset_dB", 0.0))

    @property
    def static_phase_noise_paths(self) -> int:
        """How many of the room's strongest returns carry the phase noise (the catalog's ``static_phase_noise``)."""
        return int(self.catalog.get("static_phase_noise", {}).get("paths", 0))

    def effects_dict(self, config: RadarConfig) -> dict[str, Any]:
        """The catalog effects this item carries, ``{name: {parameter: value}}`` (JSON-able)."""
        return catalog_record(self.catalog, config)

    def catalog_effects(self, config: RadarConfig) -> list[Effect]:
        """The receiver stages of the catalog effects this item carries (to insert at their place)."""
        return catalog_stages(self.catalog, config)


def check_receiver(receiver: FMCWReceiver, randomization: TwinRandomization) -> None:
    """Raise ConfigError when ``receiver`` cannot take the randomization's gain / noise offsets."""
    names = [e.name for e in receiver.effects]
    first_nonlinear = next((i for i, e in enumerate(receiver.effects) if e.kind == "nonlinear"), len(names))
    levels, catalog = randomization.levels, randomization.catalog
    wide = catalog["wide_levels"]
    assert isinstance(wide, WideLevelsPrior)
    wide_on = catalog.scale * wide.probability > 0
    zero = (0.0, 0.0)
    if levels.system_gain_offset_dB != zero or (wide_on and wide.system_gain_offset_dB != zero):
        if "system_gain" not in names:
            raise ConfigError("twin randomization: the receiver has no system_gain stage; add one or set "
                              "levels.system_gain_offset_dB (and catalog.wide_levels.system_gain_offset_dB) to [0, 0]")
        # The room's cached signal went through the linear stages before the first non-linear
        # one; only there does scaling it by the gain equal applying the gain.
        if names.index("system_gain") > first_nonlinear:
            raise ConfigError("twin randomization: the receiver's system_gain comes after a non-linear stage")
    nf_used = levels.noise_figure_offset_dB != zero or (wide_on and wide.noise_figure_offset_dB != zero)
    if nf_used and "thermal_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no thermal_noise stage; add one or set "
                          "levels.noise_figure_offset_dB (and catalog.wide_levels.noise_figure_offset_dB) to [0, 0]")
    if wide_on and wide.adc_noise_offset_dB != zero and "adc_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no adc_noise stage; add one or set "
                          "catalog.wide_levels.adc_noise_offset_dB to [0, 0] (or its probability to 0)")
    if levels.phase_noise_rms_Hz != zero and "phase_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no phase_noise stage; add one or set "
                          "levels.phase_noise_rms_Hz to [0, 0]")
    if catalog.scale * catalog["static_phase_noise"].probability > 0 and "phase_noise" not in names:
        raise ConfigError("twin randomization: the receiver has no phase_noise stage for the room's strongest "
                          "returns; add one or set catalog.static_phase_noise.probability to 0")


__all__ = [
    "DEFAULT_MATERIALS", "ItemDraw", "LevelPriors", "PeoplePriors", "RoomDraw", "RoomPriors", "TwinRandomization",
    "check_receiver",
]
