"""What the diagnosis loop simulates: the capture's scene through a candidate receiver chain.

In ``"scene"`` mode the twin traces the room once and its static paths (specular and diffuse apart,
so a candidate diffuse gain needs no retrace) go through each chain's linear stages, recomputed only
when one changes; the people and their shadow are the twin's ``frame_paths``, traced once. With the
twin's own chain the frames equal ``DigitalTwin.simulate``'s (tested). In ``"estimated"`` mode (no scene) the static scene is
the capture's mean chirp, so only what varies is diagnosed. See ``docs/diagnosis.md``, "Two modes".
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.room import ROOM_PRIORS, Room
from radaraug.errors import CalibrationError
from radaraug.sensor.effects import effect_from_dict
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sensor.synthesis import ChirpTiming

# Stages that an estimated static scene already contains (leave them out in that mode).
STATIC_STAGES = ("tx_rx_leakage", "multipath", "static_clutter")


def chain_receiver(config: RadarConfig, chain: Sequence[Mapping[str, Any]], tx_power_dBm: float | None = None,
                   front_end_gain_dB: float | None = None) -> FMCWReceiver:
    """An :class:`FMCWReceiver` for ``config`` with the effect chain ``chain`` (effect dicts)."""
    given = {"tx_power_dBm": tx_power_dBm, "front_end_gain_dB": front_end_gain_dB}
    kw: dict[str, Any] = {k: v for k, v in given.items() if v is not None}
    return FMCWReceiver(config, effects=[effect_from_dict(e) for e in chain], **kw)


def _linear_key(rx: FMCWReceiver, chain: Sequence[Mapping[str, Any]]) -> str:
    """The linear stages of ``chain`` (``rx``'s modules) as a cache key: what a static signal depends on."""
    return json.dumps([e for e, m in zip(chain, rx.effects) if m.kind == "linear"], sort_keys=True)


class TwinSource:
    """Simulates frames of one capture's scene for any effect chain.

    Args:
        config: the capture's radar config.
        static_paths: the room's paths ``(P, RX)`` (scene mode): all of them, or only the specular ones
            when ``diffuse_paths`` is given.
        diffuse_paths: the room's diffuse paths ``(P_d, RX)`` (scene mode), traced with
            ``diffuse_gain_dB``; the room's diffuse gain can then be fitted (:attr:`room_params`).
        diffuse_gain_dB: the diffuse gain ``diffuse_paths`` were traced with (the start value).
        mean_chirp: the capture's mean chirp ``(rx, samples)`` in SDK floats (estimated mode; its
            mean over samples belongs to the DC stage and is left out).
        moving: people's paths per simulated frame ``(T, P, RX)`` (scene mode with people).
        tx_power_dBm, front_end_gain_dB: receiver constants (default: the library's).
    """

    def __init__(
        self,
        config: RadarConfig,
        *,
        static_paths: Paths | None = None,
        diffuse_paths: Paths | None = None,
        diffuse_gain_dB: float = 0.0,
        mean_chirp: torch.Tensor | None = None,
        moving: Paths | None = None,
        tx_power_dBm: float | None = None,
        front_end_gain_dB: float | None = None,
    ) -> None:
        if (static_paths is None) == (mean_chirp is None):
            raise ValueError("give exactly one of static_paths (scene mode) or mean_chirp (estimated mode)")
        if diffuse_paths is not None and static_paths is None:
            raise ValueError("diffuse_paths belong to a scene: give them with static_paths")
        if not math.isfinite(float(diffuse_gain_dB)):
            raise CalibrationError(f"TwinSource: diffuse_gain_dB must be finite, got {diffuse_gain_dB!r}")
        self.config = config
        self.static_paths = static_paths
        # A room without diffuse paths (diffuse scattering off, or no material scatters) has
        # nothing for the gain to act on: the parameter is then not offered to the search.
        self.diffuse_paths = diffuse_paths if diffuse_paths is not None and diffuse_paths.num_paths else None
        self.diffuse_gain_dB = float(diffuse_gain_dB)
        self.mean_chirp = None if mean_chirp is None else mean_chirp.to(torch.float64)
        self.moving = moving
        self.tx_power_dBm = tx_power_dBm
        self.front_end_gain_dB = front_end_gain_dB
        self._static_cache: dict[str, torch.Tensor] = {}  # static signal per linear chain (scene mode)
        self._tone_paths: dict[str, Paths] = {}  # tone paths per linear chain (estimated mode)

    @property
    def mode(self) -> str:
        """``"scene"`` or ``"estimated"``."""
        return "scene" if self.static_paths is not None else "estimated"

    @property
    def room_params(self) -> tuple[str, ...]:
        """Room parameters this source can vary: ``("diffuse_gain_dB",)`` with diffuse paths, else empty."""
        return ("diffuse_gain_dB",) if self.diffuse_paths is not None else ()

    def room_start(self) -> Room:
        """The room parameters as traced (the search's start)."""
        return {"diffuse_gain_dB": self.diffuse_gain_dB} if self.diffuse_paths is not None else {}

    def check_room(self, room: Mapping[str, float] | None) -> Room:
        """``room`` completed with the traced values.

        Raises:
            CalibrationError: a parameter this source cannot vary, or a value outside its prior.
        """
        out = self.room_start()
        for k, v in (room or {}).items():
            if k not in out:
                raise CalibrationError(f"room parameter {k!r} cannot be varied here (the source varies: "
                                       f"{', '.join(self.room_params) or 'nothing'})")
            if not (math.isfinite(float(v)) and ROOM_PRIORS[k].lo <= float(v) <= ROOM_PRIORS[k].hi):
                raise CalibrationError(f"room parameter {k}={v!r} is outside [{ROOM_PRIORS[k].lo}, "
                                       f"{ROOM_PRIORS[k].hi}]")
            out[k] = float(v)
        return out

    def receiver(self, chain: Sequence[Mapping[str, Any]]) -> FMCWReceiver:
        """The receiver of ``chain`` with this source's constants."""
        return chain_receiver(self.config, chain, self.tx_power_dBm, self.front_end_gain_dB)

    def _estimated_paths(self, rx: FMCWReceiver, chain: Sequence[Mapping[str, Any]]) -> Paths:
        """The estimated static scene as paths ``(K, RX)`` at the receiver's input.

        The mean chirp is a sum of tones at the DFT bins ``k fs / N`` (``0 < k <= N/2``). Each becomes a
        static path of delay ``f_k / S`` whose amplitude is the tone divided by the chain's linear response
        at ``f_k`` and by the synthesis phase ``f0 tau - S tau^2 / 2``: the chain gives the measured chirp
        back, and the phase-noise stage can act on it.
        """
        key = "estimated:" + _linear_key(rx, chain)
        if key not in self._tone_paths:
            cfg = self.config
            N, R = cfg.num_samples_per_chirp, cfg.num_rx
            timing = ChirpTiming.from_config(cfg)
            X = torch.fft.rfft(self.mean_chirp, dim=-1)  # (R, N//2 + 1)
            k = torch.arange(1, N // 2 + 1, dtype=torch.float64)
            tau = (k * timing.fs / N) / timing.slope  # (K,)
            c = 2 * X[:, 1: N // 2 + 1] / N  # (R, K) positive-frequency coefficients
            if N % 2 == 0:
                c[:, -1] = X[:, N // 2] / N  # the Nyquist bin is real and counted once
            phase0 = 2 * math.pi * (timing.f0 * tau - timing.slope * tau**2 / 2)
            need = c * torch.polar(torch.ones_like(phase0), -phase0)[None, :]
            delay = tau[:, None].expand(-1, R).contiguous()
            unit = Paths(delay, torch.zeros_like(delay), torch.ones_like(delay, dtype=torch.complex128))
            h = rx.linear_state(unit).coef  # (R, K): the chain's coefficient for a unit input amplitude
            amp = torch.conj(need / h).transpose(0, 1).contiguous()  # (K, R)
            self._tone_paths[key] = Paths(delay, torch.zeros_like(delay), amp)
        return self._tone_paths[key]

    def _synth(self, rx: FMCWReceiver, key: str, paths: Paths) -> torch.Tensor:
        if key not in self._static_cache:
            if len(self._static_cache) > 64:
                self._static_cache.clear()
            p64 = paths.map(
                lambda t: t.to(torch.complex128) if t.is_complex() else t.to(torch.float64) if t.is_floating_point() else t)
            self._static_cache[key] = rx.static_signal(p64)
        return self._static_cache[key]

    def _static(self, rx: FMCWReceiver, chain: Sequence[Mapping[str, Any]], room: Room) -> torch.Tensor | None:
        if self.static_paths is None:  # estimated mode (the constructor takes exactly one of the two)
            return None
        key = _linear_key(rx, chain)
        spec = self._synth(rx, key, self.static_paths)
        if self.diffuse_paths is None:
            return spec
        # Each part is synthesized once per linear chain; a gain is a factor on the field.
        diff = self._synth(rx, "diffuse:" + key, self.diffuse_paths)
        return spec + 10 ** ((room["diffuse_gain_dB"] - self.diffuse_gain_dB) / 20) * diff

    @torch.no_grad()
    def frames(self, chain: Sequence[Mapping[str, Any]], num_frames: int, seed: int,
               first_frame: int = 0, room: Mapping[str, float] | None = None) -> torch.Tensor:
        """``(num_frames, rx, chirps, samples)`` SDK floats (float64) of ``chain``, seeded.

        ``room``: room parameters (:attr:`room_params`; missing ones stay as traced).
        """
        rx = self.receiver(chain)
        static = self._static(rx, chain, self.check_room(room))
        R = self.config.num_rx
        if self.moving is not None:
            T = self.moving.delay_s.shape[0]
            idx = torch.arange(first_frame, first_frame + num_frames) % T
            paths = self.moving.map(lambda t: t[idx].to(torch.float64) if t.is_floating_point() else t[idx])
        else:
            z = torch.zeros(num_frames, 0, R, dtype=torch.float64)
            paths = Paths(z, z.clone(), z.to(torch.complex128))
        if self.mean_chirp is not None:
            est = self._estimated_paths(rx, chain)
            est = Paths(*(b[None].expand(num_frames, -1, -1).to(a.dtype)
                          for a, b in ((paths.delay_s, est.delay_s), (paths.delay_rate, est.delay_rate),
                                       (paths.amplitude, est.amplitude))))
            paths = Paths.cat([paths, est])  # keeps the moving paths' per-chirp motion
        g = torch.Generator().manual_seed(int(seed))
        times = (torch.arange(num_frames, dtype=torch.float64) + first_frame) * self.config.frame_repetition_time_s
        return rx(paths, generator=g, frame_start_s=times, static_signal=static)
