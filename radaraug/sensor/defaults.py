"""A plausible BGT60TR13C: the receiver's pinned constants and default effect chain.

Which values are assumed, fitted on the public recordings or measured: ``docs/receiver.md``, "Defaults".
"""

from __future__ import annotations

import math

from radaraug.config import RadarConfig
from radaraug.sensor.effects import (
    ADCClipping,
    ADCNoise,
    ADCQuantization,
    AntiAliasLowPass,
    DCOffset,
    Effect,
    IFGain,
    IFHighPass,
    PhaseNoise,
    SystemGain,
    ThermalNoise,
    TxRxLeakage,
)

TX_POWER_MAX_DBM = 5.0
DEFAULT_NOISE_FIGURE_DB = 12.0
FRONT_END_GAIN_DB = 28.5
ADC_NOISE_RMS_COUNTS = 1.75
LEAKAGE_RANGE_M = 0.04
LEAKAGE_COUPLING_DB = {1: -35.8, 2: -43.8, 3: -43.8}
DC_LEVEL_COUNTS = {1: 1620.0, 2: 1945.0, 3: 2067.5}


def tx_power_dBm(level: int) -> float:
    """TX power ``5 + 20 log10(level / 31)`` dBm of an Infineon TX power level 0..31 (assumed law; 0 is off)."""
    if level <= 0:
        return -math.inf
    return TX_POWER_MAX_DBM + 20 * math.log10(level / 31)


def default_effects(
    config: RadarConfig,
    *,
    noise_figure_dB: float = DEFAULT_NOISE_FIGURE_DB,
    system_gain_dB: float = 0.0,
    adc_noise_rms_counts: float | None = None,
) -> list[Effect]:
    """The default BGT60TR13C chain for ``config``, in hardware order (``docs/receiver.md``, "The chain").

    ``adc_noise_rms_counts`` None: :data:`ADC_NOISE_RMS_COUNTS`, scaled to the config's ADC full scale.
    """
    mid = config.adc_full_scale_counts / 2
    rx = config.rx_antennas
    return [
        TxRxLeakage(
            coupling_dB=[LEAKAGE_COUPLING_DB.get(a, LEAKAGE_COUPLING_DB[3]) for a in rx], range_m=LEAKAGE_RANGE_M
        ),
        PhaseNoise(),
        ThermalNoise(noise_figure_dB=noise_figure_dB),
        SystemGain(gain_dB=system_gain_dB),
        IFHighPass(cutoff_Hz=config.effective_hp_cutoff_Hz),
        IFGain(gain_dB=float(config.if_gain_dB)),
        ADCNoise(rms_counts=adc_noise_rms_counts if adc_noise_rms_counts is not None else
                 ADC_NOISE_RMS_COUNTS * (2**config.adc_bits - 1) / 4095),
        AntiAliasLowPass(cutoff_Hz=config.effective_aaf_cutoff_Hz),
        DCOffset(level_counts=[DC_LEVEL_COUNTS.get(a, mid) if config.adc_bits == 12 else mid for a in rx]),
        ADCQuantization(),
        ADCClipping(),
    ]
