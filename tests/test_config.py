"""RadarConfig: validation, derived values against closed forms, JSON and Infineon round-trips."""

from __future__ import annotations

import json
import math
import pickle

import pytest

from radaraug import ConfigError, RadarConfig
from radaraug.config import SPEED_OF_LIGHT

C = SPEED_OF_LIGHT


def test_paper_preset_nominal_values() -> None:
    cfg = RadarConfig.bgt60tr13c()
    # Paper: 60 GHz, 882.35 MHz, 1 MHz ADC, 256 samples, 0.256 ms chirp.
    assert cfg.center_frequency_Hz == pytest.approx(60e9)
    assert cfg.bandwidth_Hz == pytest.approx(882.35e6)
    assert cfg.adc_time_s == pytest.approx(0.256e-3)
    assert cfg.nominal_range_resolution_m == pytest.approx(0.170, abs=1e-3)
    # Nominal (no ADC delay) slope 3.4467e12 and max range 21.7 m, as in the paper.
    ideal = cfg.replace(adc_delay_s=0.0)
    assert ideal.slope_Hz_per_s == pytest.approx(3.4467e12, rel=1e-4)
    assert ideal.max_range_m == pytest.approx(21.75, abs=0.02)
    assert ideal.range_resolution_m == pytest.approx(C / (2 * 882.35e6))
    assert cfg.frame_shape == (3, 64, 256)  # 3 RX x 64 chirps x 256 samples per frame


def test_adc_delay_shrinks_sampled_bandwidth() -> None:
    cfg = RadarConfig.bgt60tr13c()
    t_adc = 256 / 1e6
    expected_bs = 882.35e6 * t_adc / (t_adc + 3.1e-6)
    assert cfg.sampled_bandwidth_Hz == pytest.approx(expected_bs, rel=1e-12)
    assert cfg.range_resolution_m == pytest.approx(C / (2 * expected_bs), rel=1e-12)
    assert cfg.range_resolution_m == pytest.approx(0.172, abs=1e-3)  # FIELD value with sampled bandwidth
    # Beat frequency per metre: 2*slope/c; max range at fs/2.
    assert cfg.beat_Hz_per_m == pytest.approx(2 * cfg.slope_Hz_per_s / C)
    assert cfg.max_range_m == pytest.approx(0.5e6 / cfg.beat_Hz_per_m)
    # N/2 bins of spacing dR cover exactly the max range.
    assert cfg.num_range_bins * cfg.range_resolution_m == pytest.approx(cfg.max_range_m)


def test_velocity_axis_closed_forms() -> None:
    cfg = RadarConfig.bgt60tr13c()
    lam = C / 60e9
    assert cfg.wavelength_m == pytest.approx(lam)
    assert cfg.max_velocity_m_s == pytest.approx(lam / (4 * 391.55e-6))
    assert cfg.velocity_resolution_m_s == pytest.approx(lam / (2 * 64 * 391.55e-6))
    axis = cfg.velocity_axis_m_s()
    assert len(axis) == 64 and axis[32] == 0.0
    assert axis[0] == pytest.approx(-cfg.max_velocity_m_s)
    assert cfg.doppler_Hz_per_m_s == pytest.approx(2 / lam)
    assert len(cfg.range_axis_m()) == 128


def test_sensor_anchor_numbers() -> None:
    # the BGT60TR13C default: 58-63.5 GHz, 64 samples @ 2 MHz -> ~3.0 cm sampled bin, v_max ~2.1 m/s at PRT 591 us.
    cfg = RadarConfig(58e9, 63.5e9, 2e6, 64, 8, 0.0005911249900236726, 0.07726884633302689)
    assert cfg.nominal_range_resolution_m == pytest.approx(0.0273, abs=1e-4)
    assert cfg.range_resolution_m == pytest.approx(0.0300, abs=5e-4)
    assert cfg.max_velocity_m_s == pytest.approx(2.1, abs=0.05)


