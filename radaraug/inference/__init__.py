"""Trained classifiers in use: a classifier file, predictions on captures and the live sensor, export.

See docs/predict.md.
"""

from radaraug.inference.chain import MatmulChain
from radaraug.inference.classifier import Predictions, PredictionStream, RadarClassifier
from radaraug.training.classifier_file import ChainSpec

__all__ = ["ChainSpec", "MatmulChain", "PredictionStream", "Predictions", "RadarClassifier"]
