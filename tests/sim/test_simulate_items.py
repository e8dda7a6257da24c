"""Many items per call: ``DigitalTwin.simulate_items`` and the dataset's batch fetch against one call per item."""

from __future__ import annotations

import pytest
import torch
from torch.utils.data import DataLoader

from radaraug.sim.catalog import BY_NAME
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.seeding import Stream, item_generator
from radaraug.sim.twin import TwinItem

COUNT = 2 / 4095  # one ADC count in SDK floats
# Every catalog effect on (the RX mismatch turns the people's shadow per item), diffuse clutter off for speed.
ALL_ON = {"room": {"variants": 1}, "catalog": {name: {"probability": 1.0} for name in BY_NAME}}


@pytest.fixture(scope="module")
def dataset() -> SimulatedRadarDataset:
    return SimulatedRadarDataset("corridor", length=40, seed=3, randomization=ALL_ON, batched=True,
                                 twin_options={"tracer_options": {"diffuse": False}}).prepare()


def _items(ds: SimulatedRadarDataset, indices: list[int], frames: int = 1) -> list[TwinItem]:
    rz = ds._drawn_randomization
    assert rz is not None
    twin = ds.variant_twin(0)
    out = []
    for i in indices:
        sc = ds.scenario(i)
        out.append(TwinItem(sc.people, twin.frame_times(range(5 * i, 5 * i + frames)), draw=rz.item(ds.seed, i, sc.count),
                            generators=item_generator(ds.seed, i, stream=Stream.ITEM_NOISE)))
    return out


def test_items_equal_one_call_each(dataset) -> None:
    """Empty rooms, one and two walkers, several frames each, in one call: as one call per item, to an ADC count."""
    twin = dataset.variant_twin(0)
    indices = list(range(8))
    assert {dataset.scenario(i).count for i in indices} == {0, 1, 2}
    many = twin.simulate_items(_items(dataset, indices, frames=3))
    for it, x in zip(_items(dataset, indices, frames=3), many):
        one = twin.simulate(it.people, it.times, generators=it.generators, draw=it.draw)
        assert x.shape == one.shape == (3, *one.shape[1:])
        diff = (x - one).abs()
        # The continuous values agree to float rounding; a sample may round to the neighbouring ADC code.
        assert float(diff.max()) <= COUNT * 1.001
        assert float((diff > 0).double().mean()) < 1e-3


def test_items_without_draws_and_empty_calls(dataset) -> None:
    twin = dataset.variant_twin(0)
    assert twin.simulate_items([]) == []
    items = [TwinItem(dataset.scenario(i).people, twin.frame_times([i]), generators=torch.Generator().manual_seed(i))
             for i in range(4)]
    many = twin.simulate_items(items)
    for i, x in enumerate(many):
        one = twin.simulate(dataset.scenario(i).people, twin.frame_times([i]), generators=torch.Generator().manual_seed(i))
        assert float((x - one).abs().max()) <= COUNT * 1.001


def test_dataset_batch_fetch_is_the_items(dataset) -> None:
    """A DataLoader's batch goes through ``__getitems__``: the same items, in order, to an ADC count."""
    loader = DataLoader(dataset, batch_size=6, shuffle=False)
    x, y = next(iter(loader))
    for k in range(6):
        xi, yi = dataset[k]
        assert int(y[k]) == yi
        assert float((x[k] - xi).abs().max()) <= COUNT * 1.001
    again = dataset.__getitems__([5, 2, 2])
    assert [int(label) for _, label in again] == [dataset[5][1], dataset[2][1], dataset[2][1]]
    assert torch.equal(again[1][0], again[2][0])


def test_unbatched_dataset_fetches_item_by_item(dataset) -> None:
    """The default dataset's batch fetch is one ``dataset[i]`` per item: bit for bit."""
    plain = SimulatedRadarDataset("corridor", length=40, seed=3, randomization=ALL_ON,
                                  twin_options={"tracer_options": {"diffuse": False}})
    got = plain.__getitems__([3, 1])
    assert all(torch.equal(x, plain[i][0]) for (x, _), i in zip(got, [3, 1]))
