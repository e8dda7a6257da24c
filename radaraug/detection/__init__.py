"""Detectors fitted on an empty-room capture that run beside the trained classifiers (docs/static_change.md)."""

from radaraug.detection.static_change import StaticChangeDetector, zero_doppler_profile

__all__ = ["StaticChangeDetector", "zero_doppler_profile"]
