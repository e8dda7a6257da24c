"""The FMCW receiver: scattering paths -> raw ADC frames, with the sensor's effects.

``FMCWReceiver(config)(paths)`` gives ``(..., RX, chirps, samples)`` in Infineon Radar SDK 3.6
floats (``x = 2*counts/4095 - 1``), like a real capture. See ``docs/receiver.md``.
"""

from radaraug.sensor.defaults import default_effects, tx_power_dBm
from radaraug.sensor.effects import EFFECTS, HARDWARE_ORDER, Effect, Prior, effect_from_dict, insert_in_order
from radaraug.sensor.paths import Paths
from radaraug.sensor.point_target import point_target_paths
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sensor.synthesis import synthesize_exact, synthesize_fast

__all__ = [
    "FMCWReceiver",
    "Paths",
    "EFFECTS",
    "Effect",
    "effect_from_dict",
    "HARDWARE_ORDER",
    "insert_in_order",
    "Prior",
    "default_effects",
    "tx_power_dBm",
    "point_target_paths",
    "synthesize_exact",
    "synthesize_fast",
]
