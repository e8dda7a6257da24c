"""Twin randomization's effect catalog: each drawn effect varies what it claims (a spur line, an
interferer's floor in the chirps it hits, the per-RX power ratio, frame-to-frame power, a fan's
Doppler at its range, the room's phase-noise skirt, the ADC-side floor), sits at its hardware
position, is reproducible per (seed, index), round-trips through dicts, and probability 0 gives the
items of the twin without the catalog bit for bit."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
import torch
import yaml

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import ConfigError
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import (
    FrameDrift,
    Interference,
    PhaseNoise,
    RxGainPhaseMismatch,
    SpurTone,
    ThermalNoise,
    VibratingClutter,
)
from radaraug.sensor.effects.base import insert_in_order
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.catalog import BY_NAME
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.item_signal import item_receiver, static_scatterer_paths
from radaraug.sim.randomization import ItemDraw, TwinRandomization
from radaraug.sim.seeding import item_generator
from radaraug.sim.twin import DigitalTwin

FAST = {"tracer_options": {"diffuse": False}, "shadowing": False}
ALL_ON = {"catalog": {name: {"probability": 1.0} for name in BY_NAME}}
COUNTS = 4095 / 2  # ADC counts per SDK float unit
BASE = ItemDraw(0, 0.0, 0.0, ())  # empty scene, no offsets, no catalog effect


def _with(draw: ItemDraw, **effects: dict | None) -> ItemDraw:
    """``draw`` carrying ``effects`` (``{name: values}`` as the catalog entries draw them; None removes one)."""
    catalog = {**draw.catalog, **effects}
    return dataclasses.replace(draw, catalog={k: v for k, v in catalog.items() if v is not None})


def _spur(frac: float, amp: float, phase: float) -> dict:
    return {"freq_nyquist": frac, "amplitude_counts": amp, "phase_rad": phase}


def _mismatch(gains: tuple, phases: tuple) -> dict:
    return {"gain_dB": gains, "phase_deg": phases}


@pytest.fixture(scope="module")
def twin() -> DigitalTwin:
    """The corridor with the default BGT60TR13C receiver (noise, phase noise, ADC)."""
    return DigitalTwin(Scene.builtin("corridor"), **FAST)


def _sim(twin: DigitalTwin, draw: ItemDraw, frames: int = 1, seed: int = 0) -> torch.Tensor:
    times = twin.frame_times(range(frames))
    return twin.simulate([], times, generators=torch.Generator().manual_seed(seed), draw=draw)


def _quiet_chain(config, *, phase_noise: bool = False) -> list:
    """The default chain's linear stages and thermal noise at 0 K (output linear in the paths)."""
    effects = []
    for e in default_effects(config):
        if e.kind == "nonlinear" or e.name in ("dc_offset", "adc_noise") or (e.name == "phase_noise" and not phase_noise):
            continue
        if e.name == "thermal_noise":
            e = ThermalNoise(noise_figure_dB=12.0, temperature_K=0.0)
        if e.name == "phase_noise":
            e = PhaseNoise(freq_noise_rms_Hz=0.0)
        effects.append(e)
    return effects


def _rd_db(x: torch.Tensor) -> torch.Tensor:
    from radaraug.transforms import RangeDoppler, ToDecibels

    return ToDecibels()(RangeDoppler()(x))


def _range_bin(config, range_m: float) -> int:
    axis = config.range_axis_m()
    return min(range(len(axis)), key=lambda k: abs(float(axis[k]) - range_m))


