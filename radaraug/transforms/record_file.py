"""The calibration record: what one empty-room capture calibrates, in one versioned JSON file.

:func:`load_record` is the one reader; it also reads older CalibratedDR, twin-profile and noise-fit
files as partial records (docs/diagnosis.md, "The calibration record"). No other transform module is
imported here; :func:`radaraug.diagnosis.record.fit_record` fits records.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import torch

from radaraug._cache_key import content_digest as content_digest  # re-exported: the record names it
from radaraug.config import RadarConfig
from radaraug.errors import CalibrationError, ConfigError
from radaraug.files import atomic_write_json, load_json, safe_repr
from radaraug.sensor.profile import PROFILE_FORMAT, TwinProfile
from radaraug.units import DB_CONVENTION

RECORD_FORMAT = "radaraug-calibration"
RECORD_VERSION = 1
"""1: the first one-file record (CalibratedDR's floor, profile, noise fit, persistent cells, capture)."""

CDR_FORMAT = "radaraug.CalibratedDR"
CDR_VERSIONS = (1, 2)
"""The CalibratedDR JSON of earlier radaraug: 1 a normal floor, 2 an empirical one (read, no longer written)."""

NOISE_FIT_FORMAT = "radaraug-noise-fit"
NOISE_FIT_VERSIONS = (1, 2)
"""1: the noise figure moved alone; 2: thermal and ADC-side noise moved together."""

#: The record's ``cdr`` keys in the file, and the CalibratedDR argument each one is.
_CDR_KEYS = {"mean_db": "mean_db", "std_db": "std_db", "floor": "floor", "quantiles_db": "quantiles_db",
             "chain": "chain", "map_shape": "map_shape", "source": "source", "num_frames": "num_frames",
             "motion_fraction": "motion"}


@dataclass
class CalibrationRecord:
    """The empty-room fit of one capture (every section optional; a partial record has some).

    Attributes:
        cdr: CalibratedDR's fitted arguments (``mean_db``, ``std_db``, ``floor``, ``quantiles_db``, ``chain``,
            ``map_shape``, ``source``, ``num_frames``, ``motion``).
        config: the capture's radar config.
        capture: ``{"name", "sha256", "frames"}``: :func:`content_digest` (None for frames from no file) and
            the frames the floor was fitted on.
        profile: the twin profile ``diagnose`` fitted on the capture (no scene).
        noise_fit: the twin's noise fit (:func:`radaraug.diagnosis.noise_fit.fit_noise_figure`'s dict).
        persistent_cells: ``{"threshold_db", "shape": [range, doppler], "cells": [[r, d], ...]}``
            (:meth:`persistent_mask`).
        file: the file it was read from (not saved).
        read_as: the format and version it was read as, e.g. ``"radaraug.CalibratedDR 2"`` (not saved).
    """

    cdr: dict[str, Any] | None = None
    config: RadarConfig | None = None
    capture: dict[str, Any] | None = None
    profile: TwinProfile | None = None
    noise_fit: dict[str, Any] | None = None
    persistent_cells: dict[str, Any] | None = None
    file: str | None = field(default=None, compare=False)
    read_as: str = field(default=f"{RECORD_FORMAT} {RECORD_VERSION}", compare=False)

    @classmethod
    def from_cdr(cls, cdr: Any, **sections: Any) -> CalibrationRecord:
        """The record of a CalibratedDR's floor, plus the other ``sections`` given."""
        args = {arg: getattr(cdr, arg) for arg in _CDR_KEYS.values()}
        if args["quantiles_db"] is not None:
            args["quantiles_db"] = args["quantiles_db"].tolist()
        return cls(cdr=args, config=cdr.config, **sections)

    def cdr_arguments(self) -> dict[str, Any]:
        """CalibratedDR's constructor arguments (``config`` included).

        Raises:
            CalibrationError: the record holds no floor; the message names the file.
        """
        if self.cdr is None:
            raise CalibrationError(f"{self.file or 'calibration record'} ({self.read_as}) holds no CalibratedDR "
                                   "floor: fit one on the empty-room capture (radaraug fit-cdr)")
        return {**self.cdr, "config": self.config}

    def persistent_mask(self) -> torch.Tensor | None:
        """The persistent cells as a ``(range, doppler)`` bool mask (None when not recorded)."""
        if self.persistent_cells is None:
            return None
        mask = torch.zeros(tuple(self.persistent_cells["shape"]), dtype=torch.bool)
        cells = torch.as_tensor(self.persistent_cells["cells"], dtype=torch.long).reshape(-1, 2)
        mask[cells[:, 0], cells[:, 1]] = True
        return mask

    def to_dict(self) -> dict[str, Any]:
        """The JSON document :meth:`save` writes."""
        import radaraug

        cdr = None
        if self.cdr is not None:
            cdr = {key: self.cdr.get(arg) for key, arg in _CDR_KEYS.items()}
            q = cdr["quantiles_db"]
            # rounded to 0.1 mdB: the file stays small (1025 values) and the floor unchanged in effect
            cdr["quantiles_db"] = None if q is None else [round(float(v), 4) for v in q]
            cdr["map_shape"] = None if cdr["map_shape"] is None else [int(v) for v in cdr["map_shape"]]
        return {
            "format": RECORD_FORMAT,
            "version": RECORD_VERSION,
            "db_convention": DB_CONVENTION,
            "radaraug_version": radaraug.__version__,
            "capture": self.capture,
            "config": None if self.config is None else self.config.to_dict(),
            "cdr": cdr,
            "profile": None if self.profile is None else self.profile.to_dict(),
            "noise_fit": self.noise_fit,
            "persistent_cells": self.persistent_cells,
        }

    def save(self, path: str | os.PathLike) -> Path:
        """Write the record as one JSON file, atomically (a crash leaves the old file or none).

        Raises:
            CalibrationError: the file cannot be written (the message names it).
        """
        try:
            return atomic_write_json(path, self.to_dict(), indent=2)
        except OSError as e:
            raise CalibrationError(f"cannot write calibration file {path}: {e.strerror or e}") from None


def load_record(path: str | os.PathLike) -> CalibrationRecord:
    """Read a calibration record, or an older CalibratedDR JSON, twin profile or noise fit as a partial one.

    Raises:
        CalibrationError: a missing, oversized or non-JSON file, another format, version or dB convention,
            or a malformed field; the message names the file.
    """
    data = load_json(path, error=CalibrationError, what="calibration file")
    record = parse_record(data, str(path))
    record.file = str(path)
    return record


def parse_record(data: Any, source: str) -> CalibrationRecord:
    """The record in a parsed JSON document (see :func:`load_record`); ``source`` names it in errors."""
    where = f"calibration file {source}"
    if not isinstance(data, Mapping):
        raise CalibrationError(f"{where} is not a calibration record (a JSON object with a 'format')")
    fmt = data.get("format")
    if fmt == RECORD_FORMAT:
        return _parse_current(data, where)
    if fmt == CDR_FORMAT:
        version = data.get("format_version", 1)
        _check_version(version, CDR_VERSIONS, f"{where}: {CDR_FORMAT} format_version", where)
        _check_convention(data, where)
        return CalibrationRecord(cdr=_cdr_section(data, where), config=_config(data.get("config"), where),
                                 read_as=f"{CDR_FORMAT} {version}")
    if fmt == PROFILE_FORMAT:
        profile = TwinProfile.from_dict(data, source=source)
        cfg = profile.fitted_on.get("config")
        return CalibrationRecord(profile=profile, config=_config(cfg, where),
                                 read_as=f"{PROFILE_FORMAT} {data.get('version')}")
    if fmt == NOISE_FIT_FORMAT or (fmt is None and "noise_figure_dB" in data):
        version = data.get("version", 1)
        _check_version(version, NOISE_FIT_VERSIONS, f"{where}: {NOISE_FIT_FORMAT} version", where)
        return CalibrationRecord(noise_fit=_noise_fit(data, where),
                                 read_as=f"{NOISE_FIT_FORMAT} {version}{'' if fmt else ' (untagged)'}")
    raise CalibrationError(f"{where} is not a calibration record: format {safe_repr(fmt)}; this radaraug reads "
                           f"{RECORD_FORMAT} (and the older {CDR_FORMAT}, {PROFILE_FORMAT}, {NOISE_FIT_FORMAT})")


def _check_version(version: Any, readable: tuple[int, ...], what: str, where: str) -> None:
    if isinstance(version, bool) or version not in readable:
        raise CalibrationError(f"{what} {safe_repr(version)}; this radaraug reads {', '.join(map(str, readable))} "
                               "(a file written by a newer radaraug: update radaraug, or refit)")


def _check_convention(data: Mapping[str, Any], where: str) -> None:
    convention = data.get("db_convention", DB_CONVENTION)
    if convention != DB_CONVENTION:
        # (m_t, s_t) in another dB scale would clamp at a silently wrong level.
        raise CalibrationError(f"{where} was fitted in another dB convention ({safe_repr(convention)}); "
                               f"radaraug's maps use {DB_CONVENTION!r}")


def _parse_current(data: Mapping[str, Any], where: str) -> CalibrationRecord:
    _check_version(data.get("version"), (RECORD_VERSION,), f"{where}: {RECORD_FORMAT} version", where)
    _check_convention(data, where)
    sections = {k: data.get(k) for k in _SECTIONS}
    for name, value in sections.items():
        if value is not None and not isinstance(value, Mapping):
            raise CalibrationError(f"{where}: '{name}' must be an object or null, got {safe_repr(value)}")
    parsed: dict[str, Any] = {k: None if v is None else _SECTIONS[k](v, where) for k, v in sections.items()}
    return CalibrationRecord(config=_config(data.get("config"), where), **parsed)


def _capture(data: Mapping[str, Any], where: str) -> dict[str, Any]:
    frames = data.get("frames")
    ok = (isinstance(data.get("name"), (str, type(None))) and isinstance(data.get("sha256"), (str, type(None)))
          and (frames is None or (isinstance(frames, int) and not isinstance(frames, bool) and frames >= 0)))
    if not ok:
        raise CalibrationError(f"{where}: malformed 'capture' {safe_repr(data)}")
    return dict(data)


def _profile(data: Mapping[str, Any], where: str) -> TwinProfile:
    return TwinProfile.from_dict(data, source=f"{where}, profile")


def _cdr_section(data: Mapping[str, Any], where: str) -> dict[str, Any]:
    """CalibratedDR's arguments in a ``cdr`` section or an old CalibratedDR JSON (types checked here)."""
    try:
        mean, std = data["mean_db"], data["std_db"]
        if isinstance(mean, bool) or isinstance(std, bool):
            raise TypeError("mean_db/std_db must be numbers")
        chain = data.get("chain")
        if chain is not None and not (isinstance(chain, list) and all(isinstance(s, dict) for s in chain)):
            raise TypeError("chain must be a list of step objects")
        out = {arg: data.get(key) for key, arg in _CDR_KEYS.items()}
        out.update(mean_db=float(mean), std_db=float(std))
        return out
    except KeyError as e:
        raise CalibrationError(f"{where} lacks the key {e}") from None
    except (TypeError, ValueError, OverflowError) as e:
        raise CalibrationError(f"{where} is malformed: {str(e)[:200]}") from None


def _config(value: Any, where: str) -> RadarConfig | None:
    if value is None:
        return None
    if not isinstance(value, Mapping):
        raise CalibrationError(f"{where}: bad radar config: must be an object, got {safe_repr(value)}")
    try:
        return RadarConfig.from_dict(dict(value))
    except ConfigError as e:
        raise CalibrationError(f"{where}: bad radar config: {e}") from None


def _noise_fit(data: Mapping[str, Any], where: str) -> dict[str, Any]:
    for key in ("noise_figure_dB", "adc_noise_rms_counts"):
        value = data.get(key)
        if (key == "noise_figure_dB" or value is not None) and not (
                isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)):
            raise CalibrationError(f"{where}: noise fit {key} must be a finite number, got {safe_repr(value)}")
    return dict(data)


