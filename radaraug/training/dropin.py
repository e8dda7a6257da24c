"""The measured chain for your own training loop: train and test transforms and the twin that goes with them.

:func:`training_chains` builds, from the empty-room capture, what the recipes train and test with
(floor-relative maps, the capture's persistent lines excised, the method's DR with CDR's matched floor
on a quiet twin, the clip range estimated on the twin, twin randomization on), as plain transforms and
a simulated dataset, in the spirit of torchvision's ``weights.transforms()``. docs/training.md,
"In your own loop".
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Sequence
from typing import Any

import torch
from torch import nn

from radaraug import recipes
from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.training.methods import Method


@dataclasses.dataclass
class TrainingChains:
    """Transforms and twin of the measured chain (built by :func:`training_chains`).

    Attributes:
        train: raw frames ``(..., rx, chirps, samples)`` -> the method's DR -> images ``(..., 3, H, W)``.
        test: raw frames -> images, no DR (captures, and simulated validation as the recipes score it).
        config: the radar config (the calibration capture's).
        clip_range_db: the ``[vmin, vmax]`` both chains clip to (estimated on the twin after the DR).
        excise: the calibration capture's persistent cells, or None.
        dr: the method's DR on per-RX dB maps (None for ``rt``).
        method: the method.
    """

    train: nn.Module
    test: nn.Module
    config: RadarConfig
    clip_range_db: tuple[float, float]
    excise: torch.Tensor | None
    dr: nn.Module | None
    method: str
    _datamodule: Any = dataclasses.field(repr=False, default=None)

    def simulated(self, length: int, *, seed: int = 0, transform: nn.Module | None = None) -> Any:
        """The twin's dataset at this config: ``length`` items ``(image, people count)``, item ``i`` a function of ``(seed, i)``.

        Args:
            length: items.
            seed: the simulated set's seed.
            transform: applied to each item's raw frames (default: :attr:`train`). Its random draws are a
                function of ``(seed, i, epoch)``: call the dataset's ``set_epoch(epoch)`` before each epoch.
        """
        ds = self._datamodule.simulated_dataset(length, seed)
        ds.transform = self.train if transform is None else transform
        ds.augmentation = "per_item"  # the DR's draws of item i from (seed, i, epoch): call set_epoch each epoch
        return ds


def training_chains(calibration: str | os.PathLike, method: str | Method = "randomdr", *, task: str = "occupancy",
                    image_size: Sequence[int] | None = (64, 32), estimate_items: int = 256, seed: int = 0,
                    cache_dir: str | os.PathLike | None = None, progress: bool = False,
                    **data: Any) -> TrainingChains:
    """The recipes' measured chain as transforms, from the empty-room capture (or its calibration record).

    Simulates ``estimate_items`` twin items (cached) to estimate the clip range (and CDR's matched floor).

    Args:
        calibration: the empty-room capture (radaraug HDF5 or Infineon recording), or its calibration
            record (JSON, from ``radaraug calibrate`` / ``fit-cdr``): the config, excision mask and CDR's floor
            come from it (a record serves what it holds; a warning names what it lacks).
        method: ``rt``, ``randomdr`` (default) or ``cdr`` (the recipe's method), or a method object
            (:mod:`radaraug.training.methods`) that replaces the recipe's of its name.
        task: ``occupancy`` or ``counting`` (the recipe whose settings are taken).
        image_size: network input ``(H, W)`` (None: the RD map's size).
        estimate_items: twin items that estimate the clip range.
        seed: seed of the DR draws and the estimation items.
        cache_dir: where those items are cached (None: the user cache folder).
        progress: progress bars while simulating.
        **data: any other ``RadarDataModule`` key, merged into the recipe's key by key (e.g.
            ``image={"representation": "paper"}``).

    Raises:
        ConfigError: an unknown method or key, or a record without what the method needs.
        CaptureError: the capture cannot be read.
    """
    from radaraug.training.data import RadarDataModule

    given = method if isinstance(method, Method) else None
    method = method.name if isinstance(method, Method) else method
    if method == "cdr_profile":
        raise ConfigError("training_chains: cdr_profile's twin is fitted by radaraug diagnose; use the recipes")
    recipe = dict(recipes.compose(f"{task}_{method}").get("data", {}))
    kw = recipes.merge(recipe, {
        "calibration": str(calibration), "test": [], "seed": int(seed),
        "twin": {"train_items": int(estimate_items), "val_items": 0, "seed": int(seed), "progress": progress},
        "image": {"size": None if image_size is None else [int(v) for v in image_size]},
        "cache_dir": None if cache_dir is None else str(cache_dir)})
    kw = recipes.merge(kw, data)  # key by key: twin={"randomization": {"people": ...}} keeps the recipe's catalog
    dm = RadarDataModule.from_recipe(kw if given is None else kw | {"method": given})
    dm.setup("fit")
    assert dm.image is not None and dm.config is not None and dm.clip is not None
    rd = dm.rd_chain()
    image: list[nn.Module] = list(dm.image.children())
    train: list[nn.Module] = [rd, *([dm.dr] if dm.dr is not None else []), *image]
    return TrainingChains(train=nn.Sequential(*train), test=nn.Sequential(rd, *image), config=dm.config,
                          clip_range_db=dm.clip, excise=dm.excise, dr=dm.dr, method=dm.method.name, _datamodule=dm)
