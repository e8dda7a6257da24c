"""The ADC end of the chain: per-RX DC offsets, quantization and clipping, in SDK 3.6 floats."""

from __future__ import annotations

import torch

from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, per_rx, register


@register
class DCOffset(Effect):
    """Per-RX DC level at the ADC input, given as the ADC code it sits at.

    Args:
        level_counts: per-RX (or scalar) mean ADC code; mid-scale ``(2**bits - 1) / 2`` (2047.5 for 12 bits)
            is zero offset.
    """

    name = "dc_offset"
    param_names = ("level_counts",)
    level_counts: torch.Tensor
    PRIORS = {"level_counts": lambda config: Prior(0.0, float(config.adc_full_scale_counts))}  # any ADC code

    def __init__(self, level_counts: float | list | torch.Tensor = 2047.5) -> None:
        super().__init__(level_counts=level_counts)

    def forward(self, state: ChainState) -> None:
        """Add each RX's DC level, converted from ADC code to SDK floats in [-1, 1]."""
        level = per_rx(state, self.level_counts, "level_counts", self.name)
        state.add_constant(level * state.float_per_count - 1.0)


@register
class ADCQuantization(Effect):
    """Round to the nearest ADC code (straight-through gradient, so calibration can still fit).

    Args:
        bits: ADC resolution; ``None`` takes ``config.adc_bits``.
    """

    name = "adc_quantization"
    kind = "nonlinear"
    param_names = ("bits",)
    bits: torch.Tensor | None

    def __init__(self, bits: int | None = None) -> None:
        super().__init__(bits=bits)

    def forward(self, state: ChainState) -> None:
        """Round the samples to the nearest ADC code (gradient passed straight through)."""
        bits = state.config.adc_bits if self.bits is None else int(self.bits)
        full = float(2**bits - 1)
        x = state.materialize()
        q = torch.round((x + 1.0) * (full / 2.0)) * (2.0 / full) - 1.0
        state.samples = x + (q - x).detach()


@register
class ADCClipping(Effect):
    """Clip to the ADC range: codes ``0 .. 2**bits - 1``, i.e. ``[-1, 1]`` in SDK floats."""

    name = "adc_clipping"
    kind = "nonlinear"
    param_names = ()

    def forward(self, state: ChainState) -> None:
        """Clip the samples to the ADC range ``[-1, 1]``."""
        state.samples = torch.clamp(state.materialize(), -1.0, 1.0)
