"""Infineon recording folders (ifxdaq / Radar Fusion GUI, ``format.version`` 1.0.0): reader and writer.

The folder layout is described in ``docs/captures.md``, "Infineon recording folders".
"""

from __future__ import annotations

import contextlib
import json
import os
import warnings
from collections.abc import Mapping
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.config import DEFAULT_ADC_DELAY_S, RadarConfig
from radaraug.errors import CaptureError, ConfigError
from radaraug.files import MAX_TEXT_BYTES, atomic_open, atomic_write_text, load_json, read_bytes
from radaraug.io.base import CaptureReader, CaptureWarning, frames_problem, timestamp_problem
from radaraug.io.counts import as_counts, as_timestamps
from radaraug.io.npy import open_npy

DEVICE_FOLDER = "RadarIfxAvian_00"
FORMAT_VERSION = "1.0.0"


def find_device_folder(path: str | os.PathLike) -> Path:
    """The ``RadarIfxAvian_00`` folder of a recording folder, of itself, or of its ``radar.npy``/``config.json``."""
    p = Path(path)
    if not p.exists():
        raise CaptureError(f"{p}: recording does not exist")
    if not p.is_dir():
        # Not only regular files: a FIFO named radar.npy is refused later without being opened.
        if p.name in ("radar.npy", "config.json"):
            return p.parent
        raise CaptureError(f"{p}: not an Infineon recording folder")
    if (p / DEVICE_FOLDER).is_dir():
        return p / DEVICE_FOLDER
    if p.name.startswith("RadarIfxAvian_") or (p / "radar.npy").exists():
        return p
    raise CaptureError(f"{p}: not an Infineon recording (no {DEVICE_FOLDER}/ folder and no radar.npy inside)")


MAX_VERSION_BYTES = 4096
"""Largest ``format.version`` read (it holds ``1.0.0``)."""

MAX_TEMPERATURE_BYTES = 64 * 1024 * 1024
"""Largest ``temperature.npy`` read (a reading per frame is a few kB)."""


def _read_json(path: Path, *, required: bool) -> dict[str, Any]:
    """A JSON object file; unreadable: CaptureError when ``required``, else a CaptureWarning and ``{}``."""
    if not os.path.lexists(path):
        if required:
            raise CaptureError(f"{path.parent}: Infineon recording has no {path.name}")
        return {}
    try:
        data = load_json(path, error=CaptureError, what=path.name)
        if not isinstance(data, dict):
            raise CaptureError(f"{path}: expected a JSON object, got {type(data).__name__}")
    except CaptureError as e:
        if required:
            raise
        warnings.warn(f"{e}; optional {path.name} ignored", CaptureWarning, stacklevel=4)
        return {}
    return data


