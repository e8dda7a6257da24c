"""The FMCW receiver: scattering paths -> raw ADC frames, with the sensor's effects."""
