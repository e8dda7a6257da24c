"""Find Infineon radar boards on USB (pyusb), and say why one cannot be used.

Reading a serial number needs the right to open the board: on Linux the shipped udev rule grants it.
"""

from __future__ import annotations

import errno
from dataclasses import asdict, dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from radaraug.errors import DeviceError

INFINEON_VENDOR_ID = 0x058B
BOARDS = {
    0x0251: "MCU7 (virtual COM port)",
    0x0252: "MCU7 (libusb)",
    0x0253: "V9",
    0x0256: "PSoC6 kit",
}
"""Product id -> board name of Infineon's radar evaluation platforms."""

PERMISSION_DENIED = "permission denied"
UDEV_RULE_NAME = "99-infineon-radar.rules"

NO_BACKEND_HELP = (
    "no USB backend: pyusb needs the libusb library, which is not installed or not found "
    "(Debian/Ubuntu: sudo apt install libusb-1.0-0; Fedora: sudo dnf install libusb1; "
    "macOS: brew install libusb; Windows: install the board's driver from Infineon's Radar Development Kit)"
)


@dataclass(frozen=True)
class UsbBoard:
    """One Infineon radar board found on USB.

    Attributes:
        name: board name from :data:`BOARDS`.
        vendor_id, product_id, bus, address: the USB ids and where the board is on the USB tree.
        serial, product: the board's serial number and product strings, or None when unreadable.
        access: ``"ok"``, :data:`PERMISSION_DENIED`, or why the strings could not be read.
    """

    name: str
    vendor_id: int
    product_id: int
    bus: int | None
    address: int | None
    serial: str | None
    product: str | None
    access: str

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON types (ids as ``0x058b`` text)."""
        d = asdict(self)
        d["vendor_id"] = f"0x{self.vendor_id:04x}"
        d["product_id"] = f"0x{self.product_id:04x}"
        return d


def find_boards(backend: Any = None) -> list[UsbBoard]:
    """The Infineon radar boards on USB.

    Args:
        backend: a pyusb backend (``usb.backend.IBackend``); None lets pyusb choose.

    Returns:
        One :class:`UsbBoard` per board, in pyusb's order (empty when none); a board whose strings
        cannot be read (no permission) is listed with ``access`` saying why.

    Raises:
        DeviceError: no USB backend (libusb missing), or the USB bus cannot be enumerated.
    """
    import usb.core

    try:
        found = list(usb.core.find(find_all=True, idVendor=INFINEON_VENDOR_ID, backend=backend))
    except usb.core.NoBackendError:
        raise DeviceError(NO_BACKEND_HELP) from None
    except usb.core.USBError as e:
        raise DeviceError(f"cannot list USB devices ({_usb_reason(e)})") from None
    boards = []
    for dev in found:
        pid = int(dev.idProduct)
        if pid not in BOARDS:
            continue  # another Infineon USB product (a debugger, a different kit)
        serial, product, access = _strings(dev)
        boards.append(UsbBoard(BOARDS[pid], int(dev.idVendor), pid, dev.bus, dev.address, serial, product, access))
    return boards


def _strings(dev: Any) -> tuple[str | None, str | None, str]:
    """(serial, product, access) of a board; reading strings opens the device."""
    import usb.core
    import usb.util

    try:
        # get_langids (not the langids property, which hides errors) is the first request
        # that opens the device: it tells a permission problem from a board without strings.
        langids = usb.util.get_langids(dev)
        if not langids:
            return None, None, "ok"
        serial = usb.util.get_string(dev, dev.iSerialNumber, langids[0])
        product = usb.util.get_string(dev, dev.iProduct, langids[0])
        return serial, product, "ok"
    except usb.core.USBError as e:
        if e.errno in (errno.EACCES, errno.EPERM):
            return None, None, PERMISSION_DENIED
        return None, None, f"cannot read its strings ({_usb_reason(e)})"
    except (ValueError, NotImplementedError) as e:
        return None, None, f"cannot read its strings ({e})"
    finally:
        try:
            usb.util.dispose_resources(dev)
        except Exception:  # noqa: BLE001 - releasing a handle that was never opened may fail; nothing held
            pass


def _usb_reason(e: Exception) -> str:
    text = getattr(e, "strerror", None) or str(e)
    code = getattr(e, "errno", None)
    return f"{text} [errno {code}]" if code is not None else str(text)


def udev_rule_path() -> Path:
    """The udev rule file shipped with radaraug (lets users open the boards without root)."""
    return Path(str(resources.files("radaraug.capture").joinpath(UDEV_RULE_NAME)))


def permission_help() -> str:
    """How to let a normal user open the boards (Linux udev)."""
    return (
        "permission denied: this user may not open the board. On Linux install radaraug's udev rule and "
        "replug the board:\n"
        f"  radaraug devices --udev-rule | sudo tee /etc/udev/rules.d/{UDEV_RULE_NAME}\n"
        "  sudo udevadm control --reload-rules && sudo udevadm trigger\n"
        "(the rule gives the logged-in user and the 'plugdev' group access; see docs/capture.md)"
    )