class InfineonRecording(CaptureReader):
    """An Infineon ifxdaq / Radar Fusion GUI recording folder, read lazily (``radar.npy`` is memory-mapped).

    ``labels`` is always empty (the format has none: label through ``RadarCaptureDataset``'s ``label``).

    Args:
        path: the recording folder, its ``RadarIfxAvian_00`` folder, or its ``radar.npy`` / ``config.json``.

    Attributes:
        device_folder: the ``RadarIfxAvian_00`` folder.
        temperature_C: chip temperature per reading (``temperature.npy``), or ``None``.

    Raises:
        CaptureError: a missing folder, ``config.json`` or ``radar.npy``; an invalid config
            (``ConfigError`` chained); a ``radar.npy`` that is not integer frames matching the config.

    Warns:
        CaptureWarning: unusable timestamps (then ``None``) or an unreadable optional file.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        self._data: np.ndarray | None = None
        dev = find_device_folder(self.path)
        self.device_folder = dev
        config_path = dev / "config.json"
        config_dict = _read_json(config_path, required=True)
        try:
            self.config = RadarConfig.from_infineon(config_dict, source=str(config_path))
        except ConfigError as e:
            raise CaptureError(f"{config_path}: invalid radar configuration: {e}") from e
        self._data = self._load_radar(dev / "radar.npy")
        self.num_frames = int(self._data.shape[0])
        self.timestamps = self._load_timestamps(dev / "radar_timestamp.csv")
        self.temperature_C = self._load_temperature(dev / "temperature.npy")
        self.labels = {}
        version_file = dev / "format.version"
        version = None
        if os.path.lexists(version_file):
            try:
                raw = read_bytes(version_file, limit=MAX_VERSION_BYTES, error=CaptureError, what="format.version")
            except CaptureError as e:
                raise CaptureError(f"{version_file}: cannot read ({str(e).removeprefix(f'{version_file}: ')})") from None
            version = raw.decode("utf-8", errors="replace").strip()
            if version.split(".")[0] != FORMAT_VERSION.split(".")[0]:
                warnings.warn(
                    f"{version_file}: format.version {version!r} is not {FORMAT_VERSION}; reading it anyway",
                    CaptureWarning,
                    stacklevel=2,
                )
        recording_folder = dev.parent if dev.name == DEVICE_FOLDER else dev
        self.attrs = {
            "format": "infineon-ifxdaq",
            "format_version": version,
            "recording_meta": _read_json(recording_folder / "meta.json", required=False),
            "device_meta": _read_json(dev / "meta.json", required=False),
        }

    def _load_radar(self, path: Path) -> np.ndarray:
        if not os.path.lexists(path):
            raise CaptureError(f"{path.parent}: Infineon recording has no radar.npy")
        # Memory-mapped after open_npy checks the header against the file size; every plain kind
        # is let through so that the check below names a wrong one.
        data = open_npy(path, kinds="iufcbmMUSV")
        if data.dtype.kind not in "ui" or data.dtype.itemsize > 4:
            raise CaptureError(f"{path}: dtype {data.dtype}, expected uint16 raw ADC counts")
        problem = frames_problem(data.shape, self.config, "config.json")
        if problem is not None:
            raise CaptureError(f"{path}: {problem}")
        return data

    def _load_timestamps(self, path: Path) -> np.ndarray | None:
        if not os.path.lexists(path):
            return None
        raw = read_bytes(path, limit=MAX_TEXT_BYTES, error=CaptureError, what="timestamp file")
        try:
            lines = [ln.strip() for ln in raw.decode("utf-8").splitlines()]
            ts = np.array([float(ln) for ln in lines if ln], dtype=np.float64)
        except (UnicodeDecodeError, ValueError, OverflowError) as e:
            raise CaptureError(f"{path}: cannot parse timestamps ({str(e)[:200]})") from None
        n = self.num_frames
        problem = f"{len(ts)} timestamps for {n} frames" if len(ts) != n else timestamp_problem(ts)
        if problem is not None:
            warnings.warn(f"{path}: {problem}; timestamps ignored", CaptureWarning, stacklevel=3)
            return None
        return ts

    def _load_temperature(self, path: Path) -> np.ndarray | None:
        # Optional: anything wrong with it is a warning, and the recording still reads.
        if not os.path.lexists(path):
            return None
        try:
            with contextlib.suppress(OSError):  # open_npy names the problem
                if os.stat(path).st_size > MAX_TEMPERATURE_BYTES:
                    raise CaptureError(f"{path}: larger than {MAX_TEMPERATURE_BYTES} bytes")
            return np.asarray(open_npy(path, kinds="iuf", mmap=False), dtype=np.float64).reshape(-1)
        except CaptureError as e:
            warnings.warn(f"{e}; unreadable temperature file ignored", CaptureWarning, stacklevel=3)
            return None

    def _read_counts(self, start: int, stop: int) -> np.ndarray:
        if self._data is None:
            raise CaptureError(f"{self.path}: recording is closed")
        try:
            return np.array(self._data[start:stop])
        except OSError as e:
            raise CaptureError(f"{self.device_folder / 'radar.npy'}: cannot read frames ({e})") from None

    def close(self) -> None:
        """Drop the memory map (idempotent)."""
        self._data = None

    def __reduce__(self) -> tuple[type, tuple[Path]]:
        return (type(self), (self.path,))


def write_infineon_recording(
    folder: str | os.PathLike,
    counts: np.ndarray | torch.Tensor,
    config: RadarConfig,
    timestamps: np.ndarray | None = None,
    meta: Mapping[str, Any] | None = None,
    *,
    overwrite: bool = False,
) -> Path:
    """Write ADC counts as an Infineon recording folder that Infineon's tools and radaraug read.

    Each file is written atomically, ``radar.npy`` last (its presence marks a recording).

    Args:
        folder: recording folder to create (``RadarIfxAvian_00/`` goes inside).
        counts: integer ADC counts ``(F, rx, chirps, samples)`` (a single frame is allowed).
        config: radar configuration (``config.json``); ``adc_delay_s``, ``adc_bits`` and
            ``rx_positions_m`` cannot be stored: non-default values give a :class:`CaptureWarning`.
        timestamps: optional ``(F,)`` Unix seconds -> ``radar_timestamp.csv``.
        meta: extra entries for the top-level ``meta.json``.
        overwrite: replace an existing recording in ``folder``.

    Returns:
        The recording folder.

    Raises:
        CaptureError: a recording exists and ``overwrite`` is false, or timestamps do not match the frames.
        radaraug.errors.InputTensorError: counts of the wrong dtype, shape or range.
    """
    folder = Path(folder)
    dev = folder / DEVICE_FOLDER
    data = as_counts(counts, config, str(folder))
    if (dev / "radar.npy").exists() and not overwrite:
        raise CaptureError(f"{folder}: already holds an Infineon recording (pass overwrite=True)")
    ts = None if timestamps is None else as_timestamps(timestamps, len(data), str(folder))
    # the config fields the format has no place for -> the value they read back as
    not_stored = {
        "adc_delay_s": DEFAULT_ADC_DELAY_S,
        "adc_bits": 12,
        "rx_positions_m": None,
    }
    lost = [name for name, default in not_stored.items() if getattr(config, name) != default]
    if lost:
        warnings.warn(
            f"{folder}: the Infineon format cannot store {lost}; they will read back as defaults",
            CaptureWarning,
            stacklevel=2,
        )
    host_meta = {
        "date_captured": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "writer": "radaraug",
        **(meta or {}),
    }
    device_meta = {"adc_resolution": config.adc_bits, "description": "BGT60TR13C FMCW Radar Sensor"}
    try:
        dev.mkdir(parents=True, exist_ok=True)
        # Each file is written atomically (a crash or a full disk leaves the old file or none),
        # radar.npy last: its presence is what marks a folder as a recording.
        for path, doc in ((folder / "meta.json", host_meta), (dev / "config.json", config.to_infineon()),
                          (dev / "meta.json", device_meta)):
            atomic_write_text(path, json.dumps(doc, indent=4, sort_keys=True) + "\n")
        atomic_write_text(dev / "format.version", FORMAT_VERSION + "\n")
        stamp_file = dev / "radar_timestamp.csv"
        if ts is not None:
            atomic_write_text(stamp_file, "".join(f"{t!r}\n" for t in ts.tolist()))
        elif stamp_file.exists():
            stamp_file.unlink()  # an overwritten recording must not keep stale timestamps
        with atomic_open(dev / "radar.npy", "wb") as fh:
            np.save(fh, np.ascontiguousarray(data, dtype=np.uint16))
    except OSError as e:
        raise CaptureError(f"{folder}: cannot write Infineon recording ({e})") from None
    return folder
