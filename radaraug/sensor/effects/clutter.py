"""Clutter added at the antenna: static scatterers, vibrating scatterers and multipath ghosts.

Stand-ins for what a scene description lacks (an unmodelled wall, a fan, a wall bounce) when a twin is
calibrated against a capture. Levels are RX-port power relative to the TX power (no antenna or RCS
assumed); every RX sees a scatterer identically (broadside). See ``docs/receiver.md``, "The effect catalog".
"""

from __future__ import annotations

import math

import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.errors import ConfigError
from radaraug.sensor.chain_state import ChainState, ModulatedPaths
from radaraug.sensor.effects.base import (
    Effect,
    Prior,
    check_params,
    register,
    scatterer_count,
    tone_amplitude,
)


def _per_scatterer(state: ChainState, value: torch.Tensor, k: int) -> torch.Tensor:
    """A scalar or ``(K,)`` parameter as ``(K,)`` on the call's device and dtype."""
    return state.param(value).reshape(-1).expand(k)


def _range_prior(config: RadarConfig) -> Prior:
    """A scatterer's range: up to the unambiguous range."""
    return Prior(0.05, max(float(config.max_range_m), 0.1))


_LEVEL_PRIOR = Prior(-140.0, -30.0)


@register
class StaticClutter(Effect):
    """``K`` static point scatterers, as paths of delay ``2 range_m / c``, the same on every RX.

    Later stages act on them like on scene targets. Place it right after ``tx_rx_leakage``.

    Args:
        range_m: one-way range of each scatterer, m (scalar or ``(K,)``). Default 1 m.
        level_dB: RX-port power relative to the TX power, dB (scalar or ``(K,)``). Default -80 dB, about a
            1 m^2 target at 1 m with isotropic antennas.
        phase_rad: phase of each beat tone, rad (scalar or ``(K,)``).
    """

    name = "static_clutter"
    param_names = ("range_m", "level_dB", "phase_rad")
    range_m: torch.Tensor
    level_dB: torch.Tensor
    phase_rad: torch.Tensor
    PRIORS = {"range_m": _range_prior, "level_dB": _LEVEL_PRIOR, "phase_rad": Prior(-math.pi, math.pi)}

    def __init__(
        self,
        range_m: float | list | torch.Tensor = 1.0,
        level_dB: float | list | torch.Tensor = -80.0,
        phase_rad: float | list | torch.Tensor = 0.0,
    ) -> None:
        super().__init__(range_m=range_m, level_dB=level_dB, phase_rad=phase_rad)
        self.num_scatterers = scatterer_count(self, "range_m", "level_dB", "phase_rad")
        check_params(self, nonnegative=("range_m",))

    def forward(self, state: ChainState) -> None:
        """Add the ``K`` scatterers as static paths, the same on every RX."""
        k = self.num_scatterers
        amp = tone_amplitude(state, _per_scatterer(state, self.level_dB, k))
        coef = torch.polar(amp, _per_scatterer(state, self.phase_rad, k))[None, :]  # (1, K): all RX
        delay = (2 / SPEED_OF_LIGHT) * _per_scatterer(state, self.range_m, k)[None, :]
        state.add_paths(coef, delay, torch.zeros_like(delay))


