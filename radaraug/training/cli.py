"""`radaraug train`: the recipes through LightningCLI (``fit``, ``validate``, ``test``, ``predict``).

``fit`` also tests on the config's captures and keeps ``last.ckpt``; see docs/training.md.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Sequence
from typing import Any

from lightning.pytorch import Trainer
from lightning.pytorch.callbacks import ModelCheckpoint
from lightning.pytorch.cli import LightningCLI

from radaraug.training.data import RadarDataModule
from radaraug.training.module import RDClassifier


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

    def after_fit(self) -> None:
        """Test the fitted model on the datamodule's test split."""
        self.trainer.test(self.model, datamodule=self.datamodule)


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
