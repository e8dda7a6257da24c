"""`radaraug bench predict`: a classifier on raw frames, against its network alone on ready images.

Same process, same frames: the figures are frames/s of the whole prediction (the chain and the
network, in batches and one frame at a time as live) and of the export module, each as a ratio to
the network alone (docs/benchmarks.md).
"""

from __future__ import annotations

import platform
from pathlib import Path
from typing import Any

import torch

from radaraug.bench import best_seconds, write_figures
from radaraug.config import RadarConfig


def run_predict_benchmark(*, batch: int = 32, repeats: int = 5, device: str = "cpu",
                          out: str | Path | None = None) -> dict[str, Any]:
    """Time a ResNet18 occupancy classifier at the demo's image size on paper-config frames.

    Args:
        batch: frames per call.
        repeats: timed repetitions (the best is kept, after one warm-up).
        device: torch device.
        out: optional JSON file to write.
    """
    from radaraug.diagnosis.record import INTERFERENCE_THRESHOLD_DB
    from radaraug.inference import ChainSpec, RadarClassifier
    from radaraug.inference.export import ExportedClassifier, check_frames
    from radaraug.training.models import resnet18

    cfg = RadarConfig.bgt60tr13c()
    torch.manual_seed(0)
    chain = ChainSpec({}, "floor_relative", 1, (-5.0, 30.0), (64, 32),  # the demo's chain and image size
                      interference_db=INTERFERENCE_THRESHOLD_DB)
    clf = RadarClassifier(resnet18(2), arch="resnet18", task="occupancy", config=cfg, chain=chain, context_frames=8)
    dev = torch.device(device)
    clf.to(dev)
    x = check_frames(clf, n=batch).to(dev)
    with torch.inference_mode():
        images = clf.transforms().to(dev)(x)
    exported = ExportedClassifier(clf).to(dev)

    def net_alone() -> None:
        with torch.inference_mode():
            torch.softmax(clf.net(images), dim=1)

    def predict() -> None:
        clf.probabilities(x, batch_size=batch)

    def matmul() -> None:
        with torch.inference_mode():
            exported(x)

    def live() -> None:  # one frame per call, the smoothing carried: what `radaraug predict --board` does
        stream = clf.stream()
        for f in x[:8]:
            stream.push(f)

    times = {}
    for name, fn in (("network_alone", net_alone), ("predict", predict), ("export_module", matmul)):
        fn()
        times[name] = batch / best_seconds(fn, repeats, dev)
    live()
    live_fps = 8 / best_seconds(live, max(1, repeats // 2), dev)
    base = times["network_alone"]
    result = {
        "benchmark": "predict",
        "classifier": "ResNet18 occupancy, floor-relative 64x32 viridis images (the demo's), 8-frame context",
        "frame_shape": list(cfg.frame_shape), "batch": batch, "device": str(dev),
        "network_alone_frames_per_s": round(base, 1),
        "predict_frames_per_s": round(times["predict"], 1),
        "predict_vs_network_alone": round(times["predict"] / base, 3),
        "export_module_frames_per_s": round(times["export_module"], 1),
        "export_module_vs_network_alone": round(times["export_module"] / base, 3),
        "live_one_frame_at_a_time_frames_per_s": round(live_fps, 1),
        "live_vs_sensor_frame_rate": round(live_fps / cfg.frame_rate_Hz, 2),
        "sensor_frame_rate_Hz": cfg.frame_rate_Hz,
        "torch_threads": torch.get_num_threads(), "torch_version": torch.__version__,
        "cpu": platform.processor() or platform.machine(),
    }
    if dev.type == "cuda":
        result["gpu"] = torch.cuda.get_device_name(dev)
    write_figures(out, result)
    return result
