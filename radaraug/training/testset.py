"""Checks of the test captures and the calibration, run before anything is simulated or trained.

They read only metadata and labels (no frames). A count outside the task's classes is refused; a test
set of one class only warns (:class:`TestSetWarning`): a constant network scores 1.0 on it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np

from radaraug.errors import ConfigError
from radaraug.io import open_capture
from radaraug.training.methods import Method
from radaraug.training.pipeline import check_task, is_calibration_json, label_of

#: The people counts each task accepts: counting's classes, or any count >= 0 for occupancy.
COUNTING_COUNTS = (0, 1, 2)


class TestSetWarning(UserWarning):
    """The test set cannot measure the task: it holds captures of only one of the task's classes."""

    __test__ = False  # not a pytest test class, whatever its name


class CalibrationWarning(UserWarning):
    """The calibration cannot serve a step the run asked for (the run goes on without that step)."""


def parse_test_entry(entry: Any, where: str = "test") -> dict[str, Any]:
    """One test entry as ``{"path", "count"?}``: from that mapping or the string ``PATH[:COUNT]``.

    ``count`` absent: the file's per-frame ``count`` labels. The string is ``radaraug reproduce --test``'s form.
    """
    if isinstance(entry, (str, PathLike)):
        text = str(entry)
        path, sep, count = text.rpartition(":")
        if sep and count.isdigit() and path:
            return {"path": path, "count": int(count)}
        return {"path": text}
    if not isinstance(entry, Mapping) or "path" not in entry:
        raise ConfigError(f"{where} must be PATH, PATH:COUNT or a mapping with a 'path' (and optionally 'count'), "
                          f"got {entry!r}")
    return dict(entry)


def dataset_entries(dataset: Any, where: str = "test") -> list[dict[str, Any]]:
    """The test entries ``{"path", "count"?}`` of a :class:`~radaraug.io.RadarCaptureDataset` given as a test set.

    Its label must be a people count: ``label=N``, ``label="count"`` or ``label={path: N}``; one frame per
    item and no transform (the data module applies its RD chain, the simulated maps' one).

    Raises:
        ConfigError: another kind of dataset or label, several frames per item, or a transform
            (each message names ``where``).
    """
    from radaraug.io import RadarCaptureDataset

    if not isinstance(dataset, RadarCaptureDataset):
        raise ConfigError(f"{where} must be PATH, PATH:COUNT, a mapping or a RadarCaptureDataset, "
                          f"got {type(dataset).__name__}")
    if dataset.frames_per_item != 1 or dataset.transform is not None or dataset.target_transform is not None \
            or dataset.as_counts:
        raise ConfigError(f"{where}: a test RadarCaptureDataset gives one frame per item, in SDK floats, with no "
                          "transform of its own (the data module applies its RD chain to it)")
    label = dataset.label
    if label == "count":
        return [{"path": str(p)} for p in dataset.paths]
    if isinstance(label, Mapping):
        try:
            return [{"path": str(p), "count": label[next(k for k in label if Path(k) == p)]} for p in dataset.paths]
        except StopIteration:
            raise ConfigError(f"{where}: its label mapping does not name every file ({dataset.paths})") from None
    if isinstance(label, (int, np.integer)) and not isinstance(label, bool):
        return [{"path": str(p), "count": int(label)} for p in dataset.paths]
    raise ConfigError(f"{where}: a test RadarCaptureDataset's label must be the people count (an int, 'count' "
                      f"for the files' per-frame labels, or a count per file), got {label!r}")


def _whole_count(value: Any, where: str) -> int:
    """``value`` as a whole number of people (ConfigError naming ``where`` otherwise)."""
    if isinstance(value, bool) or value is None:
        raise ConfigError(f"{where}: the people count must be a whole number, got {value!r}")
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
        return int(value)
    if isinstance(value, str) and value.strip().lstrip("-").isdigit():
        return int(value.strip())
    raise ConfigError(f"{where}: the people count must be a whole number, got {value!r}")