# ------------------------------------------------------------------------------ configuration
def test_catalog_round_trip_and_errors() -> None:
    r = TwinRandomization(catalog={"scale": 0.5, "spur_tone": {"probability": 1}, "interference": {
        "duration_s": [1e-6, 2e-6]}, "static_phase_noise": {"paths": 2}})
    assert r.catalog["interference"].duration_s == (1e-6, 2e-6) and r.catalog["spur_tone"].probability == 1.0
    d = r.to_dict()
    assert d["catalog"]["scale"] == 0.5 and d["catalog"]["interference"]["duration_s"] == [1e-6, 2e-6]
    assert list(d["catalog"]) == ["scale", *BY_NAME]  # keyed by effect name, in draw order
    assert TwinRandomization.from_dict(yaml.safe_load(yaml.safe_dump(d))) == r
    assert TwinRandomization.from_dict(TwinRandomization().to_dict()) == TwinRandomization()
    assert not TwinRandomization.off().enabled
    for bad, name in (({"scale": 1.5}, "catalog.scale"),
                      ({"spur_tone": {"probability": -0.1}}, "catalog.spur_tone.probability"),
                      ({"interference": {"probability": "often"}}, "catalog.interference.probability"),
                      ({"spur_tone": {"freq_nyquist": [0.5, 1.2]}}, "catalog.spur_tone.freq_nyquist"),
                      ({"spur_tone": {"amplitude_counts": [0, 5]}}, "catalog.spur_tone.amplitude_counts"),  # log
                      ({"interference": {"chirp_probability": [0.1, 2]}}, "interference.chirp_probability"),
                      ({"vibrating_clutter": {"vibration_Hz": [60, 5]}}, "vibrating_clutter.vibration_Hz"),
                      ({"rx_gain_phase_mismatch": {"phase_deg": [-200, 30]}}, "rx_gain_phase_mismatch.phase_deg"),
                      ({"frame_drift": {"dc_rms_counts": [-1, 2]}}, "frame_drift.dc_rms_counts"),
                      ({"static_phase_noise": {"paths": 0}}, "static_phase_noise.paths"),
                      ({"spur": {"probability": 0.3}}, "spur"),
                      ({"spur_tone": {"freq_Hz": [1, 2]}}, "freq_Hz")):
        with pytest.raises(ConfigError, match=name):
            TwinRandomization.from_dict({"catalog": bad})


def test_receiver_checks_for_the_catalog() -> None:
    cfg = Scene.builtin("corridor").config
    no_adc = FMCWReceiver(cfg, effects=[e for e in default_effects(cfg) if e.name != "adc_noise"])
    with pytest.raises(ConfigError, match="adc_noise"):
        SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_adc},
                              randomization=TwinRandomization(room={"variants": 1}))
    SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_adc},
                          randomization=TwinRandomization(room={"variants": 1},
                                                          catalog={"wide_levels": {"adc_noise_offset_dB": (0, 0)}}))
    no_pn = FMCWReceiver(cfg, effects=[e for e in default_effects(cfg) if e.name != "phase_noise"])
    with pytest.raises(ConfigError, match="static_phase_noise.probability"):
        SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_pn},
                              randomization=TwinRandomization(room={"variants": 1},
                                                              levels={"phase_noise_rms_Hz": (0, 0)}))
    SimulatedRadarDataset("corridor", length=2, twin_options={**FAST, "receiver": no_pn},
                          randomization=TwinRandomization(room={"variants": 1}, levels={"phase_noise_rms_Hz": (0, 0)},
                                                          catalog={"scale": 0}))


