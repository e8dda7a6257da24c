"""`RadarCaptureDataset`: real captures as a map-style torch Dataset of frames or frame windows."""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections import OrderedDict
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import torch
from torch.utils.data import Dataset

from radaraug._augmentation import check_augmentation, check_epoch, transform_item
from radaraug.config import RadarConfig
from radaraug.errors import CaptureError, ConfigError
from radaraug.io.base import CaptureReader, CaptureWarning
from radaraug.io.dispatch import open_capture

PathLike = str | os.PathLike


def _plain(value: Any) -> Any:
    """Numpy scalars -> Python scalars, so the default collate makes tensors of them."""
    return value.item() if isinstance(value, np.generic) else value


def _config_difference(a: RadarConfig, b: RadarConfig) -> str:
    names = [f.name for f in dataclasses.fields(RadarConfig) if getattr(a, f.name) != getattr(b, f.name)]
    return ", ".join(f"{n}: {getattr(a, n)!r} vs {getattr(b, n)!r}" for n in names)


class RadarCaptureDataset(Dataset):
    """Frames (or windows of consecutive frames) of one or more captures, as tensors.

    File ``k`` gives ``(F_k - frames_per_item) // stride + 1`` items, in file order. Files are opened
    lazily in each process (DataLoader workers included); a pickled dataset holds no open file.
    Indexing, labels and workers: ``docs/captures.md``.

    Args:
        paths: one capture or a sequence of captures (anything :func:`open_capture` reads).
        frames_per_item: ``T``: ``(rx, chirps, samples)`` items for 1, ``(T, rx, chirps, samples)`` windows above.
        stride: frames between the starts of consecutive windows (default ``T``: no overlap).
        label: the target: None (items are the tensor), a label name stored in every file (a window
            takes its **last** frame's), a dict ``path -> label``, a callable ``(path, frame) -> label``,
            or any other constant (a constant string would be read as a name).
        transform: applied to the frame tensor.
        target_transform: applied to the label.
        as_counts: int32 raw ADC counts instead of float32 SDK floats.
        max_open_files: open readers kept per process (least recently used are closed).
        augmentation: ``"stream"`` or ``"per_item"`` (draws from ``(augmentation_seed, index, epoch)``:
            the same with any ``num_workers``; call :meth:`set_epoch`). See :mod:`radaraug.transforms.per_item`.
        augmentation_seed: seed of the ``"per_item"`` draws.

    Attributes:
        config: the shared :class:`RadarConfig` of every file.
        paths: the files, in index order.
        num_frames: frames per file.

    Raises:
        CaptureError: no paths, an unreadable file, files with different radar configs, a missing
            label, a dict label lacking a file, or no file holding a full window.
    """

    def __init__(
        self,
        paths: PathLike | Sequence[PathLike],
        *,
        frames_per_item: int | None = None,
        stride: int | None = None,
        label: Any = None,
        transform: Callable[[torch.Tensor], Any] | None = None,
        target_transform: Callable[[Any], Any] | None = None,
        as_counts: bool = False,
        max_open_files: int = 16,
        augmentation: str = "stream",
        augmentation_seed: int = 0,
    ) -> None:
        frames_per_item = 1 if frames_per_item is None else frames_per_item

        try:
            self.augmentation = check_augmentation(augmentation, "RadarCaptureDataset")
        except ConfigError as e:
            raise CaptureError(str(e)) from None
        if isinstance(augmentation_seed, bool) or not isinstance(augmentation_seed, (int, np.integer)):
            raise CaptureError(f"RadarCaptureDataset: augmentation_seed must be an integer, got {augmentation_seed!r}")
        self.augmentation_seed = int(augmentation_seed)
        self.epoch = 0
        self.paths = [Path(paths)] if isinstance(paths, (str, os.PathLike)) else [Path(p) for p in paths]
        if not self.paths:
            raise CaptureError("RadarCaptureDataset: no capture paths given")
        stride = frames_per_item if stride is None else stride
        for name, v in (
            ("frames_per_item", frames_per_item),
            ("stride", stride),
            ("max_open_files", max_open_files),
        ):
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 1:
                raise CaptureError(f"RadarCaptureDataset: {name} must be a positive integer, got {v!r}")
        self.frames_per_item = int(frames_per_item)
        self.stride = int(stride)
        self.label = label
        self.transform = transform
        self.target_transform = target_transform
        self.as_counts = bool(as_counts)
        self.max_open_files = int(max_open_files)

        self.num_frames: list[int] = []
        self._frame_labels: list[np.ndarray] = []  # label=str: per-frame arrays per file
        self._file_labels: list[Any] = []  # label=dict: one value per file
        self.config: RadarConfig = self._scan()

        windows = []
        for path, n in zip(self.paths, self.num_frames):
            w = 0 if n < self.frames_per_item else (n - self.frames_per_item) // self.stride + 1
            if w == 0:
                warnings.warn(
                    f"{path}: {n} frames, fewer than frames_per_item={self.frames_per_item}; file skipped",
                    CaptureWarning,
                    stacklevel=2,
                )
            windows.append(w)
        self._offsets = np.concatenate([[0], np.cumsum(windows)]).astype(np.int64)
        if self._offsets[-1] == 0:
            raise CaptureError(
                f"RadarCaptureDataset: no file holds a window of {self.frames_per_item} frames"
            )
        self._readers: OrderedDict[int, CaptureReader] = OrderedDict()
        self._pid = os.getpid()

    # ------------------------------------------------------------------ indexing the files
    def _scan(self) -> RadarConfig:
        """Open each file once for its length, config and labels; keep nothing open."""
        label = self.label
        by_path: dict[Path, Any] = {}
        if isinstance(label, Mapping):
            by_path = {Path(k).resolve(): v for k, v in label.items()}
        config: RadarConfig | None = None
        for path in self.paths:
            with open_capture(path) as cap:
                if config is None:
                    config = cap.config
                elif cap.config != config:
                    raise CaptureError(
                        f"{path} and {self.paths[0]} have different radar configurations "
                        f"({_config_difference(cap.config, config)}); a dataset needs one"
                    )
                self.num_frames.append(cap.num_frames)
                if isinstance(label, str):
                    if label not in cap.labels:
                        raise CaptureError(
                            f"{path}: has no label {label!r} (labels in the file: {sorted(cap.labels)})"
                        )
                    self._frame_labels.append(np.asarray(cap.labels[label]))
            if isinstance(label, Mapping):
                key = path.resolve()
                if key not in by_path:
                    raise CaptureError(f"{path}: no entry in the label dict")
                self._file_labels.append(by_path[key])
        assert config is not None
        return config

    def locate(self, index: int) -> tuple[Path, int]:
        """``(path, first frame)`` of item ``index``."""
        k, start = self._file_index(index)
        return self.paths[k], start

    def _file_index(self, index: int) -> tuple[int, int]:
        n = len(self)
        i = int(index) + n if index < 0 else int(index)
        if not 0 <= i < n:
            raise IndexError(f"index {index} out of range for a dataset of {n} items")
        k = int(np.searchsorted(self._offsets, i, side="right")) - 1
        return k, int(i - self._offsets[k]) * self.stride

    def _reader(self, k: int) -> CaptureReader:
        if os.getpid() != self._pid:
            # A forked worker inherited the parent's handles: never share them across processes.
            self._readers = OrderedDict()
            self._pid = os.getpid()
        reader = self._readers.get(k)
        if reader is None:
            reader = open_capture(self.paths[k])
            self._readers[k] = reader
            while len(self._readers) > self.max_open_files:
                _, old = self._readers.popitem(last=False)
                old.close()
        else:
            self._readers.move_to_end(k)
        return reader

    def _label_for(self, k: int, frame: int) -> Any:
        label = self.label
        if isinstance(label, str):
            return _plain(self._frame_labels[k][frame])
        if isinstance(label, Mapping):
            return self._file_labels[k]
        if callable(label):
            return label(self.paths[k], frame)
        return label

    @property
    def items_per_file(self) -> list[int]:
        """Items of each file, in file order (item ``i`` of the dataset runs through them in turn)."""
        return [int(n) for n in np.diff(self._offsets)]

    # ------------------------------------------------------------------ Dataset protocol
    def __len__(self) -> int:
        return int(self._offsets[-1])

    def set_epoch(self, epoch: int) -> None:
        """Set the epoch of ``augmentation="per_item"`` draws (before each epoch; persistent workers keep theirs)."""
        try:
            self.epoch = check_epoch(epoch, "RadarCaptureDataset")
        except ConfigError as e:
            raise CaptureError(str(e)) from None

    def __getitem__(self, index: int) -> Any:
        k, start = self._file_index(index)
        t = self.frames_per_item
        x = self._reader(k).read(start, start + t, as_float=not self.as_counts)
        if t == 1:
            x = x[0]
        if self.transform is not None:
            if self.augmentation == "per_item":
                item = int(self._offsets[k]) + (start // self.stride)  # the global index, >= 0
                x = transform_item(self.transform, x, mode="per_item", seed=self.augmentation_seed,
                                   index=item, epoch=self.epoch)
            else:
                x = self.transform(x)
        if self.label is None:
            return x
        y = self._label_for(k, start + t - 1)
        if self.target_transform is not None:
            y = self.target_transform(y)
        return x, y

    def close(self) -> None:
        """Close the files this process has open (they reopen on the next read)."""
        while self._readers:
            _, reader = self._readers.popitem()
            reader.close()

    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_readers"] = OrderedDict()  # open handles never travel to another process
        return state

    def __repr__(self) -> str:
        return (
            f"RadarCaptureDataset({len(self.paths)} files, {len(self)} items of "
            f"{self.frames_per_item} frame(s), stride {self.stride})"
        )
