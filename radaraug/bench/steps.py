"""`radaraug bench steps`: the user path's calibrate and export steps, each against a baseline in the same process.

calibrate: the fit of the calibration record after the recording (CDR's floor, the motion check, the
persistent cells), against reading the same frames. export: each format written and checked against
the eager classifier, against the classifier on one batch. docs/your_sensor.md quotes both.
"""

from __future__ import annotations

import platform
import tempfile
import time
from pathlib import Path
from typing import Any

import torch

from radaraug.bench import write_figures
from radaraug.config import RadarConfig


def _seconds(fn: Any) -> float:
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def run_steps_benchmark(*, frames: int = 100, out: str | Path | None = None) -> dict[str, Any]:
    """Time ``radaraug calibrate``'s fit and ``radaraug export`` at the board's preset and the demo's classifier.

    Both run on the CPU, as the commands do (neither takes ``--accelerator``).

    Args:
        frames: empty-room frames (the board's 10 s at 10 frames/s by default).
        out: optional JSON file to write.
    """
    import importlib.util

    from radaraug.capture import open_device, record
    from radaraug.diagnosis.record import PERSISTENT_THRESHOLD_DB, fit_record
    from radaraug.inference import ChainSpec, RadarClassifier
    from radaraug.inference.export import FORMATS, check_frames, export
    from radaraug.io import open_capture
    from radaraug.training.models import resnet18

    cfg = RadarConfig.bgt60tr13c()
    result: dict[str, Any] = {"benchmark": "steps", "frame_shape": list(cfg.frame_shape), "device": "cpu"}
    with tempfile.TemporaryDirectory() as tmp:
        empty = Path(tmp) / "empty.h5"
        sensor = open_device("virtual", cfg, scene="corridor", seed=0, realtime=False)
        recorded = _seconds(lambda: record(sensor, empty, frames=frames, progress=False, catch_sigint=False))

        def read() -> None:
            with open_capture(empty) as cap:
                cap.read(0, cap.num_frames)

        read()  # warm the file cache: the baseline is the read, not the disk
        read_s = _seconds(read)
        fit_s = _seconds(lambda: fit_record(empty, persistent_db=PERSISTENT_THRESHOLD_DB))
        result.update({
            "calibrate_frames": frames,
            "calibrate_recording_s_on_a_board": round(frames / cfg.frame_rate_Hz, 1),
            "calibrate_virtual_recording_s": round(recorded, 2),
            "calibrate_fit_s": round(fit_s, 2),
            "read_frames_s": round(read_s, 3),
            "calibrate_fit_vs_read": round(fit_s / read_s, 1),
        })

        torch.manual_seed(0)
        chain = ChainSpec({}, "floor_relative", 1, (-5.0, 30.0), (64, 32))  # the demo's chain and image size
        clf = RadarClassifier(resnet18(2), arch="resnet18", task="occupancy", config=cfg, chain=chain, context_frames=8)
        x = check_frames(clf, n=32)
        clf.probabilities(x)  # warm-up
        batch_s = _seconds(lambda: clf.probabilities(x))
        result["classifier_batch_of_32_s"] = round(batch_s, 3)
        formats = [f for f in FORMATS if f != "onnx" or all(importlib.util.find_spec(m) for m in ("onnx", "onnxscript", "onnxruntime"))]
        for f in formats:
            s = _seconds(lambda f=f: export(clf, Path(tmp) / "exported", formats=[f], overwrite=True))
            result[f"export_{f}_s"] = round(s, 2)
            result[f"export_{f}_vs_classifier_batch"] = round(s / batch_s, 1)
        result["export_formats_skipped"] = sorted(set(FORMATS) - set(formats))
    result.update({"torch_threads": torch.get_num_threads(), "torch_version": torch.__version__,
                   "cpu": platform.processor() or platform.machine()})
    write_figures(out, result)
    return result
