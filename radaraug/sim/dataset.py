"""`SimulatedRadarDataset`: the digital twin as an on-the-fly map-style torch Dataset.

Item ``i`` is a pure function of ``(seed, i)`` (generators seeded by
:func:`radaraug.sim.seeding.item_seed`, never worker or rank state), so any DataLoader worker,
process or DDP rank gives the same item. See docs/simulation.md.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import Any

import torch
from torch.utils.data import Dataset

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.scene.scene import Scene
from radaraug.sensor.profile import as_profile
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.randomization import RoomDraw, TwinRandomization, check_receiver
from radaraug.sim.scenarios import Scenario, ScenarioSampler
from radaraug.sim.seeding import Stream, item_generator
from radaraug.sim.twin import DigitalTwin, TwinItem
from radaraug.transforms.per_item import check_augmentation, check_epoch, transform_item

TARGETS = ("count", "occupancy", "both", "none")


class SimulatedRadarDataset(Dataset):
    """Simulated raw frames (or whatever ``transform`` makes of them) with people-count labels.

    Args:
        scene: a :class:`Scene`, a scene file, or a built-in scene name (default: the paper's empty
            ``"corridor"``; people come from ``sampler``).
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
        augmentation: ``"stream"`` (default: random transforms draw from their own stream per
            worker) or ``"per_item"`` (from a generator of ``(seed, index, epoch)``: the same with
            any ``num_workers``; call :meth:`set_epoch` each epoch; :mod:`radaraug.transforms.per_item`).
        twin_options: keyword arguments of :class:`DigitalTwin` (``tracer_options``,
            ``receiver``, ``multipath``); with randomization they apply to every room variant.
        randomization: twin randomization drawn per item (a :class:`TwinRandomization` or a dict of
            its fields; then the scene must be a corridor scene); None (default): the scene as it is.
        profile: a fitted twin profile (:class:`~radaraug.sensor.profile.TwinProfile`, its JSON path
            or dict, from ``radaraug diagnose``) for the twin's receiver and room section.
        batched: a DataLoader's batch (:meth:`__getitems__`) is simulated in one
            :meth:`~radaraug.sim.twin.DigitalTwin.simulate_items` call per room variant: equal to one item
            at a time within the synthesis' contract (a sample may land on the neighbouring ADC code), not
            bit for bit, and no faster on the CPU (``benchmarks/twin_items_cpu.json``): for a GPU, where
            one call's overhead is what batching amortizes. Default False: every item bit for bit a
            function of ``(seed, index)``.

    Raises:
        ConfigError: a bad target, size, randomization or profile, or a scene or receiver the
            randomization cannot use.
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
        randomization: TwinRandomization | dict[str, Any] | None = None,
        profile: Any = None,
        augmentation: str = "stream",
        batched: bool = False,
    ) -> None:
        self.augmentation = check_augmentation(augmentation, "SimulatedRadarDataset")
        self.batched = bool(batched)
        self.epoch = 0
        if target not in TARGETS:
            raise ConfigError(f"target must be one of {TARGETS}, got {target!r}")
        if length < 0 or frames_per_item < 1:
            raise ConfigError(f"length must be >= 0 and frames_per_item >= 1, got {length} and {frames_per_item}")
        self.scene = Scene.load(scene)
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
        self.profile = as_profile(profile)
        if self.profile is not None:
            if "receiver" in self.twin_options or "profile" in self.twin_options:
                raise ConfigError("give the twin's receiver as profile= or twin_options['receiver'], not both")
            self.twin_options["receiver"] = self.profile.receiver(self.config)
            if self.profile.room:
                # The profile's room section is a tracer option (the caller's tracer_options win).
                self.twin_options["tracer_options"] = {**self.profile.tracer_options(),
                                                       **(self.twin_options.get("tracer_options") or {})}
        self._twin: DigitalTwin | None = None
        self._static_signal: torch.Tensor | None = None
        if isinstance(randomization, dict):
            randomization = TwinRandomization.from_dict(randomization)
        if randomization is not None and not isinstance(randomization, TwinRandomization):
            raise ConfigError(f"randomization must be a TwinRandomization, a dict or None, "
                              f"got {type(randomization).__name__}")
        self.randomization = randomization
        self._rooms: list[RoomDraw] = []
        self._variant_twins: dict[int, DigitalTwin] = {}
        self._variant_static: dict[int, torch.Tensor] = {}
        rz = self._drawn_randomization
        if rz is not None:
            # Fail now, not in a DataLoader worker: a non-corridor scene, a radar outside a drawn
            # room, or a receiver without the stages the offsets act on.
            self._rooms = [rz.room_draw(self.seed, k) for k in range(rz.room.variants)]
            for room in self._rooms:
                room.scene(self.scene, self.config)
            check_receiver(self._reference_receiver(), rz)

    # The twin is built lazily in each worker and never pickled; the room's signal (traced once,
    # ~200 kB) is, so workers started after `prepare()` skip the room's ray tracing.
    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_twin"] = None
        if self._twin is not None and self._twin.cached_static_signal is not None:
            state["_static_signal"] = self._twin.cached_static_signal.cpu()
        # Same for every room variant already traced (~200 kB each).
        state["_variant_twins"] = {}
        static = {k: v.cpu() for k, v in self._variant_static.items()}
        for k, twin in self._variant_twins.items():
            if twin.cached_static_signal is not None:
                static[k] = twin.cached_static_signal.cpu()
        state["_variant_static"] = static
        return state

    @property
    def randomized(self) -> bool:
        """True when items draw the twin's randomization (given and enabled)."""
        return self._drawn_randomization is not None

    @property
    def _drawn_randomization(self) -> TwinRandomization | None:
        """The randomization items draw: :attr:`randomization` when given and enabled, else None."""
        r = self.randomization
        return r if r is not None and r.enabled else None

    @property
    def twin(self) -> DigitalTwin:
        """The process-local digital twin (built on first use)."""
        if self._twin is None:
            self._twin = self._make_twin(self.scene, self._static_signal)
        return self._twin

    def _make_twin(self, scene: Scene, static_signal: torch.Tensor | None) -> DigitalTwin:
        return DigitalTwin(scene, config=self.config, device=self.device, static_signal=static_signal,
                           **self.twin_options)

    def variant_twin(self, k: int) -> DigitalTwin:
        """The process-local twin of room variant ``k`` (built on first use; randomization only)."""
        if not self.randomized:
            raise ConfigError("room variants exist only with twin randomization enabled")
        twin = self._variant_twins.get(k)
        if twin is None:
            twin = self._make_twin(self._rooms[k].scene(self.scene, self.config), self._variant_static.get(k))
            self._variant_twins[k] = twin
        return twin

    def prepare(self) -> SimulatedRadarDataset:
        """Trace the room now (once), so DataLoader workers inherit it instead of each tracing it.

        With randomization, every room variant of the pool is traced. The shadow's static basis is made
        here too.
        """
        twins = [self.variant_twin(k) for k in range(len(self._rooms))] if self.randomized else [self.twin]
        for twin in twins:
            twin.static_signal()
            if twin.shadowing:
                twin.static_basis()
        return self

    def __len__(self) -> int:
        return self.length

    def room_variant(self, index: int) -> int | None:
        """The room variant item ``index`` is simulated in (None without randomization).

        Items of one variant share a twin, so :meth:`__getitems__` simulates them in one call.
        """
        rz = self._drawn_randomization
        return None if rz is None else rz.variant_of(self.seed, self._check_index(index))

    def scenario(self, index: int) -> Scenario:
        """The scenario of item ``index`` (people and labels), without simulating it."""
        rz = self._drawn_randomization
        g = item_generator(self.seed, index, stream=Stream.SCENARIO)
        if rz is not None:
            # People walk along the drawn corridor (+x), whatever the radar's drawn yaw.
            room = self._rooms[rz.variant_of(self.seed, index)]
            x = float(self.scene.radar.position[0])
            return rz.sampler(self.sampler, room, x).sample(g, radar_xy=(x, 0.0), axis_deg=0.0)
        radar = self.scene.radar
        pos = radar.position.tolist()
        boresight = radar.rotation[:, 2].tolist()
        axis_deg = math.degrees(math.atan2(boresight[1], boresight[0]))
        return self.sampler.sample(g, radar_xy=(pos[0], pos[1]), axis_deg=axis_deg)

    def item_params(self, index: int) -> dict[str, Any]:
        """What item ``index`` is made of (scenario, people, labels; with randomization every draw), JSON-able.

        Nothing is simulated. With randomization: ``variant``, ``room``, each person's ``rcs_scale_dB``,
        the receiver's gain and noise figure (None without the stage), scatterers, phase noise, ``effects``.
        """
        index = self._check_index(index)
        scenario = self.scenario(index)
        people = [dict(p) for p in scenario.params]
        out: dict[str, Any] = {"index": index, "seed": self.seed, "randomized": self.randomized,
                               "count": scenario.count, "occupancy": scenario.occupancy, "people": people}
        rz = self._drawn_randomization
        if rz is None:
            return out
        draw = rz.item(self.seed, index, scenario.count)
        for person, db in zip(people, draw.rcs_scale_dB):
            person["rcs_scale_dB"] = db
        base = self._reference_receiver()
        gain = _param(base, "system_gain", "gain_dB")
        nf = _param(base, "thermal_noise", "noise_figure_dB")
        out.update(
            variant=draw.variant, room=self._rooms[draw.variant].to_dict(),
            system_gain_offset_dB=draw.system_gain_offset_dB, noise_figure_offset_dB=draw.noise_figure_offset_dB,
            system_gain_dB=None if gain is None else gain + draw.system_gain_offset_dB,
            noise_figure_dB=None if nf is None else nf + draw.noise_figure_offset_dB,
            static_scatterers=[dict(zip(("range_m", "azimuth_deg", "elevation_deg", "rcs_dBsm"), s))
                               for s in draw.scatterers],
            phase_noise_rms_Hz=draw.phase_noise_rms_Hz,
            effects=draw.effects_dict(self.config),
        )
        return out

    def _reference_receiver(self) -> FMCWReceiver:
        """The receiver the twins are built with (for its calibrated gain / noise figure)."""
        given = self.twin_options.get("receiver")
        return given if given is not None else FMCWReceiver(self.config)

    def set_epoch(self, epoch: int) -> None:
        """Set the epoch of ``augmentation="per_item"`` draws (call before each epoch; workers started later see it)."""
        self.epoch = check_epoch(epoch, "SimulatedRadarDataset")

    def _check_index(self, index: int) -> int:
        if not -self.length <= index < self.length:
            raise IndexError(f"index {index} out of range for a dataset of {self.length} items")
        return index % self.length

    def __getitem__(self, index: int) -> Any:
        index = self._check_index(index)
        scenario = self.scenario(index)
        noise = item_generator(self.seed, index, stream=Stream.ITEM_NOISE, device=self.device)
        rz = self._drawn_randomization
        draw = None if rz is None else rz.item(self.seed, index, scenario.count)
        twin = self.twin if draw is None else self.variant_twin(draw.variant)
        x = twin.simulate(scenario.people, twin.frame_times(range(self.frames_per_item)), generators=noise, draw=draw)
        return self._finish(index, scenario, twin, x)

    def __getitems__(self, indices: Sequence[int]) -> list[Any]:
        """Items ``indices``, simulated together per room variant (:meth:`DigitalTwin.simulate_items`).

        What a ``DataLoader`` calls for a batch: ``[self[i] for i in indices]``, or with ``batched=True``
        the same within the synthesis' contract (docs/simulation.md, "Many items per call").
        """
        if not self.batched:
            return [self[i] for i in indices]
        idx = [self._check_index(i) for i in indices]
        scenarios = [self.scenario(i) for i in idx]
        rz = self._drawn_randomization
        draws = [None if rz is None else rz.item(self.seed, i, sc.count) for i, sc in zip(idx, scenarios)]
        groups: dict[int | None, list[int]] = {}
        for k, d in enumerate(draws):
            groups.setdefault(None if d is None else d.variant, []).append(k)
        out: list[Any] = [None] * len(idx)
        for variant, ks in groups.items():
            twin = self.twin if variant is None else self.variant_twin(variant)
            times = twin.frame_times(range(self.frames_per_item))
            items = [TwinItem(scenarios[k].people, times, draw=draws[k],
                              generators=item_generator(self.seed, idx[k], stream=Stream.ITEM_NOISE, device=self.device))
                     for k in ks]
            for k, x in zip(ks, twin.simulate_items(items)):
                out[k] = self._finish(idx[k], scenarios[k], twin, x)
        return out

    def _finish(self, index: int, scenario: Scenario, twin: DigitalTwin, x: torch.Tensor) -> Any:
        """Item ``index`` from its simulated frames: counts, one frame's shape, the transform, the label."""
        if self.as_counts:
            x = twin.receiver.to_counts(x)
        if self.frames_per_item == 1:
            x = x[0]
        if self.transform is not None:
            x = transform_item(self.transform, x, mode=self.augmentation, seed=self.seed, index=index,
                               epoch=self.epoch, device=self.device)
        if self.target == "none":
            return x
        labels = {"count": scenario.count, "occupancy": scenario.occupancy}
        label: Any = labels if self.target == "both" else labels[self.target]
        if self.target_transform is not None:
            label = self.target_transform(label)
        return x, label


def _param(receiver: FMCWReceiver, effect: str, name: str) -> float | None:
    """A scalar effect parameter of ``receiver`` as a float (None without that effect)."""
    try:
        value = receiver.effect(effect).params()[name]
    except KeyError:
        return None
    return None if value is None else float(value.detach().cpu().reshape(-1)[0])
