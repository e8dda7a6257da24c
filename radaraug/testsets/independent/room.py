"""The held-out generator's room: static point scatterers levelled by the radar equation.

Nothing of the twin's scene, materials or ray tracer: walls (specular and diffuse), corners,
fixtures and an optional fan are points with an RCS, an antenna pattern written here turns them
into received levels, and :data:`OFFICE` is the ``independent`` set's room. Model and values:
docs/heldout_worlds.md ("Room").
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from radaraug.config import RadarConfig

ROOM_SIZE_M = (9.0, 4.0, 2.8)
"""Length (x), width (y), height (z)."""
RADAR_POSITION_M = (0.12, 1.65, 1.10)
RADAR_TILT_DOWN_DEG = 3.0
ANTENNA_GAIN_DBI = 5.5
HALF_POWER_BEAMWIDTH_DEG = 80.0
PATTERN_FLOOR_DB = -15.0
"""One antenna's gain, relative to boresight, at wide angles and behind the board."""
ROOM_SEED = 20_240_919
"""Seed of the room's fixed scattering phases and roughness (not the generator's ``seed``)."""

WALL_REFLECTIVITY_DB: dict[str, float] = {
    "far_wall": -10.0,  # plasterboard partition on studs: ~-12 dB per board, layered
    "left_wall": -8.0,  # painted concrete (eps ~5.5)
    "right_wall": -7.5,  # glazing over a concrete sill (glass eps ~6.3)
    "floor": -12.0,  # carpet tiles on concrete
    "ceiling": -15.0,  # mineral-fibre acoustic tiles
}
"""Power reflectivity ``|Gamma|^2`` at normal incidence, 60 GHz (assumed from typical permittivities)."""
DIFFUSE_MU: dict[str, float] = {"left_wall": 0.03, "right_wall": 0.02, "floor": 0.05, "ceiling": 0.04}
"""Backscatter coefficient at normal incidence of the surfaces seen at grazing angles."""
DIFFUSE_STEP_M = 0.9
DIFFUSE_STRIP_M = 1.0
"""Extent across the strip of each diffuse patch (area ``DIFFUSE_STEP_M x DIFFUSE_STRIP_M``)."""

OBJECTS: tuple[tuple[str, tuple[float, float, float], float], ...] = (
    # name, position (m), RCS (dBsm)
    ("far_wall_floor_edge", (9.0, 1.65, 0.0), 4.0),  # dihedral, 1 m long, seen ~7 deg below boresight
    ("far_wall_ceiling_edge", (9.0, 1.65, 2.8), 2.0),
    ("door_frame", (9.0, 3.2, 1.0), -2.0),  # steel frame of the door in the far wall
    ("cabinet_front", (6.1, 0.55, 1.2), 8.0),  # steel filing cabinet 0.5 x 0.6 x 1.9 m by the left wall
    ("cabinet_edge", (5.85, 0.6, 0.6), 3.0),
    ("cabinet_top", (6.1, 0.3, 1.9), 0.0),
    ("desk_edge", (3.1, 3.25, 0.75), -3.0),  # desk by the window
    ("desk_legs", (3.4, 3.6, 0.35), -6.0),
    ("chair_back", (3.0, 3.0, 0.9), -5.0),  # office chair, metal base
    ("chair_base", (3.0, 3.0, 0.15), -4.0),
    ("pillar_low", (7.3, 3.45, 0.8), 5.0),  # concrete pillar, 0.35 m diameter, by the right wall
    ("pillar_high", (7.3, 3.45, 1.9), 4.0),
    ("radiator", (5.0, 3.9, 0.5), 2.0),  # ribbed steel radiator under the window
    ("window_frame", (5.0, 4.0, 1.6), -4.0),
    ("lamp_1", (3.0, 2.0, 2.75), -6.0),  # ceiling lamps with metal louvres
    ("lamp_2", (6.5, 2.0, 2.75), -6.0),
)
"""Point scatterers of the room's fixtures (RCS assumed from size and material). The furniture
stands by the walls, leaving the band ``WALK_Y_M`` free for the people."""
WALK_X_M = (1.12, 8.5)
"""Walkable floor along ``x``: from 1 m in front of the radar to 0.5 m from the far wall."""
WALK_Y_M = (0.8, 2.9)
"""Walkable floor across the room, clear of the furniture."""

