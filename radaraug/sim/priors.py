"""Sections of priors: dataclasses whose fields are the ranges twin randomization draws from.

One check serves every section of :class:`~radaraug.sim.randomization.TwinRandomization` and every
entry of the effect catalog: a field's annotation says its kind (a flag, a count, a probability or
number, a pair ``[lo, hi]``, a count pair, material names) and :func:`span`'s metadata its bounds.
"""

from __future__ import annotations

import dataclasses
import json
import math
import types
from collections.abc import Callable, Mapping, Sequence
from typing import Any, ClassVar, TypeVar

import torch

from radaraug.errors import ConfigError, SceneError
from radaraug.scene.materials import get_material
from radaraug.sim.scenarios import _uniform

_S = TypeVar("_S", bound="Section")


def span(lo: float, hi: float, *, positive: bool = False, bounds: tuple[float, float] | None = None) -> Any:
    """A dataclass field holding the range ``(lo, hi)``: ``positive`` (log-drawn ranges) or inside ``bounds``."""
    return dataclasses.field(default=(float(lo), float(hi)), metadata={"positive": positive, "bounds": bounds})


def log_uniform(lo_hi: tuple[float, float], g: torch.Generator) -> float:
    """Uniform in the logarithm over ``[lo, hi]`` (both > 0), one draw from ``g``."""
    lo, hi = lo_hi
    return math.exp(_uniform((math.log(lo), math.log(hi)), g))


uniform = _uniform


class Section:
    """Base of a dataclass of priors: fields checked on construction, plain-dict round trip.

    Subclasses are dataclasses; :attr:`where` names the section in error messages and YAML.
    """

    where: ClassVar[str] = ""

    def __post_init__(self) -> None:
        # Normalise YAML-ish input (lists, ints) and fail early, naming the field.
        for f in dataclasses.fields(self):  # type: ignore[arg-type]  # subclasses are dataclasses
            setattr(self, f.name, self.check_field(f, getattr(self, f.name)))

    def check_field(self, f: dataclasses.Field, value: Any) -> Any:
        """``value`` of field ``f``, checked and normalised by its annotation (ConfigError naming it)."""
        name = f"{self.where}.{f.name}" if self.where else f.name
        check = _CHECKS.get(_annotation(f.type))
        if check is None:
            raise TypeError(f"{type(self).__name__}.{f.name}: no check for {f.type}")
        return check(value, name, f.metadata)

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON/YAML types (pairs as lists)."""
        return json.loads(json.dumps(dataclasses.asdict(self)))  # type: ignore[call-overload]  # tuples -> lists

    @classmethod
    def from_dict(cls: type[_S], data: Any) -> _S:
        """Inverse of :meth:`to_dict`; missing keys take the defaults.

        Raises:
            ConfigError: not a mapping, an unknown key (named, with the known ones), or a bad value.
        """
        if isinstance(data, cls):
            return data
        where = f"twin randomization {cls.where}".rstrip()
        if not isinstance(data, Mapping):
            raise ConfigError(f"{where} must be a mapping, got {type(data).__name__}")
        known = {f.name for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
        unknown = sorted(str(k) for k in data if k not in known)
        if unknown:
            raise ConfigError(f"{where}: unknown key(s) {unknown}; known: {sorted(known)}")
        return cls(**dict(data))


# ---------------------------------------------------------------------------- checks by annotation
def _annotation(t: Any) -> str:
    """A field's annotation as written (a string under ``from __future__ import annotations``, else a type)."""
    if isinstance(t, str):
        return t
    if isinstance(t, type) and not isinstance(t, types.GenericAlias):
        return t.__name__
    return str(t)


def _fail(name: str, text: str) -> ConfigError:
    return ConfigError(f"twin randomization: {name} {text}")


def _flag(value: Any, name: str, meta: Mapping[str, Any]) -> bool:
    if not isinstance(value, bool):
        raise _fail(name, f"must be true or false, got {value!r}")
    return value


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(name, f"must be a finite number, got {value!r}")
    return float(value)


def _nonnegative(value: Any, name: str, meta: Mapping[str, Any]) -> float:
    """A float field: a number >= 0, and a probability in [0, 1] where the name says so."""
    value = _number(value, name)
    if value < 0:
        raise _fail(name, f"must be >= 0, got {value!r}")
    if name.endswith("probability") and value > 1.0:
        raise _fail(name, f"must be a probability in [0, 1], got {value!r}")
    return value


def _count(value: Any, name: str, meta: Mapping[str, Any]) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise _fail(name, f"must be an integer >= 1, got {value!r}")
    return value


def _pair(value: Any, name: str, meta: Mapping[str, Any]) -> tuple[float, float]:
    """A range ``(lo, hi)``: positive or inside the bounds its :func:`span` gives."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2:
        raise _fail(name, f"must be a pair [lo, hi], got {value!r}")
    lo, hi = (_number(v, name) for v in value)
    if lo > hi:
        raise _fail(name, f"must have lo <= hi, got {[lo, hi]}")
    if meta.get("positive") and lo <= 0:
        raise _fail(name, f"must be positive, got {[lo, hi]}")
    bound_lo, bound_hi = meta.get("bounds") or (-math.inf, math.inf)
    if lo < bound_lo or hi > bound_hi:
        raise _fail(name, f"must lie in [{bound_lo}, {bound_hi}], got {[lo, hi]}")
    return (lo, hi)


def _count_pair(value: Any, name: str, meta: Mapping[str, Any]) -> tuple[int, int]:
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2 or any(
            isinstance(v, bool) or not isinstance(v, int) for v in value):
        raise _fail(name, f"must be a pair of integers [lo, hi], got {value!r}")
    lo, hi = int(value[0]), int(value[1])
    if not 0 <= lo <= hi:
        raise _fail(name, f"must have 0 <= lo <= hi, got {[lo, hi]}")
    return (lo, hi)


def material_list(value: Any, name: str, meta: Mapping[str, Any] | None = None) -> tuple[str, ...]:
    """A non-empty tuple of ITU-R P.2040 material names (one name is accepted)."""
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, Sequence) or not value:
        raise _fail(name, f"must be a non-empty list of material names, got {value!r}")
    for n in value:
        try:
            get_material(n)
        except SceneError as err:
            raise ConfigError(f"twin randomization: {name}: {err}") from None
    return tuple(str(n) for n in value)


_CHECKS: dict[str, Callable[[Any, str, Mapping[str, Any]], Any]] = {
    "bool": _flag,
    "int": _count,
    "float": _nonnegative,
    "tuple[float, float]": _pair,
    "tuple[int, int]": _count_pair,
    "tuple[str, ...]": material_list,
}


__all__ = ["Section", "log_uniform", "material_list", "span", "uniform"]