def test_json_round_trip_and_immutability(tmp_path) -> None:
    cfg = RadarConfig.bgt60tr13c(if_gain_dB=38, rx_positions_m=((0, 0, 0), (0.0025, 0, 0), (0, 0.0025, 0)))
    text = cfg.to_json(tmp_path / "c.json")
    assert RadarConfig.from_json(text) == cfg
    assert RadarConfig.from_json(tmp_path / "c.json") == cfg
    assert pickle.loads(pickle.dumps(cfg)) == cfg
    assert hash(cfg) == hash(RadarConfig.from_dict(cfg.to_dict()))
    with pytest.raises(AttributeError):
        cfg.num_samples_per_chirp = 3  # type: ignore[misc]


@pytest.mark.parametrize(
    "change, fragment",
    [
        ({"end_frequency_Hz": 59e9}, "must exceed"),
        ({"num_samples_per_chirp": 0}, "positive integer"),
        ({"num_samples_per_chirp": 2.5}, "positive integer"),
        ({"sample_rate_Hz": float("nan")}, "finite positive"),
        ({"tx_power_level": 40}, "0..31"),
        ({"rx_antennas": (1, 1)}, "duplicates"),
        ({"rx_antennas": ()}, "at least one"),
        ({"chirp_repetition_time_s": 100e-6}, "longer than the chirp repetition"),
        ({"frame_repetition_time_s": 0.01}, "do not fit"),
        ({"rx_positions_m": ((0, 0, 0),)}, "rx_positions_m has 1"),
    ],
)
def test_invalid_configs_raise_config_error(change, fragment) -> None:
    with pytest.raises(ConfigError, match=fragment):
        RadarConfig.bgt60tr13c(**change)


INFINEON_INT = {
    "device_config": {
        "fmcw_single_shape": {
            "aaf_cutoff_Hz": 500000,
            "chirp_repetition_time_s": 0.0005911249900236726,
            "end_frequency_Hz": 63500000000,
            "frame_repetition_time_s": 0.07726884633302689,
            "hp_cutoff_Hz": 80000,
            "if_gain_dB": 23,
            "mimo_mode": "off",
            "num_chirps_per_frame": 64,
            "num_samples_per_chirp": 64,
            "rx_antennas": [1, 2, 3],
            "sample_rate_Hz": 2000000,
            "start_frequency_Hz": 58000000000,
            "tx_antennas": [1],
            "tx_power_level": 31,
        }
    }
}

# The exponent spelling of ifxdaq 3.0.1 recordings, with no filter keys.
INFINEON_EXP_TEXT = """{"device_config": {"fmcw_single_shape": {
  "rx_antennas": [1, 2, 3], "tx_antennas": [1], "tx_power_level": 31, "if_gain_dB": 38,
  "start_frequency_Hz": 60.5e9, "end_frequency_Hz": 61.5e9, "num_chirps_per_frame": 64,
  "num_samples_per_chirp": 128, "chirp_repetition_time_s": 400e-6, "frame_repetition_time_s": 0.05,
  "sample_rate_Hz": 2e6, "mimo_mode": "off"}}}"""


def test_infineon_round_trip_both_spellings(tmp_path) -> None:
    cfg = RadarConfig.from_infineon(INFINEON_INT)
    assert cfg.to_infineon() == INFINEON_INT
    assert cfg.num_rx == 3 and cfg.hp_cutoff_Hz == 80000

    exp = json.loads(INFINEON_EXP_TEXT)
    path = tmp_path / "config.json"
    path.write_text(INFINEON_EXP_TEXT)
    cfg2 = RadarConfig.from_infineon(path)
    assert cfg2.to_infineon() == exp
    assert cfg2.hp_cutoff_Hz is None and cfg2.effective_hp_cutoff_Hz == 80e3
    assert RadarConfig.from_json(path) == cfg2
    # radaraug JSON of an Infineon config round-trips too.
    assert RadarConfig.from_json(cfg2.to_json()) == cfg2