FAN: dict[str, Any] = {
    "position_m": (3.25, 3.6, 0.95),
    "rcs_dBsm": -8.0,  # a 30 cm desk fan: grille and housing
    "displacement_m": 0.25e-3,  # housing vibration amplitude
    "vibration_Hz": 24.3,  # 1460 rpm: a 4-pole motor on 50 Hz mains, with slip
    "blades": 3,
    "blade_rcs_dBsm": -25.0,  # each blade's scattering point, behind the grille
    "blade_radial_m": 0.08,  # 0.13 m blade radius x the sine of the view angle on the blade plane
}
"""The desk fan (a vibrating scatterer, fixed before any result was seen)."""


@dataclass(frozen=True)
class Mount:
    """Where the radar hangs and where it looks.

    Attributes:
        position_m: room-frame position of the antenna (m).
        tilt_down_deg: boresight elevation below the horizontal (a radar high on a wall looks down).
        yaw_deg: boresight azimuth from ``+x`` toward ``+y``.
    """

    position_m: tuple[float, float, float] = RADAR_POSITION_M
    tilt_down_deg: float = RADAR_TILT_DOWN_DEG
    yaw_deg: float = 0.0


@dataclass(frozen=True)
class Room:
    """A room of point scatterers: its box, surfaces, fixtures, the radar's mount and the walkable floor.

    The defaults are the ``independent`` set's office (docs/heldout_worlds.md, "Room");
    :mod:`radaraug.testsets.independent.worlds` draws others.

    Attributes:
        size_m: length (x), width (y), height (z).
        wall_reflectivity_dB: ``|Gamma|^2`` at normal incidence of ``far_wall``, ``left_wall``,
            ``right_wall``, ``floor``, ``ceiling``.
        diffuse_mu: backscatter coefficient of the surfaces seen at grazing angles (any of the
            side walls, floor and ceiling).
        objects: fixtures ``(name, position_m, rcs_dBsm)``.
        walk_x_m, walk_y_m: the walkable floor, clear of the fixtures.
        fan: a running fan (:data:`FAN`'s keys) or None.
        mount: the radar's :class:`Mount`.
        seed: seed of the fixed scattering phases and roughness.
    """

    size_m: tuple[float, float, float] = ROOM_SIZE_M
    wall_reflectivity_dB: Mapping[str, float] = field(default_factory=lambda: dict(WALL_REFLECTIVITY_DB))
    diffuse_mu: Mapping[str, float] = field(default_factory=lambda: dict(DIFFUSE_MU))
    objects: tuple[tuple[str, tuple[float, float, float], float], ...] = OBJECTS
    walk_x_m: tuple[float, float] = WALK_X_M
    walk_y_m: tuple[float, float] = WALK_Y_M
    fan: Mapping[str, Any] | None = field(default_factory=lambda: dict(FAN))
    mount: Mount = Mount()
    seed: int = ROOM_SEED


OFFICE = Room()
"""The fixed office of the ``independent`` held-out set."""


@dataclass(frozen=True)
class Scatterer:
    """A static point scatterer of the room.

    Attributes:
        name: what it is.
        position_m: room-frame position (m).
        rcs_dBsm: radar cross-section (dBsm; for walls the image-equivalent RCS).
        phase_rad: constant scattering phase.
    """

    name: str
    position_m: tuple[float, float, float]
    rcs_dBsm: float
    phase_rad: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly description."""
        return {"name": self.name, "position_m": [round(v, 4) for v in self.position_m],
                "rcs_dBsm": round(self.rcs_dBsm, 3), "phase_rad": round(self.phase_rad, 4)}


# ------------------------------------------------------------------------------- radar geometry
def radar_axes(mount: Mount = OFFICE.mount) -> np.ndarray:
    """Rows: the antenna frame's x (sensor right), y (sensor up) and z (boresight) in the room frame."""
    tilt = math.radians(mount.tilt_down_deg)
    yaw = math.radians(mount.yaw_deg)
    cy, sy = math.cos(yaw), math.sin(yaw)
    bore = np.array([math.cos(tilt) * cy, math.cos(tilt) * sy, -math.sin(tilt)])
    up = np.array([math.sin(tilt) * cy, math.sin(tilt) * sy, math.cos(tilt)])
    right = np.cross(bore, up)  # looking along +x with z up, the right hand is -y
    return np.stack([right, up, bore])