# ------------------------------------------------------------------------------ draws
def test_catalog_draws_probabilities_ranges_and_independence() -> None:
    r = TwinRandomization()
    n = 600
    draws = [r.item(7, i, 1) for i in range(n)]
    for name in BY_NAME:
        rate = np.mean([name in d.catalog for d in draws])
        assert abs(rate - (0.5 if name == "static_phase_noise" else 0.3)) < 0.08, (name, rate)  # 4.5 sigma
    assert all((d.static_phase_noise_paths > 0) == ("static_phase_noise" in d.catalog) for d in draws)

    def drawn(name: str) -> np.ndarray:
        return np.array([list(d.catalog[name].values()) for d in draws if name in d.catalog], dtype=object)

    assert max(len(d.effects_dict(Scene.builtin("corridor").config)) for d in draws) >= 4  # several per item
    # Every draw inside its range (log ranges too).
    spur = drawn("spur_tone").astype(float)
    assert spur[:, 0].min() >= 0.01 and spur[:, 0].max() <= 0.99 and np.ptp(spur[:, 0]) > 0.8
    assert spur[:, 1].min() >= 0.3 and spur[:, 1].max() <= 5.0 and np.median(spur[:, 1]) < 2.0  # log-uniform
    inter = drawn("interference").astype(float)
    assert inter[:, 0].min() >= 0.01 and inter[:, 0].max() <= 0.3
    assert inter[:, 1].min() >= 5 and inter[:, 1].max() <= 1000 and inter[:, 2].max() <= 20e-6
    vib = drawn("vibrating_clutter").astype(float)
    assert vib[:, 0].min() >= 0.5 and vib[:, 0].max() <= 10 and vib[:, 3].min() >= 5 and vib[:, 3].max() <= 60
    assert 1e-4 <= vib[:, 2].min() and vib[:, 2].max() <= 3e-3
    mis = drawn("rx_gain_phase_mismatch")
    assert max(abs(g) for m in mis for g in m[0]) <= 1.5 and max(abs(p) for m in mis for p in m[1]) <= 30
    drift = drawn("frame_drift").astype(float)
    assert drift[:, 0].min() >= 0.1 and drift[:, 0].max() <= 1.0 and drift[:, 1].max() <= 4.0
    wide = [d for d in draws if "wide_levels" in d.catalog]
    assert max(abs(d.system_gain_offset_dB) for d in wide) > 9 and max(d.noise_figure_offset_dB for d in wide) > 6
    assert all(d.adc_noise_offset_dB == 0.0 for d in draws if d not in wide)
    assert all(abs(d.system_gain_offset_dB) <= 6 for d in draws if d not in wide)

    # Reproducible per (seed, index); another index or seed differs.
    assert r.item(7, 11, 1) == draws[11] and r.effects(7, 11) == r.effects(7, 11)
    assert r.effects(7, 12) != r.effects(7, 11) and r.effects(8, 11) != r.effects(7, 11)

    # Probability 0 turns the catalog off and leaves the older draws where they were.
    off = TwinRandomization(catalog={"scale": 0})
    legacy = ("variant", "rcs_scale_dB", "scatterers", "phase_noise_rms_Hz")
    for i, d in enumerate(draws[:100]):
        o = off.item(7, i, 1)
        assert o.effects_dict(Scene.builtin("corridor").config) == {} and o.static_phase_noise_paths == 0
        assert all(getattr(o, f) == getattr(d, f) for f in legacy)
        if "wide_levels" not in d.catalog:
            assert (o.system_gain_offset_dB, o.noise_figure_offset_dB) == (d.system_gain_offset_dB,
                                                                           d.noise_figure_offset_dB)
    # One effect's probability does not shift another's draws.
    no_spur = r.replace(catalog={"spur_tone": {"probability": 0}})
    for i, d in enumerate(draws[:100]):
        o = no_spur.item(7, i, 1)
        assert "spur_tone" not in o.catalog and _with(o, spur_tone=d.catalog.get("spur_tone")) == d


