"""`RadarConfig`: one validated, immutable description of an FMCW radar and its chirp.

Field names follow Infineon's ``fmcw_single_shape`` keys, so a recording's ``config.json`` round-trips
exactly. Fields, accepted ranges and the timing model of the derived values: docs/radar_config.md.
"""

from __future__ import annotations

import dataclasses
import json
import math
import numbers
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, NoReturn

import numpy as np

from radaraug.errors import ConfigError
from radaraug.files import load_json, parse_json, safe_repr

SPEED_OF_LIGHT = 299_792_458.0
"""Speed of light in vacuum, m/s."""

_INFINEON_KEYS = (
    "start_frequency_Hz",
    "end_frequency_Hz",
    "sample_rate_Hz",
    "num_samples_per_chirp",
    "num_chirps_per_frame",
    "chirp_repetition_time_s",
    "frame_repetition_time_s",
    "rx_antennas",
    "tx_antennas",
    "tx_power_level",
    "if_gain_dB",
    "hp_cutoff_Hz",
    "aaf_cutoff_Hz",
    "mimo_mode",
)
_REQUIRED_INFINEON_KEYS = _INFINEON_KEYS[:11]

# Infineon SDK defaults for the IF filters when a recording does not state them.
DEFAULT_HP_CUTOFF_HZ = 80_000.0
DEFAULT_AAF_CUTOFF_HZ = 500_000.0
DEFAULT_ADC_DELAY_S = 3.1e-6

# Plausible ranges (docs/radar_config.md): wide enough for any FMCW sensor radaraug may model,
# narrow enough that a corrupted value cannot pass as physics or size a huge allocation.
FREQUENCY_RANGE_HZ = (1e9, 1e12)
MAX_SAMPLE_RATE_HZ = 1e10
MAX_CHIRP_REPETITION_TIME_S = 1.0
MAX_FRAME_REPETITION_TIME_S = 3600.0
MAX_SAMPLES_PER_CHIRP = 65536
MAX_CHIRPS_PER_FRAME = 65536
MAX_SAMPLES_PER_FRAME = 2**24
"""Largest frame, rx x chirps x samples (32 MiB of uint16 counts)."""
MAX_ANTENNAS = 16
ADC_BITS_RANGE = (8, 16)
"""ADC resolutions accepted: captures store counts as uint16."""


def _default_rx_positions(n_rx: int, wavelength: float) -> tuple[tuple[float, float, float], ...]:
    """L-shaped BGT60TR13C array: RX1-RX3 horizontal, RX2-RX3 vertical, lambda/2 apart (the datasheet drawing).

    Metres in the antenna frame: x to the sensor's right, y up, z along boresight.
    """
    d = wavelength / 2
    table = {1: (-d, 0.0, 0.0), 2: (0.0, d, 0.0), 3: (0.0, 0.0, 0.0)}
    return tuple(table.get(i + 1, (d * i, 0.0, 0.0)) for i in range(n_rx))


