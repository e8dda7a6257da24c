"""Unit conventions shared by captures, the simulator and the transforms.

* ADC samples: raw counts ``0 .. 2**bits - 1`` (uint16 on disk), or Infineon Radar SDK 3.6
  floats ``2 * counts / (2**bits - 1) - 1`` in ``[-1, 1]`` (what radaraug computes with).
* RD magnitude in dB: ``20 * log10(|X|)`` where both FFTs are divided by their window sums
  ("dBFS"): a real full-scale tone (amplitude 1 in SDK floats) reads -6.02 dBFS in its bin,
  because a real tone splits its amplitude between the positive and negative frequency.
"""

from __future__ import annotations

import numpy as np
import torch

FLOAT_CONVENTION = "x = 2*counts/(2**adc_bits - 1) - 1 (Infineon Radar SDK 3.6 floats, range [-1, 1])"
DB_CONVENTION = "dB = 20*log10(|X|), range and Doppler FFTs divided by their window sums (dBFS)"


def counts_to_float(counts: torch.Tensor | np.ndarray, adc_bits: int = 12) -> torch.Tensor:
    """ADC counts -> SDK 3.6 floats ``2*c/(2**bits-1) - 1`` as a float32 tensor."""
    full = float(2**adc_bits - 1)
    t = torch.as_tensor(np.asarray(counts) if not isinstance(counts, torch.Tensor) else counts)
    return t.to(torch.float32) * (2.0 / full) - 1.0


def float_to_counts(x: torch.Tensor, adc_bits: int = 12) -> torch.Tensor:
    """SDK floats -> ADC counts (rounded, clipped to the code range) as int32."""
    full = 2**adc_bits - 1
    return torch.clamp(torch.round((x + 1.0) * (full / 2.0)), 0, full).to(torch.int32)
