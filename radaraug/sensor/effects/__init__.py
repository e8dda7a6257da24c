"""Receiver effects, applied in hardware order; :data:`EFFECTS` maps names to classes."""

from radaraug.sensor.effects.adc import ADCClipping, ADCQuantization, DCOffset
from radaraug.sensor.effects.base import EFFECTS, Effect, effect_from_dict, register
from radaraug.sensor.effects.filters import AntiAliasLowPass, IFHighPass, highpass_response, lowpass_response
from radaraug.sensor.effects.gains import IFGain, RxGainPhaseMismatch, SystemGain
from radaraug.sensor.effects.leakage import TxRxLeakage
from radaraug.sensor.effects.noise import ThermalNoise, thermal_noise_power_W
from radaraug.sensor.effects.phase_noise import PhaseNoise
from radaraug.sensor.effects.spur import SpurTone

__all__ = [
    "EFFECTS",
    "Effect",
    "effect_from_dict",
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
    "thermal_noise_power_W",
    "PhaseNoise",
    "SpurTone",
]
