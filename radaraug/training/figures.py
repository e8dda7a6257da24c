"""The paper's figures (Fig. 4-9), made from one reproduce run's own data.

Every function takes tensors (per-RX dB RD maps, models, confusion matrices) and writes one PNG;
none simulates or trains. Display ranges are stated in the titles; dB values follow
``radaraug.units.DB_CONVENTION``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import torch

from radaraug._optional import pyplot  # imports matplotlib when called
from radaraug.files import atomic_savefig
from radaraug.training.metrics import balanced_accuracy, draw_confusion
from radaraug.transforms import CombineRx

if TYPE_CHECKING:
    from torchvision.models import ResNet


def _save(fig: Any, path: str | os.PathLike, *, tight: bool = True, title: str | None = None) -> Path:
    """Write ``fig`` (with its ``title`` above every panel) as a PNG to ``path`` and close it."""
    if title is not None:
        fig.suptitle(title, fontsize=10)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if tight:  # not for a figure laid out as "constrained"
        fig.tight_layout()
    atomic_savefig(fig, path, dpi=110)
    pyplot().close(fig)
    return path


def combined_db(maps: torch.Tensor) -> torch.Tensor:
    """Per-RX dB maps ``(..., rx, range, doppler)`` -> RX power-combined dB ``(..., range, doppler)``."""
    return CombineRx("mean_power", db=True)(maps.float()).squeeze(-3)


def noise_floor_histograms(groups: Mapping[str, torch.Tensor], path: str | os.PathLike) -> Path:
    """Fig. 4: histograms of all RD dB cell values of empty-room maps, one curve per group."""
    fig, ax = pyplot().subplots(figsize=(6.4, 3.6))
    for name, maps in groups.items():
        v = maps.float().flatten()
        v = v[torch.isfinite(v) & (v > -250)]
        ax.hist(v.numpy(), bins=120, density=True, histtype="step", linewidth=1.4,
                label=f"{name} (median {float(v.median()):.1f} dB)")
    ax.set_xlabel("RD cell level, dBFS (per RX)")
    ax.set_ylabel("density")
    ax.set_title("Noise-floor histograms of empty-room RD maps")
    ax.legend(fontsize=8)
    return _save(fig, path)


def rd_triplets(rows: Mapping[str, Sequence[tuple[str, torch.Tensor]]], path: str | os.PathLike,
                *, vmin: float, vmax: float, range_max_m: float, v_max_m_s: float) -> Path:
    """Fig. 5: a grid of RD maps, a row per situation, a column per source.

    Situations e.g. empty / one person; sources e.g. simulation, simulation + CDR, the profile twin + CDR,
    capture.
    """
    n_rows = len(rows)
    n_cols = max(len(r) for r in rows.values())
    fig, axes = pyplot().subplots(n_rows, n_cols, figsize=(3.2 * n_cols + 1, 3.3 * n_rows), squeeze=False,
                                  layout="constrained")
    im = None
    for i, (row_name, items) in enumerate(rows.items()):
        for j, (col_name, m) in enumerate(items):
            ax = axes[i][j]
            im = ax.imshow(combined_db(m).numpy(), origin="lower", aspect="auto", cmap="viridis", vmin=vmin,
                           vmax=vmax, extent=(-v_max_m_s, v_max_m_s, 0, range_max_m))
            ax.set_title(f"{row_name}: {col_name}", fontsize=9)
            ax.set_xlabel("velocity (m/s)", fontsize=8)
            if j == 0:
                ax.set_ylabel("range (m)", fontsize=8)
    if im is not None:
        fig.colorbar(im, ax=axes, shrink=0.8, label=f"dBFS, clipped to [{vmin:.0f}, {vmax:.0f}]")
    return _save(fig, path, tight=False,
                 title="Range-Doppler maps: " + ", ".join(name for name, _ in next(iter(rows.values()))))


def static_to_total(maps: torch.Tensor, low_doppler_bins: int = 1) -> torch.Tensor:
    """Per frame, the fraction of RD power within ``+-low_doppler_bins`` of zero Doppler."""
    p = torch.pow(10.0, combined_db(maps).double() / 10)
    m = p.shape[-1]
    lo, hi = m // 2 - low_doppler_bins, m // 2 + low_doppler_bins + 1
    return (p[..., lo:hi].sum(dim=(-1, -2)) / p.sum(dim=(-1, -2))).float()


def static_energy_plot(groups: Mapping[str, torch.Tensor], path: str | os.PathLike, low_doppler_bins: int = 1) -> Path:
    """Fig. 6: static-to-total (low-Doppler) energy ratio per frame, one series per group."""
    fig, ax = pyplot().subplots(figsize=(6.4, 3.4))
    for name, maps in groups.items():
        ratio = static_to_total(maps, low_doppler_bins).double()
        # static/total sits within 0.1 dB of 1 in every frame: its remainder 1 - static/total (the
        # moving share of the energy) shows the differences on a log axis.
        r = 10 * torch.log10((1 - ratio).clamp_min(1e-12))
        ax.plot(r.numpy(), ".", markersize=3,
                label=f"{name} (median static/total {float(ratio.median()):.4f})")
    ax.set_xlabel("frame")
    ax.set_ylabel(f"1 - static/total (dB); static: |Doppler bin| <= {low_doppler_bins}")
    ax.set_title("Static-to-total energy per frame (shown as the moving remainder)")
    ax.legend(fontsize=8)
    return _save(fig, path)


@torch.no_grad()
def first_block_features(net: ResNet, image: torch.Tensor) -> torch.Tensor:
    """Channel-averaged output of ResNet18's first residual stage (``layer1``) for one image."""
    was_training = net.training
    net.eval()
    x = image[None].to(next(net.parameters()).device)
    x = net.maxpool(net.relu(net.bn1(net.conv1(x))))
    out = net.layer1(x)[0].mean(dim=0).cpu()
    net.train(was_training)
    return out


