"""USB discovery through pyusb's public API, with fake pyusb backends (``usb.backend.IBackend``)."""

from __future__ import annotations

import array
import errno
import json
from types import SimpleNamespace

import pytest
import usb.backend
import usb.backend.libusb0
import usb.backend.libusb1
import usb.backend.openusb
import usb.core

from radaraug.capture import BOARDS, find_boards, udev_rule_path
from radaraug.capture.devices import PERMISSION_DENIED
from radaraug.cli import main
from radaraug.errors import DeviceError


def _descriptor(pid: int, address: int, vid: int = 0x058B) -> SimpleNamespace:
    return SimpleNamespace(bLength=18, bDescriptorType=1, bcdUSB=0x0200, bDeviceClass=0, bDeviceSubClass=0,
                           bDeviceProtocol=0, bMaxPacketSize0=64, idVendor=vid, idProduct=pid, bcdDevice=0x0100,
                           iManufacturer=1, iProduct=2, iSerialNumber=3, bNumConfigurations=1, address=address,
                           bus=1, port_number=address, port_numbers=(address,), speed=3)


class FakeBackend(usb.backend.IBackend):
    """A USB bus with the given devices; ``denied`` ones refuse to open (EACCES), the others answer
    string descriptor requests (LANGID table, manufacturer, product, serial)."""

    def __init__(self, devices=(), denied=False, strings=None):
        self.devices = list(devices)
        self.denied = denied
        self.strings = strings or {1: "Infineon Technologies", 2: "IFX CDC", 3: "0123ABCD"}

    def enumerate_devices(self):
        yield from self.devices

    def get_device_descriptor(self, dev):
        return dev

    def open_device(self, dev):
        if self.denied:
            raise usb.core.USBError("Access denied (insufficient permissions)", error_code=-3, errno=errno.EACCES)
        return SimpleNamespace(dev=dev)

    def close_device(self, dev_handle):
        pass

    def ctrl_transfer(self, dev_handle, bmRequestType, bRequest, wValue, wIndex, data, timeout):
        desc_type, index = wValue >> 8, wValue & 0xFF
        assert desc_type == 3  # string descriptors only
        payload = b"\x09\x04" if index == 0 else self.strings[index].encode("utf-16-le")
        raw = bytes([2 + len(payload), 3]) + payload
        n = min(len(raw), len(data))
        data[:n] = array.array("B", raw[:n])
        return n


@pytest.fixture
def use_backend(monkeypatch):
    """Make pyusb's own backend choice (usb.core.find without backend=) return the fake one."""

    def install(backend):
        monkeypatch.setattr(usb.backend.libusb1, "get_backend", lambda *a, **k: backend)
        monkeypatch.setattr(usb.backend.openusb, "get_backend", lambda *a, **k: backend)
        monkeypatch.setattr(usb.backend.libusb0, "get_backend", lambda *a, **k: backend)

    return install


def test_no_board(use_backend, capsys) -> None:
    backend = FakeBackend([_descriptor(0x1234, 5, vid=0x046D)])  # a mouse, not Infineon
    assert find_boards(backend) == []
    use_backend(backend)
    assert main(["devices"]) == 0
    assert "no Infineon radar board found" in capsys.readouterr().out
    assert main(["devices", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == {"boards": [], "permission_denied": False}


def test_readable_boards_are_named_with_their_serial(use_backend, capsys) -> None:
    devices = [_descriptor(pid, i + 2) for i, pid in enumerate(BOARDS)] + [_descriptor(0x0001, 9)]
    boards = find_boards(FakeBackend(devices))
    assert [b.name for b in boards] == ["MCU7 (virtual COM port)", "MCU7 (libusb)", "V9", "PSoC6 kit"]
    assert {b.serial for b in boards} == {"0123ABCD"} and {b.access for b in boards} == {"ok"}
    assert boards[2].to_dict()["product_id"] == "0x0253" and boards[2].product == "IFX CDC"
    use_backend(FakeBackend(devices[:1]))
    assert main(["devices"]) == 0
    out = capsys.readouterr()
    assert "MCU7 (virtual COM port)" in out.out and "0123ABCD" in out.out and "058b:0251" in out.out
    assert out.err == ""


def test_permission_denied_is_said_with_the_fix(use_backend, capsys) -> None:
    backend = FakeBackend([_descriptor(0x0252, 4)], denied=True)
    (board,) = find_boards(backend)
    assert board.access == PERMISSION_DENIED and board.serial is None and board.name == "MCU7 (libusb)"
    use_backend(backend)
    assert main(["devices"]) == 0
    out = capsys.readouterr()
    assert "permission denied" in out.out
    assert "udev" in out.err and "99-infineon-radar.rules" in out.err and "radaraug devices --udev-rule" in out.err
    assert main(["devices", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["permission_denied"] is True


def test_missing_libusb_is_a_clear_error(use_backend, capsys) -> None:
    use_backend(None)  # what pyusb's backends return when the library is not found
    with pytest.raises(DeviceError, match="libusb"):
        find_boards()
    assert main(["devices"]) == 3
    err = capsys.readouterr().err
    assert err.startswith("error: no USB backend") and err.count("\n") == 1


def test_the_udev_rule_is_shipped_and_covers_every_board(capsys) -> None:
    text = udev_rule_path().read_text(encoding="utf-8")
    assert main(["devices", "--udev-rule"]) == 0
    assert capsys.readouterr().out == text
    for pid in BOARDS:
        assert f'ATTR{{idVendor}}=="058b", ATTR{{idProduct}}=="{pid:04x}"' in text