@register
class VibratingClutter(Effect):
    """Scatterers whose range oscillates: ``R + displacement_m sin(2 pi vibration_Hz t + phase_rad)``.

    A fan blade, a pump or a monitor's case: Doppler lines at ``k vibration_Hz`` with amplitudes ``|J_k(beta)|``,
    ``beta = 4 pi displacement_m / lambda``, all at the scatterer's range; computed exactly on the absolute sample
    time, so frames continue the oscillation (``docs/receiver.md``). Common to all RX; place it after
    ``static_clutter``.

    Args:
        range_m: mean one-way range, m (scalar or ``(K,)`` for K scatterers). Default 1 m.
        level_dB: RX-port power relative to the TX power, dB (scalar or ``(K,)``). Default -80 dB.
        displacement_m: peak displacement, m (scalar or ``(K,)``, >= 0). Default 0.5 mm.
        vibration_Hz: vibration frequency, Hz (scalar or ``(K,)``, > 0). Default 50 Hz.
        phase_rad: vibration phase at absolute time 0, rad (scalar or ``(K,)``).
        carrier: 1 (default) for the whole return; 0 for only what the vibration adds (its time mean
            ``J_0(beta)`` left out), for a twin whose static scene already holds the object. Not searched.

    Raises:
        ConfigError: ``carrier`` not 0 or 1, a negative range or displacement, a frequency <= 0, unequal lengths.
    """

    name = "vibrating_clutter"
    param_names = ("range_m", "level_dB", "displacement_m", "vibration_Hz", "phase_rad", "carrier")
    range_m: torch.Tensor
    level_dB: torch.Tensor
    displacement_m: torch.Tensor
    vibration_Hz: torch.Tensor
    phase_rad: torch.Tensor
    carrier: torch.Tensor
    PRIORS = {
        "range_m": _range_prior,
        "level_dB": _LEVEL_PRIOR,
        "displacement_m": Prior(1e-5, 3e-2, "log"),  # up to a fan blade's or a swinging lamp's centimetres
        # Up to the Doppler Nyquist 1 / (2 PRT).
        "vibration_Hz": lambda cfg: Prior(0.5, max(0.5 / float(cfg.chirp_repetition_time_s), 1.0), "log"),
        "phase_rad": Prior(-math.pi, math.pi),
    }

    def __init__(
        self,
        range_m: float | list | torch.Tensor = 1.0,
        level_dB: float | list | torch.Tensor = -80.0,
        displacement_m: float | list | torch.Tensor = 0.5e-3,
        vibration_Hz: float | list | torch.Tensor = 50.0,
        phase_rad: float | list | torch.Tensor = 0.0,
        carrier: float = 1.0,
    ) -> None:
        if float(carrier) not in (0.0, 1.0):
            raise ConfigError(f"effect {self.name}: carrier must be 0 or 1, got {carrier!r}")
        super().__init__(range_m=range_m, level_dB=level_dB, displacement_m=displacement_m,
                         vibration_Hz=vibration_Hz, phase_rad=phase_rad, carrier=float(carrier))
        self.num_scatterers = scatterer_count(self, "range_m", "level_dB", "displacement_m", "vibration_Hz",
                                              "phase_rad")
        check_params(self, nonnegative=("range_m", "displacement_m"), positive=("vibration_Hz",))

    def modulation_rad(self, state: ChainState) -> torch.Tensor:
        """``psi = beta sin(w t + phi)`` at every sample, ``(…, K, 1, M, N)`` (``…``: per-frame starts)."""
        k = self.num_scatterers
        t = state.sample_times_s().unsqueeze(-3)  # (…, 1, 1, M, N)
        f = self.vibration_Hz.to(device=state.device, dtype=torch.float64).reshape(-1).expand(k)
        phase = state.cycle_phase(f[:, None, None, None] * t)  # (…, K, 1, M, N)
        phase = phase + _per_scatterer(state, self.phase_rad, k)[:, None, None, None]
        return self._beta(state)[:, None, None, None] * torch.sin(phase)

    def _beta(self, state: ChainState) -> torch.Tensor:
        """The modulation index ``4 pi displacement_m / lambda`` of each scatterer, ``(K,)``."""
        return (4 * math.pi / state.config.wavelength_m) * _per_scatterer(state, self.displacement_m, self.num_scatterers)

    def forward(self, state: ChainState) -> None:
        """Add the ``K`` scatterers: a static path each plus their vibration's phase modulation."""
        k = self.num_scatterers
        amp = tone_amplitude(state, _per_scatterer(state, self.level_dB, k))
        coef = amp.to(state.complex_dtype)[None, :].expand(state.num_rx, k)  # (RX, K)
        delay = ((2 / SPEED_OF_LIGHT) * _per_scatterer(state, self.range_m, k))[None, :].expand(state.num_rx, k)
        rate = torch.zeros_like(delay)
        if float(self.carrier) == 0.0:
            # Leave out the time mean J0(beta) C of C exp(j psi): the static path becomes (1 - J0) C.
            state.add_paths(coef * (1 - torch.special.bessel_j0(self._beta(state))).to(coef.dtype)[None, :], delay, rate)
        else:
            state.add_paths(coef, delay, rate)
        psi = self.modulation_rad(state)
        batch_coef = coef.expand(*state.batch_shape, state.num_rx, k)
        batch_delay = delay.to(state.delay_s.dtype).expand(*state.batch_shape, state.num_rx, k)
        batch_rate = torch.zeros_like(batch_delay)
        for i in range(k):
            c, d, r = (x[..., i: i + 1] for x in (batch_coef, batch_delay, batch_rate))
            p = psi[..., i, :, :, :]
            # exp(j psi) = 1 + (cos psi - 1) + j sin psi; cos psi - 1 = -2 sin^2(psi / 2) keeps
            # precision for small displacements.
            state.modulated.append(ModulatedPaths(c, d, r, -2 * torch.sin(p / 2) ** 2))
            state.modulated.append(ModulatedPaths(c * 1j, d, r, torch.sin(p)))


