"""`radaraug train`: the recipes through LightningCLI (``fit``, ``validate``, ``test``).

``fit`` also tests on the config's captures and keeps ``last.ckpt`` and ``classifier.pt`` (what
``radaraug predict`` runs); see docs/training.md. Predictions are ``radaraug predict``'s, not LightningCLI's.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from lightning.pytorch import Trainer
from lightning.pytorch.callbacks import ModelCheckpoint
from lightning.pytorch.cli import LightningCLI

from radaraug.training.classifier_file import classifier_record, save_checkpoint
from radaraug.training.data import RadarDataModule
from radaraug.training.module import RDClassifier
from radaraug.training.reproduce import CLASSIFIER_FILE


class RadarCLI(LightningCLI):
    """LightningCLI with the task linked between data and model, and a test after fit."""

    def add_arguments_to_parser(self, parser) -> None:  # noqa: ANN001 - jsonargparse parser
        """Link ``data.task`` to ``model.task``: the task is given once, on the data."""
        parser.link_arguments("data.task", "model.task")

    def instantiate_trainer(self, **kwargs: Any) -> Trainer:
        """The trainer, whose checkpoint callback also keeps ``last.ckpt`` unless told otherwise.

        Not a recipe callback, so that ``--trainer.enable_checkpointing false`` and a user's ``save_last`` still work.
        """
        trainer = super().instantiate_trainer(**kwargs)
        checkpoint = trainer.checkpoint_callback
        if isinstance(checkpoint, ModelCheckpoint) and checkpoint.save_last is None:
            checkpoint.save_last = True
        return trainer

    @staticmethod
    def subcommands() -> dict[str, set[str]]:
        """LightningCLI's subcommands but ``predict`` (``radaraug predict`` runs the classifier file)."""
        return {k: v for k, v in LightningCLI.subcommands().items() if k != "predict"}

    def after_fit(self) -> None:
        """Write ``classifier.pt`` into the log folder, then test the fitted model on the test split."""
        folder = self.trainer.log_dir
        if self.trainer.global_rank == 0 and folder is not None:
            save_checkpoint(classifier_record(self.model, self.datamodule, gate=_gate_of(self.datamodule),
                                              provenance={"recipe": "radaraug train fit"}),
                            Path(folder) / CLASSIFIER_FILE)
        self.trainer.test(self.model, datamodule=self.datamodule)


def _gate_of(datamodule: RadarDataModule) -> Any:
    """The static-change gate fitted on the data module's empty-room capture, or None (a JSON or none)."""
    from radaraug.detection import StaticChangeDetector
    from radaraug.training.pipeline import is_calibration_json

    calibration = datamodule.resolved_captures()[0]
    if calibration is None or is_calibration_json(calibration):
        return None
    return StaticChangeDetector.from_capture(calibration)


def main(argv: Sequence[str] | None = None) -> int:
    """Run LightningCLI on ``argv``: the arguments after ``radaraug train`` (None: ``sys.argv[2:]``)."""
    # LightningCLI warns when it is given args while sys.argv holds arguments too, which is always
    # the case under `radaraug train ...` (sys.argv itself must stay: DDP relaunches it on each rank).
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="LightningCLI's args parameter is intended")
        RadarCLI(RDClassifier, RadarDataModule, args=list(argv) if argv is not None else sys.argv[2:],
                 save_config_kwargs={"overwrite": True}, auto_configure_optimizers=False,
                 parser_kwargs={"prog": "radaraug train"})
    return 0
