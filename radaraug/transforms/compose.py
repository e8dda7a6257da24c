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

    Like :class:`~radaraug.transforms.base.RadarTransform`, a compose takes a tensor or a sample
    (tuple, list, dict; ``compose(x, *rest)`` is ``compose((x, *rest))``) and returns the same
    structure: every step gets the whole sample, so each radaraug step transforms the radar leaves
    it recognizes and passes the rest (e.g. a label) through. A step that is not sample-aware (a
    plain ``nn.Module``) is applied to each radar leaf (the first real or complex floating tensor
    with at least 2 dims and any other of its shape). ``.eval()``/``.train()`` reach every step.

    At construction every :class:`~radaraug.transforms.dr.CalibratedDR` (and
    :class:`~radaraug.transforms.dr.RandomDR`) is checked against the steps before it:

    * the clamp works on dB maps, so if any deterministic step precedes it, the last one must
      produce dB (``ToDecibels``, or a ``CombineRx(db=True)`` after it);
    * a CalibratedDR that records the chain it was fitted with must follow exactly that chain
      (compared step by step after expanding ``RangeDoppler`` into its parts; random steps are
      ignored). A compose that *starts* with the CalibratedDR is taken to receive maps made with
      the fitted chain elsewhere: only the map shape is then checked, at call time.

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
        """Run every step on a tensor or a sample (see the class docstring)."""
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

