"""One-step calibration: record the empty room from a device and fit its calibration record.

The fit is :func:`radaraug.calibration.record.fit_record` on the recording (CalibratedDR's floor,
exactly what ``radaraug fit-cdr`` fits on a file), written as one calibration record
(:mod:`radaraug.transforms.record_file`) that ``CalibratedDR.load`` reads. The emptiness test is
the motion check that fit already runs (:mod:`radaraug.transforms._motion`). Where ``fit-cdr`` only warns, this
refuses: a calibration of a room in which something moved is not written, and the message gives
the measured motion fraction against the threshold. What does not move (a person standing still,
a fan whose blades stay in the same cells) is not seen by the check.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from radaraug.capture.base import RadarDevice
from radaraug.capture.record import RecordResult, record
from radaraug.errors import CalibrationError
from radaraug.transforms import CalibratedDR, MotionWarning
from radaraug.transforms._motion import DEFAULT_THRESHOLD_DB, MIN_FRAMES, WARN_FRACTION
from radaraug.transforms.dr import FLOORS

if TYPE_CHECKING:
    from radaraug.transforms.record_file import CalibrationRecord

CALIBRATION_SECONDS = 10.0
"""The empty-room sequence's length (the paper's 10 s, ~100 frames at 10 Hz)."""


@dataclass
class CalibrationRun:
    """What :func:`calibrate` did.

    Attributes:
        cdr: the fitted clamp (``CalibratedDR.from_record(record)``).
        output: the calibration record written.
        recording: the recording's :class:`~radaraug.capture.record.RecordResult` (its ``path``
            is None unless the recording was kept).
        record: the calibration record saved to ``output``.
    """

    cdr: CalibratedDR
    output: Path
    recording: RecordResult
    record: CalibrationRecord


def calibrate(
    device: RadarDevice,
    output: str | os.PathLike,
    *,
    seconds: float = CALIBRATION_SECONDS,
    keep_recording: str | os.PathLike | None = None,
    overwrite: bool = False,
    motion_threshold_db: float = DEFAULT_THRESHOLD_DB,
    progress: bool = False,
    floor: str = "normal",
) -> CalibrationRun:
    """Record ``seconds`` of the empty room from ``device``, fit its calibration record, save it to ``output``.

    Args:
        device: a :class:`RadarDevice`, not started.
        output: the calibration record (``CalibratedDR.load(output)`` and
            :func:`~radaraug.calibration.record.load_record` read it).
        seconds: length of the empty-room recording.
        keep_recording: also keep the recording as this ``.h5`` capture (else it is deleted).
        overwrite: replace an existing ``keep_recording`` file.
        motion_threshold_db: threshold of the motion check (see :mod:`radaraug.transforms._motion`).
        progress: show the recording's progress bar.
        floor: the calibration's floor distribution, ``"normal"`` (the paper's) or ``"empirical"``
            (see :class:`~radaraug.transforms.CalibratedDR`).

    Returns:
        A :class:`CalibrationRun`.

    Raises:
        CalibrationError: something moved in the room (motion above the threshold), the recording
            has too few frames to check it (fewer than 16), or ``output`` cannot be written
            (checked before recording).
        CaptureError, DeviceError, ConfigError: as :func:`~radaraug.capture.record.record`.
        KeyboardInterrupt: Ctrl-C during the recording (nothing is fitted or written; a kept
            recording holds the frames so far).
    """
    from radaraug.calibration.record import fit_record

    output = Path(output)
    if floor not in FLOORS:  # before recording, not after ten seconds of it
        raise CalibrationError(f"calibrate: floor must be one of {FLOORS}, got {floor!r}")
    _check_writable(output)
    if keep_recording is not None:
        rec_path, temporary = Path(keep_recording), False
    else:
        rec_path, temporary = output.with_name(f".{output.name}.{os.getpid()}.recording.h5"), True
    try:
        rec = record(device, rec_path, seconds=seconds, progress=progress, overwrite=overwrite or temporary)
        if rec.interrupted:
            raise KeyboardInterrupt
        if rec.path is None:
            raise CalibrationError(f"{output}: the device gave no frame; nothing to calibrate")
        with warnings.catch_warnings():
            # The motion warning of fit() becomes the refusal below.
            warnings.simplefilter("ignore", MotionWarning)
            cal = fit_record(rec_path, floor=floor, motion_threshold_db=motion_threshold_db)
    finally:
        if temporary:
            rec_path.unlink(missing_ok=True)
    assert cal.cdr is not None and cal.capture is not None  # fit_record fits the floor
    motion = cal.cdr["motion"]
    if motion is None:
        raise CalibrationError(
            f"{output}: {rec.frames} frames are too few to check that the room is empty (the motion check needs "
            f"at least {MIN_FRAMES}); record longer (--seconds); nothing was written"
        )
    if motion > WARN_FRACTION:
        raise CalibrationError(
            f"{output}: the room is not empty: {100 * motion:.2f} % of the range-Doppler cells off zero Doppler "
            f"are > {motion_threshold_db:g} dB above their own median over the {rec.frames} frames (threshold "
            f"{100 * WARN_FRACTION:g} %; noise and static clutter alone give ~0 %): something moved. Leave the "
            "room, stop fans and anything that moves, and run again; nothing was written"
        )
    cal.cdr["source"] = str(rec_path) if not temporary else f"radaraug calibrate ({device.info.get('name', 'device')})"
    cal.capture["name"] = cal.cdr["source"]
    cal.save(output)
    return CalibrationRun(CalibratedDR.from_record(cal), output, rec, cal)


def _check_writable(output: Path) -> None:
    """Refuse an output the calibration could not be saved to, before 10 s of recording."""
    folder = output.parent
    if output.is_dir():
        raise CalibrationError(f"cannot write calibration file {output}: is a folder")
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=f".{output.name}.", suffix=".check"):
            pass
    except OSError as e:
        raise CalibrationError(f"cannot write calibration file {output}: {e.strerror or e}") from None
