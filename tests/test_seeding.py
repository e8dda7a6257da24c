"""The one seed mixer (radaraug._seeding) serves the simulation and the transforms."""

import pytest

from radaraug._seeding import mix, splitmix64
from radaraug.sim.seeding import item_seed
from radaraug.transforms._rng import mix_seed
from radaraug.transforms.per_item import augmentation_seed


def test_splitmix64_reference_outputs():
    # The first two outputs of SplitMix64 seeded with 0 (Steele, Lea & Flood; Vigna's splitmix64.c).
    assert splitmix64(0) == 0xE220A8397B1DCDAF
    assert splitmix64(0x9E3779B97F4A7C15) == 0x6E789E6AA1B965F4


@pytest.mark.parametrize(
    "args, value",
    [
        # item_seed values every recorded simulation was made with (computed before the mixer moved)
        ((0, 0, 0), 1279368494785126216),
        ((1, 2, 0), 8306669473171521968),
        ((7, 123456, 3), 4955779320567289510),
        ((-1, 5, 1), 1281752355951115307),
        ((2**64 + 3, 2**70, 9), 7296703906930011858),
    ],
)
def test_simulated_item_seeds_are_unchanged(args, value):
    assert item_seed(*args) == value
    s, i, st = args
    m = (1 << 64) - 1
    assert value == splitmix64(splitmix64(splitmix64(s & m) ^ (i & m)) ^ st) >> 1


def test_transform_seeds_use_the_same_mixer_and_stay_apart():
    assert 0 <= mix_seed(11, 123) < 2**63 and mix_seed(11, 123) == mix(11, 123, 0x574B5253)
    assert augmentation_seed(0, 5, 1) == mix(0, 5, 1, 0x41554721)
    # three uses of (seed, index) never give the same seed
    assert len({item_seed(3, 4), augmentation_seed(3, 4, 0), mix_seed(3, 4)}) == 3
    with pytest.raises(ValueError):
        mix()
