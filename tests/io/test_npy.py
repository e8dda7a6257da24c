"""Validated .npy headers (radaraug.io.npy): hostile headers end in a CaptureError, never numpy's
bare errors, its allow_pickle advice or a huge allocation."""

from __future__ import annotations

import struct
import time

import numpy as np
import pytest

from radaraug.errors import CaptureError
from radaraug.io.npy import open_npy


def _with_header(path, header: str, body: bytes = b"", nul: bool = False) -> None:
    pad = 64 - (10 + len(header) + 1) % 64
    text = header + (" " * (pad - 1) + "\x00" if nul else " " * pad) + "\n"
    path.write_bytes(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(text)) + text.encode("latin1") + body)


def test_round_trip(tmp_path) -> None:
    a = np.arange(24, dtype=np.uint16).reshape(2, 3, 4)
    np.save(tmp_path / "a.npy", a)
    np.testing.assert_array_equal(open_npy(tmp_path / "a.npy"), a)
    np.testing.assert_array_equal(open_npy(tmp_path / "a.npy", mmap=False), a)
    f = np.asfortranarray(a)
    np.save(tmp_path / "f.npy", f)
    np.testing.assert_array_equal(open_npy(tmp_path / "f.npy"), a)


@pytest.mark.parametrize(
    "shape, fragment",
    [
        ("(18446744073709551616, 3, 4, 32)", "needs"),
        ("(-1, 3, 4, 32)", "invalid shape"),
        ("(9223372036854775807, 3, 4, 32)", "needs"),
        ("(0, 4611686018427387904, 4611686018427387904, 128)", "longer than its header"),
        ("(True, 3, 4, 32)", "invalid shape"),
        ("(1099511627776,)", "needs"),
    ],
)
def test_hostile_shapes(tmp_path, shape, fragment) -> None:
    p = tmp_path / "radar.npy"
    _with_header(p, "{'descr': '<u2', 'fortran_order': False, 'shape': " + shape + ", }", bytes(144))
    t = time.monotonic()
    with pytest.raises(CaptureError, match=fragment) as err:
        open_npy(p)
    assert time.monotonic() - t < 1 and str(p) in str(err.value)


@pytest.mark.parametrize(
    "header, nul",
    [
        ("{'descr': '<u2', 'fortran_order': False, 'shape': (3,), }", True),
        ("{'descr': '|O', 'fortran_order': False, 'shape': (3,), }", False),
        ("{'descr': [('a', '<u2')], 'fortran_order': False, 'shape': (3,), }", False),
        ("{'descr': 'abc', 'fortran_order': False, 'shape': (3,), }", False),
        ("not a dict", False),
    ],
)
def test_hostile_headers_never_leak_numpy_advice(tmp_path, header, nul) -> None:
    p = tmp_path / "radar.npy"
    _with_header(p, header, bytes(6), nul=nul)
    with pytest.raises(CaptureError) as err:
        open_npy(p)
    assert "allow_pickle" not in str(err.value) and str(p) in str(err.value)


def test_huge_header_length_is_refused_without_numpy_advice(tmp_path) -> None:
    p = tmp_path / "radar.npy"
    p.write_bytes(b"\x93NUMPY\x01\x00" + struct.pack("<H", 65535) + b" " * 65535)
    with pytest.raises(CaptureError) as err:
        open_npy(p)
    assert "allow_pickle" not in str(err.value)
