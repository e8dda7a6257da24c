"""Record a live device into a radaraug HDF5 capture, crash-safely (see ``docs/capture.md``).

Through :class:`~radaraug.io.CaptureWriter`: a crash, ``kill -9`` or unplugged board loses at most the frame in flight.
"""

from __future__ import annotations

import math
import os
import signal
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from radaraug.capture.base import RadarDevice
from radaraug.errors import CaptureError, ConfigError, DeviceError
from radaraug.io import CaptureWriter
from radaraug.units import float_to_counts


@dataclass
class RecordResult:
    """What a recording did.

    Attributes:
        path: the capture file (None when no frame was recorded and no file was written).
        frames, dropped, requested: frames written, dropped by the device, and asked for.
        seconds: wall time of the streaming, seconds.
        interrupted: stopped early by Ctrl-C (the file is complete and closed all the same).
        device: the device's ``info``.
    """

    path: Path | None
    frames: int
    dropped: int
    requested: int
    seconds: float
    interrupted: bool
    device: dict[str, Any]

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON types."""
        return {"path": None if self.path is None else str(self.path), "frames": self.frames,
                "dropped": self.dropped, "requested": self.requested, "seconds": round(self.seconds, 3),
                "frame_rate_Hz": round(self.frames / self.seconds, 3) if self.seconds > 0 else None,
                "interrupted": self.interrupted, "device": self.device}


def frames_for(seconds: float, frame_period_s: float) -> int:
    """Frame periods in ``seconds`` (at least 1).

    Raises:
        ConfigError: ``seconds`` not a positive finite number.
    """
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not math.isfinite(seconds) or seconds <= 0:
        raise ConfigError(f"seconds must be a positive number, got {seconds!r}")
    return max(1, math.ceil(seconds / frame_period_s - 1e-9))


def record(
    device: RadarDevice,
    path: str | os.PathLike,
    *,
    seconds: float | None = None,
    frames: int | None = None,
    label: int | None = None,
    overwrite: bool = False,
    progress: bool = False,
    compression: str | None = "gzip",
    attrs: dict[str, Any] | None = None,
    catch_sigint: bool = True,
) -> RecordResult:
    """Stream ``device`` into a new capture at ``path``.

    Args:
        device: a :class:`RadarDevice`, not started (it is started and stopped here).
        path: the ``.h5`` capture to write.
        seconds: how long to record (give this or ``frames``).
        frames: how many frame periods to record.
        label: people count of the whole recording, stored per frame as ``count`` and ``occupancy``.
        overwrite: replace an existing file at ``path`` (else it is refused).
        progress: show a progress bar on stderr.
        compression: ``"gzip"``, ``"lzf"`` or None.
        attrs: extra file attributes.
        catch_sigint: in the main thread, Ctrl-C ends the run cleanly (file closed, ``interrupted``).

    Returns:
        A :class:`RecordResult`.

    Raises:
        ConfigError: bad ``seconds``/``frames``/``label``.
        CaptureError: the output exists, cannot be created or does not fit the free space (before
            the device starts), or a write fails later (the file keeps the frames completed before).
        DeviceError: the device cannot be started or fails while streaming (earlier frames are kept).
    """
    config = device.config
    if (seconds is None) == (frames is None):
        raise ConfigError("record: give seconds or frames (one of them)")
    n = frames_for(seconds, config.frame_repetition_time_s) if seconds is not None else frames
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ConfigError(f"record: frames must be a positive integer, got {frames!r}")
    if label is not None and (isinstance(label, bool) or not isinstance(label, int) or label < 0):
        raise ConfigError(f"record: label must be a people count (integer >= 0), got {label!r}")
    path = Path(path)
    if (path.exists() or path.is_symlink()) and not overwrite:
        raise CaptureError(f"{path}: exists; choose another output or pass --overwrite to replace it")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise CaptureError(f"{path}: cannot create its folder {path.parent} ({e.strerror or e})") from None
    info = device.info
    file_attrs = {"source": "radaraug capture", "description": f"recorded from {info.get('name', 'a device')}",
                  "device": info, **(attrs or {})}
    if label is not None:
        file_attrs["label_count"] = label  # also file-level, for tools that read one label per file
    schema = {"count": "int64", "occupancy": "int64"} if label is not None else None
    # Step 1: everything about the output, before the device is touched.
    writer = CaptureWriter(path, config, labels_schema=schema, compression=compression, attrs=file_attrs,
                           expected_frames=n)
    stop = _StopFlag(catch_sigint)
    written = dropped = 0
    last = -1
    bar = None
    t_start = time.monotonic()
    try:
        with stop:
            device.start()  # a failure is handled below: no frame, so the writer leaves no file
            try:
                if progress:
                    from tqdm.auto import tqdm

                    bar = tqdm(total=n, desc=f"capture {path.name}", unit="frame", mininterval=0.5)
                t_start, unix0 = time.monotonic(), time.time()
                labels = None if label is None else {"count": label, "occupancy": int(label > 0)}
                while not stop.requested:
                    frame = device.next_frame()
                    if frame.index >= n:
                        dropped += max(0, n - last - 1)
                        break
                    dropped += max(0, frame.index - last - 1)
                    last = frame.index
                    writer.append(float_to_counts(frame.data, config.adc_bits), timestamp=unix0 + frame.timestamp,
                                  labels=labels)
                    written += 1
                    if bar is not None:
                        bar.update(frame.index + 1 - bar.n)
                        bar.set_postfix(dropped=dropped, refresh=False)
                    if frame.index == n - 1:
                        break
            finally:
                device.stop()
                if bar is not None:
                    bar.close()
        elapsed = time.monotonic() - t_start
    except DeviceError as e:
        note = f"; {path} keeps the {written} frames recorded before" if written else "; no frame was recorded"
        raise DeviceError(f"{e}{note}") from None
    finally:
        # Close the file, however the run ended: CaptureWriter.discard closes a writer that appended
        # like close() (its frames are kept) and leaves no file for a run without a frame.
        writer.discard()
    return RecordResult(path if written else None, written, dropped, n, elapsed, stop.requested, info)


class _StopFlag:
    """While active, SIGINT sets ``requested`` instead of raising (main thread only)."""

    def __init__(self, enabled: bool) -> None:
        self.enabled = enabled and threading.current_thread() is threading.main_thread()
        self.requested = False
        self._old: Any = None

    def _handler(self, signum: int, frame: Any) -> None:
        self.requested = True

    def __enter__(self) -> _StopFlag:
        if self.enabled:
            self._old = signal.signal(signal.SIGINT, self._handler)
        return self

    def __exit__(self, *exc: object) -> None:
        if self.enabled:
            signal.signal(signal.SIGINT, self._old)
