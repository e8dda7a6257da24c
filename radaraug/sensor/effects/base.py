"""The effect protocol and the registry of effects by name.

An effect is one physical mechanism of the receiver (a filter, a noise source, the ADC...). It
is a ``torch.nn.Module`` whose parameters are tensors (registered as buffers, so ``.to()``
moves them and a calibration loop can call ``requires_grad_()`` on them and fit them by
gradient). It acts on a :class:`~radaraug.sensor.chain.ChainState` in place; the receiver
applies its effects in list order, which is the order the hardware applies them.

Every effect carries a ``name`` from the project's effect list (DESIGN.md), :meth:`params`
(the live tensors), :meth:`from_params` (build from numbers or tensors), and a JSON-friendly
:meth:`to_dict` / :func:`effect_from_dict` pair for twin profiles.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, ClassVar

import torch
from torch import nn

from radaraug.errors import ConfigError
from radaraug.sensor.chain import ChainState

EFFECTS: dict[str, type[Effect]] = {}
"""Registry: effect name -> effect class."""


def register(cls: type[Effect]) -> type[Effect]:
    """Class decorator: add ``cls`` to :data:`EFFECTS` under ``cls.name``."""
    if not cls.name or cls.name in EFFECTS:
        raise ValueError(f"effect name {cls.name!r} missing or registered twice")
    EFFECTS[cls.name] = cls
    return cls


def as_param(value: Any, name: str, effect: str) -> torch.Tensor:
    """A parameter value (number, list or tensor) as a float tensor; reject NaN/Inf."""
    try:
        t = value.detach().clone() if isinstance(value, torch.Tensor) else torch.as_tensor(value)
        t = t.to(torch.get_default_dtype())
    except (TypeError, ValueError, RuntimeError) as e:
        raise ConfigError(f"effect {effect}: parameter {name} must be a number or a list of numbers, got {value!r}") from e
    if not torch.isfinite(t).all():
        raise ConfigError(f"effect {effect}: parameter {name} must be finite, got {value!r}")
    return t


class Effect(nn.Module):
    """Base class of receiver effects.

    Subclasses set ``name``, ``param_names`` and ``kind`` and implement :meth:`apply`. Parameters whose
    value is ``None`` are taken from the :class:`~radaraug.RadarConfig` at call time (e.g. the
    IF gain) and are not stored.
    """

    name: ClassVar[str] = ""
    param_names: ClassVar[tuple[str, ...]] = ()
    # How the stage acts, for superposition (`FMCWReceiver.static_signal`): "linear" (LTI on the
    # whole signal: gains, filters), "additive" (adds a signal that does not depend on the input:
    # noise, leakage, offsets, spurs), "modulating" (depends on the input paths: phase noise) or
    # "nonlinear" (acts on samples: quantization, clipping).
    kind: ClassVar[str] = "additive"

    def _set(self, **values: Any) -> None:
        for key, value in values.items():
            if value is None:
                setattr(self, key, None)
            else:
                self.register_buffer(key, as_param(value, key, self.name))

    def apply(self, state: ChainState) -> None:  # pragma: no cover - abstract
        """Act on the chain state in place."""
        raise NotImplementedError

    def params(self) -> dict[str, torch.Tensor | None]:
        """The parameters as live tensors (``None``: taken from the radar config)."""
        return {k: getattr(self, k) for k in self.param_names}

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> Effect:
        """Build from a parameter dict (numbers, lists or tensors); unknown keys are an error."""
        unknown = set(params) - set(cls.param_names)
        if unknown:
            raise ConfigError(f"effect {cls.name}: unknown parameters {sorted(unknown)} (known: {list(cls.param_names)})")
        return cls(**dict(params))

    def to_dict(self) -> dict[str, Any]:
        """``{"name": ..., "params": {...}}`` with plain JSON numbers/lists."""
        out = {}
        for k, v in self.params().items():
            out[k] = None if v is None else v.detach().cpu().tolist()
        return {"name": self.name, "params": out}

    def extra_repr(self) -> str:
        parts = []
        for k, v in self.params().items():
            parts.append(f"{k}={'config' if v is None else v.detach().cpu().tolist()}")
        return ", ".join(parts)


def effect_from_dict(data: Mapping[str, Any]) -> Effect:
    """Inverse of :meth:`Effect.to_dict`, through the registry."""
    if not isinstance(data, Mapping) or "name" not in data:
        raise ConfigError(f"an effect must be a dict with a 'name', got {data!r}")
    cls = EFFECTS.get(data["name"])
    if cls is None:
        raise ConfigError(f"unknown effect {data['name']!r}; known: {sorted(EFFECTS)}")
    return cls.from_params(data.get("params", {}))


def per_rx(state: ChainState, value: torch.Tensor, name: str, effect: str) -> torch.Tensor:
    """A scalar or per-RX parameter as an ``(RX,)`` tensor on the call's device/dtype."""
    v = state.param(value)
    if v.ndim == 0:
        return v.expand(state.num_rx)
    if v.shape != (state.num_rx,):
        raise ConfigError(f"effect {effect}: {name} has {v.numel()} values for {state.num_rx} RX channels")
    return v
