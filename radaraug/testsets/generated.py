"""A generated test set: an empty-room capture and labelled captures, as the generators return them.

Shared by the held-out generators (:mod:`radaraug.testsets.proxy`, the twin in another room, and
:mod:`radaraug.testsets.independent`, which shares no simulation code with the twin): both hand ``reproduce`` and
the recipes the same object.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.files import load_json


@dataclass
class GeneratedTestSet:
    """The files of one generated test set.

    Attributes:
        calibration: the empty-room capture (fit :class:`~radaraug.transforms.CalibratedDR` on it).
        tests: ``(capture path, people count of the whole file)`` per count.
        config: the radar configuration of every file.
        manifest: the JSON file describing the set.
        reused: True when existing files were reused instead of generated.
    """

    calibration: Path
    tests: list[tuple[Path, int]]
    config: RadarConfig
    manifest: Path | None = None
    reused: bool = False
    generation_s: float | None = field(default=None, repr=False)

    def test_specs(self) -> list[str]:
        """The tests as ``PATH:COUNT`` strings."""
        return [f"{p}:{c}" for p, c in self.tests]

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly description."""
        return {
            "calibration": str(self.calibration),
            "tests": [[str(p), int(c)] for p, c in self.tests],
            "config": self.config.to_dict(),
            "manifest": None if self.manifest is None else str(self.manifest),
            "reused": self.reused,
        }


def check_count_arg(who: str, name: str, value: Any, lo: int) -> int:
    """``value`` as an int >= ``lo`` (bools refused), else ConfigError naming ``who`` and ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < lo:
        raise ConfigError(f"{who}: {name} must be an integer >= {lo}, got {value!r}")
    return int(value)


def check_people_counts(who: str, counts: Any) -> tuple[int, ...]:
    """``counts`` as distinct ints among 0, 1, 2 (one test file each), else ConfigError naming ``who``."""
    got = tuple(counts)
    if not got or len(set(got)) != len(got) or any(
            isinstance(c, bool) or not isinstance(c, (int, np.integer)) or c not in (0, 1, 2) for c in got):
        raise ConfigError(f"{who}: counts must be distinct values among 0, 1, 2, got {got!r}")
    return tuple(int(c) for c in got)


def test_file_name(count: int) -> str:
    """The file name of a generated set's capture of ``count`` people."""
    return f"test_count{count}.h5"


def load_generated_set(out_dir: str | os.PathLike, manifest_name: str, manifest_format: str,
                       what: str) -> tuple[GeneratedTestSet, dict[str, Any]]:
    """The set described by ``out_dir/manifest_name`` (files checked to exist), and the manifest.

    ``what`` names the manifest in the errors (e.g. "proxy manifest").

    Raises:
        ConfigError: no readable manifest, another format, or a file it lists is missing.
    """
    out = Path(out_dir)
    path = out / manifest_name
    try:
        data = load_json(path, error=ConfigError, what=what)
    except ConfigError as err:
        raise ConfigError(f"{path}: no readable {what} ({err})") from None
    if not isinstance(data, dict) or data.get("format") != manifest_format:
        raise ConfigError(f"{path}: not a radaraug {what}")
    files = data["files"]
    cal = out / files["calibration"]["path"]
    tests = [(out / t["path"], int(t["count"])) for t in files["tests"]]
    for p in [cal, *(p for p, _ in tests)]:
        if not p.is_file():
            raise ConfigError(f"{path}: lists {p.name}, which is missing")
    return GeneratedTestSet(cal, tests, RadarConfig.from_dict(data["config"]), manifest=path), data


def reusable_generated_set(out: Path, manifest_name: str, manifest_format: str, settings: dict[str, Any],
                           config: RadarConfig) -> tuple[GeneratedTestSet, dict[str, Any]] | None:
    """The set in ``out`` when it is complete and was made with ``settings`` (else None: generate again).

    Complete: its manifest has ``settings``, and every file it lists exists with the frames the
    settings ask for and ``config``. Returns the set (``reused`` set) and its manifest.
    """
    from radaraug.io import open_capture

    try:
        found, data = load_generated_set(out, manifest_name, manifest_format, "manifest")
        if data.get("settings") != settings:
            return None
        expected = [(found.calibration, settings["calibration_frames"])]
        expected += [(p, settings["frames_per_count"]) for p, _ in found.tests]
        for p, n in expected:
            with open_capture(p) as cap:
                if cap.num_frames != n or cap.config != config:
                    return None
    except Exception:  # noqa: BLE001 - anything unreadable means: generate again
        return None
    found.reused = True
    return found, data


def start_generated_set(out: Path, manifest_name: str) -> Path:
    """Create ``out`` and remove its manifest (the set is incomplete until a new one is written); its path."""
    out.mkdir(parents=True, exist_ok=True)
    manifest = out / manifest_name
    manifest.unlink(missing_ok=True)
    return manifest