def feature_maps(models: Mapping[str, torch.nn.Module], inputs: Mapping[str, torch.Tensor], path: str | os.PathLike) -> Path:
    """Fig. 7: first-residual-block feature maps, a row per model, a column per input image."""
    fig, axes = pyplot().subplots(len(models), len(inputs), figsize=(3.0 * len(inputs), 2.8 * len(models)),
                                  squeeze=False)
    for i, (mname, net) in enumerate(models.items()):
        for j, (iname, img) in enumerate(inputs.items()):
            f = first_block_features(net, img)
            axes[i][j].imshow(f.numpy(), origin="lower", aspect="auto", cmap="magma")
            axes[i][j].set_title(f"{mname} model, {iname} input", fontsize=9)
            axes[i][j].set_xticks([])
            axes[i][j].set_yticks([])
    return _save(fig, path, title="ResNet18 layer1 activations (channel mean)")


def confusion_grid(cms: Mapping[str, torch.Tensor], class_names: Sequence[str], path: str | os.PathLike, title: str) -> Path:
    """Fig. 8/9: confusion matrices side by side (one per method; counts summed over seeds)."""
    fig, axes = pyplot().subplots(1, len(cms), figsize=(3.0 * len(cms), 3.0), squeeze=False)
    for ax, (name, cm) in zip(axes[0], cms.items()):
        draw_confusion(ax, cm, class_names)
        ax.set_title(f"{name}: bal. acc. {balanced_accuracy(cm):.2f}", fontsize=9)
    return _save(fig, path, title=title)


def results_bars(results: Mapping[str, Mapping[str, Mapping[str, Any]]], path: str | os.PathLike) -> Path:
    """Balanced accuracy (mean +- std over seeds) per task and method, with the ablation if present."""
    tasks = list(results)
    bars = max((len(results[t]) for t in tasks), default=1)
    fig, axes = pyplot().subplots(1, len(tasks), figsize=(max(4.2, 0.8 * bars + 1.4) * len(tasks), 3.4),
                                  squeeze=False)
    for ax, task in zip(axes[0], tasks):
        names = list(results[task])
        means = [results[task][n]["balanced_accuracy"]["mean"] for n in names]
        stds = [results[task][n]["balanced_accuracy"]["std"] for n in names]
        ax.bar(range(len(names)), means, yerr=stds, capsize=4, color="tab:blue")
        ax.axhline(1 / (2 if task == "occupancy" else 3), color="gray", linestyle=":", label="chance")
        ax.set_xticks(range(len(names)), names, fontsize=8, rotation=20)
        ax.set_ylim(0, 1)
        ax.set_title(f"{task}: balanced accuracy (mean +- std over seeds)", fontsize=9)
        ax.legend(fontsize=8)
    return _save(fig, path)


def class_score(probs: torch.Tensor) -> torch.Tensor:
    """One score per item from class probabilities ``(N, K)``: P(occupied), or the expected count.

    With two classes it is the probability of the second ("occupied"); with K > 2 the expected
    class index ``sum_k k p_k`` (counting: the expected number of people, 0 .. K-1).
    """
    probs = probs.double()
    if probs.shape[-1] == 2:
        return probs[:, 1]
    return probs @ torch.arange(probs.shape[-1], dtype=torch.float64)


def score_histograms(scores: Mapping[str, Mapping[str, tuple[torch.Tensor, torch.Tensor]]],
                     class_names: Sequence[str], path: str | os.PathLike, title: str) -> Path:
    """Score distributions per true class, simulated validation against test, one panel per method.

    ``scores[method][split] = (probs (N, K), labels (N,))`` with splits such as ``"simulated val"``
    and ``"test"``. A network that collapses to one class shows every test class piled at one
    end while the simulated classes stay apart.
    """
    k = len(class_names)
    fig, axes = pyplot().subplots(1, len(scores), figsize=(3.4 * max(len(scores), 1), 3.0), squeeze=False)
    top = 1.0 if k == 2 else float(k - 1)
    bins = torch.linspace(0.0, top, 26).numpy()
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:red"]
    for ax, (name, by_split) in zip(axes[0], scores.items()):
        for s, (split, (probs, labels)) in enumerate(by_split.items()):
            score = class_score(probs)
            for c in range(k):
                v = score[labels == c]
                if len(v) == 0:
                    continue
                ax.hist(v.numpy(), bins=bins, density=True, histtype="step" if s else "stepfilled",
                        alpha=1.0 if s else 0.25, linewidth=1.4, linestyle="-" if s else "--",
                        color=colors[c % len(colors)], label=f"{split}: {class_names[c]}")
        ax.set_xlabel("P(occupied)" if k == 2 else "expected count", fontsize=8)
        ax.set_title(name, fontsize=9)
        ax.tick_params(labelsize=7)
    axes[0][-1].legend(fontsize=6, loc="upper center")
    return _save(fig, path, title=title)
