"""Test sets: the tasks' classes, checks of labelled captures, and the generators of held-out sets.

* :mod:`~radaraug.testsets.tasks`: each task's classes and what a people count means for it;
* :mod:`~radaraug.testsets.checks`: a test set's captures checked before anything is trained;
* :mod:`~radaraug.testsets.generated`: :class:`GeneratedTestSet`, what every generator returns;
* :mod:`~radaraug.testsets.proxy`: the twin's simulator in another room (``make_proxy``);
* :mod:`~radaraug.testsets.independent`: a generator that shares no simulation code with the twin
  (the ``independent`` set and the held-out worlds).

The generators are imported from their modules (``radaraug.testsets.proxy`` needs the twin; the
independent one must not load it). See docs/proxy.md and docs/heldout_worlds.md.
"""

from radaraug.testsets.checks import TestSetWarning, check_test_set
from radaraug.testsets.generated import GeneratedTestSet
from radaraug.testsets.tasks import TASKS, check_task, label_of

__all__ = ["TASKS", "GeneratedTestSet", "TestSetWarning", "check_task", "check_test_set", "label_of"]