def _persistent(data: Mapping[str, Any], where: str) -> dict[str, Any]:
    shape, cells, threshold = data.get("shape"), data.get("cells"), data.get("threshold_db")

    def index(v: Any, n: int) -> bool:
        return isinstance(v, int) and not isinstance(v, bool) and 0 <= v < n

    if not (isinstance(shape, list) and len(shape) == 2 and all(index(v, 2**20 + 1) and v > 0 for v in shape)
            and isinstance(threshold, (int, float)) and not isinstance(threshold, bool) and isinstance(cells, list)
            and all(isinstance(c, list) and len(c) == 2 and index(c[0], shape[0]) and index(c[1], shape[1])
                    for c in cells)):
        raise CalibrationError(f"{where}: malformed 'persistent_cells' (need threshold_db, shape [range, doppler] and "
                               "cells [[r, d], ...] inside it)")
    return {"threshold_db": float(threshold), "shape": list(shape), "cells": [list(c) for c in cells]}


#: The record's sections, each with its reader ``(section, where)``: checked, then made.
_SECTIONS: dict[str, Callable[[Mapping[str, Any], str], Any]] = {
    "capture": _capture, "cdr": _cdr_section, "profile": _profile, "noise_fit": _noise_fit,
    "persistent_cells": _persistent}

__all__ = ["CDR_FORMAT", "CDR_VERSIONS", "NOISE_FIT_FORMAT", "NOISE_FIT_VERSIONS", "RECORD_FORMAT", "RECORD_VERSION",
           "CalibrationRecord", "content_digest", "load_record", "parse_record"]
