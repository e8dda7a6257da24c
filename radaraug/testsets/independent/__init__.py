"""An independent held-out test generator: a NumPy simulation that shares no code with the twin.

Its room (:mod:`~radaraug.testsets.independent.room`), people (:mod:`~radaraug.testsets.independent.walkers`) and receiver
(:mod:`~radaraug.testsets.independent.receiver`) are written anew, so a modelling error of the twin is not
shared by the test. :func:`make_independent_set` writes the ``independent`` set, :func:`make_suite`
the drawn test worlds. It imports none of the twin's packages (tested). See docs/heldout_worlds.md.
"""

from radaraug.testsets.independent.generator import (
    GENERATOR_VERSION,
    load_independent_set,
    make_independent_set,
)
from radaraug.testsets.independent.worlds import SUITES, World, draw_world, load_world, make_suite, make_world

__all__ = ["GENERATOR_VERSION", "SUITES", "World", "draw_world", "load_world",
           "load_independent_set", "make_independent_set", "make_suite", "make_world"]
