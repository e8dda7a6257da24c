"""The Infineon SDK adapter against a stand-in ``ifxradarsdk`` module injected into ``sys.modules``.

The stand-in has the calls of the SDK's public FMCW API that the adapter uses and records them;
nothing here runs on a board.
"""

from __future__ import annotations

import sys
import types

import numpy as np
import pytest

from radaraug.capture import SdkDevice, open_device, record
from radaraug.cli import main
from radaraug.errors import ConfigError, DeviceError
from radaraug.io import open_capture
from radaraug.units import counts_to_float


class ErrorFifoOverflow(Exception):
    pass


class ErrorCommunication(Exception):
    pass


def _fake_sdk(config, *, fail_after=None, overflow_at=None, shape=None):
    """A module tree ifxradarsdk / .fmcw / .fmcw.types; frame i is filled with ADC code 100 + i."""
    log = {"opened": [], "calls": []}

    class Struct:
        def __init__(self, **kw):
            self.__dict__.update(kw)

    class DeviceFmcw:
        def __init__(self, uuid=None):
            log["opened"].append(uuid)
            self.n = 0

        @staticmethod
        def get_list():
            return [{"uuid": "0123ABCD", "board_type": "BGT60TR13C"}]

        def get_sensor_information(self):
            return {"description": "BGT60TR13C", "num_rx_antennas": 3}

        def create_simple_sequence(self, cfg):
            log["calls"].append(("create_simple_sequence", cfg))
            return ("sequence", cfg)

        def set_acquisition_sequence(self, seq):
            log["calls"].append(("set_acquisition_sequence", seq))

        def get_next_frame(self, timeout_ms=None):
            self.n += 1
            if overflow_at is not None and self.n == overflow_at:
                raise ErrorFifoOverflow("FIFO overflow")
            if fail_after is not None and self.n > fail_after:
                raise ErrorCommunication("device disconnected")
            c = config
            s = shape or (c.num_rx, c.num_chirps_per_frame, c.num_samples_per_chirp)
            return [counts_to_float(np.full(s, 100 + self.n, np.int64)).numpy()]

        def stop_acquisition(self):
            log["calls"].append(("stop_acquisition",))

        def __exit__(self, *exc):
            log["calls"].append(("close",))

    root, fmcw, fmcw_types = (types.ModuleType(n) for n in ("ifxradarsdk", "ifxradarsdk.fmcw", "ifxradarsdk.fmcw.types"))
    fmcw.DeviceFmcw = DeviceFmcw
    fmcw.types = fmcw_types
    fmcw_types.FmcwSimpleSequenceConfig = Struct
    fmcw_types.FmcwSequenceChirp = Struct
    root.fmcw = fmcw
    return {"ifxradarsdk": root, "ifxradarsdk.fmcw": fmcw, "ifxradarsdk.fmcw.types": fmcw_types}, log


@pytest.fixture
def sdk(monkeypatch, cfg):
    def install(**kw):
        modules, log = _fake_sdk(cfg, **kw)
        for name, mod in modules.items():
            monkeypatch.setitem(sys.modules, name, mod)
        return log

    return install


def test_without_the_sdk_the_error_says_what_to_install(monkeypatch, cfg, tmp_path, capsys) -> None:
    monkeypatch.setitem(sys.modules, "ifxradarsdk", None)  # import fails as if not installed
    with pytest.raises(DeviceError, match="ifxradarsdk.*Infineon"):
        SdkDevice(cfg).start()
    assert main(["capture", "--board", "auto", "-o", str(tmp_path / "x.h5"), "--seconds", "1"]) == 3
    assert "pip install its ifxradarsdk wheel" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("option", [["--scene", "corridor"], ["--seed", "0"], ["--no-realtime"],
                                    ["--realtime"], ["--profile", "p.json"]])
def test_a_virtual_only_option_given_for_a_board_is_refused_not_ignored(sdk, tmp_path, capsys, option) -> None:
    log = sdk()
    # even the options' default values, given explicitly: a board would silently ignore them
    assert main(["capture", "--board", "auto", "-o", str(tmp_path / "x.h5"), "--seconds", "1", *option]) == 3
    assert "only for the virtual sensor" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == [] and log["opened"] == []
    with pytest.raises(ConfigError, match="scene, seed: only for the virtual sensor"):
        open_device("auto", scene="corridor", seed=0)


def test_the_config_goes_to_the_sdk_and_frames_to_the_file(sdk, cfg, tmp_path) -> None:
    log = sdk()
    result = record(open_device("0123ABCD", cfg), tmp_path / "board.h5", frames=5)
    assert log["opened"] == ["0123ABCD"]
    (_, seq_cfg), (_, seq) = log["calls"][:2]
    assert seq == ("sequence", seq_cfg)
    assert seq_cfg.num_chirps == cfg.num_chirps_per_frame and seq_cfg.tdm_mimo is False
    assert seq_cfg.frame_repetition_time_s == cfg.frame_repetition_time_s
    chirp = seq_cfg.chirp
    assert (chirp.rx_mask, chirp.tx_mask, chirp.num_samples) == (0b111, 0b1, cfg.num_samples_per_chirp)
    assert chirp.start_frequency_Hz == cfg.start_frequency_Hz and chirp.if_gain_dB == int(cfg.if_gain_dB)
    assert log["calls"][-2:] == [("stop_acquisition",), ("close",)]
    assert result.frames == 5
    with open_capture(tmp_path / "board.h5") as cap:
        assert cap.read(as_float=False)[:, 0, 0, 0].tolist() == [101, 102, 103, 104, 105]


def test_an_unplugged_board_keeps_the_frames_before(sdk, cfg, tmp_path) -> None:
    log = sdk(fail_after=3)
    with pytest.raises(DeviceError, match="disconnected.*keeps the 3 frames"):
        record(SdkDevice(cfg), tmp_path / "u.h5", frames=10)
    assert log["opened"] == [None] and ("close",) in log["calls"]
    with open_capture(tmp_path / "u.h5") as cap:
        assert cap.num_frames == 3


def test_a_fifo_overflow_is_a_dropped_frame_not_the_end(sdk, cfg, tmp_path) -> None:
    sdk(overflow_at=2)
    dev = SdkDevice(cfg)
    result = record(dev, tmp_path / "o.h5", frames=6)
    assert dev.dropped_by_sdk == 1 and result.dropped >= 1 and result.frames + result.dropped == 6


def test_a_frame_of_the_wrong_shape_is_refused(sdk, cfg, tmp_path) -> None:
    sdk(shape=(1, 2, 3))
    with pytest.raises(DeviceError, match=r"shape \(1, 2, 3\)"):
        record(SdkDevice(cfg), tmp_path / "s.h5", frames=2)


def test_an_sdk_without_the_fmcw_api_is_named(monkeypatch, cfg) -> None:
    monkeypatch.setitem(sys.modules, "ifxradarsdk", types.ModuleType("ifxradarsdk"))  # e.g. a 2.x SDK
    monkeypatch.setitem(sys.modules, "ifxradarsdk.fmcw", None)
    with pytest.raises(DeviceError, match="has no 'ifxradarsdk.fmcw'.*FMCW API"):
        SdkDevice(cfg).start()
