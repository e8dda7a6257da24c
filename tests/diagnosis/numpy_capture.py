"""The independent NumPy capture generator, now :mod:`radaraug.testsets.independent.receiver`.

Kept as a re-export so the calibration tests (and anything else that imports
``tests.diagnosis.numpy_capture``) keep working; the private names the tests use are
re-exported explicitly because ``import *`` skips them.
"""

from radaraug.testsets.independent.receiver import *  # noqa: F403
from radaraug.testsets.independent.receiver import _lo_frequency_noise, _rng  # noqa: F401
