"""IF filters: ``order`` cascaded first-order sections (the BGT60's order is not public; 1 by default)."""

from __future__ import annotations

from typing import Any, ClassVar

import torch

from radaraug.errors import ConfigError
from radaraug.sensor.chain_state import ChainState
from radaraug.sensor.effects.base import Effect, Prior, register


def highpass_response(freq_Hz: torch.Tensor, cutoff_Hz: torch.Tensor, order: int = 1) -> torch.Tensor:
    """``((j f/fc) / (1 + j f/fc)) ** order``: complex, Hermitian in ``f``."""
    x = torch.complex(torch.zeros_like(freq_Hz), freq_Hz / cutoff_Hz)
    return (x / (1 + x)) ** order


def section_cutoff(cutoff_3db_Hz: float, order: int) -> float:
    """Cutoff of each of ``order`` cascaded first-order sections whose cascade is -3 dB at ``cutoff_3db_Hz``.

    The cascade's -3 dB point is ``1 / sqrt(2^(1/n) - 1)`` times its sections' (1.55x for two).
    """
    return float(cutoff_3db_Hz) * (2 ** (1 / int(order)) - 1) ** 0.5


def lowpass_response(freq_Hz: torch.Tensor, cutoff_Hz: torch.Tensor, order: int = 1) -> torch.Tensor:
    """``(1 / (1 + j f/fc)) ** order``: complex, Hermitian in ``f``."""
    x = torch.complex(torch.zeros_like(freq_Hz), freq_Hz / cutoff_Hz)
    return (1 / (1 + x)) ** order


class _FirstOrderFilter(Effect):
    kind = "linear"
    param_names: ClassVar[tuple[str, ...]] = ("cutoff_Hz", "order")
    cutoff_Hz: torch.Tensor | None
    order: torch.Tensor

    def __init__(self, cutoff_Hz: float | torch.Tensor | None = None, order: int = 1) -> None:
        if int(order) != order or order < 1:
            raise ConfigError(f"effect {self.name}: order must be a positive integer, got {order!r}")
        super().__init__(cutoff_Hz=cutoff_Hz, order=int(order))
        if self.cutoff_Hz is not None and not bool((self.cutoff_Hz > 0).all()):
            raise ConfigError(f"effect {self.name}: cutoff_Hz must be positive, got {cutoff_Hz!r}")

    # Set by each filter: its sections' response and the config attribute of its default cutoff.
    _response: ClassVar[staticmethod[[torch.Tensor, torch.Tensor, int], torch.Tensor]]
    _config_cutoff: ClassVar[str]

    def _cutoff(self, state: ChainState) -> torch.Tensor:
        if self.cutoff_Hz is None:
            cutoff = getattr(state.config, self._config_cutoff)
            return torch.tensor(cutoff, dtype=torch.float64, device=state.device)
        return self.cutoff_Hz.to(device=state.device, dtype=torch.float64)

    def response(self, freq_Hz: torch.Tensor, state: ChainState) -> torch.Tensor:
        """Complex response at ``freq_Hz``."""
        return self._response(freq_Hz, self._cutoff(state), int(self.order))

    def forward(self, state: ChainState) -> None:
        """Apply the filter's frequency response to what is present."""
        state.apply_linear(response=lambda f: self.response(f, state))


@register
class IFHighPass(_FirstOrderFilter):
    """IF high-pass (BGT60: 20/45/70/80 kHz options).

    Args:
        cutoff_Hz: -3 dB frequency of each section; ``None`` takes ``config.effective_hp_cutoff_Hz``.
        order: number of cascaded first-order sections.
        startup: 1: the sections start each chirp at rest at the ramp start, so a path's beat tone
            adds its start-up transient to the first samples (a strong near-DC path's can clip;
            ``ChainState.startup_transient``, docs/receiver.md); 0 (default): steady state only.

    Raises:
        ConfigError: a bad cutoff or order, or ``startup`` not 0 or 1.
    """

    name = "if_highpass"
    param_names = ("cutoff_Hz", "order", "startup")
    startup: torch.Tensor

    def __init__(self, cutoff_Hz: float | torch.Tensor | None = None, order: int = 1, startup: int | bool = 0) -> None:
        if startup not in (0, 1):
            raise ConfigError(f"effect {self.name}: startup must be 0 or 1, got {startup!r}")
        super().__init__(cutoff_Hz=cutoff_Hz, order=order)
        self._set(startup=int(startup))

    def forward(self, state: ChainState) -> None:
        """Apply the response; with ``startup``, add the sections' start-up transient of the paths present."""
        if not bool(self.startup):
            super().forward(state)
            return
        if state.samples is not None:
            raise ConfigError("effect if_highpass: the start-up transient needs the high-pass before any "
                              "non-linear stage (the paths are already synthesized)")
        state.add_startup_transient(self._cutoff(state), int(self.order))
        super().forward(state)

    def to_dict(self) -> dict[str, Any]:
        """As :meth:`Effect.to_dict`, without ``startup`` when 0 (descriptions written before it stay the same)."""
        out = super().to_dict()
        if not bool(self.startup):
            del out["params"]["startup"]
        return out

    PRIORS = {"cutoff_Hz": Prior(5e3, 300e3, "log")}
    _response = staticmethod(highpass_response)
    _config_cutoff = "effective_hp_cutoff_Hz"


@register
class AntiAliasLowPass(_FirstOrderFilter):
    """Anti-alias low-pass before the ADC (BGT60: 500 kHz).

    Args:
        cutoff_Hz: -3 dB frequency of each section; ``None`` takes ``config.effective_aaf_cutoff_Hz``.
        order: number of cascaded first-order sections.
    """

    name = "anti_alias_lowpass"

    # From 50 kHz up to the sample rate (a cutoff above it no longer matters).
    PRIORS = {"cutoff_Hz": lambda config: Prior(50e3, max(float(config.sample_rate_Hz), 100e3), "log")}
    _response = staticmethod(lowpass_response)
    _config_cutoff = "effective_aaf_cutoff_Hz"

    def forward(self, state: ChainState) -> None:
        """Apply the response; the high-pass start-up transients pass the sections exactly."""
        state.lowpass_transients(float(self._cutoff(state)), int(self.order))
        super().forward(state)
