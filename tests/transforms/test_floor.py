"""FloorRelative and the matched CDR floor against closed forms (not against radaraug's own output)."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.transforms import FloorRelative
from radaraug.transforms import functional as F
from radaraug.transforms.floor_fit import floor_values, matched_floor_quantiles
from radaraug.transforms.functional._floor import kept_cells


def exp_noise_db(shape: tuple[int, ...], mean_db: float, seed: int) -> torch.Tensor:
    """dB values of exponential power with mean ``mean_db`` (a receiver's noise in one RD cell)."""
    g = torch.Generator().manual_seed(seed)
    power = torch.empty(shape, dtype=torch.float64).exponential_(generator=g)
    return mean_db + 10 * torch.log10(power)


def test_floor_relative_removes_level_gain_and_skirt_keeps_the_mover() -> None:
    doppler = 32
    x = exp_noise_db((4, 64, doppler), -100.0, seed=0)
    x[:, 10, :] += 20.0  # a phase-noise skirt: a whole range row lifted across Doppler
    x[:, 30, 20] = -60.0  # a mover 40 dB above the floor, 4 bins off zero Doppler
    x[:, 12, doppler // 2] = -30.0  # a static return at zero Doppler
    y = F.floor_relative(x)
    # noise in dB has its median at 10 log10(ln 2) dB re the mean power (closed form): every row
    # referenced to its own median sits at 0 dB, skirt row included, whatever the absolute level
    assert float(y[:, 10].median()) == pytest.approx(0.0, abs=0.5)
    assert float(y[:, 40].median()) == pytest.approx(0.0, abs=0.5)
    mover = float(y[:, 30, 20].mean())
    assert mover == pytest.approx(-60.0 - (-100.0 + 10 * math.log10(math.log(2))), abs=1.0)
    assert bool((y[..., doppler // 2 - 1: doppler // 2 + 2] == 0).all())  # zero Doppler +-1 blanked
    # a common gain or floor shift changes nothing
    torch.testing.assert_close(F.floor_relative(x + 7.5), y)


def test_floor_relative_blanking_options_and_refusals() -> None:
    x = exp_noise_db((2, 8, 16), -90.0, seed=1)
    kept = F.floor_relative(x, blank_zero_doppler=0)
    assert bool((kept[..., 8] != 0).any())
    wide = F.floor_relative(x, blank_zero_doppler=3)
    assert bool((wide[..., 5:12] == 0).all()) and bool((wide[..., 4] != 0).any())
    with pytest.raises(ConfigError, match="bins"):
        FloorRelative(blank_zero_doppler=-1)
    with pytest.raises(ConfigError, match="bins"):
        F.floor_relative(x, blank_zero_doppler=1.5)  # type: ignore[arg-type]
    assert FloorRelative(2).chain_spec() == {"name": "FloorRelative", "blank_zero_doppler": 2}


@pytest.mark.parametrize("twin_db", [-106.0, -101.0])
def test_matched_floor_makes_max_of_twin_and_clamp_the_captures_law(twin_db: float) -> None:
    cap = exp_noise_db((400_000,), -100.0, seed=2)
    twin = exp_noise_db((400_000,), twin_db, seed=3)
    q_cap = torch.quantile(cap[:200_000], torch.linspace(0, 1, 1025, dtype=torch.float64))
    q_n = matched_floor_quantiles(q_cap, twin[:200_000])
    assert q_n.shape == (1025,) and bool((q_n.diff() >= 0).all())
    n = F.empirical_floor((200_000,), q_n, like=cap, generator=torch.Generator().manual_seed(4))
    out = torch.maximum(twin[200_000:], n)
    for p in (0.05, 0.5, 0.9, 0.99):
        # the closed form of the capture's law, 10 log10(-ln(1 - p)) dB re its mean power
        expect = -100.0 + 10 * math.log10(-math.log1p(-p))
        assert float(torch.quantile(out, p)) == pytest.approx(expect, abs=0.3), p


def test_matched_floor_stays_out_of_a_twin_that_already_has_the_floor() -> None:
    cap = exp_noise_db((200_000,), -100.0, seed=5)
    q_cap = torch.quantile(cap, torch.linspace(0, 1, 1025, dtype=torch.float64))
    q_n = matched_floor_quantiles(q_cap, exp_noise_db((200_000,), -98.0, seed=6))  # twin 2 dB above
    # nothing to add: the clamp's draws sit below the twin's floor (the paper's clamp would add a second floor)
    assert float(q_n[512]) < -100.0 - 15


def test_floor_values_leave_the_zero_doppler_main_lobe_out() -> None:
    maps = torch.zeros(2, 3, 4, 16)
    maps[..., 6:11] = 50.0  # zero Doppler (8) and its Hann main lobe +- 2
    v = floor_values(maps, "hann")
    assert v.numel() == 2 * 3 * 4 * (16 - 5) and float(v.max()) == 0.0


def test_persistent_cells_mark_lines_of_the_empty_room_not_its_noise() -> None:
    maps = exp_noise_db((40, 64, 32), -100.0, seed=7)
    maps[:, 20, 5] += 25.0  # a spur's line, in every frame
    maps[:, 33, [10, 22]] += 8.0  # a fan's two Doppler lines
    maps[7, 50, 3] += 40.0  # one frame's event: not persistent
    mask = F.persistent_cells(maps, threshold_db=3.0)
    # the median over 40 frames of a noise cell referenced to its row's median is ~0 dB, far below 3 dB
    assert mask.shape == (64, 32) and set(map(tuple, mask.nonzero().tolist())) == {(20, 5), (33, 10), (33, 22)}
    y = F.floor_relative(maps, excise=mask)
    assert bool((y[:, 20, 5] == 0).all()) and bool((y[7, 50, 3] > 30).all())
    t = FloorRelative(excise=mask)
    torch.testing.assert_close(t(maps), y)
    assert t.chain_spec()["excised_cells"] == 3
    with pytest.raises(ConfigError, match="excise"):
        F.floor_relative(maps, excise=mask[:10])
    with pytest.raises(ConfigError, match="frames"):
        F.persistent_cells(maps[:2])



@pytest.mark.parametrize("bins", [0, 1, 2])
def test_kept_cells_are_the_cells_floor_relative_leaves(bins):
    x = torch.randn(6, 16, generator=torch.Generator().manual_seed(bins)) * 10 - 100
    excise = torch.zeros(6, 16, dtype=torch.bool)
    excise[2, 3] = excise[4, 12] = True
    keep = kept_cells(6, 16, bins, excise)
    # what floor_relative sets to 0 dB: the excised cells and zero Doppler +-bins (none for 0), whatever the map
    assert bool((F.floor_relative(x, bins, excise)[~keep] == 0).all())
    assert int((~keep).sum()) == 2 + (6 * (2 * bins + 1) if bins else 0)
    assert bool(keep[:, 16 // 2 - bins: 16 // 2 + bins + 1].any()) == (bins == 0)
