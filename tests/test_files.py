"""The bounded, non-blocking file reads and the one safe JSON loader (radaraug.files)."""

from __future__ import annotations

import os
import time

import pytest

from radaraug.errors import CalibrationError, ConfigError
from radaraug.files import MAX_JSON_DEPTH, load_json, parse_json, read_bytes, safe_repr


def test_reads_a_regular_file_and_parses_json(tmp_path) -> None:
    p = tmp_path / "a.json"
    p.write_text('{"a": [1, 2.5, "x", null], "b": 63500000000}')
    assert load_json(p, error=ConfigError) == {"a": [1, 2.5, "x", None], "b": 63500000000}


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
        ("[" * (MAX_JSON_DEPTH + 1) + "]" * (MAX_JSON_DEPTH + 1), "nested too deeply"),
        ("9" * 5000, "5000 digits"),
        ('{"mean_db": ' + "1" * 401 + "}", "401 digits"),
        ("{not json", "not valid JSON"),
        ("", "not valid JSON"),
    ],
)
def test_hostile_json_is_one_error_naming_the_source(tmp_path, text, fragment) -> None:
    p = tmp_path / "hostile.json"
    p.write_text(text)
    with pytest.raises(CalibrationError, match=fragment) as err:
        load_json(p, error=CalibrationError)
    assert str(p) in str(err.value)


def test_depth_limit_is_exact() -> None:
    ok = "[" * MAX_JSON_DEPTH + "]" * MAX_JSON_DEPTH
    parse_json(ok, source="x", error=ConfigError)


def test_not_utf8_and_too_large(tmp_path) -> None:
    p = tmp_path / "bin.json"
    p.write_bytes(b'{"a": "\xff"}')
    with pytest.raises(ConfigError, match="not UTF-8"):
        load_json(p, error=ConfigError)
    big = tmp_path / "big.json"
    big.write_bytes(b" " * 2000)
    with pytest.raises(ConfigError, match="more than the 1000-byte limit"):
        read_bytes(big, limit=1000, error=ConfigError)


@pytest.mark.parametrize("kind", ["fifo", "devzero", "folder", "missing"])
def test_special_files_are_refused_without_blocking(tmp_path, kind) -> None:
    p = tmp_path / "config.json"
    if kind == "fifo":
        os.mkfifo(p)  # open() for reading would block until a writer appears
    elif kind == "devzero":
        os.symlink("/dev/zero", p)  # would be read without end
    elif kind == "folder":
        p.mkdir()
    t = time.monotonic()
    with pytest.raises(ConfigError, match="not a regular file|does not exist") as err:
        load_json(p, error=ConfigError)
    assert time.monotonic() - t < 2
    assert str(p) in str(err.value)


def test_safe_repr_of_a_huge_integer() -> None:
    assert "digits" in safe_repr(10**5000)
    assert safe_repr("x" * 1000).endswith("...")