def pattern_exponent() -> float:
    """``q`` of ``cos(theta)^q`` with half power at half the beamwidth."""
    return math.log(0.5) / math.log(math.cos(math.radians(HALF_POWER_BEAMWIDTH_DEG / 2.0)))


def antenna_gain(cos_theta: np.ndarray) -> np.ndarray:
    """One antenna's linear power gain at ``cos(theta)`` off boresight."""
    shape = np.clip(cos_theta, 0.0, 1.0) ** pattern_exponent()
    return 10.0 ** (ANTENNA_GAIN_DBI / 10.0) * np.maximum(shape, 10.0 ** (PATTERN_FLOOR_DB / 10.0))


def look(points_m: np.ndarray, mount: Mount = OFFICE.mount) -> tuple[np.ndarray, np.ndarray]:
    """Range ``(...)`` and unit direction in the antenna frame ``(..., 3)`` of room points ``(..., 3)``."""
    d = np.asarray(points_m, dtype=np.float64) - np.asarray(mount.position_m)
    r = np.linalg.norm(d, axis=-1)
    return r, (d / r[..., None]) @ radar_axes(mount).T


def level_dB(rcs_m2: np.ndarray, range_m: np.ndarray, u_ant: np.ndarray, wavelength_m: float) -> np.ndarray:
    """Received power relative to TX power (dB) by the radar equation with the antenna pattern."""
    g = antenna_gain(u_ant[..., 2])
    p = g * g * wavelength_m**2 * np.asarray(rcs_m2) / ((4.0 * math.pi) ** 3 * np.asarray(range_m) ** 4)
    return 10.0 * np.log10(np.maximum(p, 1e-300))


def rx_phase_rad(u_ant: np.ndarray, config: RadarConfig) -> np.ndarray:
    """Far-field phase of each RX ``(..., RX)``: ``-2 pi (d_rx . u) / lambda``.

    An RX displaced by ``d_rx`` toward the target hears the echo ``d_rx . u`` earlier (its path is
    shorter), which lowers the beat's phase ``f0 tau`` by that much over the wavelength.
    """
    d = np.asarray(config.rx_positions, dtype=np.float64)  # (RX, 3), antenna frame
    return -2.0 * math.pi * (u_ant @ d.T) / config.wavelength_m


# ------------------------------------------------------------------------------------ the room
def room_scatterers(room: Room = OFFICE) -> list[Scatterer]:
    """Every static point of ``room`` (walls, corners, objects), with fixed phases."""
    rng = np.random.default_rng(np.random.SeedSequence(room.seed))
    length, width, height = room.size_m
    rx_, ry, rz = room.mount.position_m
    pts: list[tuple[str, tuple[float, float, float], float]] = []
    # Specular points: the foot of the perpendicular from the radar on each plane, RCS pi d^2 |Gamma|^2.
    planes = {"far_wall": ((length, ry, rz), length - rx_), "left_wall": ((rx_, 0.0, rz), ry),
              "right_wall": ((rx_, width, rz), width - ry), "floor": ((rx_, ry, 0.0), rz),
              "ceiling": ((rx_, ry, height), height - rz)}
    for name, (foot, d) in planes.items():
        sigma = math.pi * d * d * 10.0 ** (room.wall_reflectivity_dB[name] / 10.0)
        pts.append((f"{name}_specular", foot, 10.0 * math.log10(sigma)))
    # Diffuse strips along the surfaces seen at grazing angles: the specular foot moved along x.
    xs = np.arange(0.6, length - 0.2, DIFFUSE_STEP_M)
    for name, mu in room.diffuse_mu.items():
        (_, y, z), d = planes[name]
        for x in xs:
            cos_i = d / math.hypot(x - rx_, d)
            sigma = mu * cos_i**2 * DIFFUSE_STEP_M * DIFFUSE_STRIP_M
            rough = float(rng.uniform(-3.0, 3.0))
            pts.append((f"{name}_diffuse_{x:.1f}", (float(x), y, z), 10.0 * math.log10(sigma) + rough))
    pts += room.objects
    phases = rng.uniform(0.0, 2.0 * math.pi, len(pts))
    return [Scatterer(n, tuple(float(v) for v in p), float(s), float(ph))  # type: ignore[arg-type]
            for (n, p, s), ph in zip(pts, phases)]


