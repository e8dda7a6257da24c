"""The 256-entry viridis lookup table of matplotlib (RGB in [0, 1]).

The numbers live in ``radaraug/data/viridis_rgb.txt``, copied from
``matplotlib.colormaps["viridis"].colors`` (matplotlib 3.11): viridis by Stefan van der Walt,
Nathaniel Smith and Eric Firing, released under CC0. Shipped with the package so radaraug needs no
matplotlib at run time; the tests compare it with matplotlib.
"""

import io
from importlib import resources

import numpy as np

_TABLE = resources.files("radaraug") / "data" / "viridis_rgb.txt"
VIRIDIS_RGB: tuple[tuple[float, float, float], ...] = tuple(
    (float(r), float(g), float(b)) for r, g, b in np.loadtxt(io.StringIO(_TABLE.read_text()), dtype=np.float64, ndmin=2)
)
