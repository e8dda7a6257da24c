"""`RadarDevice`: what every live radar source offers, a real board or the virtual sensor."""

from __future__ import annotations

import abc
import dataclasses
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.errors import DeviceError


@dataclasses.dataclass(frozen=True)
class Frame:
    """One frame from a :class:`RadarDevice`.

    Attributes:
        data: ``(rx, chirps, samples)`` float32 tensor in SDK floats (``2*counts/4095 - 1``).
        timestamp: start of the frame in seconds since acquisition started.
        index: the frame's number in the device's sequence (0, 1, 2, ...; a gap is a dropped frame).
    """

    data: torch.Tensor
    timestamp: float
    index: int


class RadarDevice(abc.ABC):
    """A live source of radar frames (a board on USB, or :class:`~radaraug.capture.VirtualSensor`).

    Subclasses implement ``_open``, ``_read`` and ``_close``; ``start``/``stop`` are idempotent.
    """

    def __init__(self) -> None:
        self._running = False

    @property
    @abc.abstractmethod
    def config(self) -> RadarConfig:
        """The radar configuration of every frame."""

    @property
    @abc.abstractmethod
    def info(self) -> dict[str, Any]:
        """What the device is: at least ``kind`` (``"virtual"`` or ``"sdk"``) and ``name``."""

    @property
    def running(self) -> bool:
        """Whether acquisition is on (between :meth:`start` and :meth:`stop`)."""
        return self._running

    def start(self) -> None:
        """Open the device and start acquisition (no-op when started).

        Raises:
            DeviceError: the device cannot be opened or configured.
        """
        if not self._running:
            self._open()
            self._running = True

    def next_frame(self) -> Frame:
        """Block until the next frame is ready and return it.

        Raises:
            DeviceError: the device is not started, or reading failed (e.g. a board unplugged).
        """
        if not self._running:
            raise DeviceError(f"{self.info.get('name', type(self).__name__)}: not started; call start() first")
        return self._read()

    def stop(self) -> None:
        """Stop acquisition and release the device (idempotent; never raises for a lost board)."""
        if self._running:
            self._running = False
            self._close()

    def __enter__(self) -> RadarDevice:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    @abc.abstractmethod
    def _open(self) -> None: ...

    @abc.abstractmethod
    def _read(self) -> Frame: ...

    @abc.abstractmethod
    def _close(self) -> None: ...