@register
class Multipath(Effect):
    """A ghost of every path present: the same return again, ``extra_range_m`` farther.

    A bounce the scene lacks (target -> wall -> radar): each path present gets copies delayed by
    ``2 extra_range_m / c``, same delay rate, coefficient times ``10**(level_dB / 20) exp(j phase_rad)``. It is
    linear, so :meth:`FMCWReceiver.static_signal` ghosts a static room too. Place it first, so the leakage and
    clutter added later get no ghost (modulated copies and additive signals are not ghosted).

    Args:
        extra_range_m: extra one-way range of the ghost, m (scalar or ``(K,)`` for K ghosts, >= 0). Default 0.5 m.
        level_dB: ghost power relative to its path, dB (scalar or ``(K,)``). Default -10 dB.
        phase_rad: extra phase of the ghost's beat tone, rad (scalar or ``(K,)``).
    """

    name = "multipath"
    kind = "linear"
    param_names = ("extra_range_m", "level_dB", "phase_rad")
    extra_range_m: torch.Tensor
    level_dB: torch.Tensor
    phase_rad: torch.Tensor
    PRIORS = {
        "extra_range_m": Prior(0.05, 5.0),
        "level_dB": Prior(-40.0, 0.0),
        "phase_rad": Prior(-math.pi, math.pi),
    }

    def __init__(
        self,
        extra_range_m: float | list | torch.Tensor = 0.5,
        level_dB: float | list | torch.Tensor = -10.0,
        phase_rad: float | list | torch.Tensor = 0.0,
    ) -> None:
        super().__init__(extra_range_m=extra_range_m, level_dB=level_dB, phase_rad=phase_rad)
        self.num_ghosts = scatterer_count(self, "extra_range_m", "level_dB", "phase_rad")
        check_params(self, nonnegative=("extra_range_m",))

    def forward(self, state: ChainState) -> None:
        """Add a ghost of every path present, ``extra_range_m`` farther and scaled by ``level_dB``."""
        if state.samples is not None:
            raise ConfigError("effect multipath acts on paths: place it before any non-linear stage (first)")
        k = self.num_ghosts
        ratio = torch.polar(torch.pow(10.0, _per_scatterer(state, self.level_dB, k) / 20),
                            _per_scatterer(state, self.phase_rad, k))
        extra = (2 / SPEED_OF_LIGHT) * _per_scatterer(state, self.extra_range_m, k)
        coef = (state.coef[..., None] * ratio.to(state.coef.dtype)).flatten(-2)  # (…, RX, P*K)
        delay = (state.delay_s[..., None] + extra.to(state.delay_s.dtype)).flatten(-2)
        rate = state.delay_rate[..., None].expand(*state.delay_rate.shape, k).flatten(-2)

        def ghosts(t: torch.Tensor | None) -> torch.Tensor | None:  # (…, 1, P, M) -> (…, 1, P*K, M)
            return None if t is None else t[..., None, :].expand(*t.shape[:-1], k, t.shape[-1]).flatten(-3, -2)

        state.add_paths(coef, delay, rate, ghosts(state.chirp_delay), ghosts(state.chirp_gain))
