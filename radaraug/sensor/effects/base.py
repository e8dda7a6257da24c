"""The effect protocol and the registry of effects by name.

An effect is one physical mechanism of the receiver: an ``nn.Module`` whose parameters are tensor buffers,
acting on a :class:`~radaraug.sensor.chain_state.ChainState` in place. The catalog: ``docs/receiver.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, cast

import torch
from torch import nn

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.sensor.chain_state import ChainState, ModulatedPaths

EFFECTS: dict[str, type[Effect]] = {}
"""Registry: effect name -> effect class."""

HARDWARE_ORDER: tuple[str, ...] = (
    "multipath",
    "tx_rx_leakage",
    "static_clutter",
    "vibrating_clutter",
    "phase_noise",
    "chirp_nonlinearity",
    "thermal_noise",
    "system_gain",
    "rx_gain_phase_mismatch",
    "if_highpass",
    "if_gain",
    "interference",
    "adc_noise",
    "anti_alias_lowpass",
    "frame_drift",
    "spur_tone",
    "dc_offset",
    "adc_quantization",
    "adc_clipping",
)
"""Every registered effect name, in the order the hardware applies the stages.

Multipath comes first so that it ghosts the scene's paths but not the on-chip leakage; the
clutter paths enter at the antenna, before the LO's phase noise and ramp non-linearity act on
them; the noise sources sit where they are referred (thermal noise at the RX port, ADC-driver
noise after the IF gain); the frame drift acts on the filtered signal before the ADC's own DC
level, spurs and quantization.
"""


@dataclass(frozen=True)
class Prior:
    """Search range of one effect parameter, in its physical unit (per element for per-RX parameters).

    Attributes:
        lo: lower bound (``> 0`` for ``scale="log"``).
        hi: upper bound, ``> lo``.
        scale: ``"lin"`` (uniform in the value) or ``"log"`` (uniform in its logarithm).
    """

    lo: float
    hi: float
    scale: str = "lin"

    def __post_init__(self) -> None:
        if self.scale not in ("lin", "log"):
            raise ConfigError(f"Prior scale must be 'lin' or 'log', got {self.scale!r}")
        if not (math.isfinite(self.lo) and math.isfinite(self.hi) and self.lo < self.hi):
            raise ConfigError(f"Prior needs finite lo < hi, got [{self.lo}, {self.hi}]")
        if self.scale == "log" and self.lo <= 0:
            raise ConfigError(f"a log-scale Prior needs lo > 0, got {self.lo}")

    def contains(self, value: float) -> bool:
        """True when ``lo <= value <= hi``."""
        return self.lo <= value <= self.hi

    def from_unit(self, u: float) -> float:
        """Map ``u`` in [0, 1] onto the range (linearly, or geometrically for ``"log"``)."""
        if self.scale == "log":
            return math.exp(math.log(self.lo) + u * (math.log(self.hi) - math.log(self.lo)))
        return self.lo + u * (self.hi - self.lo)


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

    Subclasses set ``name``, ``param_names`` and ``kind``, pass their parameters to ``super().__init__(**params)``
    (which registers them) and implement :meth:`forward`, which acts on the chain state in place. A parameter
    whose value is ``None`` is taken from the :class:`~radaraug.RadarConfig` at call time (e.g. the IF gain).
    """

    name: ClassVar[str] = ""
    # Subclasses annotate each parameter (``gain_dB: torch.Tensor``, ``| None`` when it may come
    # from the config): buffers are read through ``nn.Module.__getattr__``, which a type checker
    # only knows as ``Tensor | Module``.
    param_names: ClassVar[tuple[str, ...]] = ()
    # How the stage acts, for superposition (`FMCWReceiver.static_signal`): "linear" (LTI on the
    # whole signal: gains, filters), "additive" (adds a signal that does not depend on the input:
    # noise, leakage, offsets, spurs), "modulating" (depends on the input paths: phase noise) or
    # "nonlinear" (acts on samples: quantization, clipping).
    kind: ClassVar[str] = "additive"
    # Search ranges of the parameters a calibration search may move (see `priors`); parameters
    # absent here (orders, bit depths, path counts) are not searched. A range that depends on the
    # radar (a frequency up to Nyquist, a range up to `config.max_range_m`) is given as a function
    # of the RadarConfig.
    PRIORS: ClassVar[Mapping[str, Prior | Callable[[RadarConfig], Prior]]] = {}

    @classmethod
    def priors(cls, config: RadarConfig) -> dict[str, Prior]:
        """Search range of each searchable parameter (:attr:`PRIORS` evaluated for ``config``).

        Args:
            config: the radar configuration the effect will run with.

        Returns:
            ``{parameter name: Prior}`` (a fresh dict the caller may modify).
        """
        return {k: p if isinstance(p, Prior) else p(config) for k, p in cls.PRIORS.items()}

    def __init__(self, **values: Any) -> None:
        """Register ``values`` as the effect's parameters (:meth:`_set`)."""
        super().__init__()
        self._set(**values)

    def _set(self, **values: Any) -> None:
        for key, value in values.items():
            if value is None:
                setattr(self, key, None)
            else:
                self.register_buffer(key, as_param(value, key, self.name))

    def forward(self, state: ChainState) -> None:  # pragma: no cover - abstract
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
        out = {k: None if v is None else v.detach().cpu().tolist() for k, v in self.params().items()}
        return {"name": self.name, "params": out}

    def extra_repr(self) -> str:
        """The parameters for ``repr`` (``config`` where a value comes from the radar config)."""
        return ", ".join(
            f"{k}={'config' if v is None else v.detach().cpu().tolist()}" for k, v in self.params().items()
        )


