"""Training from the twin and testing on captures: Lightning data module and classifier, metrics, reports.

``radaraug train`` (:mod:`.cli`) runs the recipes, ``radaraug reproduce`` (:mod:`.reproduce`) the paper's
experiment; see docs/training.md.
"""

from radaraug.training.data import RadarDataModule
from radaraug.training.dropin import TrainingChains, training_chains
from radaraug.training.inputs import CalibrationWarning
from radaraug.training.methods import CDR, RT, CDRProfile, Method, OwnDR, RandomDR
from radaraug.training.metrics import (
    accuracy,
    balanced_accuracy,
    classification_report,
    confusion_matrix,
    save_metrics,
)
from radaraug.training.models import TorchvisionClassifier
from radaraug.training.module import RDClassifier
from radaraug.training.pipeline import estimate_clip_range, image_chain, rd_db_chain
from radaraug.training.preparation import ImageSpec, TwinSplits, prepare

__all__ = [
    "RadarDataModule",
    "Method",
    "RT",
    "RandomDR",
    "CDR",
    "CDRProfile",
    "OwnDR",
    "TwinSplits",
    "ImageSpec",
    "prepare",
    "TrainingChains",
    "training_chains",
    "RDClassifier",
    "TorchvisionClassifier",
    "rd_db_chain",
    "image_chain",
    "estimate_clip_range",
    "confusion_matrix",
    "balanced_accuracy",
    "accuracy",
    "classification_report",
    "save_metrics",
    "CalibrationWarning",
]
