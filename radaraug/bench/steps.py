"""`radaraug bench steps`: the user path's calibrate and export steps, each against a baseline in the same process.

calibrate: the fit of the calibration record after the recording (CDR's floor, the motion check, the
persistent cells), against reading the same frames. export: each format written and checked against
the eager classifier, against the classifier on one batch. docs/your_sensor.md quotes both.
"""

from __future__ import annotations

import platform
import tempfile
from pathlib import Path
from typing import Any

import torch

from radaraug.bench import best_seconds, write_figures
from radaraug.config import RadarConfig
from radaraug.errors import DependencyNotFoundError


def run_steps_benchmark(*, frames: int = 100, out: str | Path | None = None) -> dict[str, Any]:
    """Time ``radaraug calibrate``'s fit and ``radaraug export`` at the board's preset and the demo's classifier.

    Both run on the CPU, as the commands do (neither takes ``--accelerator``).

    Args:
        frames: empty-room frames (the board's 10 s at 10 frames/s by default).
        out: optional JSON file to write.
    """
    from radaraug.capture import open_device, record
    from radaraug.diagnosis.record import (
        INTERFERENCE_THRESHOLD_DB,
        PERSISTENT_THRESHOLD_DB,
        fit_record,
        recipes_map_chain,
    )
    from radaraug.inference import ChainSpec, RadarClassifier
    from radaraug.inference.export import FORMATS, check_frames, export
    from radaraug.io import open_capture
    from radaraug.training.models import resnet18

    cfg = RadarConfig.bgt60tr13c()
    result: dict[str, Any] = {"benchmark": "steps", "frame_shape": list(cfg.frame_shape), "device": "cpu"}
    with tempfile.TemporaryDirectory() as tmp:
        empty = Path(tmp) / "empty.h5"
        sensor = open_device("virtual", cfg, scene="corridor", seed=0, realtime=False)
        recorded = best_seconds(lambda: record(sensor, empty, frames=frames, progress=False, catch_sigint=False), 1)

        def read() -> None:
            with open_capture(empty) as cap:
                cap.read(0, cap.num_frames)

        read()  # warm the file cache: the baseline is the read, not the disk
        read_s = best_seconds(read, 1)
        fit_s = best_seconds(lambda: fit_record(empty, persistent_db=PERSISTENT_THRESHOLD_DB,
                                                      pipeline=recipes_map_chain()), 1)
        result.update({
            "calibrate_frames": frames,
            "calibrate_recording_s_on_a_board": round(frames / cfg.frame_rate_Hz, 1),
            "calibrate_virtual_recording_s": round(recorded, 2),
            "calibrate_fit_s": round(fit_s, 2),
            "read_frames_s": round(read_s, 3),
            "calibrate_fit_vs_read": round(fit_s / read_s, 1),
        })

        torch.manual_seed(0)
        chain = ChainSpec({}, "floor_relative", 1, (-5.0, 30.0), (64, 32),  # the demo's chain and image size
                      interference_db=INTERFERENCE_THRESHOLD_DB)
        clf = RadarClassifier(resnet18(2), arch="resnet18", task="occupancy", config=cfg, chain=chain, context_frames=8)
        x = check_frames(clf, n=32)
        clf.probabilities(x)  # warm-up
        batch_s = best_seconds(lambda: clf.probabilities(x), 1)
        result["classifier_batch_of_32_s"] = round(batch_s, 3)
        skipped = []
        for f in FORMATS:
            def one(fmt: str = f) -> None:
                export(clf, Path(tmp) / "exported", formats=[fmt], overwrite=True)

            try:  # export itself says when an exporter's packages are missing (ONNX: the [export] extra)
                s = best_seconds(one, 1)
            except DependencyNotFoundError:
                skipped.append(f)
                continue
            result[f"export_{f}_s"] = round(s, 2)
            result[f"export_{f}_vs_classifier_batch"] = round(s / batch_s, 1)
        result["export_formats_skipped"] = sorted(skipped)
    result.update({"torch_threads": torch.get_num_threads(), "torch_version": torch.__version__,
                   "cpu": platform.processor() or platform.machine()})
    write_figures(out, result)
    return result
