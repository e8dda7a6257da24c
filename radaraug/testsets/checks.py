"""Checks of a test set's captures, run before anything is simulated or trained.

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
from radaraug.testsets.tasks import COUNTING_COUNTS, check_task, label_of


class TestSetWarning(UserWarning):
    """The test set cannot measure the task: it holds captures of only one of the task's classes."""

    __test__ = False  # not a pytest test class, whatever its name


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
