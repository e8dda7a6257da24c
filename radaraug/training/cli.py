"""`radaraug train`: the recipes through LightningCLI (``fit``, ``validate``, ``test``, ``predict``).

Example::

    radaraug train fit --config recipes/occupancy_cdr.yaml --trainer.max_epochs 3

``data.task`` is linked to ``model.task``. After ``fit``, the test captures of the config are
scored with the trained weights (``test_metrics.json`` / ``test_confusion.png`` in the log dir).
"""

from __future__ import annotations

from collections.abc import Sequence

from lightning.pytorch.cli import LightningCLI

from radaraug.training.data import RadarDataModule
from radaraug.training.module import RDClassifier


class RadarCLI(LightningCLI):
    """LightningCLI with the task linked between data and model, and a test after fit."""

    def add_arguments_to_parser(self, parser) -> None:  # noqa: ANN001 - jsonargparse parser
        """Link ``data.task`` to ``model.task``: the task is given once, on the data."""
        parser.link_arguments("data.task", "model.task")

    def after_fit(self) -> None:
        """Test the fitted model on the datamodule's test split."""
        self.trainer.test(self.model, datamodule=self.datamodule)


def main(argv: Sequence[str] | None = None) -> int:
    """Run LightningCLI on ``argv`` (the arguments after ``radaraug train``)."""
    RadarCLI(RDClassifier, RadarDataModule, args=list(argv) if argv is not None else None,
             save_config_kwargs={"overwrite": True}, auto_configure_optimizers=False)
    return 0
