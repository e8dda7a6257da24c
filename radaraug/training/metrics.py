"""Classification metrics from the confusion matrix, frame context and operating points.

Balanced accuracy is the mean recall over the classes *present* in the labels, so a test split without
one class (no 2-person frames) is not penalised for it (docs/training.md, "Metrics").
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import torch

from radaraug.errors import ConfigError
from radaraug.files import atomic_savefig, atomic_write_json


def confusion_matrix(preds: torch.Tensor, targets: torch.Tensor, num_classes: int) -> torch.Tensor:
    """Counts ``cm[true, predicted]`` as an int64 ``(num_classes, num_classes)`` tensor.

    Raises:
        ConfigError: shapes differ, or a label lies outside ``[0, num_classes)``.
    """
    preds, targets = torch.as_tensor(preds).reshape(-1), torch.as_tensor(targets).reshape(-1)
    if preds.shape != targets.shape:
        raise ConfigError(f"confusion_matrix: {preds.numel()} predictions for {targets.numel()} targets")
    for name, t in (("prediction", preds), ("target", targets)):
        if t.numel() and (int(t.min()) < 0 or int(t.max()) >= num_classes):
            raise ConfigError(f"confusion_matrix: a {name} lies outside [0, {num_classes}): {t.unique().tolist()}")
    idx = targets.long() * num_classes + preds.long()
    return torch.bincount(idx.cpu(), minlength=num_classes * num_classes).reshape(num_classes, num_classes)


def _recalls(cm: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    cm = torch.as_tensor(cm, dtype=torch.float64)
    support = cm.sum(dim=1)
    recall = torch.where(support > 0, cm.diagonal() / support.clamp_min(1), torch.full_like(support, float("nan")))
    return recall, support


def balanced_accuracy(cm: torch.Tensor) -> float:
    """Mean recall over the classes with at least one true sample (NaN for an empty matrix)."""
    recall, support = _recalls(cm)
    present = support > 0
    return float(recall[present].mean()) if bool(present.any()) else float("nan")


def accuracy(cm: torch.Tensor) -> float:
    """Fraction of correct predictions (NaN for an empty matrix)."""
    cm = torch.as_tensor(cm, dtype=torch.float64)
    total = float(cm.sum())
    return float(cm.diagonal().sum()) / total if total > 0 else float("nan")


def classification_report(cm: torch.Tensor, class_names: Sequence[str] | None = None) -> dict[str, Any]:
    """Balanced accuracy, accuracy, per-class recall and support, and the matrix itself (JSON types)."""
    cm = torch.as_tensor(cm)
    k = cm.shape[0]
    names = list(class_names) if class_names is not None else [str(i) for i in range(k)]
    if len(names) != k:
        raise ConfigError(f"classification_report: {len(names)} class names for a {k}-class matrix")
    recall, support = _recalls(cm)
    return {
        "balanced_accuracy": balanced_accuracy(cm),
        "accuracy": accuracy(cm),
        "classes": names,
        "recall": {n: (None if torch.isnan(r) else float(r)) for n, r in zip(names, recall)},
        "support": {n: int(s) for n, s in zip(names, support)},
        "confusion_matrix": cm.long().tolist(),
        "confusion_matrix_layout": "rows: true class, columns: predicted class",
    }


def causal_context(probs: torch.Tensor, starts: torch.Tensor, frames: int) -> torch.Tensor:
    """Each frame's class probabilities averaged with those of the ``frames - 1`` frames before it.

    Causal, so it works on a live stream; it never reaches across the start of a recording.

    Args:
        probs: ``(N, classes)`` per-frame probabilities, frames in recording order.
        starts: ``(N,)`` bool, True where a recording starts.
        frames: context length (1: the frames alone).

    Returns:
        ``(N, classes)`` averaged probabilities.

    Raises:
        ValueError: ``frames < 1`` or mismatched lengths.
    """
    if frames < 1:
        raise ValueError(f"context frames must be >= 1, got {frames}")
    if len(starts) != len(probs):
        raise ValueError(f"{len(starts)} recording-start flags for {len(probs)} frames")
    if frames == 1 or len(probs) == 0:
        return probs.clone()
    starts = starts.to(torch.bool).clone()
    starts[0] = True
    idx = torch.arange(len(probs))
    first = torch.cummax(torch.where(starts, idx, torch.zeros_like(idx)), dim=0).values  # the recording's first frame
    lo = torch.maximum(first, idx - frames + 1)  # window [lo, i]
    csum = torch.cat([torch.zeros_like(probs[:1]), probs.cumsum(dim=0)])
    return (csum[idx + 1] - csum[lo]) / (idx - lo + 1).unsqueeze(1).to(probs.dtype)


def context_predictions(probs: torch.Tensor, starts: torch.Tensor | None, frames: int) -> torch.Tensor:
    """Predicted classes ``(N,)``: the argmax of :func:`causal_context` (of ``probs`` alone without context)."""
    if frames <= 1 or starts is None:
        return probs.argmax(dim=1)
    return causal_context(probs, starts, frames).argmax(dim=1)


def empty_room_threshold(calibration_probs: torch.Tensor, frames: int) -> float:
    """The classifier's largest "somebody" score ``1 - P(class 0)`` (in context) on an empty-room capture.

    Used as the operating point, it sets the false-alarm rate in the user's own room: an empty frame
    scored like the ``n`` calibration frames exceeds it with probability ``1 / (n + 1)``.

    Args:
        calibration_probs: ``(n, classes)`` probabilities of the empty-room frames, in recording order.
        frames: the classifier's context length.

    Raises:
        ValueError: no frames.
    """
    if len(calibration_probs) == 0:
        raise ValueError("no empty-room frames to set the operating point from")
    starts = torch.zeros(len(calibration_probs), dtype=torch.bool)
    starts[0] = True
    return float((1 - causal_context(calibration_probs, starts, frames)[:, 0]).max())


def operating_point_predictions(probs: torch.Tensor, starts: torch.Tensor | None, frames: int,
                                threshold: float) -> torch.Tensor:
    """Class predictions ``(N,)`` at an operating point: nobody unless the "somebody" score exceeds it.

    In context, a frame is class 0 when ``1 - P(class 0) <= threshold``, else the most probable other
    class. At 0.5 this is the two-class argmax; :func:`empty_room_threshold` sets it from the empty room.

    Args:
        probs: ``(N, classes)`` per-frame probabilities, in recording order.
        starts: ``(N,)`` bool recording starts (None: no context).
        frames: context length.
        threshold: the operating point, in ``[0, 1)``.
    """
    ctx = causal_context(probs, starts, frames) if frames > 1 and starts is not None else probs
    somebody = 1 - ctx[:, 0]
    return torch.where(somebody > threshold, ctx[:, 1:].argmax(dim=1) + 1, torch.zeros_like(somebody, dtype=torch.long))


def gated_predictions(preds: torch.Tensor, gate: torch.Tensor, starts: torch.Tensor | None,
                      frames: int) -> torch.Tensor:
    """Class predictions ``(N,)`` raised to at least one person where a presence gate fires.

    The gate (e.g. :class:`~radaraug.detection.StaticChangeDetector`'s decisions) fires on a frame when
    it fired on more than half of the frame's causal context; there class 0 becomes 1, other classes stay.

    Args:
        preds: ``(N,)`` predicted classes (0 = nobody).
        gate: ``(N,)`` bool per-frame detections, frames in recording order.
        starts: ``(N,)`` bool recording starts (None: no context).
        frames: context length.
    """
    if len(gate) != len(preds):
        raise ValueError(f"{len(gate)} gate decisions for {len(preds)} predictions")
    g = gate.to(torch.float64)
    if frames > 1 and starts is not None:
        g = causal_context(torch.stack([1 - g, g], dim=1), starts, frames)[:, 1]
    return torch.where((preds == 0) & (g > 0.5), torch.ones_like(preds), preds)


def draw_confusion(ax: Any, cm: torch.Tensor, class_names: Sequence[str], *, with_counts: bool = False,
                   text_size: float = 8, label_size: float | None = 8) -> None:
    """Draw ``cm`` on the matplotlib axes ``ax``: row-normalised recall as colour and text (+ the counts)."""
    cm = torch.as_tensor(cm, dtype=torch.float64)
    rows = cm.sum(dim=1, keepdim=True)
    frac = torch.where(rows > 0, cm / rows.clamp_min(1), torch.zeros_like(cm))
    ax.imshow(frac.numpy(), cmap="Blues", vmin=0, vmax=1)
    k = cm.shape[0]
    for i in range(k):
        for j in range(k):
            text = f"{int(cm[i, j])}\n{frac[i, j]:.2f}" if with_counts else f"{frac[i, j]:.2f}"
            ax.text(j, i, text, ha="center", va="center", fontsize=text_size,
                    color="white" if frac[i, j] > 0.5 else "black")
    ax.set_xticks(range(k), class_names, fontsize=label_size)
    ax.set_yticks(range(k), class_names, fontsize=label_size)
    ax.set_xlabel("predicted", fontsize=label_size)
    ax.set_ylabel("true", fontsize=label_size)


def plot_confusion_matrix(
    cm: torch.Tensor, class_names: Sequence[str], path: str | os.PathLike, *, title: str = ""
) -> Path:
    """Write a confusion-matrix figure (counts and row-normalised recall) as PNG."""
    from radaraug._optional import pyplot

    plt = pyplot()
    k = torch.as_tensor(cm).shape[0]
    fig, ax = plt.subplots(figsize=(1.2 * k + 1.8, 1.2 * k + 1.2))
    draw_confusion(ax, cm, class_names, with_counts=True, text_size=9, label_size=None)
    ax.set_title(title or f"balanced accuracy {balanced_accuracy(cm):.3f}", fontsize=9)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, path, dpi=110)
    plt.close(fig)
    return path


def save_metrics(
    cm: torch.Tensor, class_names: Sequence[str], out_dir: str | os.PathLike, name: str = "test",
    *, extra: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Write ``<name>_metrics.json`` and ``<name>_confusion.png`` into ``out_dir``; return the report."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    report = {**classification_report(cm, class_names), **(extra or {})}
    atomic_write_json(out / f"{name}_metrics.json", report, newline=False, indent=2)
    plot_confusion_matrix(cm, class_names, out / f"{name}_confusion.png",
                          title=f"{name}: balanced accuracy {report['balanced_accuracy']:.3f}")
    return report
