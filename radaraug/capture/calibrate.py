"""One-step calibration: record the empty room and fit its calibration record as ``radaraug fit-cdr`` does."""

from __future__ import annotations

import os
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from radaraug.capture.base import RadarDevice
from radaraug.capture.record import RecordResult, record
from radaraug.diagnosis.record import INTERFERENCE_THRESHOLD_DB
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
        cdr, record: the fitted clamp (``CalibratedDR.from_record(record)``) and its record.
        output: where the record was saved.
        recording: the :class:`~radaraug.capture.record.RecordResult` (``path`` None unless kept).
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
    interference_db: float | None = INTERFERENCE_THRESHOLD_DB,
) -> CalibrationRun:
    """Record ``seconds`` of the empty room from ``device``, fit its calibration record, save it to ``output``.

    Args:
        device: a :class:`RadarDevice`, not started.
        output: the calibration record to write (``CalibratedDR.load`` reads it).
        seconds: length of the empty-room recording.
        keep_recording: also keep the recording as this ``.h5`` capture (else it is deleted).
        overwrite: replace an existing ``keep_recording`` file.
        motion_threshold_db: threshold of the motion check.
        progress: show a progress bar.
        floor: ``"normal"`` (the paper's) or ``"empirical"`` (see :class:`~radaraug.transforms.CalibratedDR`).
        interference_db: fit on maps with another radar's bursts excised at this threshold, as the recipes
            make them (None: ``RangeDoppler -> ToDecibels`` alone, the paper's chain).

    Returns:
        A :class:`CalibrationRun`.

    Raises:
        CalibrationError: something moved, fewer than 16 frames, or ``output`` not writable
            (checked before recording).
        CaptureError, DeviceError, ConfigError: as :func:`~radaraug.capture.record.record`.
        KeyboardInterrupt: Ctrl-C while recording (nothing is written; a kept recording keeps its frames).
    """
    from radaraug.diagnosis.record import PERSISTENT_THRESHOLD_DB, fit_record, recipes_map_chain

    output = Path(output)
    if floor not in FLOORS:  # before recording, not after ten seconds of it
        raise CalibrationError(f"calibrate: floor must be one of {FLOORS}, got {floor!r}")
    if interference_db is not None and not interference_db > 0:
        raise CalibrationError(f"calibrate: interference_db must be > 0 dB or None, got {interference_db!r}")
    chain = recipes_map_chain(interference_db)
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
            cal = fit_record(rec_path, floor=floor, motion_threshold_db=motion_threshold_db,
                             persistent_db=PERSISTENT_THRESHOLD_DB, pipeline=chain)
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
