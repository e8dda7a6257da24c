"""Infineon recording folders: writer/reader round trip, bad folders, and the real recordings."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import torch
from radaraug_tests_io_data import pattern_counts

from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError, InputTensorError
from radaraug.io import CaptureWarning, InfineonRecording, open_capture, write_infineon_recording


def _expect_error(path, fragment):
    with pytest.raises(CaptureError, match=fragment) as err:
        open_capture(path)
    return err.value


def test_writer_produces_the_infineon_layout(infineon_recording, tiny_config):
    dev = infineon_recording / "RadarIfxAvian_00"
    assert sorted(p.name for p in dev.iterdir()) == [
        "config.json",
        "format.version",
        "meta.json",
        "radar.npy",
        "radar_timestamp.csv",
    ]
    assert (infineon_recording / "meta.json").is_file()
    assert (dev / "format.version").read_text() == "1.0.0\n"
    config_dict = json.loads((dev / "config.json").read_text())
    assert config_dict == tiny_config.to_infineon()
    radar = np.load(dev / "radar.npy")
    assert radar.dtype == np.uint16 and radar.shape == (5, 3, 4, 32)
    assert len((dev / "radar_timestamp.csv").read_text().splitlines()) == 5


@pytest.mark.parametrize("where", ["recording", "device", "radar.npy", "config.json"])
def test_round_trip_from_any_entry_point(infineon_recording, tiny_config, where):
    dev = infineon_recording / "RadarIfxAvian_00"
    path = {
        "recording": infineon_recording,
        "device": dev,
        "radar.npy": dev / "radar.npy",
        "config.json": dev / "config.json",
    }[where]
    with open_capture(path) as cap:
        assert isinstance(cap, InfineonRecording)
        assert cap.config == tiny_config
        assert cap.shape == (5, 3, 4, 32)
        np.testing.assert_array_equal(cap.read(as_float=False).numpy(), pattern_counts(tiny_config, 5))
        np.testing.assert_array_equal(cap.timestamps, 1.7e9 + 0.01 * np.arange(5))
        assert cap.labels == {}
        assert cap.attrs["format"] == "infineon-ifxdaq" and cap.attrs["format_version"] == "1.0.0"
        assert cap.attrs["device_meta"]["adc_resolution"] == 12
        floats = cap.read(1, 3)
    torch.testing.assert_close(
        floats.double(), 2 * torch.from_numpy(pattern_counts(tiny_config, 2, 1)).double() / 4095 - 1
    )


def test_radar_npy_is_memory_mapped(infineon_recording):
    with open_capture(infineon_recording) as cap:
        assert isinstance(cap._data, np.memmap)


def test_writer_refuses_to_overwrite_and_warns_about_unstorable_fields(
    tmp_path, tiny_config, infineon_recording
):
    with pytest.raises(CaptureError, match="overwrite=True"):
        write_infineon_recording(infineon_recording, pattern_counts(tiny_config, 2), tiny_config)
    write_infineon_recording(infineon_recording, pattern_counts(tiny_config, 2), tiny_config, overwrite=True)
    with open_capture(infineon_recording) as cap:
        assert cap.num_frames == 2 and cap.timestamps is None  # stale timestamps removed
    odd = tiny_config.replace(adc_delay_s=0.0)
    with pytest.warns(CaptureWarning, match="adc_delay_s"):
        write_infineon_recording(tmp_path / "odd", pattern_counts(odd, 2), odd)
    with pytest.raises(CaptureError, match="timestamps"):
        write_infineon_recording(
            tmp_path / "ts", pattern_counts(tiny_config, 2), tiny_config, timestamps=[1.0]
        )
    with pytest.raises(InputTensorError, match="shape"):
        write_infineon_recording(tmp_path / "bad", np.zeros((2, 1, 4, 32), np.uint16), tiny_config)


def test_missing_recording_and_unknown_folder(tmp_path):
    _expect_error(tmp_path / "nope", "does not exist")
    (tmp_path / "empty").mkdir()
    _expect_error(tmp_path / "empty", "not an Infineon recording")


def test_folder_without_config_json(infineon_recording):
    (infineon_recording / "RadarIfxAvian_00" / "config.json").unlink()
    err = _expect_error(infineon_recording, "has no config.json")
    assert "RadarIfxAvian_00" in str(err)


def test_invalid_config_json(infineon_recording):
    path = infineon_recording / "RadarIfxAvian_00" / "config.json"
    path.write_text("{broken")
    _expect_error(infineon_recording, r"config.json: config.json is not valid JSON")
    path.write_text(json.dumps({"device_config": {"fmcw_single_shape": {"rx_antennas": [1]}}}))
    err = _expect_error(infineon_recording, "invalid radar configuration.*lacks required keys")
    assert isinstance(err.__cause__, ConfigError)


def test_missing_radar_npy(infineon_recording):
    (infineon_recording / "RadarIfxAvian_00" / "radar.npy").unlink()
    _expect_error(infineon_recording, "has no radar.npy")


def test_truncated_radar_npy(infineon_recording):
    npy = infineon_recording / "RadarIfxAvian_00" / "radar.npy"
    data = npy.read_bytes()
    npy.write_bytes(data[: len(data) // 2])
    err = _expect_error(infineon_recording, "truncated .npy")
    assert str(npy) in str(err)


def test_radar_npy_that_is_not_npy(infineon_recording):
    npy = infineon_recording / "RadarIfxAvian_00" / "radar.npy"
    npy.write_bytes(b"garbage" * 50)
    _expect_error(infineon_recording, "not a readable .npy")


@pytest.mark.parametrize(
    "shape, fragment",
    [
        ((5, 1, 4, 32), "1 rx"),
        ((5, 3, 8, 32), "8 chirps"),
        ((5, 3, 4, 64), "64 samples"),
        ((5, 12, 32), "4-D"),
    ],
)
def test_radar_npy_not_matching_config(infineon_recording, shape, fragment):
    np.save(infineon_recording / "RadarIfxAvian_00" / "radar.npy", np.zeros(shape, np.uint16))
    _expect_error(infineon_recording, fragment)


def test_radar_npy_of_floats_or_empty(infineon_recording):
    npy = infineon_recording / "RadarIfxAvian_00" / "radar.npy"
    np.save(npy, np.zeros((5, 3, 4, 32), np.float32))
    _expect_error(infineon_recording, "dtype float32")
    np.save(npy, np.zeros((0, 3, 4, 32), np.uint16))
    _expect_error(infineon_recording, "empty capture")


def test_codes_above_full_scale_are_an_error_on_read(infineon_recording):
    npy = infineon_recording / "RadarIfxAvian_00" / "radar.npy"
    data = np.load(npy)
    data[3, 0, 0, 0] = 4096
    np.save(npy, data)
    with open_capture(infineon_recording) as cap:
        cap.read(0, 3)
        with pytest.raises(CaptureError, match="frame 3 holds ADC code 4096"):
            cap.read()


def test_timestamp_count_mismatch_warns(infineon_recording):
    csv = infineon_recording / "RadarIfxAvian_00" / "radar_timestamp.csv"
    csv.write_text("1.0\n2.0\n")
    with pytest.warns(CaptureWarning, match="2 timestamps for 5 frames"):
        cap = open_capture(infineon_recording)
    assert cap.timestamps is None
    csv.write_text("1.0\nnot a number\n")
    _expect_error(infineon_recording, "cannot parse timestamps")


# --------------------------------------------------------------------------- real recordings
REAL = {
    "zharfanw__bgt60tr13c_processing/.dataset/BGT60TR13C_record_napaszhar_220260106-151615": (
        (256, 3, 8, 64),
        None,
    ),
    "ssalehi152431__Beamforming-with-Infineon-BGT60TR13C/Beamforming/beamforming_data/2_reflectors20251027-150925": (
        (128, 3, 64, 64),
        None,
    ),
    "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_48_07": ((232, 1, 64, 128), 232),
    "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_52_43": ((31, 1, 64, 128), 31),
    "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_53_49": ((31, 3, 64, 128), 31),
}


@pytest.mark.real
@pytest.mark.parametrize("folder", sorted(REAL), ids=lambda f: f.split("/")[-1])
def test_real_recordings(real_data: Path, folder):
    shape, n_stamps = REAL[folder]
    path = real_data / folder
    with open_capture(path) as cap:
        assert cap.shape == shape
        config_dict = json.loads((path / "RadarIfxAvian_00" / "config.json").read_text())
        assert RadarConfig.from_infineon(config_dict).to_infineon() == config_dict
        if n_stamps is None:
            assert cap.timestamps is None
        else:
            assert cap.timestamps is not None and len(cap.timestamps) == n_stamps
            assert np.all(np.diff(cap.timestamps) > 0)
        counts = cap.read(as_float=False)
        assert counts.min() >= 0 and counts.max() <= 4095
        raw = np.load(path / "RadarIfxAvian_00" / "radar.npy")
        np.testing.assert_array_equal(counts.numpy(), raw)


def test_non_finite_timestamps_warn_and_are_dropped(infineon_recording):
    csv = infineon_recording / "RadarIfxAvian_00" / "radar_timestamp.csv"
    csv.write_text("1.0\n2.0\nnan\n4.0\n5.0\n")
    with pytest.warns(CaptureWarning, match="NaN or Inf"):
        cap = open_capture(infineon_recording)
    assert cap.timestamps is None
    assert np.isfinite(cap.duration_s)


def test_unreadable_format_version_is_a_capture_error(infineon_recording):
    version = infineon_recording / "RadarIfxAvian_00" / "format.version"
    version.unlink()
    version.mkdir()
    err = _expect_error(infineon_recording, "format.version: cannot read")
    assert str(version) in str(err)


# --------------------------------------------------------------------------- hostile folders
@pytest.mark.parametrize("name", ["radar.npy", "config.json", "radar_timestamp.csv", "format.version"])
@pytest.mark.parametrize("kind", ["fifo", "devzero"])
def test_special_files_are_refused_without_blocking(infineon_recording, name, kind):
    import os
    import time

    path = infineon_recording / "RadarIfxAvian_00" / name
    path.unlink()
    if kind == "fifo":
        os.mkfifo(path)  # open() would block until a writer appears
    else:
        os.symlink("/dev/zero", path)  # would be read without end
    t = time.monotonic()
    err = _expect_error(infineon_recording, "not a regular file")
    assert time.monotonic() - t < 2 and name in str(err)


def test_bad_optional_files_warn_and_the_recording_reads(infineon_recording):
    dev = infineon_recording / "RadarIfxAvian_00"
    # The 144 bytes of data under a header declaring 2**40 float32 values (4 TiB).
    header = b"{'descr': '<f4', 'fortran_order': False, 'shape': (1099511627776,), }"
    text = header + b" " * (128 - 10 - len(header) - 1) + b"\n"
    (dev / "temperature.npy").write_bytes(b"\x93NUMPY\x01\x00" + len(text).to_bytes(2, "little") + text + bytes(144))
    (infineon_recording / "meta.json").write_text("[" * 100_000 + "]" * 100_000)
    with pytest.warns(CaptureWarning) as caught:
        cap = open_capture(infineon_recording)
    messages = " | ".join(str(w.message) for w in caught)
    assert "temperature.npy" in messages and "meta.json" in messages
    with cap:
        assert cap.temperature_C is None and cap.attrs["recording_meta"] == {}
        assert cap.read().shape == (5, 3, 4, 32)


def test_backwards_timestamps_warn_and_are_dropped(infineon_recording):
    csv = infineon_recording / "RadarIfxAvian_00" / "radar_timestamp.csv"
    csv.write_text("5.0\n4.0\n3.0\n2.0\n1.0\n")
    with pytest.warns(CaptureWarning, match="timestamps go backwards"):
        cap = open_capture(infineon_recording)
    assert cap.timestamps is None and cap.duration_s > 0


@pytest.mark.parametrize(
    "key, value, fragment",
    [
        ("tx_power_level", "NaN", "tx_power_level must be an integer"),
        ("if_gain_dB", '"64"', "if_gain_dB must be a number"),
        ("rx_antennas", '"1"', "rx_antennas must be a list"),
        ("tx_antennas", '"64"', "tx_antennas must be a list"),
        ("aaf_cutoff_Hz", '"500k"', "aaf_cutoff_Hz must be a number"),
        ("start_frequency_Hz", "64.5", "start_frequency_Hz must be a finite number in"),
        ("mimo_mode", '"tdm"', "MIMO is not supported"),
        ("tx_power_level", "1" * 401, "401 digits"),
    ],
)
def test_hostile_config_values_name_the_file_and_field(infineon_recording, key, value, fragment):
    path = infineon_recording / "RadarIfxAvian_00" / "config.json"
    data = json.loads(path.read_text())
    data["device_config"]["fmcw_single_shape"][key] = "@@"
    path.write_text(json.dumps(data).replace('"@@"', value))
    err = _expect_error(infineon_recording, fragment)
    assert "config.json" in str(err)