def test_real_recording_configs_round_trip(real_data) -> None:
    files = sorted(real_data.rglob("RadarIfxAvian_00/config.json"))
    assert files, "no config.json found in the real recordings"
    for f in files:
        original = json.loads(f.read_text())
        cfg = RadarConfig.from_infineon(f)
        assert cfg.to_infineon() == original, f
        assert math.isfinite(cfg.max_range_m)


def test_infineon_errors_name_the_file(tmp_path) -> None:
    with pytest.raises(ConfigError, match="does not exist"):
        RadarConfig.from_infineon(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ConfigError, match="bad.json.*not valid JSON"):
        RadarConfig.from_infineon(bad)
    partial = tmp_path / "partial.json"
    shape = dict(INFINEON_INT["device_config"]["fmcw_single_shape"])
    del shape["sample_rate_Hz"]
    partial.write_text(json.dumps({"device_config": {"fmcw_single_shape": shape}}))
    with pytest.raises(ConfigError, match=r"partial.json.*sample_rate_Hz"):
        RadarConfig.from_infineon(partial)
    other = tmp_path / "other.json"
    other.write_text(json.dumps({"device_config": {"fmcw_multi_shape": {}}}))
    with pytest.raises(ConfigError, match="fmcw_single_shape"):
        RadarConfig.from_infineon(other)


HOSTILE_FIELDS = [
    ("tx_power_level", None), ("tx_power_level", [1]), ("tx_power_level", {}), ("tx_power_level", "abc"),
    ("tx_power_level", float("nan")), ("tx_power_level", float("inf")), ("tx_power_level", -float("inf")),
    ("if_gain_dB", None), ("if_gain_dB", "abc"), ("if_gain_dB", "64"), ("hp_cutoff_Hz", "abc"),
    ("aaf_cutoff_Hz", "500k"), ("rx_antennas", [0]), ("rx_antennas", [-2]), ("rx_antennas", [99]),
    ("rx_antennas", "1"), ("rx_antennas", [1.9]), ("tx_antennas", "64"), ("tx_antennas", [1, 2]),
    ("start_frequency_Hz", 64.5), ("end_frequency_Hz", 1e308), ("sample_rate_Hz", 1e308),
    ("frame_repetition_time_s", 1e308), ("mimo_mode", "tdm"), ("adc_bits", 64), ("adc_bits", 1000),
    ("adc_bits", True), ("num_samples_per_chirp", 2**22), ("tx_power_level", 10**5000),
    ("rx_positions_m", [[0, 0, float("nan")]] * 3), ("tx_position_m", "abc"),
]


@pytest.mark.parametrize("field, value", HOSTILE_FIELDS, ids=[f"{f}-{i}" for i, (f, _) in enumerate(HOSTILE_FIELDS)])
def test_hostile_values_are_one_config_error_naming_the_field(field, value) -> None:
    """Every field is checked for type and plausible range (docs/radar_config.md); before, these
    gave bare TypeError/ValueError/OverflowError or were accepted ("64" as antennas (6, 4))."""
    with pytest.raises(ConfigError, match=field):
        RadarConfig.bgt60tr13c(**{field: value})
    data = RadarConfig.bgt60tr13c().to_dict()
    data[field] = value
    with pytest.raises(ConfigError, match=f"{field}.*in cfg.json"):
        RadarConfig.from_dict(data, source="cfg.json")


def test_numpy_scalars_become_plain_numbers() -> None:
    import numpy as np

    cfg = RadarConfig.bgt60tr13c(num_chirps_per_frame=np.int64(32), sample_rate_Hz=np.float32(1e6))
    assert type(cfg.num_chirps_per_frame) is int and type(cfg.sample_rate_Hz) is float
    json.dumps(cfg.to_dict())
