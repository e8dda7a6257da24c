"""Observable counting labels: people a detector finds apart, on maps whose answer is known by construction."""

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.sim import SimulatedRadarDataset
from radaraug.training import TwinSplits
from radaraug.training.observable import _regions, observable_counts, person_range_bins

R, D, RX = 40, 32, 3


def _maps(n: int, seed: int = 0) -> torch.Tensor:
    """Per-RX dB maps of complex-Gaussian noise at -100 dB: ``(n, rx, R, D)``."""
    g = torch.Generator().manual_seed(seed)
    power = -torch.log(torch.rand(n, RX, R, D, generator=g).clamp_min(1e-12))  # exponential: |noise|^2
    return -100 + 10 * torch.log10(power)


def _blob(maps: torch.Tensor, i: int, r: int, d: int, db: float, width: int = 1) -> None:
    maps[i, :, r - width: r + width + 1, d] = -100 + db


def test_regions_are_eight_connected():
    over = torch.zeros(1, 6, 6, dtype=torch.bool)
    over[0, 0, 0] = over[0, 1, 1] = True  # diagonal neighbours: one region
    over[0, 4, 4] = over[0, 4, 5] = True  # another
    lab = _regions(over)[0]
    assert lab[0, 0] == lab[1, 1] != 0 and lab[4, 4] == lab[4, 5] != 0 and lab[0, 0] != lab[4, 4]
    assert int((lab > 0).sum()) == 4


def test_lowered_to_what_the_maps_show_apart():
    n_empty = 40
    maps = _maps(n_empty + 4)
    counts = torch.tensor([0] * n_empty + [2, 2, 2, 1])
    bins = [[]] * n_empty + [[10, 30], [10, 30], [20, 22], [30]]
    e = n_empty
    _blob(maps, e, 10, 5, 40.0)      # item e: both people 40 dB over the floor, 20 bins apart -> 2
    _blob(maps, e, 30, 25, 40.0)
    _blob(maps, e + 1, 10, 5, 40.0)  # item e+1: the second person left at the noise -> 1
    maps[e + 2, :, 19:24, 8] = -60.0  # item e+2: one ridge over both people's ranges -> one region -> 1
    counts_out, threshold = observable_counts(maps, counts, bins, blank_zero_doppler=1)
    # noise-only maxima of ~1,000 cells of 3 averaged exponentials sit ~10 dB over the median (not 40)
    assert 5 < threshold < 20
    assert counts_out[:e].tolist() == [0] * e
    assert counts_out[e:].tolist() == [2, 1, 1, 1]  # a one-person item stays one even unseen


def test_zero_doppler_and_excised_cells_do_not_count():
    maps = _maps(41)
    counts = torch.tensor([0] * 40 + [2])
    _blob(maps, 40, 10, 5, 40.0)
    _blob(maps, 40, 30, D // 2, 40.0)  # the second person on zero Doppler: blanked
    out, _ = observable_counts(maps, counts, [[]] * 40 + [[10, 30]])
    assert int(out[40]) == 1
    _blob(maps, 40, 30, 25, 40.0)
    excise = torch.zeros(R, D, dtype=torch.bool)
    excise[29:32, 25] = True  # an empty room's persistent line there
    assert int(observable_counts(maps, counts, [[]] * 40 + [[10, 30]], excise=excise)[0][40]) == 1
    assert int(observable_counts(maps, counts, [[]] * 40 + [[10, 30]])[0][40]) == 2


def test_bad_input_is_a_clear_error():
    maps = _maps(3)
    with pytest.raises(ConfigError, match="no empty item"):
        observable_counts(maps, torch.tensor([1, 1, 2]), [[3], [4], [5, 6]])
    with pytest.raises(ConfigError, match="one range bin per person"):
        observable_counts(maps, torch.tensor([0, 1, 2]), [[], [4], [5]])
    with pytest.raises(ConfigError, match="count_labels"):
        TwinSplits(count_labels="seen")


def test_person_range_bins_are_the_people_slant_ranges():
    ds = SimulatedRadarDataset("corridor", length=12, seed=3)
    step = float(ds.config.range_resolution_m)
    radar = ds.twin.scene.radar.position.double()
    for i in range(12):
        sc = ds.scenario(i)
        bins = person_range_bins(ds, i)
        assert len(bins) == sc.count
        for b, person in zip(bins, sc.people):
            c = person.ellipsoids(torch.zeros(1, dtype=torch.float64)).centers.reshape(-1, 3).double()
            # every body ellipsoid lies within a body's size (1 m) of the binned range
            assert ((c - radar).norm(dim=-1) / step - b).abs().max() * step < 1.0
