"""A plausible BGT60TR13C: the receiver's pinned constants and default effect chain.

Every default and where it comes from (values marked *assumed* are not public; the
calibration loop fits them against a capture):

* ``TX_POWER_MAX_DBM = 5`` at TX power level 31 (*assumed*: order of magnitude of 60 GHz
  radar-on-chip PAs); lower levels scale the TX *amplitude* linearly with the level
  (``P = P_max + 20 log10(level / 31)``, level 0 = TX off; *assumed* DAC law).
* ``DEFAULT_NOISE_FIGURE_DB = 12`` (*assumed*, typical of 60 GHz SiGe/CMOS radar receivers).
* ``FRONT_END_GAIN_DB = 28.5`` and ``ADC_NOISE_RMS_COUNTS = 1.75``: *fitted* jointly on the five
  public BGT60TR13C recordings (IF gain 23, 23, 38, 48, 48 dB; see ``docs/calibration.md``,
  "Default constants"). Real noise floors barely follow the IF gain (RD floor -100.2 dBFS at
  23 dB, -102.0 at 38 dB with twice the samples, -96.8 at 48 dB), so most of the noise enters
  *after* the IF gain: the ``adc_noise`` stage (1.75 counts RMS before the anti-alias filter,
  1.3 counts at the ADC, the chirp-to-chirp noise of the static recordings) plus thermal noise
  (F = 12 dB) that only shows at high gain. Solving both levels from the floors gives the
  front-end gain (ADC SDK-float units per sqrt(W) at the RX port with 0 dB IF gain); with
  these constants the default twin's RD noise floor is within 0.5 dB of every recording's at
  its own IF gain (``radaraug.calibration.noise_defaults``). The earlier 49.0 dB was pinned on
  the assumption that all the noise was thermal, which put signals ~20 dB too high (a simulated
  walker clipped the ADC at 48 dB; real ones do not).
* TX->RX leakage, equivalent range 4 cm (*assumed*), coupling -35.8 dB on RX1 and -43.8 dB on
  RX2/RX3: *pinned* to the measured range-domain leakage levels (-19 dB on RX1, -27 dB on
  RX2/RX3 at 23 dB, Hann-normalised range FFT; ``docs/receiver.md``) through the front-end gain
  above.
* DC offsets RX1 1620, RX2 1945, RX3 2067.5 counts (measured at 23 dB IF gain, see
  ``docs/receiver.md``; kept in counts at every gain: how they scale with the gain is not known).
* Phase noise: 100 kHz RMS frequency noise, 200 kHz corner, 4 strongest paths (*assumed*; with
  the ~0.3 ns leakage delay its skirt stays below the thermal noise).
* IF filters: first-order, cutoffs from the config (80 kHz / 500 kHz SDK defaults).
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
    """TX power (dBm) for an Infineon TX power level 0..31 (assumed law, see module doc)."""
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
    """The default BGT60TR13C chain for ``config``, in hardware order.

    ``adc_noise_rms_counts`` None: :data:`ADC_NOISE_RMS_COUNTS`, scaled to the config's ADC full scale.

    leakage -> phase noise -> thermal noise -> system gain -> IF high-pass -> IF gain ->
    ADC-side noise -> anti-alias low-pass -> DC offset -> ADC quantization -> ADC clipping.
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
