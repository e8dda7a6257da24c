"""Simulate once: per-RX RD dB maps of simulated items, cached on disk (HDF5) under a content key.

Stored before DR, so every DR method and seed shares one simulated set; the key covers everything the
maps depend on, so any change re-simulates (docs/training.md, "Simulate once").
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import torch
from torch.utils.data import DataLoader, Dataset, Subset

from radaraug._cache_key import cache_key
from radaraug._cache_key import content_digest as content_digest  # re-exported: its old home
from radaraug._optional import lazy_import
from radaraug.errors import CaptureError
from radaraug.files import parse_json, remove_stale_temporaries, temporaries_of, temporary_name
from radaraug.raytrace.cache import default_cache_dir as default_cache_dir  # one folder for every cache
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.twin import TWIN_MODEL_VERSION
from radaraug.training.pipeline import rd_db_chain
from radaraug.units import DB_CONVENTION

CACHE_FORMAT = "radaraug-sim-rd-cache"
CACHE_VERSION = 1


def _jsonable(value: Any) -> Any:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return _jsonable(dataclasses.asdict(value))
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    if isinstance(value, Path):
        return str(value)
    if hasattr(value, "to_dict"):
        return _jsonable(value.to_dict())
    return repr(value)


def cache_spec(dataset: SimulatedRadarDataset, indices: Sequence[int], *,
               interference_db: float | None = None) -> dict[str, Any]:
    """Everything the cached maps of ``dataset[indices]`` depend on (JSON types)."""
    idx = list(indices)
    receiver = dataset.twin_options.get("receiver")
    return {
        "format": CACHE_FORMAT,
        "version": CACHE_VERSION,
        "twin_model": TWIN_MODEL_VERSION,
        "scene": _jsonable(dataset.scene.to_dict()),
        "config": dataset.config.to_dict(),
        "receiver": _jsonable(receiver.to_dict()) if receiver is not None else "default",
        "twin_options": _jsonable({k: v for k, v in dataset.twin_options.items() if k != "receiver"}),
        "sampler": _jsonable(dataset.sampler),
        "randomization": _jsonable(getattr(dataset, "randomization", None)),
        "seed": dataset.seed,
        "frames_per_item": dataset.frames_per_item,
        # a hash, not the list: a 100k-item index list would bloat every file's attributes
        "indices": {"count": len(idx), "first": idx[0] if idx else None, "last": idx[-1] if idx else None,
                    "sha1": hashlib.sha1(np.asarray(idx, dtype=np.int64).tobytes()).hexdigest()},
        "chain": rd_db_chain(interference_db).chain_spec(),
        "db_convention": DB_CONVENTION,
    }


def build_map_cache(
    dataset: SimulatedRadarDataset,
    indices: Sequence[int],
    cache_dir: str | os.PathLike,
    *,
    batch_size: int = 16,
    num_workers: int = 0,
    progress: bool = True,
    name: str = "sim",
    interference_db: float | None = None,
) -> Path:
    """The cache file of ``dataset[indices]``: reused when it exists, else simulated and written.

    Args:
        dataset: the simulated dataset (its ``transform`` and ``target`` are ignored: raw frames
            and people counts are read through :meth:`SimulatedRadarDataset.scenario`).
        indices: the items to cache, in order.
        cache_dir: folder of the cache files.
        batch_size: frames turned into RD maps at once.
        num_workers: DataLoader workers that simulate in parallel (the room is traced once,
            here, and inherited by them).
        progress: show a progress bar.
        name: file name prefix.
        interference_db: the map chain's interference excision threshold (:func:`~radaraug.training.rd_db_chain`).

    Returns:
        ``cache_dir/<name>-<key>.h5``.
    """
    return build_map_caches(dataset, {name: indices}, cache_dir, batch_size=batch_size, num_workers=num_workers,
                            progress=progress, interference_db=interference_db)[name]


def build_map_caches(
    dataset: SimulatedRadarDataset,
    splits: Mapping[str, Sequence[int]],
    cache_dir: str | os.PathLike,
    *,
    batch_size: int = 16,
    num_workers: int = 0,
    progress: bool = True,
    interference_db: float | None = None,
) -> dict[str, Path]:
    """One cache file per split (``{name: indices}``), as :func:`build_map_cache`, the missing ones in one pass.

    One DataLoader simulates every missing split, so its workers set up each room variant once.
    """
    cache_dir = Path(cache_dir)
    paths = {name: cache_dir / f"{name}-{cache_key(cache_spec(dataset, idx, interference_db=interference_db))}.h5"
             for name, idx in splits.items()}
    todo = [name for name, path in paths.items() if not path.is_file() and len(splits[name])]
    if not todo:
        return paths
    cache_dir.mkdir(parents=True, exist_ok=True)
    for name in todo:
        _remove_dead_partials(paths[name])
    sim = _RawItems(dataset)
    if num_workers > 0:
        dataset.prepare()
    # (split, row in the split's file, item) of every item to simulate, in loader order: grouped by room
    # variant, so that a batch's items share one twin and are simulated in one call (the rows say where each goes)
    order = [(name, row, i) for name in todo for row, i in enumerate(splits[name])]
    order.sort(key=lambda o: -1 if (v := dataset.room_variant(o[2])) is None else v)
    loader = DataLoader(Subset(sim, [i for _, _, i in order]), batch_size=batch_size, num_workers=num_workers,
                        persistent_workers=False)
    chain = rd_db_chain(interference_db)
    tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm
    partials = {name: temporary_name(paths[name]) for name in todo}
    total = len(order)
    try:
        files = {name: h5py.File(partials[name], "w") for name in todo}
        try:
            for name, f in files.items():
                spec = cache_spec(dataset, splits[name], interference_db=interference_db)
                f.attrs.update({"format": CACHE_FORMAT, "version": CACHE_VERSION, "key": cache_key(spec),
                                "spec": json.dumps(spec), "db_convention": DB_CONVENTION})
                f.create_dataset("index", data=np.asarray(list(splits[name]), dtype=np.int64))
            done = 0  # position in ``order``
            bar = tqdm(total=total, desc=f"simulating {total} items", disable=not progress, leave=False)
            for x, count in loader:
                db = chain(x).clamp(-300, 300).numpy().astype(np.float16)
                for k in range(db.shape[0]):  # rows of the batch may belong to two splits
                    name, row, _ = order[done]
                    f = files[name]
                    if "maps" not in f:
                        n = len(splits[name])
                        f.create_dataset("maps", (n, *db.shape[1:]), dtype="float16", chunks=(1, *db.shape[1:]))
                        f.create_dataset("count", (n,), dtype="int64")
                    f["maps"][row] = db[k]
                    f["count"][row] = int(count[k])
                    done += 1
                bar.update(db.shape[0])
            bar.close()
        finally:
            for f in files.values():
                f.close()
        for name in todo:
            os.replace(partials[name], paths[name])
    finally:
        for partial in partials.values():
            if partial.exists():
                partial.unlink()
    return paths


def _writer_alive(tmp: Path) -> bool:
    """True when the process that named ``tmp`` (``.<name>.<pid>.<random>.tmp``) still runs."""
    try:
        os.kill(int(tmp.name.rsplit(".", 3)[1]), 0)
    except (ValueError, IndexError, ProcessLookupError):
        return False
    except PermissionError:  # alive, another user's process
        return True
    return True


def _remove_dead_partials(path: Path) -> None:
    """Delete temporary files of this cache left by killed processes (SIGKILL skips cleanup)."""
    # any age: a dead writer's file is stale at once, a live one's (another rank's) never
    remove_stale_temporaries(path.parent, temporaries_of(path), older_than_s=0.0, in_use=_writer_alive)


class _RawItems(Dataset):
    """Raw frames and people counts of a simulated dataset (whatever its target/transform)."""

    def __init__(self, dataset: SimulatedRadarDataset) -> None:
        self.dataset = dataset

    def __len__(self) -> int:
        return len(self.dataset)

    def __getitem__(self, index: int) -> tuple[torch.Tensor, int]:
        return self._raw(lambda ds: [ds[index]])[0]

    def __getitems__(self, indices: Sequence[int]) -> list[tuple[torch.Tensor, int]]:
        """A batch of items, simulated together (:meth:`SimulatedRadarDataset.__getitems__`)."""
        return self._raw(lambda ds: ds.__getitems__(indices))

    def _raw(self, get: Callable[[SimulatedRadarDataset], list[Any]]) -> list[tuple[torch.Tensor, int]]:
        ds = self.dataset
        saved = ds.transform, ds.target
        ds.transform, ds.target = None, "count"
        try:
            items = get(ds)
        finally:
            ds.transform, ds.target = saved
        return [(x.float(), int(count)) for x, count in items]


class CachedMaps(Dataset):
    """Items of a map cache: ``(db_map float32 (rx, range, doppler), people count)``.

    The file is opened lazily in each process (safe with DataLoader workers of any start method).

    Raises:
        CaptureError: the file is missing or not a radaraug map cache.
    """

    def __init__(self, path: str | os.PathLike, *, in_memory: bool = True) -> None:
        self.path = Path(path)
        try:
            with h5py.File(self.path, "r") as f:
                if f.attrs.get("format") != CACHE_FORMAT:
                    raise CaptureError(f"{self.path}: not a radaraug simulated-map cache")
                self.spec = parse_json(f.attrs["spec"], source=self.path, error=CaptureError, what="cache spec")
                self.counts = torch.from_numpy(f["count"][()])
                self.indices = torch.from_numpy(f["index"][()])
                self.map_shape = tuple(f["maps"].shape[1:])
                self._maps = torch.from_numpy(f["maps"][()]) if in_memory else None
        except (OSError, KeyError) as e:
            raise CaptureError(f"{self.path}: cannot read the map cache ({e})") from None
        self._file: h5py.File | None = None

    def __len__(self) -> int:
        return int(self.counts.shape[0])

    def maps(self, items: slice | Sequence[int] = slice(None)) -> torch.Tensor:
        """Several maps at once as float32."""
        if self._maps is not None:
            return self._maps[items].float()
        rows = range(len(self))[items] if isinstance(items, slice) else items
        return torch.stack([self[i][0] for i in rows])

    def __getitem__(self, i: int) -> tuple[torch.Tensor, int]:
        if self._maps is not None:
            return self._maps[i].float(), int(self.counts[i])
        if self._file is None:
            self._file = h5py.File(self.path, "r")
        return torch.from_numpy(self._file["maps"][i]).float(), int(self.counts[i])

    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_file"] = None
        return state