@dataclass(frozen=True)
class RadarConfig:
    """Validated, immutable FMCW radar configuration.

    Args:
        start_frequency_Hz: TX ramp start frequency.
        end_frequency_Hz: TX ramp end frequency (> start).
        sample_rate_Hz: ADC sample rate.
        num_samples_per_chirp: ADC samples per chirp (fast time).
        num_chirps_per_frame: chirps per frame (slow time).
        chirp_repetition_time_s: time between chirp starts (PRT).
        frame_repetition_time_s: time between frame starts.
        rx_antennas: 1-based RX antenna numbers, in the order of the data's RX axis.
        tx_antennas: 1-based TX antenna numbers.
        tx_power_level: Infineon TX power level 0..31.
        if_gain_dB: total IF gain (18..60 dB on the BGT60TR13C).
        hp_cutoff_Hz: IF high-pass cutoff; ``None`` when the recording does not state it
            (then :attr:`effective_hp_cutoff_Hz` uses the SDK default 80 kHz).
        aaf_cutoff_Hz: anti-alias low-pass cutoff; ``None`` as above (default 500 kHz).
        mimo_mode: Infineon MIMO mode string ("off" for 1 TX).
        adc_delay_s: time from ramp start to the first ADC sample (3.1 us on the BGT60).
        adc_bits: ADC resolution in bits.
        rx_positions_m: per-RX phase-centre positions (x, y, z) in metres in the antenna frame;
            ``None`` gives the L-shaped lambda/2 layout of the BGT60TR13C.
        tx_position_m: TX phase centre in the antenna frame.
    """

    start_frequency_Hz: float
    end_frequency_Hz: float
    sample_rate_Hz: float
    num_samples_per_chirp: int
    num_chirps_per_frame: int
    chirp_repetition_time_s: float
    frame_repetition_time_s: float
    rx_antennas: tuple[int, ...] = (1, 2, 3)
    tx_antennas: tuple[int, ...] = (1,)
    tx_power_level: int = 31
    if_gain_dB: float = 33
    hp_cutoff_Hz: float | None = None
    aaf_cutoff_Hz: float | None = None
    mimo_mode: str = "off"
    adc_delay_s: float = DEFAULT_ADC_DELAY_S
    adc_bits: int = 12
    rx_positions_m: tuple[tuple[float, float, float], ...] | None = field(default=None)
    tx_position_m: tuple[float, float, float] = (0.0, -0.0025, 0.0)

    # ------------------------------------------------------------------ validation
    def __post_init__(self) -> None:
        # Every field is checked for its type and a physically plausible range here, the one
        # validation layer for configs from code, radaraug JSON, HDF5 attributes and Infineon
        # config.json files (docs/radar_config.md lists the ranges).
        def fail(msg: str) -> NoReturn:
            raise ConfigError(f"invalid RadarConfig: {msg}")

        def set_(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        def real(name: str, lo: float, hi: float, *, lo_open: bool = True) -> float:
            v = getattr(self, name)
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Real, np.floating, np.integer)):
                fail(f"{name} must be a number, got {safe_repr(v)} ({type(v).__name__})")
            if isinstance(v, (np.floating, np.integer)):
                v = v.item()  # plain Python numbers, so to_dict() stays JSON-able
                set_(name, v)
            try:
                ok = math.isfinite(v) and (v > lo if lo_open else v >= lo) and v <= hi
            except OverflowError:  # an int too large for a float
                ok = False
            if not ok:
                kind = "a finite positive number" if lo_open and lo == 0 else "a finite number"
                bound = "(" if lo_open else "["
                fail(f"{name} must be {kind} in {bound}{lo:g}, {hi:g}], got {safe_repr(v)}")
            return v

        def integer(name: str, lo: int, hi: int) -> int:
            v = getattr(self, name)
            kind = "a positive integer" if lo >= 1 else "an integer"
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Integral, np.integer)):
                fail(f"{name} must be {kind}, got {safe_repr(v)} ({type(v).__name__})")
            v = int(v)
            if not lo <= v <= hi:
                fail(f"{name} must be {kind} in {lo}..{hi}, got {safe_repr(v)}")
            set_(name, v)
            return v

        def antennas(name: str) -> tuple[int, ...]:
            value = getattr(self, name)
            # A string is iterable too: "64" must not become antennas (6, 4).
            if not isinstance(value, (list, tuple, np.ndarray)):
                fail(f"{name} must be a list of antenna numbers, got {safe_repr(value)} ({type(value).__name__})")
            out = []
            for v in value:
                if isinstance(v, float) and v.is_integer():
                    v = int(v)
                if isinstance(v, (bool, np.bool_)) or not isinstance(v, (numbers.Integral, np.integer)):
                    fail(f"{name} must hold integer antenna numbers, got {safe_repr(value)}")
                if not 1 <= int(v) <= MAX_ANTENNAS:
                    fail(f"{name} must hold antenna numbers 1..{MAX_ANTENNAS}, got {safe_repr(value)}")
                out.append(int(v))
            if not out:
                fail(f"{name} must name at least one antenna")
            if len(set(out)) != len(out):
                fail(f"{name} has duplicates: {tuple(out)}")
            set_(name, tuple(out))
            return tuple(out)

        def position(value: Any, what: str) -> tuple[float, float, float]:
            if not isinstance(value, (list, tuple, np.ndarray)) or len(value) != 3:
                fail(f"{what} must be an (x, y, z) triple in metres, got {safe_repr(value)}")
            try:
                pos = tuple(float(c) for c in value)
                bad = any(isinstance(c, (bool, str, bytes)) for c in value) or not all(
                    math.isfinite(c) for c in pos
                )
            except (TypeError, ValueError, OverflowError):
                bad = True
            if bad:
                fail(f"{what} must be an (x, y, z) triple of finite numbers, got {safe_repr(value)}")
            return pos  # type: ignore[return-value]

        rx = antennas("rx_antennas")
        tx = antennas("tx_antennas")
        mimo = self.mimo_mode
        if not isinstance(mimo, str) or mimo != "off":
            fail(f"mimo_mode must be \"off\": MIMO is not supported, got {safe_repr(mimo)}")
        if len(tx) != 1:
            fail(f"exactly one TX antenna is supported (MIMO is not), got tx_antennas {tx}")
        if self.rx_positions_m is not None:
            if not isinstance(self.rx_positions_m, (list, tuple, np.ndarray)):
                fail(f"rx_positions_m must be a list of (x, y, z) triples, got {safe_repr(self.rx_positions_m)}")
            set_("rx_positions_m", tuple(position(p, "each rx_positions_m entry") for p in self.rx_positions_m))
            if len(self.rx_positions_m) != len(rx):
                fail(f"rx_positions_m has {len(self.rx_positions_m)} entries for {len(rx)} RX antennas")
        set_("tx_position_m", position(self.tx_position_m, "tx_position_m"))

        start = real("start_frequency_Hz", *FREQUENCY_RANGE_HZ, lo_open=False)
        end = real("end_frequency_Hz", *FREQUENCY_RANGE_HZ, lo_open=False)
        real("sample_rate_Hz", 0, MAX_SAMPLE_RATE_HZ)
        prt = real("chirp_repetition_time_s", 0, MAX_CHIRP_REPETITION_TIME_S)
        frame_time = real("frame_repetition_time_s", 0, MAX_FRAME_REPETITION_TIME_S)
        n = integer("num_samples_per_chirp", 2, MAX_SAMPLES_PER_CHIRP)
        m = integer("num_chirps_per_frame", 1, MAX_CHIRPS_PER_FRAME)
        integer("adc_bits", *ADC_BITS_RANGE)
        integer("tx_power_level", 0, 31)
        real("if_gain_dB", 0, 80, lo_open=False)
        real("adc_delay_s", 0, MAX_CHIRP_REPETITION_TIME_S, lo_open=False)
        for name in ("hp_cutoff_Hz", "aaf_cutoff_Hz"):
            if getattr(self, name) is not None:
                real(name, 0, MAX_SAMPLE_RATE_HZ)
        if end <= start:
            fail(f"end_frequency_Hz ({end:g}) must exceed start_frequency_Hz ({start:g})")
        if len(rx) * m * n > MAX_SAMPLES_PER_FRAME:
            fail(
                f"a frame of {len(rx)} RX x {m} chirps x {n} samples holds more than "
                f"{MAX_SAMPLES_PER_FRAME} samples"
            )
        if self.chirp_time_s > prt * (1 + 1e-9):
            fail(
                f"chirp (ADC delay + {n} samples = {self.chirp_time_s * 1e6:.2f} us) is longer than the "
                f"chirp repetition time ({prt * 1e6:.2f} us)"
            )
        if m * prt > frame_time * (1 + 1e-9):
            fail(
                f"{m} chirps x {prt * 1e6:.1f} us do not fit in the frame repetition time "
                f"{frame_time * 1e3:.2f} ms"
            )

    # ------------------------------------------------------------------ presets
    @classmethod
    def bgt60tr13c(cls, **overrides: Any) -> RadarConfig:
        """The paper's BGT60TR13C setting: 60 GHz, 882.35 MHz, 1 MHz ADC, 256 samples, 3 RX.

        Chirps per frame and chirp repetition time, which the paper does not give, are Infineon's
        people-tracking defaults (64 chirps at 391.55 us, 10 frames/s); docs/radar_config.md.
        """
        bandwidth = 882.35e6
        params: dict[str, Any] = dict(
            start_frequency_Hz=60e9 - bandwidth / 2,
            end_frequency_Hz=60e9 + bandwidth / 2,
            sample_rate_Hz=1e6,
            num_samples_per_chirp=256,
            num_chirps_per_frame=64,
            chirp_repetition_time_s=391.55e-6,
            frame_repetition_time_s=0.1,
            rx_antennas=(1, 2, 3),
            tx_antennas=(1,),
            tx_power_level=31,
            if_gain_dB=33,
            hp_cutoff_Hz=DEFAULT_HP_CUTOFF_HZ,
            aaf_cutoff_Hz=DEFAULT_AAF_CUTOFF_HZ,
        )
        params.update(overrides)
        return cls(**params)

    def replace(self, **changes: Any) -> RadarConfig:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------------ derived values
    @property
    def frame_shape(self) -> tuple[int, int, int]:
        """One frame's raw shape ``(num_rx, num_chirps_per_frame, num_samples_per_chirp)``."""
        return (self.num_rx, self.num_chirps_per_frame, self.num_samples_per_chirp)

    @property
    def bandwidth_Hz(self) -> float:
        """Nominal RF bandwidth ``end - start`` (TX on)."""
        return self.end_frequency_Hz - self.start_frequency_Hz

    @property
    def center_frequency_Hz(self) -> float:
        """Centre of the nominal sweep."""
        return 0.5 * (self.start_frequency_Hz + self.end_frequency_Hz)

    @property
    def wavelength_m(self) -> float:
        """Wavelength at the centre frequency."""
        return SPEED_OF_LIGHT / self.center_frequency_Hz

    @property
    def adc_time_s(self) -> float:
        """Duration of the ADC window of one chirp, ``N / fs``."""
        return self.num_samples_per_chirp / self.sample_rate_Hz

    @property
    def chirp_time_s(self) -> float:
        """Ramp duration: ADC delay plus ADC window."""
        return self.adc_delay_s + self.adc_time_s

    @property
    def slope_Hz_per_s(self) -> float:
        """Chirp slope of the TX ramp."""
        return self.bandwidth_Hz / self.chirp_time_s

    @property
    def sampled_bandwidth_Hz(self) -> float:
        """Bandwidth swept while the ADC samples (``slope * T_adc``)."""
        return self.slope_Hz_per_s * self.adc_time_s

    @property
    def sampled_start_frequency_Hz(self) -> float:
        """RF frequency at the first ADC sample."""
        return self.start_frequency_Hz + self.slope_Hz_per_s * self.adc_delay_s

    @property
    def beat_Hz_per_m(self) -> float:
        """Beat frequency per metre of (one-way) range, ``2 * slope / c``."""
        return 2 * self.slope_Hz_per_s / SPEED_OF_LIGHT

    @property
    def range_resolution_m(self) -> float:
        """Range bin spacing ``c / (2 * sampled_bandwidth)``."""
        return SPEED_OF_LIGHT / (2 * self.sampled_bandwidth_Hz)

    @property
    def nominal_range_resolution_m(self) -> float:
        """Textbook ``c / (2 B)`` with the nominal bandwidth (what the paper quotes)."""
        return SPEED_OF_LIGHT / (2 * self.bandwidth_Hz)

    @property
    def num_range_bins(self) -> int:
        """Positive range bins kept from a real-sampled chirp: ``N // 2``."""
        return self.num_samples_per_chirp // 2

    @property
    def max_range_m(self) -> float:
        """Unambiguous range of real sampling: beat frequency ``fs / 2``."""
        return (self.sample_rate_Hz / 2) / self.beat_Hz_per_m

    @property
    def max_velocity_m_s(self) -> float:
        """Unambiguous radial velocity ``lambda / (4 * PRT)`` (Doppler wraps beyond it)."""
        return self.wavelength_m / (4 * self.chirp_repetition_time_s)

    @property
    def velocity_resolution_m_s(self) -> float:
        """Doppler bin spacing ``lambda / (2 * M * PRT)``."""
        return self.wavelength_m / (2 * self.num_chirps_per_frame * self.chirp_repetition_time_s)

    @property
    def doppler_Hz_per_m_s(self) -> float:
        """Doppler shift per m/s of radial velocity, ``2 / lambda``."""
        return 2 / self.wavelength_m

    @property
    def num_rx(self) -> int:
        """Number of receive channels."""
        return len(self.rx_antennas)

    @property
    def frame_rate_Hz(self) -> float:
        """Frames per second."""
        return 1 / self.frame_repetition_time_s

    @property
    def effective_hp_cutoff_Hz(self) -> float:
        """High-pass cutoff, with the SDK default when the recording does not state it."""
        return DEFAULT_HP_CUTOFF_HZ if self.hp_cutoff_Hz is None else float(self.hp_cutoff_Hz)

    @property
    def effective_aaf_cutoff_Hz(self) -> float:
        """Anti-alias cutoff, with the SDK default when the recording does not state it."""
        return DEFAULT_AAF_CUTOFF_HZ if self.aaf_cutoff_Hz is None else float(self.aaf_cutoff_Hz)

    @property
    def rx_positions(self) -> tuple[tuple[float, float, float], ...]:
        """RX phase centres in metres (the default L layout when not given)."""
        if self.rx_positions_m is not None:
            return self.rx_positions_m
        return tuple(_default_rx_positions(max(self.rx_antennas), self.wavelength_m)[a - 1] for a in self.rx_antennas)

    @property
    def adc_full_scale_counts(self) -> int:
        """Largest ADC code, ``2**bits - 1`` (4095 for 12 bits)."""
        return 2**self.adc_bits - 1

    def range_axis_m(self) -> list[float]:
        """Range of each kept range bin (``k * range_resolution``), ``N // 2`` values."""
        return [k * self.range_resolution_m for k in range(self.num_range_bins)]

    def velocity_axis_m_s(self) -> list[float]:
        """Radial velocity of each Doppler bin after fftshift (zero in the middle).

        Positive velocity means the target moves *away* from the radar (range grows).
        """
        m = self.num_chirps_per_frame
        return [(k - m // 2) * self.velocity_resolution_m_s for k in range(m)]

    # ------------------------------------------------------------------ serialisation
    def to_dict(self) -> dict[str, Any]:
        """All fields as plain JSON types."""
        return json.loads(json.dumps(dataclasses.asdict(self)))  # tuples -> lists; floats round-trip exactly

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, source: str | None = None) -> RadarConfig:
        """Build from :meth:`to_dict` output (unknown keys are an error)."""
        where = f" in {source}" if source else ""
        if not isinstance(data, Mapping):
            raise ConfigError(f"radar config{where} must be a JSON object, got {type(data).__name__}")
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = set(data) - names
        if unknown:
            raise ConfigError(f"unknown radar config keys{where}: {sorted(unknown)}")
        missing = [n for n in _REQUIRED_INFINEON_KEYS[:7] if n not in data]
        if missing:
            raise ConfigError(f"radar config{where} lacks required keys {missing}")
        return cls._build(dict(data), where)

    @classmethod
    def _build(cls, kwargs: dict[str, Any], where: str) -> RadarConfig:
        """``cls(**kwargs)``, any error raised as a ConfigError that ends with ``where`` (the source)."""
        try:
            return cls(**kwargs)
        except ConfigError as e:
            raise ConfigError(f"{e}{where}") from None
        except (TypeError, ValueError, OverflowError) as e:
            raise ConfigError(f"invalid radar config{where}: {e}") from None

    def to_json(self, path: str | os.PathLike | None = None) -> str:
        """JSON text of :meth:`to_dict`; also written to ``path`` when given."""
        text = json.dumps(self.to_dict(), indent=2, sort_keys=True)
        if path is not None:
            from radaraug.files import atomic_write_text

            atomic_write_text(path, text + "\n")
        return text

    @classmethod
    def from_json(cls, text_or_path: str | os.PathLike) -> RadarConfig:
        """Parse JSON text, or read a file: a radaraug config or an Infineon ``config.json``."""
        source = None
        text = str(text_or_path)
        if not text.lstrip().startswith("{"):
            source = text
            data = load_json(text_or_path, error=ConfigError, what="radar config")
        else:
            data = parse_json(text, source="radar config (text)", error=ConfigError)
        # radaraug's own JSON always carries adc_bits; Infineon's never does.
        if isinstance(data, Mapping) and "adc_bits" not in data:
            return cls.from_infineon(data, source=source)
        return cls.from_dict(data, source=source)

    # Infineon ifxdaq / Radar Fusion GUI `config.json`
    def to_infineon(self) -> dict[str, Any]:
        """The ``{"device_config": {"fmcw_single_shape": {...}}}`` dict of an Infineon recording.

        Fields Infineon does not store (RX positions, ADC delay/bits) are left out; optional
        filter cutoffs are written only when set.
        """
        values = {key: getattr(self, key) for key in _INFINEON_KEYS}
        shape = {k: list(v) if isinstance(v, tuple) else v for k, v in values.items() if v is not None}
        return {"device_config": {"fmcw_single_shape": shape}}

    @classmethod
    def from_infineon(
        cls, data: Mapping[str, Any] | str | os.PathLike, *, source: str | None = None, **extra: Any
    ) -> RadarConfig:
        """Read an Infineon ``config.json`` (dict or path): the full ``device_config`` form or the bare dict.

        Values are kept exactly as read, so :meth:`to_infineon` returns an equal dict. ``extra`` sets
        radaraug-only fields (e.g. ``rx_positions_m``).
        """
        if not isinstance(data, Mapping):
            source = str(data)
            data = load_json(data, error=ConfigError, what="radar config")
            if not isinstance(data, Mapping):
                raise ConfigError(f"{source}: radar config must be a JSON object, got {type(data).__name__}")
        where = source or "(dict)"
        shape: Any = data
        if "device_config" in data:
            dc = data["device_config"]
            if not isinstance(dc, Mapping) or "fmcw_single_shape" not in dc:
                kinds = list(dc) if isinstance(dc, Mapping) else type(dc).__name__
                raise ConfigError(
                    f"radar config {where}: device_config has no 'fmcw_single_shape' "
                    f"(found {kinds}); only single-shape FMCW recordings are supported"
                )
            shape = dc["fmcw_single_shape"]
        if not isinstance(shape, Mapping):
            raise ConfigError(f"radar config {where}: fmcw_single_shape must be an object")
        missing = [k for k in _REQUIRED_INFINEON_KEYS if k not in shape]
        if missing:
            raise ConfigError(f"radar config {where} lacks required keys {missing}")
        kwargs = {k: shape[k] for k in _INFINEON_KEYS if k in shape}
        for k in ("num_samples_per_chirp", "num_chirps_per_frame", "tx_power_level"):
            v = kwargs[k]
            if isinstance(v, float) and v.is_integer():
                kwargs[k] = int(v)
        kwargs.update(extra)
        return cls._build(kwargs, f" (in {where})")

    def describe(self) -> str:
        """A short human-readable summary with the derived values."""
        return (
            f"{self.start_frequency_Hz / 1e9:.3f}-{self.end_frequency_Hz / 1e9:.3f} GHz, "
            f"{self.num_rx} RX, {self.num_chirps_per_frame} chirps x {self.num_samples_per_chirp} "
            f"samples @ {self.sample_rate_Hz / 1e6:g} MHz, PRT {self.chirp_repetition_time_s * 1e6:.2f} us, "
            f"{self.frame_rate_Hz:.2f} frames/s | slope {self.slope_Hz_per_s:.4g} Hz/s, "
            f"range res {self.range_resolution_m * 100:.2f} cm, max range {self.max_range_m:.2f} m, "
            f"v res {self.velocity_resolution_m_s:.3f} m/s, v max +-{self.max_velocity_m_s:.2f} m/s"
        )
