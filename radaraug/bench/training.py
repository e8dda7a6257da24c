"""`radaraug bench training`: one training step of the recipe pipeline vs a bare ResNet18 step.

Same process, batch and image size; the ratio says what the radar chain costs on top of the network.
"""

from __future__ import annotations

import platform
import time
from pathlib import Path
from typing import Any

import torch
import torch.nn.functional as F
import torchvision

from radaraug.bench import write_figures
from radaraug.config import RadarConfig
from radaraug.training.pipeline import image_chain
from radaraug.transforms import CalibratedDR


def _best_rates(steps: dict[str, Any], n: int, rounds: int = 3) -> dict[str, float]:
    """Steps/s of each step function, the best of ``rounds`` interleaved rounds of ``n`` steps.

    One warm-up each first; interleaving spreads drifts of a shared machine over both.
    """
    for step in steps.values():
        step()
    best = dict.fromkeys(steps, 0.0)
    for _ in range(rounds):
        for name, step in steps.items():
            t0 = time.perf_counter()
            for _ in range(n):
                step()
            best[name] = max(best[name], n / (time.perf_counter() - t0))
    return best


def _amp_channels_last(dev: torch.device, net: torch.nn.Module, opt: torch.optim.Optimizer, y: torch.Tensor,
                       ready: torch.Tensor, images: Any, steps: int) -> dict[str, float]:
    """Steps/s of the same steps under bf16 autocast with a channels-last network and input (CUDA).

    bf16 needs no loss scaler; channels-last lets cuDNN use tensor-core kernels without transposes.
    """
    net = net.to(memory_format=torch.channels_last)

    def step(x: torch.Tensor) -> None:
        with torch.autocast(dev.type, dtype=torch.bfloat16):
            loss = F.cross_entropy(net(x.contiguous(memory_format=torch.channels_last)), y)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        torch.cuda.synchronize()

    try:
        return _best_rates({"bare": lambda: step(ready), "pipeline": lambda: step(images())}, steps)
    finally:
        net.to(memory_format=torch.contiguous_format)


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

    rates = _best_rates({"bare": lambda: train_step(ready), "pipeline": lambda: train_step(chain(cdr(maps)))}, steps)
    bare, full = rates["bare"] * batch, rates["pipeline"] * batch
    fast = _amp_channels_last(dev, net, opt, y, ready, lambda: chain(cdr(maps)), steps) if dev.type == "cuda" else None
    res = {
        "benchmark": "training_step",
        "device": str(dev),
        "batch": batch,
        "image_size": list(image_size),
        "map_shape": list(maps.shape[1:]),
        "bare_resnet18_images_per_s": round(bare, 1),
        "pipeline_images_per_s": round(full, 1),
        "pipeline_vs_bare": round(full / bare, 3),
        **({} if fast is None else {"amp_channels_last": {
            "bare_resnet18_images_per_s": round(fast["bare"] * batch, 1),
            "pipeline_images_per_s": round(fast["pipeline"] * batch, 1),
            "pipeline_vs_fp32_pipeline": round(fast["pipeline"] * batch / full, 3),
        }}),
        "torch_threads": torch.get_num_threads(),
        "torch_version": torch.__version__,
        "cpu": platform.machine(),
    }
    write_figures(out, res, newline=False)
    return res
