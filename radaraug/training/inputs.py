"""Checks of a run's empty-room capture (or calibration record) and test set, before anything is simulated.

The test set's own checks are :mod:`radaraug.testsets.checks`; here, what the calibration can serve.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from typing import Any

from radaraug.errors import ConfigError
from radaraug.testsets.checks import check_test_set
from radaraug.training.methods import Method
from radaraug.training.pipeline import is_calibration_json


class CalibrationWarning(UserWarning):
    """The calibration cannot serve a step the run asked for (the run goes on without that step)."""


#: What leaving out the excision cost on the independent set (docs/training.md, ablation ``rt_no_excision``).
NO_EXCISION_COST = "-0.08 occupancy, -0.17 counting balanced accuracy on the independent set without it"


def check_calibration(calibration: str | None, method: Method, *, profile: str | None = None,
                      calibrate_noise: bool = True, excise: bool = False) -> None:
    """Check that ``calibration`` can serve what ``method``, the excision and the noise fit ask of it.

    The empty-room capture is where the run learns the user's room: its persistent lines are excised
    from every map, CDR's floor and the static-change gate are fitted on it. A calibration record (JSON)
    serves what it holds (the floor, and the persistent cells, profile and noise fit where recorded). A
    step it cannot serve is left out with a :class:`CalibrationWarning` naming it; ``CDRProfile`` with
    neither frames nor a recorded profile is refused.

    Args:
        calibration: the empty-room capture, a calibration record (JSON), or None.
        method: the run's method (:mod:`radaraug.training.methods`).
        profile: a given twin profile (``CDRProfile`` then needs no frames).
        calibrate_noise: whether the run fits the twin's noise to the capture.
        excise: whether the run excises the capture's persistent lines (floor-relative maps).

    Raises:
        ConfigError: ``CDRProfile`` with a record that holds no profile, and no ``profile``.
    """
    from radaraug.transforms.record_file import load_record

    record = None if calibration is None or not is_calibration_json(calibration) else load_record(calibration)
    if calibration is not None and record is None:
        return  # a capture serves everything
    # Every lever the missing frames turn off is named (the excision only where the run excises).
    lost = (f"the empty room's persistent lines are not excised from the maps ({NO_EXCISION_COST}) and "
            if excise and (record is None or record.persistent_cells is None) else "")
    lost += "no static-change gate goes into the classifier file"
    if record is None:
        lost += "" if not calibrate_noise else ", and the twin's noise is not fitted to your sensor"
        warnings.warn(f"no data.calibration: {lost}; give the empty-room capture recorded like the test captures "
                      "(radaraug calibrate --keep-recording PATH)", CalibrationWarning, stacklevel=2)
        return
    warnings.warn(f"data.calibration {calibration} is a calibration record (JSON): it holds no frames, so {lost}; "
                  "give the empty-room capture itself (radaraug calibrate --keep-recording PATH keeps it)",
                  CalibrationWarning, stacklevel=2)
    own = (record.cdr or {}).get("floor")
    if method.floor is not None and method.needs_calibration and own is not None:
        used = "empirical" if method.floor == "matched" else method.floor
        if own != used:
            warnings.warn(f"data.calibration {calibration} was fitted with floor {own!r}; this run draws CDR's floor "
                          f"as {method.floor!r} (data.method's floor) from the quantiles it recorded",
                          CalibrationWarning, stacklevel=2)
    if profile is not None:
        return
    if method.fits_profile and record.profile is None:
        raise ConfigError(
            f"method {method.name!r} fits a twin profile on the empty-room capture in data.calibration, but "
            f"{calibration} is a calibration record without one (no frames to fit on): give the capture itself "
            "(radaraug calibrate --keep-recording PATH keeps it), or a fitted profile as data.twin.profile "
            "(radaraug diagnose CAPTURE -o DIR writes DIR/profile.json)")
    if calibrate_noise and record.noise_fit is None and not method.fits_profile:
        warnings.warn(
            f"data.calibration {calibration} is a calibration record without a noise fit: the twin's noise figure "
            "cannot be fitted from it (the fit measures the empty-room capture's frames), so the twin simulates with "
            "the default receiver, whose noise floor may sit dBs away from your sensor's. Give the empty-room capture "
            "itself (radaraug calibrate --keep-recording PATH keeps it), or set data.twin.calibrate_noise false to "
            "run on the default receiver on purpose.", CalibrationWarning, stacklevel=2)


def check_inputs(test: Sequence[Mapping[str, Any]], task: str, *, calibration: str | None, method: Method,
                 profile: str | None = None, calibrate_noise: bool = True, excise: bool = False) -> dict[str, int]:
    """:func:`check_calibration` then :func:`check_test_set`; returns the test frames per class name."""
    check_calibration(calibration, method, profile=profile, calibrate_noise=calibrate_noise, excise=excise)
    return check_test_set(test, task)
