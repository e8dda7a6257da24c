"""The twin's effect catalog: sensor effects drawn per item, one file per effect.

Each entry (:class:`CatalogEffect`) owns its probability, its ranges, its draw, the receiver stages it
adds and how ``diagnose``'s fit on a calibration capture centres it. :class:`Catalog` is the
``catalog`` section of :class:`~radaraug.sim.randomization.TwinRandomization`, keyed by effect name.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.sensor.effects.base import Effect
from radaraug.sim.catalog.base import CatalogEffect
from radaraug.sim.catalog.frame_drift import FrameDriftPrior
from radaraug.sim.catalog.interference import InterferencePrior
from radaraug.sim.catalog.rx_gain_phase_mismatch import RxGainPhaseMismatchPrior
from radaraug.sim.catalog.spur_tone import SpurTonePrior
from radaraug.sim.catalog.static_phase_noise import StaticPhaseNoisePrior
from radaraug.sim.catalog.vibrating_clutter import VibratingClutterPrior
from radaraug.sim.catalog.wide_levels import WideLevelsPrior
from radaraug.sim.priors import _nonnegative

ENTRIES: tuple[type[CatalogEffect], ...] = (
    SpurTonePrior, InterferencePrior, VibratingClutterPrior, RxGainPhaseMismatchPrior, FrameDriftPrior,
    WideLevelsPrior, StaticPhaseNoisePrior,
)
"""The built-in catalog in draw order (the order is part of every item's contract: never reorder it)."""
BY_NAME: dict[str, type[CatalogEffect]] = {e.name: e for e in ENTRIES}
"""Every entry by effect name, the built-ins first, then those :func:`register` added, in draw order."""


def register(entry: type[CatalogEffect]) -> type[CatalogEffect]:
    """Add an entry to the catalog (a class decorator); it draws after every entry before it.

    An entry added at the end shifts no earlier draw, so items that do not carry it stay bit-identical
    when its default probability is 0. Randomizations built before the call do not have it.

    Raises:
        ConfigError: not a :class:`CatalogEffect` subclass, no ``name``, or a name already taken.
    """
    if not (isinstance(entry, type) and issubclass(entry, CatalogEffect)) or not entry.name:
        raise ConfigError(f"register needs a named CatalogEffect subclass, got {entry!r}")
    if entry.name in BY_NAME:
        raise ConfigError(f"the catalog already has an entry named {entry.name!r} ({BY_NAME[entry.name].__name__})")
    BY_NAME[entry.name] = entry
    return entry


class Catalog(Mapping[str, CatalogEffect]):
    """The ``catalog`` section: ``scale`` and one :class:`CatalogEffect` per effect name.

    Args:
        scale: factor on every entry's probability (0: the catalog off).
        **entries: per effect name, its entry or a mapping of its fields; the rest keep their defaults.

    Raises:
        ConfigError: an unknown effect name (the known ones listed) or a bad value.
    """

    where = "catalog"

    def __init__(self, scale: float = 1.0, **entries: CatalogEffect | Mapping[str, Any]) -> None:
        unknown = sorted(set(entries) - set(BY_NAME))
        if unknown:
            raise ConfigError(f"twin randomization catalog: unknown effect(s) {unknown}; "
                              f"known: {['scale', *BY_NAME]}")
        self.scale = _nonnegative(scale, "catalog.scale", {})
        if self.scale > 1.0:
            raise ConfigError(f"twin randomization: catalog.scale must be in [0, 1], got {scale!r}")
        self._entries = {name: e.from_dict(entries.get(name, {})) for name, e in BY_NAME.items()}

    def __getitem__(self, name: str) -> CatalogEffect:
        return self._entries[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Catalog) and self.scale == other.scale and self._entries == other._entries

    def __repr__(self) -> str:
        return f"Catalog(scale={self.scale!r}, " + ", ".join(f"{k}={v!r}" for k, v in self._entries.items()) + ")"

    def draw(self, g: torch.Generator) -> dict[str, dict[str, Any]]:
        """One item's effects, ``{name: values}`` for those it carries, every entry drawing in turn from ``g``."""
        drawn = {name: e.draw(g, self.scale) for name, e in self._entries.items()}
        return {name: values for name, values in drawn.items() if values is not None}

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON/YAML types."""
        return {"scale": self.scale, **{n: e.to_dict() for n, e in self._entries.items()}}

    @classmethod
    def from_dict(cls, data: Any) -> Catalog:
        """Inverse of :meth:`to_dict` (a Catalog is returned as it is).

        Raises:
            ConfigError: not a mapping, an unknown key, or a bad value.
        """
        if isinstance(data, Catalog):
            return data
        if not isinstance(data, Mapping):
            raise ConfigError(f"twin randomization catalog must be a mapping, got {type(data).__name__}")
        return cls(**{str(k): v for k, v in data.items()})


def record(drawn: Mapping[str, Mapping[str, Any]], config: RadarConfig) -> dict[str, Any]:
    """The drawn effects as an item's description records them, ``{name: {parameter: value}}``."""
    return {name: BY_NAME[name].record(values, config) for name, values in drawn.items()}


def stages(drawn: Mapping[str, Mapping[str, Any]], config: RadarConfig) -> list[Effect]:
    """The receiver stages of the drawn effects (each inserted later at its hardware position)."""
    return [s for name, values in drawn.items() for s in BY_NAME[name].stages(values, config)]


__all__ = [
    "BY_NAME", "ENTRIES", "Catalog", "CatalogEffect", "FrameDriftPrior", "InterferencePrior",
    "RxGainPhaseMismatchPrior", "SpurTonePrior", "StaticPhaseNoisePrior", "VibratingClutterPrior",
    "WideLevelsPrior", "record", "register", "stages",
]