class EffectList(nn.ModuleList):
    """The ``nn.ModuleList`` of a receiver's effects, typed to iterate as :class:`Effect` s (checked on build)."""

    def __iter__(self) -> Iterator[Effect]:
        return cast(Iterator[Effect], super().__iter__())


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


def insert_in_order(effects: Sequence[Effect], new: Effect) -> list[Effect]:
    """A new chain with ``new`` at its place in :data:`HARDWARE_ORDER`, replacing any effect of its name.

    Args:
        effects: the current chain (not modified); effects not in :data:`HARDWARE_ORDER` keep their place.
        new: the effect to add.

    Returns:
        The new list (the effect objects are shared, not copied).
    """
    if not isinstance(new, Effect):
        raise ConfigError(f"insert_in_order needs an Effect, got {type(new).__name__}")
    out = [e for e in effects if e.name != new.name]
    i = hardware_position([e.name for e in out], new.name)
    return [*out[:i], new, *out[i:]]


def hardware_position(names: Sequence[str], name: str) -> int:
    """Index where effect ``name`` goes among ``names``: before the first later one in hardware order, else the end.

    Raises:
        ConfigError: ``name`` has no place in :data:`HARDWARE_ORDER`.
    """
    order = {n: i for i, n in enumerate(HARDWARE_ORDER)}
    if name not in order:
        raise ConfigError(f"effect {name!r} has no place in HARDWARE_ORDER; insert it by hand")
    pos = order[name]
    return next((i for i, n in enumerate(names) if order.get(n, -1) > pos), len(names))


def tone_amplitude(state: ChainState, level_dB: torch.Tensor) -> torch.Tensor:
    """Peak ADC-float amplitude of a path whose RX-port power is ``level_dB`` relative to P_tx.

    ``sqrt(2 P_tx 10**(level/10)) G_fe``, a product so the gradient stays finite with the TX off.
    """
    return math.sqrt(2 * state.tx_power_W) * state.front_end_gain * torch.pow(10.0, level_dB / 20)


def check_params(
    effect: Effect, *, single: Sequence[str] = (), nonnegative: Sequence[str] = (),
    positive: Sequence[str] = (),
) -> None:
    """Raise :class:`ConfigError` unless the named parameters are single numbers, ``>= 0``, ``> 0``."""
    for key in single:
        if getattr(effect, key).ndim != 0:
            raise ConfigError(f"effect {effect.name}: {key} must be a single number")
    # Each rule with the comparison that finds the values breaking it.
    for keys, breaks, rule in ((nonnegative, torch.lt, ">= 0"), (positive, torch.le, "> 0")):
        for key in keys:
            v = getattr(effect, key)
            if v is not None and bool(breaks(v, 0).any()):
                raise ConfigError(f"effect {effect.name}: {key} must be {rule}, got {v.tolist()}")


def scatterer_count(effect: Effect, *names: str) -> int:
    """Common length K of the per-scatterer parameters ``names`` (scalars or 1-D, of length K or 1)."""
    values: dict[str, torch.Tensor] = {k: getattr(effect, k) for k in names}
    for key, v in values.items():
        if v.ndim > 1:
            raise ConfigError(f"effect {effect.name}: {key} must be a number or a list, got shape {tuple(v.shape)}")
    try:
        shape = torch.broadcast_shapes(*(v.shape for v in values.values()))
    except RuntimeError:
        lens = {k: (v.numel() if v.ndim else 1) for k, v in values.items()}
        raise ConfigError(f"effect {effect.name}: per-scatterer parameters have different lengths {lens}") from None
    k = int(shape[0]) if len(shape) else 1
    if k < 1:
        raise ConfigError(f"effect {effect.name}: needs at least one scatterer, got empty parameter lists")
    return k


def modulate_strongest_paths(state: ChainState, k: int, multiplier: torch.Tensor) -> None:
    """Add the LO-borne copies ``j 2 pi tau C`` of the ``k`` paths with the largest ``|C| tau``, times ``multiplier``.

    Chosen per frame over RX; each copy follows its path's per-chirp delay and gain.
    """
    strength = (state.coef.abs() * state.delay_s.abs()).amax(dim=-2)  # (…, P)
    idx = torch.topk(strength, k, dim=-1).indices[..., None, :].expand(*state.batch_shape, state.num_rx, k)
    coef, delay, rate = (t.gather(-1, idx) for t in (state.coef, state.delay_s, state.delay_rate))
    mod_coef = coef * (2j * math.pi) * delay.to(coef.dtype)
    state.modulated.append(ModulatedPaths(mod_coef, delay, rate, multiplier, *state.chirp_terms(idx)))
