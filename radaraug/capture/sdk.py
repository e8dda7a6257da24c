"""`SdkDevice`: a real Infineon board, streamed through Infineon's optional Python SDK ``ifxradarsdk``.

Untested on hardware in CI (tested against a stand-in module). Frame timing: ``docs/capture.md``.
"""

from __future__ import annotations

import importlib
import time
from typing import Any

import numpy as np
import torch

from radaraug.capture.base import Frame, RadarDevice
from radaraug.config import RadarConfig
from radaraug.errors import DeviceError

SDK_MODULE = "ifxradarsdk"
SDK_MISSING = (
    "reading a real board needs Infineon's Radar SDK Python package 'ifxradarsdk', which is not installed: "
    "download the Radar Development Kit from Infineon (https://www.infineon.com, 'Radar Development Kit') and "
    "pip install its ifxradarsdk wheel; or use --board virtual"
)
_RECOVERABLE = ("FifoOverflow", "FrameAcquisitionFailed")
"""SDK exception class names that mean frames were lost but the stream goes on."""


def _import_sdk() -> tuple[Any, Any]:
    """``(DeviceFmcw, types module)`` of the installed SDK."""
    try:
        from ifxradarsdk.fmcw import DeviceFmcw
        from ifxradarsdk.fmcw import types as fmcw_types
    except ImportError as e:
        try:
            importlib.import_module(SDK_MODULE)
        except ImportError:
            raise DeviceError(SDK_MISSING) from None
        missing = getattr(e, "name", None) or ""
        if missing.startswith(SDK_MODULE + "."):
            raise DeviceError(f"the installed {SDK_MODULE} has no '{missing}' (radaraug needs the SDK's FMCW API, "
                              f"Radar SDK 3.x): {e}") from None
        raise DeviceError(f"the installed {SDK_MODULE} cannot be imported ({e})") from None
    return DeviceFmcw, fmcw_types


def _mask(antennas: tuple[int, ...]) -> int:
    """Infineon antenna bit mask of 1-based antenna numbers."""
    return sum(1 << (a - 1) for a in antennas)


class SdkDevice(RadarDevice):
    """An Infineon FMCW board (BGT60TR13C and relatives) through ``ifxradarsdk``.

    Args:
        config: the radar config to apply (one FMCW shape, one TX: ``mimo_mode="off"``).
        serial: the board's serial/UUID; None opens the first board the SDK finds.
        timeout_ms: longest wait for one frame before the board counts as lost (default: two
            frame periods plus one second).

    Raises:
        DeviceError: a MIMO config (not supported).
    """

    def __init__(self, config: RadarConfig, *, serial: str | None = None, timeout_ms: int | None = None) -> None:
        super().__init__()
        if config.mimo_mode != "off" or len(config.tx_antennas) != 1:
            raise DeviceError(f"SDK device: only one TX antenna without MIMO is supported, got "
                              f"tx_antennas={list(config.tx_antennas)}, mimo_mode={config.mimo_mode!r}")
        self._config = config
        self.serial = serial
        self.timeout_ms = timeout_ms or int(2000 * config.frame_repetition_time_s + 1000)
        self._dev: Any = None
        self._sensor: dict[str, Any] = {}
        self._t0: float | None = None
        self._last = -1
        self.dropped_by_sdk = 0
        """Frames the SDK reported lost (FIFO overflow) since :meth:`start`."""

    @property
    def config(self) -> RadarConfig:
        """The radar configuration the board was set to (a frame's shape and timing)."""
        return self._config

    @property
    def info(self) -> dict[str, Any]:
        """``kind`` ``"sdk"``, ``name``, the board's ``serial`` and the SDK's ``sensor`` description."""
        name = "Infineon board" + (f" {self.serial}" if self.serial else "")
        return {"kind": "sdk", "name": name, "serial": self.serial, "sensor": dict(self._sensor)}

    def _where(self) -> str:
        return f"board {self.serial}" if self.serial else "the first Infineon board"

    def _open(self) -> None:
        DeviceFmcw, types = _import_sdk()
        try:
            self._dev = DeviceFmcw(uuid=self.serial) if self.serial else DeviceFmcw()
        except Exception as e:  # noqa: BLE001 - the SDK's exception types are its own; report any
            raise DeviceError(f"cannot open {self._where()} with {SDK_MODULE} ({e}); is it plugged in "
                              "(radaraug devices)?") from None
        try:
            sensor = self._dev.get_sensor_information()
            self._sensor = {str(k): _plain(v) for k, v in dict(sensor).items()} if sensor else {}
            c = self._config
            chirp = types.FmcwSequenceChirp(
                start_frequency_Hz=c.start_frequency_Hz,
                end_frequency_Hz=c.end_frequency_Hz,
                sample_rate_Hz=c.sample_rate_Hz,
                num_samples=c.num_samples_per_chirp,
                rx_mask=_mask(c.rx_antennas),
                tx_mask=_mask(c.tx_antennas),
                tx_power_level=c.tx_power_level,
                lp_cutoff_Hz=int(c.effective_aaf_cutoff_Hz),
                hp_cutoff_Hz=int(c.effective_hp_cutoff_Hz),
                if_gain_dB=int(c.if_gain_dB),
            )
            seq_config = types.FmcwSimpleSequenceConfig(
                frame_repetition_time_s=c.frame_repetition_time_s,
                chirp_repetition_time_s=c.chirp_repetition_time_s,
                num_chirps=c.num_chirps_per_frame,
                tdm_mimo=False,
                chirp=chirp,
            )
            sequence = self._dev.create_simple_sequence(seq_config)
            self._dev.set_acquisition_sequence(sequence)
        except Exception as e:  # noqa: BLE001 - as above
            self._close()
            raise DeviceError(f"{self._where()}: the SDK refused the radar config ({e})") from None
        self._t0 = None
        self._last = -1
        self.dropped_by_sdk = 0

    def _read(self) -> Frame:
        period = self._config.frame_repetition_time_s
        while True:
            try:
                frames = self._dev.get_next_frame(timeout_ms=self.timeout_ms)
                break
            except Exception as e:  # noqa: BLE001 - as above
                if any(name in type(e).__name__ for name in _RECOVERABLE):
                    self.dropped_by_sdk += 1
                    self._last += 1  # at least one frame is gone
                    continue
                raise DeviceError(f"{self._where()}: reading a frame failed after {self._last + 1} frames "
                                  f"({type(e).__name__}: {e}); unplugged?") from None
        now = time.monotonic()
        data = np.asarray(frames[0] if isinstance(frames, (list, tuple)) else frames, dtype=np.float32)
        c = self._config
        want = c.frame_shape
        if data.shape != want:
            raise DeviceError(f"{self._where()}: the SDK returned a frame of shape {data.shape}, the config "
                              f"asks for {want} (rx, chirps, samples)")
        if self._t0 is None:
            self._t0 = now
        t = now - self._t0
        index = max(self._last + 1, round(t / period))
        self._last = index
        return Frame(torch.from_numpy(data.copy()), index * period, index)

    def _close(self) -> None:
        dev, self._dev = self._dev, None
        if dev is None:
            return
        for step in ("stop_acquisition", "__exit__"):
            fn = getattr(dev, step, None)
            if fn is None:
                continue
            try:
                fn(None, None, None) if step == "__exit__" else fn()
            except Exception:  # noqa: BLE001 - a board already unplugged cannot be stopped; nothing to do
                pass


def _plain(v: Any) -> Any:
    if isinstance(v, (str, int, float, bool)) or v is None:
        return v
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return str(v)
