"""Receiver effects, applied in hardware order; :data:`EFFECTS` maps names to classes.

:data:`HARDWARE_ORDER` lists every registered name in the order the hardware applies them and
:func:`insert_in_order` adds an effect to a chain at its place; :meth:`Effect.priors` gives each
effect's search ranges (:class:`Prior`).
"""

from radaraug.sensor.effects.adc import ADCClipping, ADCQuantization, DCOffset
from radaraug.sensor.effects.base import (
    EFFECTS,
    HARDWARE_ORDER,
    Effect,
    Prior,
    effect_from_dict,
    insert_in_order,
    register,
)
from radaraug.sensor.effects.clutter import Multipath, StaticClutter, VibratingClutter
from radaraug.sensor.effects.drift import FrameDrift
from radaraug.sensor.effects.filters import AntiAliasLowPass, IFHighPass, highpass_response, lowpass_response
from radaraug.sensor.effects.gains import IFGain, RxGainPhaseMismatch, SystemGain
from radaraug.sensor.effects.interference import Interference
from radaraug.sensor.effects.leakage import TxRxLeakage
from radaraug.sensor.effects.noise import ADCNoise, ThermalNoise, thermal_noise_power_W
from radaraug.sensor.effects.nonlinearity import ChirpNonlinearity
from radaraug.sensor.effects.phase_noise import PhaseNoise
from radaraug.sensor.effects.spur import SpurTone

__all__ = [
    "EFFECTS",
    "HARDWARE_ORDER",
    "Effect",
    "Prior",
    "effect_from_dict",
    "insert_in_order",
    "register",
    "ADCClipping",
    "ADCQuantization",
    "DCOffset",
    "AntiAliasLowPass",
    "IFHighPass",
    "highpass_response",
    "lowpass_response",
    "IFGain",
    "RxGainPhaseMismatch",
    "SystemGain",
    "TxRxLeakage",
    "ThermalNoise",
    "ADCNoise",
    "thermal_noise_power_W",
    "PhaseNoise",
    "ChirpNonlinearity",
    "SpurTone",
    "StaticClutter",
    "VibratingClutter",
    "Multipath",
    "Interference",
    "FrameDrift",
]
