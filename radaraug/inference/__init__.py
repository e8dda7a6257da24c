"""Trained classifiers in use: a classifier file, predictions on captures and the live sensor, export.

See docs/predict.md.
"""

from radaraug.inference.chain import ChainSpec, MatmulChain
from radaraug.inference.classifier import Predictions, PredictionStream, RadarClassifier

__all__ = ["ChainSpec", "MatmulChain", "PredictionStream", "Predictions", "RadarClassifier"]
