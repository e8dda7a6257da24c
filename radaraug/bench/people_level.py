"""`radaraug bench people-level`: a moving person's level in captures against the twin's walker.

Fits :func:`radaraug.diagnosis.people_level.fit_people_level` per capture, the twin simulated in the
same process at its config and IF gain; see docs/benchmarks.md.
"""

from __future__ import annotations

import os
import platform
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from radaraug.bench import write_figures


def run_people_level_benchmark(
    captures: Sequence[str | os.PathLike], *, out: str | os.PathLike | None = None,
) -> dict[str, Any]:
    """Fit every capture (radaraug .h5 or Infineon folder); figures keyed by file name, also written to ``out``.

    Raises:
        ConfigError: no captures given.
        CalibrationError: a capture without enough frames of a moving person (the message names it).
    """
    import torch

    from radaraug.diagnosis.people_level import fit_people_level
    from radaraug.errors import ConfigError
    from radaraug.units import DB_CONVENTION

    if not captures:
        raise ConfigError("bench people-level: give the captures with a moving person (--capture PATH, repeated)")
    fits = {Path(c).name: fit_people_level(c).to_dict() for c in captures}
    figures: dict[str, Any] = {
        "benchmark": "people-level",
        "db_convention": DB_CONVENTION,
        "what": "capture-minus-twin MTI range-Doppler peak (RX1, dBFS) of a moving person at matched range bin; "
                "twin = DigitalTwin(corridor) at the capture's config and IF gain, single walkers crossing the "
                "same ranges (radaraug.diagnosis.people_level.fit_people_level, defaults)",
        "torch": torch.__version__,
        "machine": platform.machine(),
        "recordings": fits,
    }
    write_figures(out, figures)
    return figures