def test_catalog_effects_sit_at_their_hardware_position() -> None:
    cfg = Scene.builtin("corridor").config
    draw = _with(BASE, spur_tone=_spur(0.5, 1.0, 0.0),
                 interference={"probability": 0.1, "amplitude_counts": 50.0, "duration_s": 5e-6},
                 vibrating_clutter={"range_m": 2.0, "rcs_dBsm": 0.0, "displacement_m": 1e-3, "vibration_Hz": 20.0,
                                    "phase_rad": 0.0},
                 rx_gain_phase_mismatch=_mismatch(tuple(float(a) for a in range(16)),
                                                  tuple(float(-a) for a in range(16))),
                 frame_drift={"gain_rms_dB": 0.5, "dc_rms_counts": 1.0})
    base = FMCWReceiver(cfg)
    names = [e.name for e in item_receiver(base, 0.0, 0.0, extra_effects=draw.catalog_effects(cfg)).effects]
    assert names == ["tx_rx_leakage", "vibrating_clutter", "phase_noise", "thermal_noise", "system_gain",
                     "rx_gain_phase_mismatch", "if_highpass", "if_gain", "interference", "adc_noise",
                     "anti_alias_lowpass", "frame_drift", "spur_tone", "dc_offset", "adc_quantization",
                     "adc_clipping"]
    assert [e.name for e in base.effects] == [e.name for e in FMCWReceiver(cfg).effects]  # not changed
    effects = {e.name: e for e in draw.catalog_effects(cfg)}
    assert float(effects["spur_tone"].freq_Hz) == pytest.approx(0.5 * cfg.sample_rate_Hz / 2)
    assert isinstance(effects["spur_tone"], SpurTone) and isinstance(effects["interference"], Interference)
    assert isinstance(effects["frame_drift"], FrameDrift)
    mismatch = effects["rx_gain_phase_mismatch"]
    assert isinstance(mismatch, RxGainPhaseMismatch)
    assert mismatch.gain_dB.tolist() == [0.0, 1.0, 2.0]  # antennas 1, 2, 3
    assert mismatch.phase_rad.tolist() == pytest.approx([0.0, -math.pi / 180, -2 * math.pi / 180])
    # The fan's level is the radar equation with the static scatterers' antenna gain: 0 dBsm at 2 m
    # gives the same tone as a 0 dBsm static scatterer at 2 m.
    vib = effects["vibrating_clutter"]
    assert isinstance(vib, VibratingClutter)
    like = Paths(torch.zeros(1, 0, 3), torch.zeros(1, 0, 3), torch.zeros(1, 0, 3, dtype=torch.complex64))
    amp = static_scatterer_paths(cfg, [(2.0, 0.0, 0.0, 0.0)], like).amplitude.abs()
    assert 20 * math.log10(float(amp.mean())) == pytest.approx(float(vib.level_dB), abs=0.05)
    # A profile's own stage of the same name stays; the drawn one comes after it.
    fitted = FMCWReceiver(cfg, effects=insert_in_order(default_effects(cfg), SpurTone(freq_Hz=1e5)))
    names = [e.name for e in item_receiver(fitted, 0.0, 0.0, extra_effects=[SpurTone(freq_Hz=2e5)]).effects]
    assert names.count("spur_tone") == 2 and names.index("dc_offset") == names.index("spur_tone") + 2


# ------------------------------------------------------------------------------ physics
def test_spur_is_a_narrow_line_at_its_beat_frequency(twin) -> None:
    cfg = twin.config
    frac = 0.95
    plain = _sim(twin, BASE)
    spur = _sim(twin, _with(BASE, spur_tone=_spur(frac, 2.0, 0.3)))
    n = cfg.num_samples_per_chirp
    w = torch.hann_window(n, periodic=False, dtype=plain.dtype)

    def profile(x: torch.Tensor) -> torch.Tensor:  # mean power over RX and chirps, per FFT bin
        return torch.fft.rfft((x - x.mean(-1, keepdim=True)) * w, dim=-1).abs().pow(2).mean(dim=(0, 1, 2))

    ratio = 10 * torch.log10(profile(spur) / profile(plain))
    k0 = round(frac * (cfg.sample_rate_Hz / 2) / cfg.sample_rate_Hz * n)
    assert float(ratio[k0 - 1: k0 + 2].max()) > 10.0  # the line
    far = torch.cat([ratio[: k0 - 4], ratio[k0 + 5:]])
    assert float(far.abs().max()) < 0.5  # nothing elsewhere (the same noise draws)


def test_interference_raises_the_floor_of_the_chirps_it_hits(twin) -> None:
    def chirp_energy(x: torch.Tensor) -> torch.Tensor:  # (chirps,): the room (same every chirp) out
        return (x - x.median(-2, keepdim=True).values).pow(2).sum(dim=(0, 1, 3))

    plain = chirp_energy(_sim(twin, BASE))
    hit = chirp_energy(_sim(twin, _with(BASE, interference={"probability": 0.3, "amplitude_counts": 300.0,
                                                            "duration_s": 5e-6})))
    floor = float(plain.median())
    assert int((plain > 3 * floor).sum()) == 0
    n_hit = int((hit > 3 * floor).sum())
    assert 8 <= n_hit <= 32  # ~0.3 x 64 chirps
    assert float(hit.median()) == pytest.approx(floor, rel=0.3)  # the others keep their floor


