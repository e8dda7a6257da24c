"""One effect of the twin's catalog: its per-item probability, its ranges, its draw and its stages.

A subclass is a dataclass named after the receiver effect it draws (:attr:`CatalogEffect.name`, the
name ``diagnose`` and :class:`~radaraug.sensor.profile.TwinProfile` use). docs/receiver.md, "Adding an
effect to the catalog", walks through one.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects.base import Effect
from radaraug.sim.priors import Section


@dataclass
class CatalogEffect(Section):
    """Base of a catalog entry: drawn per item with ``probability`` (times the catalog's scale).

    Subclasses add their ranges as fields and override :meth:`draw_values`, :meth:`stages` and,
    where ``diagnose`` fits the effect, :meth:`centred_on`.

    Args:
        probability: per-item chance that an item carries the effect.
    """

    name: ClassVar[str] = ""
    probability: float = 0.0

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.where = f"catalog.{cls.name}"  # how errors and YAML name the entry

    def draw(self, g: torch.Generator, scale: float) -> dict[str, Any] | None:
        """The item's values of this effect, or None when it does not carry it.

        Every value is drawn whether the effect hits or not, so one probability shifts no other draw.
        """
        on = bool(torch.rand((), generator=g, dtype=torch.float64) < scale * self.probability)
        values = self.draw_values(g)
        return values if on else None

    def draw_values(self, g: torch.Generator) -> dict[str, Any]:
        """The effect's values for one item (plain numbers and tuples), drawn from ``g`` in a fixed order."""
        return {}

    @classmethod
    def record(cls, values: Mapping[str, Any], config: RadarConfig) -> dict[str, Any]:
        """The drawn values as the item's description records them (JSON types)."""
        return dict(values)

    @classmethod
    def stages(cls, values: Mapping[str, Any], config: RadarConfig) -> list[Effect]:
        """The receiver stages that carry the drawn values (none for levels)."""
        return []

    def centred_on(self, fitted: Mapping[str, Any], config: RadarConfig,
                   probability: float) -> dict[str, Any] | None:
        """Field changes that centre this entry on what ``diagnose`` fitted on a calibration capture.

        Args:
            fitted: the fitted effect's parameters (its ``TwinProfile`` entry).
            config: the calibration capture's radar config.
            probability: the entry's new probability.

        Returns:
            ``{field: value}`` (the probability included), or None when the fit cannot move it.
        """
        return None

    def replace(self, **changes: Any) -> CatalogEffect:
        """A copy with ``changes`` (checked)."""
        return dataclasses.replace(self, **changes)


# ---------------------------------------------------------------------------- bands around a fit
def factor_band(value: float, factor: float, lo: float, hi: float) -> tuple[float, float]:
    """``(value / factor, value * factor)`` clipped to ``[lo, hi]`` (and kept non-empty)."""
    a = min(max(value / factor, lo), hi)
    b = min(max(value * factor, lo), hi)
    return (a, b) if b > a else (max(lo, b * 0.99), b)


def fit_band(p: Mapping[str, Any], key: str, default: float, lo: float, hi: float,
             factor: float = 2.0) -> tuple[float, float]:
    """:func:`factor_band` around the fitted ``p[key]`` (``default`` when it was not fitted)."""
    return factor_band(first(p.get(key, default)), factor, lo, hi)


def band(value: float, half: float, lo: float, hi: float) -> tuple[float, float]:
    """``value +- half`` clipped to ``[lo, hi]`` (and kept non-empty)."""
    a, b = max(value - half, lo), min(value + half, hi)
    return (a, b) if b > a else (min(a, b), max(a, b) + 1e-9)


def first(value: Any) -> float:
    """A fitted parameter's first value (per-RX parameters are lists)."""
    return float(value[0] if isinstance(value, (list, tuple)) else value)


__all__ = ["CatalogEffect", "band", "factor_band", "first", "fit_band"]
