"""An independent held-out test generator: a NumPy simulation that shares no code with the twin.

Its room (:mod:`~radaraug.heldout.room`), people (:mod:`~radaraug.heldout.walkers`) and receiver
(:mod:`~radaraug.heldout.receiver`) are written anew, so a modelling error of the twin is not
shared by the test. :func:`make_independent_set` writes the ``independent`` set, :func:`make_suite`
the drawn test worlds. It imports none of the twin's packages (tested). See docs/heldout_worlds.md.
"""

from radaraug.heldout.generator import (
    GENERATOR_VERSION,
    load_independent_set,
    make_independent_set,
)
from radaraug.heldout.worlds import SUITES, World, draw_world, load_world, make_suite, make_world

__all__ = ["GENERATOR_VERSION", "SUITES", "World", "draw_world", "load_world",
           "load_independent_set", "make_independent_set", "make_suite", "make_world"]
