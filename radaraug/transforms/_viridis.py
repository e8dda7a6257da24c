"""matplotlib's 256-entry viridis table (RGB in [0, 1]), shipped so that radaraug needs no matplotlib.

``radaraug/data/viridis_rgb.txt`` holds ``matplotlib.colormaps["viridis"].colors`` (matplotlib 3.11):
viridis by Stefan van der Walt, Nathaniel Smith and Eric Firing, released under CC0.
"""

import functools
import io
from importlib import resources

import numpy as np


@functools.lru_cache(maxsize=1)
def viridis_rgb() -> tuple[tuple[float, float, float], ...]:
    """The table as 256 ``(r, g, b)`` tuples, read on first use (not at import: it costs ~25 ms)."""
    text = (resources.files("radaraug") / "data" / "viridis_rgb.txt").read_text()
    rows = np.loadtxt(io.StringIO(text), dtype=np.float64, ndmin=2)
    return tuple((float(r), float(g), float(b)) for r, g, b in rows)
