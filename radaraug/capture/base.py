"""`RadarDevice`: what every live radar source offers, a real board or the virtual sensor.

A device is created cheaply (nothing is opened), then :meth:`RadarDevice.start` opens the board
(or builds the twin) and starts acquisition, :meth:`RadarDevice.next_frame` blocks until the
next frame is ready, and :meth:`RadarDevice.stop` ends acquisition and releases the board. Used
as a context manager, ``with device:`` starts and stops it.

Frames come as :class:`Frame`: the raw cube ``(rx, chirps, samples)`` in Infineon SDK floats
(``2*counts/4095 - 1``, the unit of every raw cube in radaraug), the frame's start time in
seconds since acquisition started, and the frame's index in the device's frame sequence. A gap
in the indices is a frame the device dropped (a host that did not read in time).
"""

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
        data: ``(rx, chirps, samples)`` float32 tensor in SDK floats.
        timestamp: start of the frame in seconds since acquisition started.
        index: the frame's number in the device's sequence (0, 1, 2, ...; a gap is a dropped frame).
    """

    data: torch.Tensor
    timestamp: float
    index: int


class RadarDevice(abc.ABC):
    """A live source of radar frames (a board on USB, or :class:`~radaraug.capture.VirtualSensor`).

    Subclasses implement :meth:`_open`, :meth:`_read` and :meth:`_close`; this class keeps the
    started/stopped state so that ``start``/``stop`` are idempotent and ``next_frame`` on a
    stopped device is a clear error.
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
        """Open the device and start acquisition (no-op when already started).

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
