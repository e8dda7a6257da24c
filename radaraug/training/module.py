"""`RDClassifier`: a classifier of viridis RD images, as a LightningModule."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import Any

import lightning as L
import torch
import torch.nn.functional as F

from radaraug.testsets.tasks import check_task
from radaraug.training.metrics import (
    balanced_accuracy,
    classification_report,
    confusion_matrix,
    context_predictions,
    save_metrics,
)
from radaraug.training.models import resnet18


class RDClassifier(L.LightningModule):
    """A classifier of viridis RD images (default ResNet18, random init: paper Sec. 2.2) as a LightningModule.

    Validation and test log balanced accuracy over DDP ranks; a test writes ``test_metrics.json`` and
    ``test_confusion.png`` to ``out_dir`` (default: the trainer's log dir).

    Args:
        task: ``occupancy`` (2 classes) or ``counting`` (3).
        lr: AdamW learning rate.
        weight_decay: AdamW weight decay.
        balance_classes: weight the loss by inverse class frequency of the training set (1/3 is empty).
        precise_bn_batches: before each evaluation, recompute the BatchNorm statistics from the last this
            many training batches with the final weights (0: off): short runs leave the running averages
            behind the weights (docs/training.md).
        out_dir: where test metrics are written.
        context_frames: at test, also classify each frame from the mean class probabilities of itself and
            the frames before it in its recording, this many in all (the report's ``context``; 1: off).
            Needs the data module's ``test_recording_starts`` (one process).
        backbone: a callable taking the class count and returning the network (None: ResNet18;
            e.g. :class:`radaraug.training.TorchvisionClassifier`). Not saved in the checkpoint's
            hyperparameters: pass it again to ``RDClassifier.load_from_checkpoint(path, backbone=...)``.
    """

    # The constructor's arguments are read from ``self.hparams`` (Lightning's record of them,
    # which checkpoints and the LR finder update), typed there as a plain mapping.
    class_weights: torch.Tensor  # buffer

    def __init__(
        self,
        task: str = "occupancy",
        lr: float = 1e-3,
        weight_decay: float = 1e-4,
        balance_classes: bool = True,
        precise_bn_batches: int = 8,
        out_dir: str | None = None,
        context_frames: int = 1,
        backbone: Callable[[int], torch.nn.Module] | None = None,
    ) -> None:
        super().__init__()
        # the backbone is an object (a class or partial): the saved config names it, hparams cannot
        self.save_hyperparameters(ignore=["backbone"])
        self.class_names = check_task(task)
        k = len(self.class_names)
        self.net = (backbone or resnet18)(k)
        self.register_buffer("class_weights", torch.ones(k), persistent=False)
        self._cm: dict[str, torch.Tensor] = {}
        self._recent: deque[torch.Tensor] = deque(maxlen=max(int(precise_bn_batches), 1))
        self._bn_stale = False
        self.last_test_report: dict[str, Any] | None = None
        #: the last test's per-frame class probabilities ``(N, classes)`` and labels ``(N,)``, in test order
        self.last_test_probs: torch.Tensor | None = None
        self.last_test_labels: torch.Tensor | None = None
        self._test_out: list[tuple[torch.Tensor, torch.Tensor]] = []

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        """Class logits ``(B, classes)`` of images ``x`` ``(B, 3, H, W)``."""
        return self.net(x)

    def setup(self, stage: str) -> None:
        """Class weights from the training split's counts when ``balance_classes`` (fit only)."""
        dm = getattr(self.trainer, "datamodule", None)
        counts = getattr(dm, "train_class_counts", None)
        if self.hparams["balance_classes"] and counts is not None and stage == "fit":
            c = counts.double().clamp_min(1)
            self.class_weights = (c.sum() / (len(c) * c)).float().to(self.class_weights.device)
            # every rank must use the same weights: its own shard's counts differ slightly
            self.class_weights = self.trainer.strategy.broadcast(self.class_weights, src=0)

    def training_step(self, batch: Any, batch_idx: int) -> torch.Tensor:
        """Weighted cross-entropy of the batch (logged); keeps the batch for precise BatchNorm."""
        x, y = batch
        if self.hparams["precise_bn_batches"] > 0:
            self._recent.append(x.detach())
            self._bn_stale = True
        logits = self(x)
        loss = F.cross_entropy(logits, y, weight=self.class_weights.to(logits.dtype))
        self.log("train/loss", loss, prog_bar=True, batch_size=y.shape[0])
        return loss

    @torch.no_grad()
    def recompute_bn_stats(self) -> None:
        """Precise BatchNorm: running mean/var = exact averages over the recent training batches."""
        if not self._bn_stale or not self._recent:
            return
        bns = [m for m in self.net.modules() if isinstance(m, torch.nn.modules.batchnorm._BatchNorm)]
        was_training = self.net.training
        momenta = [m.momentum for m in bns]
        for m in bns:
            m.reset_running_stats()
            m.momentum = None  # cumulative average over the batches below
        self.net.train()
        for x in self._recent:
            self.net(x)
        for m, mom in zip(bns, momenta):
            m.momentum = mom
        if self.trainer is not None and self.trainer.world_size > 1:
            for m in bns:  # one set of statistics for every rank
                if m.running_mean is None or m.running_var is None:
                    continue  # track_running_stats=False: no statistics to share
                m.running_mean.copy_(self.trainer.strategy.reduce(m.running_mean, reduce_op="mean"))
                m.running_var.copy_(self.trainer.strategy.reduce(m.running_var, reduce_op="mean"))
        self.net.train(was_training)
        self._bn_stale = False

    def on_validation_epoch_start(self) -> None:
        """Recompute the BatchNorm statistics before validating."""
        self.recompute_bn_stats()

    def on_train_end(self) -> None:
        """Recompute the BatchNorm statistics the checkpoint will hold."""
        self.recompute_bn_stats()

    def _eval_step(self, batch: Any, split: str) -> torch.Tensor:
        x, y = batch
        logits = self(x)
        self.log(f"{split}/loss", F.cross_entropy(logits, y), batch_size=y.shape[0], sync_dist=True)
        cm = confusion_matrix(logits.argmax(dim=1), y, len(self.class_names)).to(self.device)
        self._cm[split] = self._cm.get(split, torch.zeros_like(cm)) + cm
        return logits

    def validation_step(self, batch: Any, batch_idx: int) -> None:
        """Log the batch's loss and add it to the epoch's confusion matrix."""
        self._eval_step(batch, "val")

    def test_step(self, batch: Any, batch_idx: int) -> None:
        """Log the batch's loss, add it to the epoch's confusion matrix and keep its probabilities."""
        logits = self._eval_step(batch, "test")
        self._test_out.append((torch.softmax(logits.detach().float(), dim=1).cpu(), batch[1].detach().cpu()))

    def on_test_epoch_start(self) -> None:
        """Forget the previous test's probabilities."""
        self._test_out = []

    def _epoch_cm(self, split: str) -> torch.Tensor:
        k = len(self.class_names)
        cm = self._cm.pop(split, torch.zeros(k, k, dtype=torch.long, device=self.device))
        return self.trainer.strategy.reduce(cm, reduce_op="sum") if self.trainer.world_size > 1 else cm

    def on_validation_epoch_end(self) -> None:
        """Log the epoch's balanced accuracy over all ranks."""
        cm = self._epoch_cm("val")
        # already summed over ranks: sync_dist only averages equal values (and silences a warning)
        self.log("val/balanced_accuracy", balanced_accuracy(cm.cpu()), prog_bar=True, sync_dist=True)

    def on_test_epoch_end(self) -> None:
        """Log the test balanced accuracy; keep (and on rank 0 save) the classification report."""
        cm = self._epoch_cm("test").cpu()
        bacc = balanced_accuracy(cm)
        self.log("test/balanced_accuracy", bacc, sync_dist=True)
        dm = getattr(self.trainer, "datamodule", None)
        out = self.hparams["out_dir"] or self.trainer.log_dir
        self.last_test_probs = torch.cat([p for p, _ in self._test_out]) if self._test_out else None
        self.last_test_labels = torch.cat([y for _, y in self._test_out]) if self._test_out else None
        self._test_out = []
        extra = self._context_report(getattr(dm, "test_recording_starts", None))
        if out is not None and self.trainer.global_rank == 0:
            self.last_test_report = save_metrics(cm, self.class_names, out, "test") | extra
        else:
            self.last_test_report = classification_report(cm, self.class_names) | extra

    def _context_report(self, starts: torch.Tensor | None) -> dict[str, Any]:
        """``{"context": report}`` of the context-averaged predictions, or ``{}`` (1 frame, no order)."""
        k = int(self.hparams.get("context_frames", 1))
        probs, labels = self.last_test_probs, self.last_test_labels
        if k <= 1 or starts is None or probs is None or labels is None or len(starts) != len(probs):
            return {}
        cm = confusion_matrix(context_predictions(probs, starts, k), labels, len(self.class_names))
        return {"context": {"frames": k, **classification_report(cm, self.class_names)}}

    def configure_optimizers(self) -> Any:
        """AdamW, with a cosine learning-rate schedule over ``max_epochs`` when the trainer has one."""
        opt = torch.optim.AdamW(self.parameters(), lr=self.hparams["lr"], weight_decay=self.hparams["weight_decay"])
        max_epochs = self.trainer.max_epochs if self.trainer is not None and self.trainer.max_epochs else None
        if not max_epochs or max_epochs < 0:
            return opt
        sched = torch.optim.lr_scheduler.CosineAnnealingLR(opt, T_max=max_epochs)
        return {"optimizer": opt, "lr_scheduler": sched}

