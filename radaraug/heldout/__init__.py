"""An independent held-out test generator that shares no simulation code with the twin.

radaraug's classifiers train on the digital twin (:mod:`radaraug.sim`, :mod:`radaraug.raytrace`,
:mod:`radaraug.sensor`, :mod:`radaraug.scene`). The held-out proxy of :mod:`radaraug.sim.proxy` is
that same twin in another room, so a shared modelling error is invisible on it. This package
writes a second test set from a simulation written separately, in NumPy:

* :mod:`radaraug.heldout.walkers`: people as 14 point scatterers on a sinusoidal gait;
* :mod:`radaraug.heldout.room`: an office as static point scatterers levelled by the radar equation;
* :mod:`radaraug.heldout.receiver`: the FMCW receiver chain with undeclared effects;
* :mod:`radaraug.heldout.generator`: :func:`make_independent_proxy`, the labelled captures;
* :mod:`radaraug.heldout.worlds`: whole test worlds (room, mounting, radar config, people,
  disturbances) drawn from wide priors, in a ``design`` suite to look at and a ``report`` suite
  run only to report (:func:`make_suite`).

It imports none of the twin's packages (a test checks it); it uses only
:class:`~radaraug.config.RadarConfig`, :mod:`radaraug.io` (the capture writer) and
:mod:`radaraug.errors`.
"""

from radaraug.heldout.generator import (
    GENERATOR_VERSION,
    IndependentProxySet,
    load_independent_proxy,
    make_independent_proxy,
)
from radaraug.heldout.worlds import SUITES, World, draw_world, load_world, make_suite, make_world

__all__ = ["GENERATOR_VERSION", "SUITES", "IndependentProxySet", "World", "draw_world", "load_world",
           "load_independent_proxy", "make_independent_proxy", "make_suite", "make_world"]
