"""Predictions from captures, a recording still being written, or a live device, as rows a user keeps.

Each source is read in order, a chunk at a time, through one :class:`PredictionStream` per
recording; rows go to JSON lines or CSV (docs/predict.md).
"""

from __future__ import annotations

import csv
import io
import json
import os
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from pathlib import Path
from typing import IO, Any

from radaraug.errors import CaptureError, ConfigError
from radaraug.inference.classifier import Predictions, RadarClassifier
from radaraug.io.hdf5_format import HDF5_SUFFIXES
from radaraug.io.infineon import find_device_folder

CHUNK_FRAMES = 64
"""Frames read and classified at a time (a long recording is never held whole)."""
OUTPUT_FORMATS = ("jsonl", "csv")


def expand_sources(paths: Sequence[str | os.PathLike]) -> list[Path]:
    """Capture paths: files and recording folders as given, a folder of captures as its sorted captures.

    Raises:
        CaptureError: a path that does not exist, or a folder with no capture in it.
    """
    out: list[Path] = []
    for given in paths:
        p = Path(given)
        if not os.path.lexists(p):
            raise CaptureError(f"{p}: capture does not exist")
        if not p.is_dir() or _is_recording(p):
            out.append(p)
            continue
        found = sorted(c for c in p.iterdir() if (c.is_file() and c.suffix.lower() in HDF5_SUFFIXES
                                                  and not c.name.startswith(".")) or (c.is_dir() and _is_recording(c)))
        if not found:
            raise CaptureError(f"{p}: folder holds no capture (.h5/.hdf5 files or Infineon recording folders)")
        out += found
    return out


def _is_recording(folder: Path) -> bool:
    """Whether ``open_capture`` reads ``folder`` as an Infineon recording."""
    try:
        find_device_folder(folder)
    except CaptureError:
        return False
    return True


def predict_captures(classifier: RadarClassifier, paths: Sequence[str | os.PathLike], *, window: int | None = None,
                     gate: bool = True, progress: bool = True) -> Iterator[tuple[Path, int, Predictions]]:
    """``(capture, first frame, predictions)`` per chunk of every capture, each capture its own recording.

    Raises:
        CaptureError: a capture cannot be read (named). ConfigError: a capture of another radar config.
    """
    from radaraug._optional import lazy_import
    from radaraug.io import open_capture

    sources = expand_sources(paths)
    total = 0
    for p in sources:  # every config is checked before the first prediction; one file open at a time
        with open_capture(p) as reader:
            classifier.check_config(reader.config, str(p))
            total += len(reader)
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm
    with tqdm(total=total, unit="frame", desc="predict", disable=not progress) as bar:
        for p in sources:
            stream = classifier.stream(window=window, gate=gate)
            with open_capture(p) as reader:
                for start in range(0, len(reader), CHUNK_FRAMES):
                    stop = min(start + CHUNK_FRAMES, len(reader))
                    yield p, start, stream.push(reader.read(start, stop))
                    bar.update(stop - start)


def follow_capture(classifier: RadarClassifier, path: str | os.PathLike, *, window: int | None = None,
                   gate: bool = True, poll_s: float = 0.5, idle_timeout_s: float | None = None,
                   sleep: Callable[[float], None] = time.sleep) -> Iterator[tuple[Path, int, Predictions]]:
    """Predictions of a radaraug capture while it is recorded: new flushed frames as they appear.

    Waits for the file to appear (the recorder may start later), then ends when the writer has closed
    it and every frame is read, or after ``idle_timeout_s`` seconds without a new frame.

    Raises:
        CaptureError: the capture cannot be read, or did not appear in time (named). ConfigError: another
            radar config.
    """
    from radaraug.io import open_capture
    from radaraug.io.hdf5_recovery import writer_is_alive

    p = Path(path)
    stream = classifier.stream(window=window, gate=gate)
    done, idle_since = 0, time.monotonic()
    while not p.exists():  # started before the recorder: its file appears at the first flushed frame
        if idle_timeout_s is not None and time.monotonic() - idle_since > idle_timeout_s:
            raise CaptureError(f"{p}: no capture appeared within {idle_timeout_s:g} s")
        sleep(poll_s)
    while True:
        writing = p.is_file() and writer_is_alive(p)  # asked before reading: frames flushed after it are read next
        with open_capture(p) as reader:  # reopened: the frame count a reader sees is fixed when it opens
            if done == 0:
                classifier.check_config(reader.config, str(p))
            n = len(reader)
            for start in range(done, n, CHUNK_FRAMES):
                stop = min(start + CHUNK_FRAMES, n)
                yield p, start, stream.push(reader.read(start, stop))
        if n > done:
            done, idle_since = n, time.monotonic()
            continue
        if not writing:
            return
        if idle_timeout_s is not None and time.monotonic() - idle_since > idle_timeout_s:
            return
        sleep(poll_s)


def predict_device(classifier: RadarClassifier, device: Any, *, seconds: float | None = None,
                   max_frames: int | None = None, window: int | None = None,
                   gate: bool = True) -> Iterator[tuple[str, int, Predictions]]:
    """Predictions of a live :class:`~radaraug.capture.RadarDevice`, one frame at a time, until time or frames run out.

    Raises:
        ConfigError: the device's radar config is not the classifier's. DeviceError: the device fails.
    """
    name = str(device.info.get("name", "the device"))
    classifier.check_config(device.config, name)
    stream = classifier.stream(window=window, gate=gate)
    t0, n = time.monotonic(), 0
    with device:
        while (seconds is None or time.monotonic() - t0 < seconds) and (max_frames is None or n < max_frames):
            frame = device.next_frame()
            yield name, int(frame.index), stream.push(frame.data)
            n += 1


class RowWriter:
    """Prediction rows to a text stream as JSON lines or CSV (the CSV header from the first row)."""

    def __init__(self, out: IO[str], fmt: str = "jsonl") -> None:
        if fmt not in OUTPUT_FORMATS:
            raise ConfigError(f"output format must be one of {OUTPUT_FORMATS}, got {fmt!r}")
        self.out, self.fmt, self.rows = out, fmt, 0
        self._csv: Any = None
        self.decisions: dict[str, int] = {}

    def write(self, source: str | os.PathLike, first_frame: int, predictions: Predictions) -> None:
        """Append one row per frame of ``predictions``; flushed so that a reader sees them at once."""
        for row in predictions.rows(first_frame):
            row = {"source": str(source), **row}
            self.decisions[row["decision"]] = self.decisions.get(row["decision"], 0) + 1
            if self.fmt == "jsonl":
                self.out.write(json.dumps(row) + "\n")
            else:
                if self._csv is None:
                    self._csv = csv.DictWriter(self.out, fieldnames=list(row), lineterminator="\n")
                    self._csv.writeheader()
                self._csv.writerow(row)
            self.rows += 1
        self.out.flush()

    def write_all(self, chunks: Iterable[tuple[Any, int, Predictions]]) -> None:
        """:meth:`write` every ``(source, first frame, predictions)`` chunk, in order."""
        for source, first, preds in chunks:
            self.write(source, first, preds)


def rows_text(chunks: Iterable[tuple[Any, int, Predictions]], fmt: str = "jsonl") -> str:
    """All rows as one string (tests, notebooks)."""
    buf = io.StringIO()
    RowWriter(buf, fmt).write_all(chunks)
    return buf.getvalue()
