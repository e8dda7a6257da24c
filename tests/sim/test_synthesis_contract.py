"""The synthesis' error contract: the fast synthesis' error stays >= 30 dB under the mean noise cell.

Against the exact per-sample sum, in every range-Doppler cell, with the twin as it runs (two walkers,
diffuse clutter, shadowing, motion inside the frame): the contract that chooses ``DEFAULT_TAYLOR_TOL``
(docs/simulation.md, "The synthesis' error contract"; ``benchmarks/synthesis_contract_cpu.json``).
"""

from __future__ import annotations

import pytest

from radaraug.bench.contract import CONTRACT_CONFIGS, CONTRACT_DB, contract_margin
from radaraug.config import RadarConfig

#: The binding config: at the highest IF gain the receiver's own noise is lowest against the paths.
BINDING = "IF 60 dB"


def test_the_default_tolerance_meets_the_contract_where_it_binds() -> None:
    r = contract_margin(RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[BINDING]), name=BINDING, frames=1)
    assert r.margin_dB >= CONTRACT_DB, r


def test_the_contract_fails_a_tolerance_loosened_past_it() -> None:
    # At 1e-2 the binding config's worst cell is ~13 dB under the noise (the record): the check sees it.
    r = contract_margin(RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[BINDING]), name=BINDING, frames=1, taylor_tol=1e-2)
    assert r.margin_dB < CONTRACT_DB, r


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CONTRACT_CONFIGS))
def test_every_config_meets_the_contract(name: str) -> None:
    r = contract_margin(RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[name]), name=name, frames=2)
    assert r.margin_dB >= CONTRACT_DB, r


@pytest.mark.slow
def test_a_near_walker_meets_the_contract() -> None:
    # Frames 75-76: the walker coming toward the radar is ~1.5 m away (the strongest moving path).
    r = contract_margin(RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[BINDING]), name="near", frames=2, start_frame=75)
    assert r.margin_dB >= CONTRACT_DB, r


@pytest.mark.slow
def test_noise_referenced_orders_keep_one_margin_for_near_and_far_walkers() -> None:
    # FMCWReceiver(noise_tol=...): the orders follow the noise, so the margin no longer falls with the
    # strongest moving path (relative orders: 65.4 vs 57.9 dB at 1e-5, 34.7 vs 16.5 at 1e-3).
    cfg = RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[BINDING])
    far, near = (contract_margin(cfg, frames=2, start_frame=s, noise_tol=3e-3) for s in (10, 75))
    assert far.margin_dB >= CONTRACT_DB and near.margin_dB >= CONTRACT_DB
    assert abs(far.margin_dB - near.margin_dB) < 6.0, (far, near)
