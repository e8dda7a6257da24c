"""Twin profiles: a fitted receiver chain as a small JSON the simulator and the recipes load.

A profile holds the receiver description (:meth:`FMCWReceiver.to_dict`: TX power, front-end
gain, the effect chain with every parameter) and what it was fitted on. Parameters that belong
to the radar *configuration* rather than to the sensor are stored as ``null`` so that they are
taken from whatever config the profile is applied to: the IF gain. Everything else (noise
figure, ADC-side noise, filter cutoffs, DC levels, spurs, drift...) is the sensor's and is kept.

Applying a profile to a config with another RX count fails with a clear error for per-RX
parameters (a per-RX list for 3 channels cannot serve 1).
"""

from __future__ import annotations

import copy
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError
from radaraug.safe_read import load_json
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

PROFILE_FORMAT = "radaraug-twin-profile"
PROFILE_VERSION = 1
CONFIG_OWNED = {"if_gain": ("gain_dB",)}
"""Effect parameters that follow the radar config (stored as null)."""


class TwinProfile:
    """A fitted receiver chain.

    Args:
        receiver: the receiver description (:meth:`FMCWReceiver.to_dict`).
        fitted_on: provenance (capture, scene, mode, config, errors).
    """

    def __init__(self, receiver: Mapping[str, Any], fitted_on: Mapping[str, Any] | None = None) -> None:
        if not isinstance(receiver, Mapping) or not isinstance(receiver.get("effects"), list):
            raise CalibrationError("a twin profile needs a receiver description with an 'effects' list")
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

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly dict."""
        return {
            "format": PROFILE_FORMAT,
            "version": PROFILE_VERSION,
            "receiver": self.receiver_dict,
            "fitted_on": self.fitted_on,
            "units": FLOAT_CONVENTION,
            "db_convention": DB_CONVENTION,
        }

    def save(self, path: str | os.PathLike) -> Path:
        """Write the profile atomically (a temporary file of this process + rename, so concurrent
        writers of the same profile never mix their bytes)."""
        p = Path(path)
        tmp = p.with_name(f"{p.name}.{os.getpid()}.tmp")
        tmp.write_text(json.dumps(self.to_dict(), indent=1))
        os.replace(tmp, p)
        return p

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "twin profile") -> TwinProfile:
        """Inverse of :meth:`to_dict`; :class:`CalibrationError` for anything else."""
        if not isinstance(data, Mapping) or data.get("format") != PROFILE_FORMAT:
            raise CalibrationError(f"{source}: not a radaraug twin profile (format must be {PROFILE_FORMAT!r})")
        if data.get("version") != PROFILE_VERSION:
            raise CalibrationError(f"{source}: twin profile version {data.get('version')!r}, this radaraug reads "
                                   f"{PROFILE_VERSION}")
        prof = cls(data.get("receiver") or {}, data.get("fitted_on"))
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


def as_profile(profile: TwinProfile | str | os.PathLike | Mapping[str, Any] | None) -> TwinProfile | None:
    """A :class:`TwinProfile` from a profile, a path or a dict (None stays None)."""
    if profile is None or isinstance(profile, TwinProfile):
        return profile
    if isinstance(profile, Mapping):
        return TwinProfile.from_dict(profile)
    return TwinProfile.load(profile)
