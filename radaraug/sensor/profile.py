"""Twin profiles: a fitted receiver chain as a small JSON the simulator and the recipes load.

A profile holds the receiver description (:meth:`FMCWReceiver.to_dict`), the fitted ``room`` section
(ray-tracer options, :data:`ROOM_PARAMS`) and what it was fitted on. The IF gain belongs to the radar
configuration and is stored as ``null``; per-RX parameters fail clearly on a config with another RX count.
Format and use: ``docs/diagnosis.md``, "Twin profiles".
"""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError
from radaraug.files import atomic_write_json, load_json
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

PROFILE_FORMAT = "radaraug-twin-profile"
PROFILE_VERSION = 2
READABLE_VERSIONS = (1, 2)
"""Versions this radaraug reads (1: no ``room`` section)."""
ROOM_PARAMS = {"diffuse_gain_dB": "power gain on every diffuse scattering path of the room, dB (tracer option)"}
"""Parameters a profile's ``room`` section may hold (each a finite number, a RayTracer option)."""
CONFIG_OWNED = {"if_gain": ("gain_dB",)}
"""Effect parameters that follow the radar config (stored as null)."""


class TwinProfile:
    """A fitted receiver chain, and the room parameters fitted with it.

    Args:
        receiver: the receiver description (:meth:`FMCWReceiver.to_dict`).
        fitted_on: provenance (capture, scene, mode, config, errors).
        room: fitted room parameters (keys of :data:`ROOM_PARAMS`, e.g.
            ``{"diffuse_gain_dB": 4.2}``); empty when the room was not fitted.

    Raises:
        CalibrationError: no effect list, or a room parameter that is unknown or not a finite number.
    """

    def __init__(self, receiver: Mapping[str, Any], fitted_on: Mapping[str, Any] | None = None,
                 room: Mapping[str, Any] | None = None) -> None:
        if not isinstance(receiver, Mapping) or not isinstance(receiver.get("effects"), list):
            raise CalibrationError("a twin profile needs a receiver description with an 'effects' list")
        self.room = _check_room(room)
        rec = copy.deepcopy(dict(receiver))
        for e in rec["effects"]:
            for p in CONFIG_OWNED.get(e.get("name"), ()):
                if p in e.get("params", {}):
                    e["params"][p] = None
        self.receiver_dict = rec
        self.fitted_on = dict(fitted_on or {})

    @property
    def effect_names(self) -> list[str]:
        """The chain's effect names in hardware order."""
        return [e["name"] for e in self.receiver_dict["effects"]]

    def receiver(self, config: RadarConfig) -> FMCWReceiver:
        """An :class:`FMCWReceiver` with this profile's chain for ``config``."""
        try:
            return FMCWReceiver.from_dict(config, self.receiver_dict)
        except ConfigError as e:
            raise CalibrationError(f"twin profile {self.fitted_on.get('capture', '')}: {e}") from None

    def tracer_options(self) -> dict[str, float]:
        """The room section as :class:`~radaraug.raytrace.RayTracer` keyword arguments."""
        return dict(self.room)

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly dict."""
        return {
            "format": PROFILE_FORMAT,
            "version": PROFILE_VERSION,
            "receiver": self.receiver_dict,
            "room": dict(self.room),
            "fitted_on": self.fitted_on,
            "units": FLOAT_CONVENTION,
            "db_convention": DB_CONVENTION,
        }

    def save(self, path: str | os.PathLike) -> Path:
        """Write the profile atomically (temporary file, fsync, rename; :mod:`radaraug.files`)."""
        return atomic_write_json(path, self.to_dict(), newline=False, indent=1)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "twin profile") -> TwinProfile:
        """Inverse of :meth:`to_dict`; :class:`CalibrationError` for anything else."""
        if not isinstance(data, Mapping) or data.get("format") != PROFILE_FORMAT:
            raise CalibrationError(f"{source}: not a radaraug twin profile (format must be {PROFILE_FORMAT!r})")
        version = data.get("version")
        if isinstance(version, bool) or version not in READABLE_VERSIONS:
            raise CalibrationError(f"{source}: twin profile version {version!r}, this radaraug reads "
                                   f"{', '.join(map(str, READABLE_VERSIONS))}")
        room = data.get("room") if version >= 2 else None
        try:
            prof = cls(data.get("receiver") or {}, data.get("fitted_on"), room)
        except CalibrationError as e:
            raise CalibrationError(f"{source}: {e}") from None
        try:
            prof.receiver(RadarConfig.from_dict(prof.fitted_on["config"])) if "config" in prof.fitted_on else None
        except (CalibrationError, ConfigError) as e:
            raise CalibrationError(f"{source}: {e}") from None
        return prof

    @classmethod
    def load(cls, path: str | os.PathLike) -> TwinProfile:
        """Read a profile JSON; :class:`CalibrationError` naming the file for anything wrong."""
        p = Path(path)
        data = load_json(p, error=CalibrationError, what="twin profile")
        return cls.from_dict(data, source=str(p))


def _check_room(room: Mapping[str, Any] | None) -> dict[str, float]:
    """The room section as ``{name: float}``; :class:`CalibrationError` for anything else."""
    if room is None:
        return {}
    if not isinstance(room, Mapping):
        raise CalibrationError(f"the profile's room section must be a mapping, got {type(room).__name__}")
    out = {}
    for k, v in room.items():
        if k not in ROOM_PARAMS:
            raise CalibrationError(f"unknown room parameter {k!r} (known: {', '.join(ROOM_PARAMS)})")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise CalibrationError(f"room parameter {k!r} must be a finite number, got {v!r}")
        out[k] = float(v)
    return out


def as_profile(profile: TwinProfile | str | os.PathLike | Mapping[str, Any] | None) -> TwinProfile | None:
    """A :class:`TwinProfile` from a profile, a path or a dict (None stays None)."""
    if profile is None or isinstance(profile, TwinProfile):
        return profile
    if isinstance(profile, Mapping):
        return TwinProfile.from_dict(profile)
    return TwinProfile.load(profile)
