"""`SimulatedRadarDataset`: the digital twin as an on-the-fly map-style torch Dataset.

Item ``i`` is a pure function of ``(seed, i)``: its scenario and its receiver noise come from
generators seeded by :func:`radaraug.sim.seeding.item_seed`, never from worker or rank state,
so the same item comes out in any DataLoader worker, process or DDP rank (use a
``DistributedSampler`` to split the indices; nothing else is needed).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import torch
from torch.utils.data import Dataset

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.scene.scene import Scene
from radaraug.sim.scenarios import Scenario, ScenarioSampler
from radaraug.sim.seeding import item_generator
from radaraug.sim.twin import DigitalTwin

TARGETS = ("count", "occupancy", "both", "none")


def load_scene(scene: Scene | str | os.PathLike) -> Scene:
    """A :class:`Scene`, a scene file (``.yaml``/``.yml``/``.json``) or a built-in scene name.

    Raises:
        SceneError: missing or invalid file, or unknown built-in name.
    """
    if isinstance(scene, Scene):
        return scene
    p = Path(scene)
    if p.suffix.lower() in (".yaml", ".yml", ".json") or p.is_file():
        return Scene.from_file(p)
    return Scene.builtin(str(scene))



class SimulatedRadarDataset(Dataset):
    """Simulated raw frames (or whatever ``transform`` makes of them) with people-count labels.

    Args:
        scene: a :class:`Scene`, a scene file, or a built-in scene name (default ``"corridor"``:
            the paper's empty corridor; people come from ``sampler``, not from the scene).
        length: number of items.
        seed: dataset seed; item ``i`` depends only on ``(seed, i)``.
        frames_per_item: consecutive frames per item (1 -> ``(rx, chirps, samples)``, else
            ``(T, rx, chirps, samples)``).
        config: simulate this radar config instead of the scene's (e.g. a real recording's).
        sampler: scenario sampler (default :class:`ScenarioSampler`: 0/1/2 walkers, balanced).
        target: ``"count"``, ``"occupancy"``, ``"both"`` (a dict) or ``"none"`` (item only).
        transform: applied to the raw frames (SDK floats), e.g. the RD chain and CalibratedDR.
        target_transform: applied to the label.
        as_counts: return uint16 ADC codes instead of SDK floats (before ``transform``).
        device: where the twin runs (the item is returned on that device).
        twin_options: keyword arguments of :class:`DigitalTwin` (``tracer_options``,
            ``receiver``, ``multipath``).
    """

    def __init__(
        self,
        scene: Scene | str | os.PathLike = "corridor",
        *,
        length: int = 1000,
        seed: int = 0,
        frames_per_item: int = 1,
        config: RadarConfig | None = None,
        sampler: ScenarioSampler | None = None,
        target: str = "count",
        transform: Callable[[torch.Tensor], Any] | None = None,
        target_transform: Callable[[Any], Any] | None = None,
        as_counts: bool = False,
        device: torch.device | str = "cpu",
        twin_options: dict[str, Any] | None = None,
    ) -> None:
        if target not in TARGETS:
            raise ConfigError(f"target must be one of {TARGETS}, got {target!r}")
        if length < 0 or frames_per_item < 1:
            raise ConfigError(f"length must be >= 0 and frames_per_item >= 1, got {length} and {frames_per_item}")
        self.scene = load_scene(scene)
        self.config = config or self.scene.config
        self.length = int(length)
        self.seed = int(seed)
        self.frames_per_item = int(frames_per_item)
        self.sampler = sampler or ScenarioSampler()
        self.target = target
        self.transform = transform
        self.target_transform = target_transform
        self.as_counts = as_counts
        self.device = torch.device(device)
        self.twin_options = dict(twin_options or {})
        self._twin: DigitalTwin | None = None
        self._static_signal: torch.Tensor | None = None

    # The twin is built lazily in each worker and never pickled; the room's signal (traced once,
    # ~200 kB) is, so workers started after `prepare()` skip the room's ray tracing.
    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_twin"] = None
        if self._twin is not None and self._twin._static_signal is not None:
            state["_static_signal"] = self._twin._static_signal.cpu()
        return state

    @property
    def twin(self) -> DigitalTwin:
        """The process-local digital twin (built on first use)."""
        if self._twin is None:
            self._twin = DigitalTwin(self.scene, config=self.config, device=self.device,
                                     static_signal=self._static_signal, **self.twin_options)
        return self._twin

    def prepare(self) -> SimulatedRadarDataset:
        """Trace the room now (once), so DataLoader workers inherit it instead of each tracing it."""
        self.twin.static_signal()
        return self

    def __len__(self) -> int:
        return self.length

    def scenario(self, index: int) -> Scenario:
        """The scenario of item ``index`` (people and labels), without simulating it."""
        radar = self.scene.radar
        pos = radar.position.tolist()
        boresight = radar.rotation[:, 2].tolist()
        axis_deg = math.degrees(math.atan2(boresight[1], boresight[0]))
        return self.sampler.sample(item_generator(self.seed, index, stream=0), radar_xy=(pos[0], pos[1]),
                                   axis_deg=axis_deg)

    def __getitem__(self, index: int) -> Any:
        if not -self.length <= index < self.length:
            raise IndexError(f"index {index} out of range for a dataset of {self.length} items")
        index %= self.length
        scenario = self.scenario(index)
        noise = item_generator(self.seed, index, stream=1, device=self.device)
        times = self.twin.frame_times(range(self.frames_per_item))
        x = self.twin.simulate(scenario.people, times, generators=noise)
        if self.as_counts:
            x = self.twin.receiver.to_counts(x)
        if self.frames_per_item == 1:
            x = x[0]
        if self.transform is not None:
            x = self.transform(x)
        if self.target == "none":
            return x
        label: Any
        if self.target == "count":
            label = scenario.count
        elif self.target == "occupancy":
            label = scenario.occupancy
        else:
            label = {"count": scenario.count, "occupancy": scenario.occupancy}
        if self.target_transform is not None:
            label = self.target_transform(label)
        return x, label
