"""The effect catalog: one entry per effect, in a fixed draw order, extensible without moving any draw."""

from __future__ import annotations

from dataclasses import dataclass

import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.sensor.effects import ChirpNonlinearity
from radaraug.sensor.effects.base import HARDWARE_ORDER
from radaraug.sim import catalog as catalog_module
from radaraug.sim.catalog import BY_NAME, ENTRIES, Catalog, CatalogEffect, register
from radaraug.sim.priors import log_uniform, span
from radaraug.sim.randomization import TwinRandomization

CFG = RadarConfig.bgt60tr13c()


def test_the_draw_order_is_pinned() -> None:
    # Reordering ENTRIES changes every randomized item of every seed (tests/sim/test_streams.py).
    assert [e.name for e in ENTRIES] == ["spur_tone", "interference", "vibrating_clutter", "rx_gain_phase_mismatch",
                                         "frame_drift", "wide_levels", "static_phase_noise"]
    assert list(BY_NAME)[:len(ENTRIES)] == [e.name for e in ENTRIES]


def test_each_entry_round_trips_and_its_stages_have_a_hardware_place() -> None:
    cat = Catalog()
    assert Catalog.from_dict(cat.to_dict()) == cat and list(cat) == list(BY_NAME)
    for name, entry in cat.items():
        assert type(entry).from_dict(entry.to_dict()) == entry
        values = entry.draw(torch.Generator().manual_seed(0), scale=1.0) if entry.probability else None
        values = values or entry.draw_values(torch.Generator().manual_seed(0))
        for stage in type(entry).stages(values, CFG):
            assert stage.name == name and name in HARDWARE_ORDER
        assert set(type(entry).record(values, CFG))  # every entry records what it drew


def test_centred_on_a_fit_gives_valid_entries() -> None:
    fits = {"spur_tone": {"freq_Hz": 2e5, "amplitude_counts": 3.0},
            "interference": {"probability": 0.1, "amplitude_counts": 50.0, "duration_s": 4e-6},
            "vibrating_clutter": {"range_m": 2.5, "level_dB": -90.0, "displacement_m": 1e-3, "vibration_Hz": 30.0},
            "rx_gain_phase_mismatch": {"gain_dB": [0.0, 1.0, -1.0], "phase_rad": [0.0, 0.3, -0.2]},
            "frame_drift": {"gain_rms_dB": 0.3, "dc_rms_counts": 1.0}}
    cat = Catalog()
    for name, fitted in fits.items():
        changes = cat[name].centred_on(fitted, CFG, 0.7)
        assert changes is not None and changes["probability"] == 0.7
        moved = cat[name].replace(**changes)  # checked: every band is a valid range
        assert moved != cat[name]
    assert cat["spur_tone"].centred_on({}, CFG, 0.7) is None  # nothing to centre on
    assert cat["wide_levels"].centred_on({}, CFG, 0.7) is None  # diagnose fits no such effect


def test_scale_and_unknown_names_are_checked() -> None:
    with pytest.raises(ConfigError, match="unknown effect"):
        Catalog(fan={"probability": 1})
    with pytest.raises(ConfigError, match="catalog.scale"):
        Catalog(scale=2.0)
    with pytest.raises(ConfigError, match="catalog must be a mapping"):
        Catalog.from_dict([1, 2])


def test_a_registered_entry_draws_last_and_moves_no_other_draw() -> None:
    before = [TwinRandomization().item(4, i, 1) for i in range(30)]

    @dataclass
    class RipplePrior(CatalogEffect):
        """A test entry."""

        name = "chirp_nonlinearity"
        probability: float = 0.0
        ripple_Hz: tuple[float, float] = span(1e4, 4e5, positive=True)

        def draw_values(self, g):
            return {"deviation_Hz": 1e4, "ripple_Hz": log_uniform(self.ripple_Hz, g), "phase_rad": 0.0}

        @classmethod
        def stages(cls, values, config):
            return [ChirpNonlinearity(**values)]

    register(RipplePrior)
    try:
        assert list(BY_NAME)[-1] == "chirp_nonlinearity"
        assert [TwinRandomization().item(4, i, 1) for i in range(30)] == before  # probability 0: unchanged
        on = TwinRandomization(catalog={"chirp_nonlinearity": {"probability": 1.0}})
        for i, old in enumerate(before):
            d = on.item(4, i, 1)
            assert {k: v for k, v in d.catalog.items() if k != "chirp_nonlinearity"} == dict(old.catalog)
            assert 1e4 <= d.catalog["chirp_nonlinearity"]["ripple_Hz"] <= 4e5
            assert "chirp_nonlinearity" in [e.name for e in d.catalog_effects(CFG)]
        with pytest.raises(ConfigError, match="already has"):
            register(RipplePrior)
    finally:
        del catalog_module.BY_NAME["chirp_nonlinearity"]
    with pytest.raises(ConfigError, match="CatalogEffect"):
        register(dict)  # type: ignore[arg-type]
