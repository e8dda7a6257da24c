"""`radaraug bench training`: one training step of the recipe pipeline vs a bare ResNet18 step.

Both run in the same process on the same batch size and image size: the baseline trains
ResNet18 on ready-made images; the pipeline starts from cached per-RX dB maps and applies the
recipe's on-device chain (CalibratedDR -> CombineRx -> ClipNormalize -> viridis -> Resize) before
the same step. The ratio says what the radar chain costs on top of the network.
"""

from __future__ import annotations

import json
import platform
import time
from pathlib import Path
from typing import Any

import torch
import torch.nn.functional as F
import torchvision

from radaraug.config import RadarConfig
from radaraug.training.chain import image_chain
from radaraug.transforms import CalibratedDR


def _steps_per_s(step, n: int) -> float:
    step()  # warm-up
    t0 = time.perf_counter()
    for _ in range(n):
        step()
    return n / (time.perf_counter() - t0)


def run_training_benchmark(
    *, batch: int = 32, steps: int = 5, image_size: tuple[int, int] = (128, 64), device: str = "cpu",
    out: str | Path | None = None,
) -> dict[str, Any]:
    """Images/s of the recipe's training step with and without the radar chain, same process."""
    dev = torch.device(device)
    cfg = RadarConfig.bgt60tr13c()
    g = torch.Generator().manual_seed(0)
    maps = (-100 + 6 * torch.randn(batch, cfg.num_rx, cfg.num_range_bins, cfg.num_chirps_per_frame,
                                   generator=g)).to(dev)
    cdr = CalibratedDR(-95.0, 5.6, seed=0).to(dev)
    chain = image_chain(-110.0, -30.0, image_size).to(dev)
    y = torch.randint(0, 3, (batch,), generator=g).to(dev)
    net = torchvision.models.resnet18(weights=None, num_classes=3).to(dev)
    opt = torch.optim.AdamW(net.parameters(), 1e-3)
    ready = chain(maps)

    def train_step(x: torch.Tensor) -> None:
        loss = F.cross_entropy(net(x), y)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        if dev.type == "cuda":
            torch.cuda.synchronize()

    bare = _steps_per_s(lambda: train_step(ready), steps) * batch
    full = _steps_per_s(lambda: train_step(chain(cdr(maps))), steps) * batch
    res = {
        "benchmark": "training_step",
        "device": str(dev),
        "batch": batch,
        "image_size": list(image_size),
        "map_shape": list(maps.shape[1:]),
        "bare_resnet18_images_per_s": round(bare, 1),
        "pipeline_images_per_s": round(full, 1),
        "pipeline_vs_bare": round(full / bare, 3),
        "torch_threads": torch.get_num_threads(),
        "torch_version": torch.__version__,
        "cpu": platform.machine(),
    }
    if out is not None:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(json.dumps(res, indent=2))
    return res