def read_test_counts(test: Sequence[Mapping[str, Any]]) -> list[tuple[str, dict[int, int]]]:
    """The people counts of test entries: ``[(path, {count: frames})]``, one per entry.

    ``{"path": P, "count": N}``: N people in every frame; ``{"path": P}``: P's per-frame ``count`` labels.

    Raises:
        ConfigError: an entry without a ``path``, a count that is not a whole number, or a file
            without per-frame ``count`` labels where the entry gives no ``count`` (each message
            names the file).
        CaptureError: a file that cannot be opened as a capture.
    """
    out: list[tuple[str, dict[int, int]]] = []
    for i, entry in enumerate(test):
        if not isinstance(entry, Mapping) or "path" not in entry:
            raise ConfigError(f"test[{i}] must be a mapping with a 'path' (and optionally 'count'), got {entry!r}")
        path = str(entry["path"])
        count = entry.get("count")
        with open_capture(path) as cap:
            frames = int(cap.num_frames)
            labels = None if count is not None else cap.labels.get("count")
            if count is None and labels is None:
                raise ConfigError(
                    f"test capture {path}: no people count: the entry gives no 'count' and the file has no "
                    f"per-frame 'count' labels (labels in the file: {sorted(cap.labels) or 'none'}); give the "
                    f"whole file's count ({{path: {path}, count: N}}, radaraug reproduce --test {path}:N)")
        if count is not None:
            out.append((path, {_whole_count(count, f"test capture {path}"): frames}))
            continue
        arr = np.asarray(labels)
        if arr.dtype.kind not in "iuf" or (arr.dtype.kind == "f" and not np.all(np.isfinite(arr) & (arr == np.round(arr)))):
            raise ConfigError(f"test capture {path}: its per-frame 'count' labels must be whole numbers of people, "
                              f"got values of type {arr.dtype} ({arr.ravel()[:3].tolist()} ...)")
        values, frames_per = np.unique(arr.astype(np.int64), return_counts=True)
        out.append((path, {int(v): int(n) for v, n in zip(values, frames_per)}))
    return out


def check_test_set(test: Sequence[Mapping[str, Any]], task: str) -> dict[str, int]:
    """Check that the test entries can score ``task``; return the test frames per class name.

    Warns with :class:`TestSetWarning` when only one of the task's classes is present.

    Raises:
        ConfigError: an unknown task, a count the task cannot score (negative; for counting, not 0, 1
            or 2), or any error of :func:`read_test_counts`.
    """
    names = check_task(task)
    per_class = dict.fromkeys(names, 0)
    files: dict[str, list[str]] = {name: [] for name in names}
    for path, counts in read_test_counts(test):
        for count, frames in sorted(counts.items()):
            if count < 0:
                raise ConfigError(f"test capture {path}: people count {count} ({frames} frame(s)) is negative")
            if task == "counting" and count not in COUNTING_COUNTS:
                raise ConfigError(
                    f"test capture {path}: people count {count} ({frames} frame(s)) is outside the counting task's "
                    f"classes {', '.join(map(str, COUNTING_COUNTS))}; leave the file out, relabel it, or test it "
                    "with task occupancy (any count >= 0 is 'occupied')")
            name = names[int(label_of(count, task))]
            per_class[name] += frames
            if path not in files[name]:
                files[name].append(path)
    present = [name for name in names if per_class[name] > 0]
    if len(present) == 1:
        (only,) = present
        shown = ", ".join(files[only][:3]) + (" ..." if len(files[only]) > 3 else "")
        need = ("an empty-room capture (count 0) must be included" if only != names[0]
                else "captures with people in the room must be included")
        warnings.warn(
            f"the test set holds only class {only!r} of task {task} ({per_class[only]} frames: {shown}). "
            f"Balanced accuracy is the mean recall over the classes present, so a net that always answers "
            f"{only!r} scores 1.0 on it: the score cannot tell a working classifier from a constant one. "
            f"Test on every class of the task: {need} (docs/your_sensor.md).",
            TestSetWarning, stacklevel=2)
    return per_class


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
