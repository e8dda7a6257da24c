"""Live capture: find boards on USB, record crash-safely, calibrate in one step, a virtual sensor.

Boards (:class:`SdkDevice`) and the twin (:class:`VirtualSensor`) are each a :class:`RadarDevice` (``docs/capture.md``).
"""

from __future__ import annotations

from typing import Any

from radaraug.capture.base import Frame, RadarDevice
from radaraug.capture.calibrate import CalibrationRun, calibrate
from radaraug.capture.devices import BOARDS, INFINEON_VENDOR_ID, UsbBoard, find_boards, udev_rule_path
from radaraug.capture.record import RecordResult, record
from radaraug.capture.sdk import SdkDevice
from radaraug.capture.virtual import VirtualSensor
from radaraug.config import RadarConfig
from radaraug.errors import ConfigError


def open_device(
    spec: str,
    config: RadarConfig | None = None,
    *,
    scene: Any = None,
    profile: Any = None,
    seed: int | None = None,
    realtime: bool | None = None,
) -> RadarDevice:
    """A device from a ``--board`` value (nothing is opened until ``start()``).

    Args:
        spec: ``"virtual"``, ``"auto"`` (the first board the SDK finds) or a board's serial/UUID.
        config: radar config (default: the scene's, or ``RadarConfig.bgt60tr13c()`` for a board).
        scene: the virtual sensor's scene (default ``"corridor"``).
        profile: the virtual sensor's fitted twin profile (default: none).
        seed: the virtual sensor's noise seed (default 0).
        realtime: the virtual sensor's pacing at the frame rate (default True).

    Raises:
        ConfigError: a virtual-sensor argument given for a board (it would be ignored).
        DeviceError: a MIMO config for a board. SceneError: an unknown scene (virtual).
    """
    if spec == "virtual":
        return VirtualSensor("corridor" if scene is None else scene, config=config, profile=profile,
                             seed=0 if seed is None else seed, realtime=True if realtime is None else realtime)
    given = [name for name, value in (("scene", scene), ("profile", profile), ("seed", seed), ("realtime", realtime))
             if value is not None]
    if given:
        raise ConfigError(f"{', '.join(given)}: only for the virtual sensor (--board virtual), not for a board "
                          f"({spec!r})")
    return SdkDevice(config or RadarConfig.bgt60tr13c(), serial=None if spec == "auto" else spec)


__all__ = [
    "BOARDS",
    "CalibrationRun",
    "INFINEON_VENDOR_ID",
    "Frame",
    "RadarDevice",
    "RecordResult",
    "SdkDevice",
    "UsbBoard",
    "VirtualSensor",
    "calibrate",
    "find_boards",
    "open_device",
    "record",
    "udev_rule_path",
]
