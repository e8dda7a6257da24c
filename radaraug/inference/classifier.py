"""`RadarClassifier`: a trained network with the chain it was tested with, run on raw frames.

It carries everything a prediction needs (radar config, DSP chain, clip range, excision mask,
context length, the static-change gate) and refuses frames of another config. docs/predict.md.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Any

import torch
import torchvision
from torch import nn

from radaraug.config import RadarConfig
from radaraug.detection import StaticChangeDetector
from radaraug.errors import CheckpointError, ConfigError, InputTensorError
from radaraug.testsets.tasks import TASKS
from radaraug.training.classifier_file import (
    ChainSpec,
    classifier_record,
    file_record,
    load_checkpoint,
    save_checkpoint,
)
from radaraug.training.metrics import causal_context, gated_predictions

#: Frames through the network at a time.
DEFAULT_BATCH = 64


@dataclasses.dataclass(frozen=True)
class Predictions:
    """Per-frame predictions of consecutive frames of one recording.

    Attributes:
        probs: ``(N, classes)`` each frame's own class probabilities.
        smoothed: ``(N, classes)`` their causal mean over the last ``window`` frames.
        decisions: ``(N,)`` the class of ``smoothed``, raised to one person where the gate fires.
        gate: ``(N,)`` bool per-frame static-change detections, or None (no gate).
        class_names: the task's classes.
        window: frames averaged.
    """

    probs: torch.Tensor
    smoothed: torch.Tensor
    decisions: torch.Tensor
    gate: torch.Tensor | None
    class_names: tuple[str, ...]
    window: int

    @property
    def classes(self) -> torch.Tensor:
        """``(N,)`` each frame's own most probable class (the paper's single-frame protocol)."""
        return self.probs.argmax(dim=1)

    def rows(self, first_frame: int = 0) -> Iterator[dict[str, Any]]:
        """One plain dict per frame: frame index, class, score, smoothed decision, probabilities, gate."""
        for i in range(len(self.probs)):
            c, d = int(self.probs[i].argmax()), int(self.decisions[i])
            yield {"frame": first_frame + i, "class": self.class_names[c], "score": round(float(self.probs[i, c]), 5),
                   "decision": self.class_names[d], "decision_score": round(float(self.smoothed[i, d]), 5),
                   "gate": None if self.gate is None else bool(self.gate[i]),
                   **{f"p_{n}": round(float(p), 5) for n, p in zip(self.class_names, self.probs[i])}}


class RadarClassifier(nn.Module):
    """A trained RD-image classifier and its test chain, from raw frames (SDK floats) to classes.

    Args:
        net: the network, images ``(B, 3, H, W)`` -> logits ``(B, classes)``.
        arch: its torchvision architecture name (rebuilt from it when loaded).
        task: ``occupancy`` or ``counting``.
        config: the radar config it was trained for (frames of another are refused).
        chain: the test chain (:class:`~radaraug.inference.chain.ChainSpec`).
        context_frames: the default smoothing window (frames).
        gate: the static-change gate fitted on the empty room, or None.
        provenance: plain values saying where it came from (method, seed, validation score, ...).
    """

    def __init__(self, net: nn.Module, *, arch: str, task: str, config: RadarConfig, chain: ChainSpec,
                 context_frames: int = 1, gate: StaticChangeDetector | None = None,
                 provenance: Mapping[str, Any] | None = None) -> None:
        super().__init__()
        if task not in TASKS:
            raise ConfigError(f"task must be one of {sorted(TASKS)}, got {task!r}")
        if context_frames < 1:
            raise ConfigError(f"context_frames must be >= 1, got {context_frames}")
        self.net, self.arch, self.task, self.config, self.chain = net, arch, task, config, chain
        self.class_names: tuple[str, ...] = TASKS[task]
        self.context_frames, self.gate = int(context_frames), gate
        self.provenance: dict[str, Any] = dict(provenance or {})
        self._chain = chain.eager()
        self.eval()

    # ------------------------------------------------------------------ building and files
    @classmethod
    def from_training(cls, model: Any, datamodule: Any, *, gate: StaticChangeDetector | None = None,
                      provenance: Mapping[str, Any] | None = None) -> RadarClassifier:
        """From a trained :class:`~radaraug.training.RDClassifier` and its set-up :class:`~radaraug.training.RadarDataModule`.

        Raises:
            CheckpointError: a backbone that is not a torchvision model, or a data module not set up.
        """
        return cls.from_record(classifier_record(model, datamodule, gate=gate, provenance=dict(provenance or {})),
                               source="the trained run")

    @classmethod
    def from_record(cls, data: Mapping[str, Any], *, source: str) -> RadarClassifier:
        """From a classifier file's dict (:func:`~radaraug.training.classifier_file.classifier_record`).

        Raises:
            CheckpointError: fields, network or chain that do not fit together (``source`` named).
        """
        try:
            task, arch = str(data["task"]), str(data["arch"])
            if task not in TASKS:
                raise CheckpointError(f"{source}: unknown task {task!r}")
            config = RadarConfig.from_dict(data["config"], source=source)
            chain = ChainSpec.from_dict(data["chain"], source=source)
            gate = None if data.get("gate") is None else StaticChangeDetector(**data["gate"])
            net = _build_net(arch, len(TASKS[task]), source)
            net.load_state_dict(data["state_dict"])
            return cls(net, arch=arch, task=task, config=config, chain=chain,
                       context_frames=int(data.get("context_frames", 1)), gate=gate,
                       provenance=data.get("provenance") or {})
        except CheckpointError:
            raise
        except (KeyError, TypeError, ValueError, RuntimeError) as e:
            raise CheckpointError(f"{source}: the classifier file is inconsistent ({type(e).__name__}: {e})") from None

    def record(self) -> dict[str, Any]:
        """The classifier file's dict (tensors and plain values)."""
        return file_record(task=self.task, arch=self.arch, net=self.net, config=self.config, chain=self.chain,
                           context_frames=self.context_frames, gate=self.gate, provenance=self.provenance)

    def save(self, path: str | os.PathLike) -> Path:
        """Write the classifier file (tensors and plain values; docs/predict.md); atomic."""
        return save_checkpoint(self.record(), path)

    @classmethod
    def load(cls, path: str | os.PathLike) -> RadarClassifier:
        """Load a classifier file without running code from it.

        Raises:
            CheckpointError: see :func:`~radaraug.training.classifier_file.load_checkpoint`; also a file whose
                fields, network or chain do not fit together (named).
        """
        return cls.from_record(load_checkpoint(path), source=str(path))

    def with_gate(self, calibration: str | os.PathLike, *, margin_db: float | None = None) -> RadarClassifier:
        """This classifier with its static-change gate fitted on another empty-room capture (the user's room).

        Raises:
            CaptureError: the capture cannot be read. ConfigError: another radar config.
        """
        from radaraug.detection.static_change import DEFAULT_MARGIN_DB
        from radaraug.io import open_capture

        with open_capture(calibration) as cap:
            self.check_config(cap.config, str(calibration))
        margin = margin_db if margin_db is not None else (self.gate.margin_db if self.gate else DEFAULT_MARGIN_DB)
        gate = StaticChangeDetector.from_capture(calibration, margin_db=margin)
        return type(self)(self.net, arch=self.arch, task=self.task, config=self.config, chain=self.chain,
                          context_frames=self.context_frames, gate=gate,
                          provenance=self.provenance | {"gate_calibration": Path(calibration).name})

    # ------------------------------------------------------------------ running
    def transforms(self) -> nn.Module:
        """The test chain: raw frames ``(B, rx, chirps, samples)`` in SDK floats -> images ``(B, 3, H, W)``."""
        return self._chain

    def check_config(self, config: RadarConfig, source: str = "the frames") -> None:
        """Refuse ``config`` unless it is the one this classifier was trained for (both named).

        Raises:
            ConfigError: another radar config.
        """
        if config != self.config:
            raise ConfigError(f"{source} has radar config {config.describe()}; this classifier was trained for "
                              f"{self.config.describe()}")

    def _checked(self, frames: torch.Tensor) -> torch.Tensor:
        shape = (self.config.num_rx, self.config.num_chirps_per_frame, self.config.num_samples_per_chirp)
        if frames.ndim == 3:
            frames = frames.unsqueeze(0)
        if frames.ndim != 4 or tuple(frames.shape[1:]) != shape:
            raise InputTensorError(f"frames of shape {tuple(frames.shape)} do not match the classifier's radar config "
                                   f"(frames, {', '.join(map(str, shape))}): {self.config.describe()}")
        if frames.is_floating_point() and frames.numel() and float(frames.abs().max()) > 1.0 + 1e-6:
            raise InputTensorError("frames must be SDK floats in [-1, 1] (capture.read() or a device's frames), "
                                   f"got values up to {float(frames.abs().max()):.3g}: raw ADC counts?")
        return frames.float()

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        """Logits ``(B, classes)`` of raw frames ``(B, rx, chirps, samples)`` (SDK floats)."""
        return self.net(self._chain(self._checked(frames)))

    def probabilities(self, frames: torch.Tensor, batch_size: int = DEFAULT_BATCH) -> torch.Tensor:
        """``(N, classes)`` class probabilities of each frame alone (float32, CPU)."""
        return self._probabilities(self._checked(frames), batch_size)

    def gate_detections(self, frames: torch.Tensor) -> torch.Tensor | None:
        """``(N,)`` bool static-change detections of raw frames (SDK floats), or None without a gate."""
        return self._gate_detections(self._checked(frames))

    @torch.no_grad()
    def _probabilities(self, x: torch.Tensor, batch_size: int = DEFAULT_BATCH) -> torch.Tensor:
        """:meth:`probabilities` of frames :meth:`_checked` already passed."""
        dev = next(self.net.parameters()).device
        out = [torch.softmax(self.net(self._chain(x[i:i + batch_size].to(dev))).float(), dim=1).cpu()
               for i in range(0, len(x), batch_size)]
        return torch.cat(out) if out else torch.zeros(0, len(self.class_names))

    def _gate_detections(self, x: torch.Tensor) -> torch.Tensor | None:
        """:meth:`gate_detections` of frames :meth:`_checked` already passed."""
        if self.gate is None:
            return None
        # The gate was fitted on ADC counts; the chirp-mean removal drops the float offset, this the scale.
        return self.gate.detect(x.double() * (self.config.adc_full_scale_counts / 2))

    def predict(self, frames: torch.Tensor, *, window: int | None = None, gate: bool = True) -> Predictions:
        """Predictions for consecutive frames of one recording (the first frame starts the context).

        Args:
            frames: ``(N, rx, chirps, samples)`` raw frames in SDK floats.
            window: frames of the causal smoothing (None: the classifier's ``context_frames``).
            gate: fuse the static-change gate, when the classifier has one.
        """
        return self.stream(window=window, gate=gate).push(frames)

    def stream(self, *, window: int | None = None, gate: bool = True) -> PredictionStream:
        """A stream of predictions that carries the smoothing window over calls (a live sensor, a growing file)."""
        return PredictionStream(self, self.context_frames if window is None else int(window), gate and self.gate is not None)