def room_scene(config: RadarConfig, scatterers: list[Scatterer] | None = None,
               room: Room = OFFICE) -> list[dict[str, Any]]:
    """The room as the receiver's ``scene`` points ``{"range_m", "level_dB", "phase_rad", "rx_phase_rad"}``."""
    scatterers = room_scatterers(room) if scatterers is None else scatterers
    pos = np.array([s.position_m for s in scatterers])
    r, u = look(pos, room.mount)
    lev = level_dB(10.0 ** (np.array([s.rcs_dBsm for s in scatterers]) / 10.0), r, u, config.wavelength_m)
    ph = rx_phase_rad(u, config)
    return [{"range_m": float(r[i]), "level_dB": float(lev[i]), "phase_rad": s.phase_rad,
             "rx_phase_rad": [float(v) for v in ph[i]]} for i, s in enumerate(scatterers)]


def fan_effects(config: RadarConfig, room: Room = OFFICE) -> list[dict[str, Any]]:
    """The room's fan as ``vibrating_clutter`` effects: the housing, then each blade (none without a fan)."""
    fan = room.fan
    if fan is None:
        return []
    r, u = look(np.array(fan["position_m"]), room.mount)

    def part(rcs_dBsm: float, displacement_m: float, phase_rad: float, path_phase_rad: float) -> dict[str, Any]:
        return {"name": "vibrating_clutter", "range_m": float(r),
                "level_dB": float(level_dB(10.0 ** (rcs_dBsm / 10.0), r, u, config.wavelength_m)),
                "displacement_m": float(displacement_m), "vibration_Hz": float(fan["vibration_Hz"]),
                "phase_rad": phase_rad, "path_phase_rad": path_phase_rad}

    n = int(fan["blades"])
    return [part(fan["rcs_dBsm"], fan["displacement_m"], 0.4, 2.1)] + [
        part(fan["blade_rcs_dBsm"], fan["blade_radial_m"], 2.0 * math.pi * k / n, 0.9 + 1.7 * k) for k in range(n)]


def describe(room: Room = OFFICE) -> dict[str, Any]:
    """The room, radar mount and antenna model (for the manifest)."""
    fan = room.fan
    return {
        "size_m": list(room.size_m),
        "radar_position_m": list(room.mount.position_m),
        "radar_tilt_down_deg": room.mount.tilt_down_deg,
        **({"radar_yaw_deg": room.mount.yaw_deg} if room.mount.yaw_deg else {}),
        "antenna": {"gain_dBi": ANTENNA_GAIN_DBI, "half_power_beamwidth_deg": HALF_POWER_BEAMWIDTH_DEG,
                    "pattern": "G0 max(cos(theta)^q, floor)", "q": round(pattern_exponent(), 4),
                    "floor_dB": PATTERN_FLOOR_DB},
        "level_law": "P_r/P_t = G(theta)^2 lambda^2 sigma / ((4 pi)^3 R^4)",
        "wall_reflectivity_dB": dict(room.wall_reflectivity_dB),
        "diffuse": {"mu": dict(room.diffuse_mu), "step_m": DIFFUSE_STEP_M, "strip_m": DIFFUSE_STRIP_M,
                    "law": "sigma = mu cos^2(i) A, x U(-3, 3) dB roughness"},
        "scatterers": [s.to_dict() for s in room_scatterers(room)],
        "walkable_m": {"x": list(room.walk_x_m), "y": list(room.walk_y_m)},
        "fan": None if fan is None else {**fan, "position_m": list(fan["position_m"])},
        "room_seed": room.seed,
    }


__all__ = [
    "FAN", "OBJECTS", "OFFICE", "RADAR_POSITION_M", "ROOM_SIZE_M", "Mount", "Room", "Scatterer", "antenna_gain", "describe", "fan_effects",
    "level_dB", "look", "room_scatterers", "room_scene", "rx_phase_rad",
]
