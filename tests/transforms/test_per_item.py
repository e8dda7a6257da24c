"""Per-item augmentation generators and the use_generator scope."""

from __future__ import annotations

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.transforms import CalibratedDR, RandomDR
from radaraug.transforms._rng import use_generator
from radaraug.transforms.per_item import augmentation_generator, augmentation_seed, check_augmentation


def test_augmentation_seeds_are_a_pure_function_of_seed_index_epoch() -> None:
    assert augmentation_seed(0, 5, 1) == augmentation_seed(0, 5, 1)
    seeds = {augmentation_seed(s, i, e) for s in range(3) for i in range(20) for e in range(3)}
    assert len(seeds) == 3 * 20 * 3  # no collisions between neighbours
    a = torch.rand(4, generator=augmentation_generator(1, 2, 3))
    b = torch.rand(4, generator=augmentation_generator(1, 2, 3))
    assert torch.equal(a, b)


def test_use_generator_wins_over_seed_user_generator_and_global_rng() -> None:
    x = torch.full((2, 3, 8, 4), -200.0)
    own = CalibratedDR(-50.0, 5.0, seed=11)
    user = RandomDR(generator=torch.Generator().manual_seed(3))
    glob = CalibratedDR(-50.0, 5.0)
    for t in (own, user, glob):
        with use_generator(torch.Generator().manual_seed(9)):
            first = t(x)
        with use_generator(torch.Generator().manual_seed(9)):
            again = t(x)
        assert torch.equal(first, again)
        with use_generator(torch.Generator().manual_seed(10)):
            assert not torch.equal(t(x), first)
    # Outside the scope each draws from its own source again.
    assert not torch.equal(own(x), own(x))


def test_bad_modes_are_config_errors() -> None:
    with pytest.raises(ConfigError, match="augmentation must be"):
        check_augmentation("per-worker", "here")
    with pytest.raises(TypeError):
        with use_generator(3):  # type: ignore[arg-type]
            pass
