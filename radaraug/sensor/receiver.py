"""`FMCWReceiver`: propagation paths -> raw ADC frames in the real sensor's units.

Paths are scaled by the TX power, passed through the effect chain in hardware order (default:
:mod:`radaraug.sensor.defaults`) and synthesized once, as late as the effects allow (:mod:`.synthesis`). The
output ``(..., RX, chirps, samples)`` is in Infineon Radar SDK 3.6 floats
(:data:`radaraug.units.FLOAT_CONVENTION`). See ``docs/receiver.md``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import Any

import torch
from torch import nn

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, InputTensorError
from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.defaults import FRONT_END_GAIN_DB, default_effects, tx_power_dBm
from radaraug.sensor.effects import Effect, effect_from_dict
from radaraug.sensor.effects.base import EffectList
from radaraug.sensor.paths import Paths
from radaraug.sensor.synthesis import DEFAULT_TAYLOR_TOL, SYNTHESIS_METHODS
from radaraug.units import FLOAT_CONVENTION, float_to_counts


class FMCWReceiver(nn.Module):
    """Simulates the BGT60-style FMCW receiver for a :class:`RadarConfig`.

    Args:
        config: radar configuration (chirp, IF gain, filter cutoffs, ADC bits, RX layout).
        noise_figure_dB: noise figure of the default chain's thermal noise. Only with ``effects=None``.
        tx_power_dBm: TX power; ``None`` maps ``config.tx_power_level`` by the assumed law of
            :func:`~radaraug.sensor.defaults.tx_power_dBm`.
        system_gain_dB: gain of the default chain's ``system_gain`` stage. Only with ``effects=None``.
        effects: the effect chain in hardware order; ``None`` builds the default BGT60TR13C chain; ``[]`` gives
            the ideal receiver (front-end gain only).
        synthesis: ``"fast"`` (separable GEMM, default) or ``"exact"`` (direct sum, reference).
        front_end_gain_dB: ADC float units per sqrt(W) at the RX port at 0 dB IF gain
            (:data:`~radaraug.sensor.defaults.FRONT_END_GAIN_DB`).
        taylor_tol: truncation bound of the fast synthesis' coupling expansion, relative to the strongest path.
        noise_tol: the bound relative to the RMS per sample of the noise the chain has added before the
            synthesis instead (None: ``taylor_tol``); docs/simulation.md, "The synthesis' error contract".
        adc_noise_rms_counts: RMS of the default chain's ``adc_noise`` stage (None: the fitted
            :data:`~radaraug.sensor.defaults.ADC_NOISE_RMS_COUNTS`). Only with ``effects=None``.
    """

    units = FLOAT_CONVENTION

    def __init__(
        self,
        config: RadarConfig,
        *,
        noise_figure_dB: float | None = None,
        tx_power_dBm: float | None = None,
        system_gain_dB: float = 0.0,
        effects: Sequence[Effect] | None = None,
        synthesis: str = "fast",
        front_end_gain_dB: float = FRONT_END_GAIN_DB,
        taylor_tol: float = DEFAULT_TAYLOR_TOL,
        adc_noise_rms_counts: float | None = None,
        noise_tol: float | None = None,
    ) -> None:
        super().__init__()
        if not isinstance(config, RadarConfig):
            raise ConfigError(f"FMCWReceiver needs a RadarConfig, got {type(config).__name__}")
        if synthesis not in SYNTHESIS_METHODS:
            raise ConfigError(f"synthesis must be one of {SYNTHESIS_METHODS}, got {synthesis!r}")
        if not (taylor_tol > 0 and math.isfinite(taylor_tol)):
            raise ConfigError(f"taylor_tol must be positive, got {taylor_tol!r}")
        self.config = config
        self.synthesis = synthesis
        self.taylor_tol = float(taylor_tol)
        if noise_tol is not None and not (noise_tol > 0 and math.isfinite(noise_tol)):
            raise ConfigError(f"noise_tol must be positive or None, got {noise_tol!r}")
        self.noise_tol = None if noise_tol is None else float(noise_tol)
        self.tx_power_dBm = _tx_power(config, tx_power_dBm)
        self.front_end_gain_dB = float(front_end_gain_dB)
        if effects is None:
            kw: dict[str, float] = {"system_gain_dB": float(system_gain_dB)}
            if noise_figure_dB is not None:
                kw["noise_figure_dB"] = float(noise_figure_dB)
            if adc_noise_rms_counts is not None:
                kw["adc_noise_rms_counts"] = float(adc_noise_rms_counts)
            effects = default_effects(config, **kw)
        else:
            if noise_figure_dB is not None or system_gain_dB != 0.0 or adc_noise_rms_counts is not None:
                raise ConfigError(
                    "noise_figure_dB, system_gain_dB and adc_noise_rms_counts configure the default chain "
                    "only; with an explicit effects list set them in its ThermalNoise / SystemGain / "
                    "ADCNoise effects"
                )
            bad = [e for e in effects if not isinstance(e, Effect)]
            if bad:
                raise ConfigError(f"effects must be Effect instances, got {[type(b).__name__ for b in bad]}")
        self.effects = EffectList(list(effects))

    # ------------------------------------------------------------------ public API
    @property
    def tx_power_W(self) -> float:
        """TX power in watts."""
        return 0.0 if self.tx_power_dBm == -math.inf else 10 ** (self.tx_power_dBm / 10) / 1000

    @property
    def front_end_gain(self) -> float:
        """Front-end gain as an amplitude factor (ADC floats per sqrt(W))."""
        return 10 ** (self.front_end_gain_dB / 20)

    def effect(self, name: str) -> Effect:
        """The first effect called ``name`` (KeyError when absent)."""
        for e in self.effects:
            if e.name == name:
                return e
        raise KeyError(f"no effect {name!r} in this receiver; it has {[e.name for e in self.effects]}")

    def forward(
        self,
        paths: Paths,
        *,
        generator: torch.Generator | None = None,
        frame_start_s: float | torch.Tensor = 0.0,
        static_signal: torch.Tensor | None = None,
    ) -> torch.Tensor:
        """Simulate the ADC samples of ``paths``.

        Args:
            paths: propagation paths ``(..., P, RX)``; their device and delay dtype set the output's.
            generator: source of every random draw (on the paths' device); None: global RNG.
            frame_start_s: absolute time of the frame's first ramp start (time-locked effects): a number, or a
                tensor broadcastable to the paths' batch dims (one start per frame).
            static_signal: precomputed signal of static paths (:meth:`static_signal`), added before the first
                non-linear stage.

        Returns:
            ``(..., RX, chirps, samples)`` in SDK 3.6 floats.
        """
        state = self._initial_state(paths, generator, frame_start_s)
        if static_signal is not None:
            _check_static_signal(static_signal, state.sample_shape)
        pending = static_signal
        for eff in self.effects:
            if pending is not None and eff.kind == "nonlinear":
                state.add_samples_after_synthesis(pending)
                pending = None
            eff(state)
        if pending is not None:
            state.add_samples_after_synthesis(pending)
        return state.materialize()

    @torch.no_grad()
    def static_signal(self, paths: Paths) -> torch.Tensor:
        """The deterministic signal of paths that are the same in every frame (a static room).

        Their synthesis through the linear stages; passed to :meth:`forward` as ``static_signal`` it gives the same
        frames as tracing them with the moving paths (``docs/receiver.md``, "Static paths once").

        Args:
            paths: static paths ``(P, RX)`` (any leading dims are kept).

        Returns:
            ``(..., RX, chirps, samples)`` in SDK floats, before DC offset and ADC.
        """
        return self.linear_state(paths).materialize()

    @torch.no_grad()
    def static_chirp(self, paths: Paths) -> torch.Tensor:
        """One chirp ``(..., RX, samples)`` of :meth:`static_signal`, for paths that do not move.

        Such a path gives the same samples on every chirp, so this is ``static_signal(paths)[..., 0, :]`` at
        1/chirps of the work (equal up to float rounding).

        Raises:
            InputTensorError: a path moves (non-zero ``delay_rate``) or has per-chirp terms.
        """
        if paths.chirp_delay_s is not None or paths.chirp_gain is not None or bool((paths.delay_rate != 0).any()):
            raise InputTensorError("static_chirp: the paths must not move (zero delay_rate, no per-chirp terms)")
        state = self.linear_state(paths)
        state.timing = dataclasses.replace(state.timing, num_chirps=1)
        return state.materialize()[..., 0, :]

    @torch.no_grad()
    def linear_state(self, paths: Paths) -> ChainState:
        """The chain state of ``paths`` after the linear stages before the first non-linear one.

        What :meth:`static_signal` synthesizes; ``state.coef`` holds each path's coefficient.
        """
        state = self._initial_state(paths, None, 0.0)
        for eff in self.effects:
            if eff.kind == "nonlinear":
                break
            if eff.kind == "linear":
                eff(state)
        return state

    def to_counts(
        self,
        paths_or_samples: Paths | torch.Tensor,
        *,
        generator: torch.Generator | None = None,
        frame_start_s: float | torch.Tensor = 0.0,
    ) -> torch.Tensor:
        """ADC counts (``torch.uint16``) of simulated ``paths`` or of SDK-float samples."""
        if isinstance(paths_or_samples, Paths):
            x = self(paths_or_samples, generator=generator, frame_start_s=frame_start_s)
        elif isinstance(paths_or_samples, torch.Tensor):
            x = paths_or_samples
        else:
            raise InputTensorError(f"to_counts needs Paths or a tensor, got {type(paths_or_samples).__name__}")
        return float_to_counts(x.detach(), self.config.adc_bits).to(torch.uint16)

    def to_dict(self) -> dict[str, Any]:
        """JSON-friendly description: synthesis, TX power, front-end gain and the effect chain."""
        return {
            "synthesis": self.synthesis,
            "tx_power_dBm": None if self.tx_power_dBm == -math.inf else self.tx_power_dBm,
            "front_end_gain_dB": self.front_end_gain_dB,
            "taylor_tol": self.taylor_tol,
            "noise_tol": self.noise_tol,
            "effects": [e.to_dict() for e in self.effects],
            "units": FLOAT_CONVENTION,
        }

    @classmethod
    def from_dict(cls, config: RadarConfig, data: Mapping[str, Any]) -> FMCWReceiver:
        """Inverse of :meth:`to_dict` for ``config``."""
        try:
            effects = [effect_from_dict(e) for e in data["effects"]]
            tx = data.get("tx_power_dBm")
            return cls(
                config,
                effects=effects,
                tx_power_dBm=-math.inf if tx is None else float(tx),
                synthesis=data.get("synthesis", "fast"),
                front_end_gain_dB=float(data.get("front_end_gain_dB", FRONT_END_GAIN_DB)),
                taylor_tol=float(data.get("taylor_tol", DEFAULT_TAYLOR_TOL)),
                noise_tol=None if data.get("noise_tol") is None else float(data["noise_tol"]),
            )
        except (KeyError, TypeError) as e:
            raise ConfigError(f"invalid receiver description: {e}") from None

    def extra_repr(self) -> str:
        """The synthesis, the TX power and the front-end gain for ``repr``."""
        return f"synthesis={self.synthesis!r}, tx_power_dBm={self.tx_power_dBm:.2f}, front_end_gain_dB={self.front_end_gain_dB}"

    # ------------------------------------------------------------------ internals
    def _initial_state(
        self, paths: Paths, generator: torch.Generator | None, frame_start_s: float | torch.Tensor
    ) -> ChainState:
        delay, rate, amp, mask, chirp_delay, chirp_gain = _validated(paths, self.config.num_rx,
                                                                     self.config.num_chirps_per_frame)
        frame_start_s = _validated_start(frame_start_s, tuple(delay.shape[:-2]))
        dtype = delay.dtype
        cdtype = torch.complex64 if dtype == torch.float32 else torch.complex128
        # The IF is TX x conj(RX): a path's scattering phase enters conjugated; a real tone of
        # power P has peak amplitude sqrt(2 P).
        coef = amp.to(cdtype).conj() * (math.sqrt(2 * self.tx_power_W) * self.front_end_gain)
        if mask is not None:
            coef = coef * mask[..., None].to(coef.real.dtype)
        keep = _live_slots(coef, chirp_gain)
        if keep is not None:
            # Slots that are masked (or zero) in every frame of the batch contribute exactly
            # nothing: dropping them before synthesis saves their GEMM columns (multipath slots
            # of walls a person cannot be seen in, occluded segments).
            coef, delay, rate = (t.index_select(-2, keep) for t in (coef, delay, rate))
            chirp_delay, chirp_gain = (None if t is None else t.index_select(-2, keep)
                                       for t in (chirp_delay, chirp_gain))
        return ChainState(
            self.config,
            coef.transpose(-1, -2),
            delay.transpose(-1, -2),
            rate.transpose(-1, -2),
            chirp_delay=None if chirp_delay is None else chirp_delay.to(dtype).unsqueeze(-3),
            chirp_gain=None if chirp_gain is None else chirp_gain.to(dtype).unsqueeze(-3),
            dtype=dtype,
            generator=generator,
            frame_start_s=frame_start_s,
            tx_power_W=self.tx_power_W,
            front_end_gain=self.front_end_gain,
            method=self.synthesis,
            taylor_tol=self.taylor_tol,
            noise_tol=self.noise_tol,
        )


def _tx_power(config: RadarConfig, tx_power_dBm_value: float | None) -> float:
    if tx_power_dBm_value is None:
        return tx_power_dBm(int(config.tx_power_level))
    v = float(tx_power_dBm_value)
    if math.isnan(v) or v == math.inf:
        raise ConfigError(f"tx_power_dBm must be a finite number (or -inf for TX off), got {tx_power_dBm_value!r}")
    return v


def _broadcasts_to(shape: torch.Size, target: tuple[int, ...]) -> bool:
    """True when ``shape`` broadcasts to exactly ``target``."""
    try:
        return torch.broadcast_shapes(shape, target) == torch.Size(target)
    except RuntimeError:
        return False


def _check_static_signal(x: torch.Tensor, sample_shape: tuple[int, ...]) -> None:
    """A ``static_signal`` must be a real tensor broadcastable to ``(..., RX, chirps, samples)``."""
    if not isinstance(x, torch.Tensor) or not x.is_floating_point():
        got = x.dtype if isinstance(x, torch.Tensor) else type(x).__name__
        raise InputTensorError(f"static_signal must be a real floating-point tensor, got {got}")
    if not _broadcasts_to(x.shape, sample_shape):
        raise InputTensorError(
            f"static_signal has shape {tuple(x.shape)}, which does not broadcast to the frames' "
            f"{tuple(sample_shape)} (computed for another config?)"
        )


def _validated_start(start: float | torch.Tensor, batch_shape: tuple[int, ...]) -> float | torch.Tensor:
    """``frame_start_s`` as a finite float, or a float64 tensor broadcastable to ``batch_shape``."""
    if isinstance(start, torch.Tensor):
        if start.is_complex() or start.dtype == torch.bool:
            raise InputTensorError(f"frame_start_s must be real, got {start.dtype}")
        if not _broadcasts_to(start.shape, batch_shape):
            raise InputTensorError(
                f"frame_start_s has shape {tuple(start.shape)}; it must broadcast to the paths' batch "
                f"shape {batch_shape}"
            )
        start = start.to(torch.float64)
        if not bool(torch.isfinite(start).all()):
            raise InputTensorError("frame_start_s holds NaN or Inf")
        return start
    try:
        value = float(start)
    except (TypeError, ValueError):
        raise InputTensorError(f"frame_start_s must be a number or a tensor, got {start!r}") from None
    if not math.isfinite(value):
        raise InputTensorError(f"frame_start_s must be finite, got {start!r}")
    return value


def _live_slots(coef: torch.Tensor, chirp_gain: torch.Tensor | None) -> torch.Tensor | None:
    """Indices of the path slots ``(…, P, RX)`` non-zero in some frame of the batch; None when all are."""
    if coef.numel() == 0:
        return None
    live = coef != 0
    if chirp_gain is not None:
        live = live & (chirp_gain != 0).any(-1, keepdim=True)
    live = live.reshape(-1, *coef.shape[-2:]).any(0).any(-1)  # (P,)
    if bool(live.all()):
        return None
    return live.nonzero()[:, 0]


def _validated(paths: Paths, num_rx: int, num_chirps: int):
    """Check a Paths object; return (delay, rate, amplitude, mask, chirp_delay, chirp_gain) tensors."""
    if not isinstance(paths, Paths):
        raise InputTensorError(f"receiver input must be radaraug.sensor.Paths, got {type(paths).__name__}")
    delay, rate, amp, mask = paths.delay_s, paths.delay_rate, paths.amplitude, paths.mask
    for name, t in (("delay_s", delay), ("delay_rate", rate), ("amplitude", amp)):
        if not isinstance(t, torch.Tensor):
            raise InputTensorError(f"Paths.{name} must be a tensor, got {type(t).__name__}")
    if delay.dtype not in (torch.float32, torch.float64):
        raise InputTensorError(f"Paths.delay_s must be float32 or float64, got {delay.dtype}")
    if delay.ndim < 2:
        raise InputTensorError(f"Paths.delay_s must be (..., P, RX), got shape {tuple(delay.shape)}")
    if delay.shape[-1] != num_rx:
        raise InputTensorError(
            f"Paths have {delay.shape[-1]} RX channels (last dim) but the config has {num_rx}"
        )
    for name, t in (("delay_rate", rate), ("amplitude", amp)):
        if t.shape != delay.shape:
            raise InputTensorError(f"Paths.{name} has shape {tuple(t.shape)}, delay_s {tuple(delay.shape)}")
        if t.device != delay.device:
            raise InputTensorError(f"Paths.{name} is on {t.device}, delay_s on {delay.device}")
    if not rate.is_floating_point():
        raise InputTensorError(f"Paths.delay_rate must be floating point, got {rate.dtype}")
    if not (amp.is_floating_point() or amp.is_complex()):
        raise InputTensorError(f"Paths.amplitude must be real or complex floating point, got {amp.dtype}")
    for name, t in (("delay_s", delay), ("delay_rate", rate), ("amplitude", amp)):
        if not bool(torch.isfinite(t).all()):
            raise InputTensorError(f"Paths.{name} holds NaN or Inf")
    if bool((delay < 0).any()):
        raise InputTensorError("Paths.delay_s must be >= 0 (a round-trip delay)")
    if bool((rate.abs() >= 1).any()):
        raise InputTensorError("Paths.delay_rate must be |rate| < 1 (it is 2 v / c for a radial speed v)")
    if mask is not None:
        if not isinstance(mask, torch.Tensor) or mask.shape != delay.shape[:-1]:
            shape = tuple(mask.shape) if isinstance(mask, torch.Tensor) else type(mask).__name__
            raise InputTensorError(f"Paths.mask must be (..., P) = {tuple(delay.shape[:-1])}, got {shape}")
        mask = mask.to(device=delay.device, dtype=torch.bool)
    per_chirp = []
    for name in ("chirp_delay_s", "chirp_gain"):
        pc = getattr(paths, name, None)
        if pc is not None:
            want = (*delay.shape[:-1], num_chirps)
            if not isinstance(pc, torch.Tensor) or tuple(pc.shape) != want:
                got = tuple(pc.shape) if isinstance(pc, torch.Tensor) else type(pc).__name__
                raise InputTensorError(f"Paths.{name} must be (..., P, chirps) = {want}, got {got}")
            if not pc.is_floating_point() or pc.device != delay.device:
                raise InputTensorError(f"Paths.{name} must be a real tensor on {delay.device}, got {pc.dtype} on {pc.device}")
            if not bool(torch.isfinite(pc).all()):
                raise InputTensorError(f"Paths.{name} holds NaN or Inf")
        per_chirp.append(pc)
    return delay, rate.to(delay.dtype), amp, mask, *per_chirp
