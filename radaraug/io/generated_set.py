"""A generated test set: an empty-room capture and labelled captures, as the generators return them.

Shared by the held-out generators (:mod:`radaraug.sim.proxy`, the twin in another room, and
:mod:`radaraug.heldout`, which shares no simulation code with the twin): both hand ``reproduce`` and
the recipes the same object.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError


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


def test_file_name(count: int) -> str:
    """The file name of a generated set's capture of ``count`` people."""
    return f"test_count{count}.h5"