def test_rx_mismatch_is_exact_on_the_cached_room_and_changes_the_rx_power_ratio() -> None:
    """The drawn mismatch applied to the room's cached signal equals tracing the room with the paths
    through a receiver with that mismatch stage; the per-RX power changes by the drawn gain."""
    scene = Scene.builtin("corridor")
    cfg = scene.config
    quiet = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=_quiet_chain(cfg)), **FAST)
    gains = (1.5, -1.5, 0.5) + (0.0,) * 13
    phases = (20.0, -30.0, 5.0) + (0.0,) * 13
    scatterer = ((7.0, 10.0, 0.0, 5.0),)
    draw = _with(ItemDraw(0, 0.0, 0.0, (), scatterer), rx_gain_phase_mismatch=_mismatch(gains, phases))
    times = quiet.frame_times([0])
    got = quiet.simulate([], times, draw=draw)
    plain = quiet.simulate([], times, draw=_with(draw, rx_gain_phase_mismatch=None))
    chain = insert_in_order(_quiet_chain(cfg), RxGainPhaseMismatch(
        gain_dB=list(gains[:3]), phase_rad=[math.radians(p) for p in phases[:3]]))
    room = quiet.tracer.static_paths().map(lambda t: t.expand(1, *t.shape))
    people = quiet.paths([], times)
    ref = FMCWReceiver(cfg, effects=chain)(Paths.cat([room, static_scatterer_paths(cfg, scatterer, people)]),
                                           frame_start_s=times)
    assert torch.allclose(got, ref, rtol=1e-4, atol=1e-5 * float(ref.abs().max()))
    # At the scatterer's range bin each RX's tone is scaled and turned by its drawn gain and phase (the
    # whole-signal power is not a clean measure: the near-DC leakage's power depends on its phase).
    n = cfg.num_samples_per_chirp
    k = round(float(static_scatterer_paths(cfg, scatterer, people).delay_s.mean()) * cfg.slope_Hz_per_s
              / cfg.sample_rate_Hz * n)
    w = torch.hann_window(n, periodic=False, dtype=got.dtype)

    def tone(x: torch.Tensor) -> torch.Tensor:  # (RX,) complex range-FFT value at the bin, chirp 0
        return torch.fft.rfft(x[0, :, 0] * w, dim=-1)[:, k]

    ratio = tone(got) / tone(plain)
    assert (20 * torch.log10(ratio.abs())).tolist() == pytest.approx(list(gains[:3]), abs=0.2)
    # The IF tone is conj(path): its phase turns by the drawn phase (the mismatch multiplies the IF tone).
    assert torch.rad2deg(ratio.angle()).tolist() == pytest.approx(list(phases[:3]), abs=2.0)
    ratio_db = 10 * torch.log10(tone(got).abs().pow(2) / tone(plain).abs().pow(2))
    assert float(ratio_db[0] - ratio_db[1]) == pytest.approx(gains[0] - gains[1], abs=0.2)  # RX1 / RX2

    # With a walker shadowing the room: the shadow correction gets the mismatch exactly too.
    from radaraug.scene.people import Walker

    shadowed = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=_quiet_chain(cfg)),
                           tracer_options=FAST["tracer_options"], static_signal=quiet.static_signal())
    walker = Walker(height_m=1.8, speed_m_s=1.2, start=(4.1, 0.0), heading_rad=0.0)
    got = shadowed.simulate([walker], times, draw=dataclasses.replace(draw, scatterers=()))
    ref = FMCWReceiver(cfg, effects=chain)(Paths.cat([room, shadowed.frame_paths([walker], times)]),
                                           frame_start_s=times)
    assert shadowed.shadow_signal([walker], times) is not None
    assert torch.allclose(got, ref, rtol=1e-4, atol=1e-5 * float(ref.abs().max()))