class PredictionStream:
    """Frames pushed in order, in any chunks; the smoothing and gate context carry over between pushes.

    Pushing frames one by one gives the same predictions as pushing them all at once.
    """

    def __init__(self, classifier: RadarClassifier, window: int, gate: bool) -> None:
        if window < 1:
            raise ConfigError(f"smoothing window must be >= 1 frame, got {window}")
        self.classifier, self.window, self.use_gate = classifier, window, gate
        # the last window - 1 frames' probabilities and gate decisions: what the next frames' windows reach
        self._probs = torch.zeros(0, len(classifier.class_names))
        self._gate = torch.zeros(0, dtype=torch.bool)

    def push(self, frames: torch.Tensor) -> Predictions:
        """Predictions of the next frames ``(N, rx, chirps, samples)`` (or one frame ``(rx, chirps, samples)``)."""
        c = self.classifier
        x = c._checked(frames)
        probs = c._probabilities(x)
        det = c._gate_detections(x) if self.use_gate else None
        h, keep = len(self._probs), self.window - 1
        all_probs = torch.cat([self._probs, probs])
        # The carried frames are at most window - 1: no window reaches past them, so one start suffices.
        starts = torch.zeros(len(all_probs), dtype=torch.bool)
        starts[:1] = True
        smoothed = causal_context(all_probs, starts, self.window)
        decisions = smoothed.argmax(dim=1)
        if det is not None:
            all_gate = torch.cat([self._gate, det])
            decisions = gated_predictions(decisions, all_gate, starts, self.window)
            self._gate = all_gate[len(all_gate) - min(keep, len(all_gate)):]
        self._probs = all_probs[len(all_probs) - min(keep, len(all_probs)):]
        return Predictions(probs, smoothed[h:], decisions[h:], det, c.class_names, self.window)


def _build_net(arch: str, num_classes: int, source: str) -> nn.Module:
    if arch not in torchvision.models.list_models(torchvision.models):
        raise CheckpointError(f"{source}: unknown torchvision architecture {arch!r}")
    return torchvision.models.get_model(arch, weights=None, num_classes=num_classes)
