"""`RadarCompose`: a sequential pipeline that records its DSP chain and checks CalibratedDR use."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import torch
from torch import nn

from radaraug.transforms import _sample
from radaraug.transforms.dsp_spec import chain_of


class RadarCompose(nn.Module):
    """Apply transforms in order; ``chain_spec()`` lists every step (JSON-able).

    Takes a tensor or a sample: sample-aware steps get the whole sample, any other ``nn.Module`` each
    radar leaf. At construction each DR step is checked: the steps before it must end in dB maps, and a
    CalibratedDR must follow the chain it was fitted with (docs/transforms.md, "Checks").

    Args:
        transforms: the steps (radaraug transforms, nested composes, or any ``nn.Module``).

    Raises:
        CalibrationError: a DR step in the wrong place or after a different chain.
    """

    #: Takes whole samples (tuples, dicts) itself (read by ``_sample.is_sample_aware``).
    takes_samples: bool = True

    def __init__(self, transforms: Sequence[nn.Module]) -> None:
        super().__init__()
        if isinstance(transforms, nn.Module) or not isinstance(transforms, Sequence):
            raise TypeError("RadarCompose takes a list of transforms")
        self.transforms = nn.ModuleList(transforms)
        self._check_dr_placement()

    def forward(self, *inputs: Any) -> Any:
        """Run every step on a tensor or a sample."""
        sample = _sample.as_sample(inputs)
        for t in self.transforms:
            if isinstance(sample, torch.Tensor) or _sample.is_sample_aware(t):
                sample = t(sample)
            else:
                sample = _sample.apply_to_radar_leaves(t, sample)
        return sample

    def chain_spec(self) -> list[dict[str, Any]]:
        """Every step's spec in order (nested composes flattened)."""
        specs = chain_of(list(self.transforms))
        return specs if specs is not None else [{"name": "opaque"}]

    def _check_dr_placement(self) -> None:
        # Steps that care what precedes them (the DR clamps) say so through
        # ``check_preceding_chain``; RadarCompose needs not know their classes.
        for i, step in enumerate(self.transforms):
            check = getattr(step, "check_preceding_chain", None)
            if not callable(check):
                continue
            before = chain_of(list(self.transforms)[:i])
            if before is None:
                continue  # a step we cannot describe precedes: nothing reliable to check
            check(before, f"RadarCompose: {type(step).__name__} at position {i}")

    def __len__(self) -> int:
        return len(self.transforms)

    def __getitem__(self, i: int) -> nn.Module:
        return self.transforms[i]