def test_frame_drift_changes_frame_to_frame_power(twin) -> None:
    def per_frame(x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        dc = x.mean(dim=(-1, -2))  # (T, RX)
        ac = (x - dc[..., None, None]).pow(2).mean(dim=(1, 2, 3))  # (T,)
        return 10 * torch.log10(ac), dc * COUNTS

    p0, dc0 = per_frame(_sim(twin, BASE, frames=6))
    p1, dc1 = per_frame(_sim(twin, _with(BASE, frame_drift={"gain_rms_dB": 1.0, "dc_rms_counts": 4.0}), frames=6))
    assert float(p0.std()) < 0.05 and float(p1.std()) > 0.3
    assert float(dc0.std(0).max()) < 0.3 and float(dc1.std(0).mean()) > 1.0


def test_vibrating_clutter_puts_energy_off_zero_doppler_at_its_range(twin) -> None:
    cfg = twin.config
    plain = _rd_db(_sim(twin, BASE))[0].amax(0)  # (range, doppler), strongest RX
    fan = _rd_db(_sim(twin, _with(BASE, vibrating_clutter={"range_m": 3.0, "rcs_dBsm": 5.0, "displacement_m": 2e-3,
                                                           "vibration_Hz": 50.0, "phase_rad": 0.4})))[0].amax(0)
    r = _range_bin(cfg, 3.0)
    m = cfg.num_chirps_per_frame
    off = [*range(m // 2 - 8, m // 2 - 1), *range(m // 2 + 2, m // 2 + 9)]  # +-2..8 bins: 80-320 Hz
    assert float((fan[r, off] - plain[r, off]).mean()) > 10.0
    far = _range_bin(cfg, 12.0)
    assert float((fan[far, off] - plain[far, off]).abs().mean()) < 1.0  # only at its range


def test_room_returns_carry_the_phase_noise_skirt(twin) -> None:
    """With the room's strongest returns (the corridor's far wall at ~20 m) passed through the
    phase_noise stage, the range bins around them fill across Doppler; without, the cached room gets no
    skirt. (At the drawn 400 kHz the skirt of this wall is ~3 dB over the floor, as real near-range
    skirts; 1 MHz makes it clear of the noise's spread.)"""
    cfg = twin.config
    strong, _ = twin.strongest_room_paths(4)
    top = int((strong.amplitude.abs() * strong.delay_s).amax(-1).argmax())
    wall = float(strong.delay_s[top].mean()) * SPEED_OF_LIGHT / 2
    assert wall > 15.0
    draw = dataclasses.replace(BASE, phase_noise_rms_Hz=1e6)
    without = _rd_db(_sim(twin, draw))[0].amax(0)
    with_skirt = _rd_db(_sim(twin, _with(draw, static_phase_noise={"paths": 4})))[0].amax(0)
    m = cfg.num_chirps_per_frame
    off = torch.cat([torch.arange(0, m // 2 - 3), torch.arange(m // 2 + 4, m)])
    axis = torch.as_tensor(cfg.range_axis_m())
    near = (axis - wall).abs() < 1.5

    def level(rd: torch.Tensor) -> float:  # mean power (dB) off zero Doppler at the wall's range bins
        return float(10 * torch.log10((10 ** (rd[near][:, off] / 10)).mean()))

    assert level(with_skirt) - level(without) > 4.0
    # The wall's own zero-Doppler return is the cached one's (the paths moved out of the cache and back).
    assert float(with_skirt[near, m // 2].max() - without[near, m // 2].max()) == pytest.approx(0.0, abs=0.3)


def test_moving_room_paths_out_of_the_cache_changes_nothing_else() -> None:
    """Without phase noise, the room's strongest paths through the receiver as paths plus the rest of the
    cached signal equal the cached signal; with a mismatch too (the quadrature less those paths')."""
    scene = Scene.builtin("corridor")
    cfg = scene.config
    quiet = DigitalTwin(scene, receiver=FMCWReceiver(cfg, effects=_quiet_chain(cfg, phase_noise=True)), **FAST)
    mismatch = ((1.0, -0.5, 0.2) + (0.0,) * 13, (25.0, -10.0, 3.0) + (0.0,) * 13)
    for extra in ({}, {"rx_gain_phase_mismatch": _mismatch(*mismatch)}):
        draw = _with(BASE, **extra)
        a = quiet.simulate([], quiet.frame_times([0]), draw=draw)
        b = quiet.simulate([], quiet.frame_times([0]), draw=_with(draw, static_phase_noise={"paths": 4}))
        assert torch.allclose(a, b, rtol=1e-4, atol=1e-5 * float(a.abs().max()))


def test_adc_noise_offset_raises_the_floor(twin) -> None:
    def floor(x: torch.Tensor) -> float:
        return float((x - x.mean(-2, keepdim=True)).std())

    wide = {"system_gain_offset_dB": 0.0, "noise_figure_offset_dB": 0.0, "adc_noise_offset_dB": 6.0}
    assert floor(_sim(twin, _with(BASE, wide_levels=wide))) > 1.5 * floor(_sim(twin, BASE))


# ------------------------------------------------------------------------------ dataset
def test_items_with_every_effect_are_reproducible_and_reported() -> None:
    r = TwinRandomization(room={"variants": 1}, **ALL_ON)
    ds = SimulatedRadarDataset("corridor", length=4, seed=3, twin_options=FAST, randomization=r).prepare()
    x1, y1 = ds[1]
    assert torch.isfinite(x1).all()
    assert torch.equal(ds[1][0], x1)
    fresh = SimulatedRadarDataset("corridor", length=4, seed=3, twin_options=FAST, randomization=r)
    fresh._variant_static = {0: ds.variant_twin(0).static_signal()}  # skip a second room trace
    assert torch.equal(fresh[1][0], x1) and fresh[1][1] == y1
    assert not torch.equal(ds[2][0], x1)
    effects = ds.item_params(1)["effects"]
    assert set(effects) == {"spur_tone", "interference", "vibrating_clutter", "rx_gain_phase_mismatch",
                            "frame_drift", "wide_levels", "static_phase_noise"}
    assert len(effects["rx_gain_phase_mismatch"]["gain_dB"]) == ds.config.num_rx
    json.dumps(ds.item_params(1))


def test_probability_zero_gives_the_items_without_the_catalog() -> None:
    """``catalog.scale = 0`` items are the randomized twin's items before the catalog existed (the
    older draws are untouched, no stage is added); so is any default item that draws no effect."""
    base = {"room": {"variants": 1}}
    off = SimulatedRadarDataset("corridor", length=200, seed=4, twin_options=FAST,
                                randomization=TwinRandomization(catalog={"scale": 0}, **base)).prepare()
    on = SimulatedRadarDataset("corridor", length=200, seed=4, twin_options=FAST,
                               randomization=TwinRandomization(**base))
    on._variant_static = {0: off.variant_twin(0).static_signal()}
    twin = off.variant_twin(0)
    i = next(i for i in range(200) if not on.item_params(i)["effects"])  # ~6 % of items draw none
    j = next(j for j in range(200) if on.item_params(j)["effects"])
    for k in (i, j):
        scenario = off.scenario(k)
        d = off.randomization.item(off.seed, k, scenario.count)
        legacy = ItemDraw(d.variant, d.system_gain_offset_dB, d.noise_figure_offset_dB, d.rcs_scale_dB,
                          d.scatterers, d.phase_noise_rms_Hz)
        assert d == legacy
        ref = twin.simulate(scenario.people, twin.frame_times([0]), generators=item_generator(off.seed, k, stream=1),
                            draw=legacy)[0]
        assert torch.equal(off[k][0], ref)
    assert torch.equal(on[i][0], off[i][0])
    assert not torch.equal(on[j][0], off[j][0])
