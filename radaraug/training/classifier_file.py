"""A trained classifier's file: the network and its test chain, as tensors and plain values only.

:func:`classifier_record` gathers what a prediction needs from a trained run (the test chain as a
:class:`ChainSpec`); :class:`radaraug.inference.RadarClassifier` runs it. The layout is in docs/predict.md ("The classifier file"). Loading uses torch's weights-only
unpickler, which refuses any object but tensors, numbers, strings, lists and dicts: a file that
holds anything else is refused before it could run code.
"""

from __future__ import annotations

import dataclasses
import os
import pickle
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

import torch
import torchvision
from torch import nn

from radaraug.errors import CheckpointError
from radaraug.files import atomic_write_bytes, regular_file_size

FORMAT = "radaraug-classifier"
"""The ``format`` field of every classifier file."""
FORMAT_VERSION = 3
"""Bumped when the layout changes; a file of a newer version is refused (2: the chain's ``interference_db``;
3: its ``resample``)."""

if TYPE_CHECKING:
    from radaraug.config import RadarConfig
    from radaraug.detection import StaticChangeDetector


@dataclasses.dataclass(frozen=True)
class ChainSpec:
    """What a classifier's test chain is, in plain values (a checkpoint stores it).

    Attributes:
        range_doppler: :class:`~radaraug.transforms.RangeDoppler`'s arguments.
        representation: ``"floor_relative"`` or ``"paper"`` (:data:`radaraug.training.pipeline.REPRESENTATIONS`).
        blank_zero_doppler: Doppler bins blanked on each side of zero (floor-relative maps).
        clip_range_db: the ``[vmin, vmax]`` the training maps were clipped to.
        image_size: the network input ``(H, W)``, or None for the RD map's own size.
        excise: bool ``(range, doppler)`` mask of the calibration's persistent cells, or None.
        interference_db: the interference excision's threshold before the RD FFTs, or None (none).
        resample: how the map shrinks to ``image_size``: ``"bilinear"`` or ``"max"``
            (:func:`radaraug.training.pipeline.image_chain`).
    """

    range_doppler: dict[str, Any]
    representation: str
    blank_zero_doppler: int
    clip_range_db: tuple[float, float]
    image_size: tuple[int, int] | None
    excise: torch.Tensor | None = None
    interference_db: float | None = None
    resample: str = "bilinear"

    def eager(self) -> nn.Sequential:
        """The chain from the library's transforms: raw frames ``(B, rx, chirps, samples)`` -> ``(B, 3, H, W)``."""
        from radaraug.training.pipeline import image_chain
        from radaraug.transforms import InterferenceExcision, RadarCompose, RangeDoppler, ToDecibels

        steps: list[nn.Module] = [RangeDoppler(**self.range_doppler), ToDecibels()]  # rd_db_chain() with these windows
        if self.interference_db is not None:
            steps.insert(0, InterferenceExcision(self.interference_db))
        rd = RadarCompose(steps)
        return nn.Sequential(rd, *image_chain(*self.clip_range_db, self.image_size, self.representation, self.excise,
                                              self.blank_zero_doppler, self.resample))

    def to_dict(self) -> dict[str, Any]:
        """Plain values and tensors only (what a weights-only load accepts)."""
        return {"range_doppler": dict(self.range_doppler), "representation": self.representation,
                "blank_zero_doppler": int(self.blank_zero_doppler), "clip_range_db": [float(v) for v in self.clip_range_db],
                "image_size": None if self.image_size is None else [int(v) for v in self.image_size],
                "excise": None if self.excise is None else self.excise.to(torch.bool).cpu(),
                "interference_db": None if self.interference_db is None else float(self.interference_db),
                "resample": self.resample}

    @classmethod
    def from_dict(cls, data: dict[str, Any], *, source: str) -> ChainSpec:
        """The spec a checkpoint stored (CheckpointError naming ``source`` for a missing or bad field)."""
        try:
            size = data["image_size"]
            excise = data["excise"]
            interference = data.get("interference_db")  # absent from files of before the excision: none
            resample = str(data.get("resample", "bilinear"))  # absent from files of before version 3: bilinear
            spec = cls(dict(data["range_doppler"]), str(data["representation"]), int(data["blank_zero_doppler"]),
                       (float(data["clip_range_db"][0]), float(data["clip_range_db"][1])),
                       None if size is None else (int(size[0]), int(size[1])),
                       None if excise is None else torch.as_tensor(excise, dtype=torch.bool),
                       None if interference is None else float(interference), resample)
        except (KeyError, TypeError, ValueError, IndexError) as e:
            raise CheckpointError(f"{source}: the test chain it records is incomplete or malformed ({e!r})") from None
        from radaraug.training.pipeline import RESAMPLES

        if spec.resample not in RESAMPLES:
            raise CheckpointError(f"{source}: the test chain's resample must be one of {RESAMPLES}, got {spec.resample!r}")
        if spec.interference_db is not None and not spec.interference_db > 0:
            raise CheckpointError(f"{source}: the test chain's interference_db must be > 0 dB or null, "
                                  f"got {spec.interference_db}")
        return spec



def classifier_record(model: Any, datamodule: Any, *, gate: StaticChangeDetector | None = None,
                      provenance: dict[str, Any] | None = None) -> dict[str, Any]:
    """What a classifier file holds, from a trained ``RDClassifier`` and its set-up ``RadarDataModule``.

    Args:
        model: the trained :class:`~radaraug.training.RDClassifier`.
        datamodule: its :class:`~radaraug.training.RadarDataModule`, set up (clip range, config, excision).
        gate: the static-change gate fitted on the empty room the classifier is meant for, or None.
        provenance: plain values added to the record's ``provenance``.

    Raises:
        CheckpointError: a backbone that is not a torchvision model, or a data module not set up.
    """
    from radaraug.transforms import RangeDoppler

    if datamodule.clip is None or datamodule.config is None:
        raise CheckpointError("the data module has not been set up (no clip range or radar config)")
    net, arch = torchvision_net(model.net)
    spec, size = datamodule.image_spec, datamodule.image_spec.size
    chain = ChainSpec(RangeDoppler().extra_spec(),  # the chain rd_db_chain() builds
                      str(spec.representation), int(spec.blank_zero_doppler),
                      (float(datamodule.clip[0]), float(datamodule.clip[1])),
                      None if size is None else (int(size[0]), int(size[1])), datamodule.excise,
                      spec.excise_interference_db, str(spec.resample))
    info = {"method": datamodule.method.name, "train_items": int(datamodule.twin.train_items),
            "sim_seed": int(datamodule.twin.seed), "dr_seed": int(datamodule.hparams["seed"]), **(provenance or {})}
    return file_record(task=str(model.hparams["task"]), arch=arch, net=net, config=datamodule.config, chain=chain,
                       context_frames=int(model.hparams.get("context_frames", 1)), gate=gate, provenance=info)


def file_record(*, task: str, arch: str, net: nn.Module, config: RadarConfig, chain: ChainSpec, context_frames: int,
                gate: StaticChangeDetector | None, provenance: dict[str, Any]) -> dict[str, Any]:
    """The classifier file's dict (tensors and plain values only) of its parts (layout: docs/predict.md)."""
    from radaraug import __version__
    from radaraug.testsets.tasks import TASKS

    return {"radaraug_version": __version__, "task": task, "classes": list(TASKS[task]), "arch": arch,
            "state_dict": {k: v.detach().cpu().clone() for k, v in net.state_dict().items()},
            "config": config.to_dict(), "chain": chain.to_dict(), "context_frames": int(context_frames),
            # the detector's fields as they are: StaticChangeDetector(**record["gate"]) rebuilds it
            "gate": None if gate is None else dataclasses.asdict(gate), "provenance": dict(provenance)}


def torchvision_net(net: nn.Module) -> tuple[nn.Module, str]:
    """``(torchvision network, its architecture name)`` of a backbone ``RDClassifier`` trained.

    Raises:
        CheckpointError: not a torchvision classification network the file can name.
    """
    from radaraug.training.models import TorchvisionClassifier

    if isinstance(net, TorchvisionClassifier):
        return net.net, net.arch
    if type(net) is torchvision.models.ResNet:
        layers: list[Any] = [net.layer1, net.layer2, net.layer3, net.layer4]
        blocks = tuple(len(layer) for layer in layers)
        basic = isinstance(layers[0][0], torchvision.models.resnet.BasicBlock)
        known: dict[tuple[tuple[int, ...], bool], str] = {((2, 2, 2, 2), True): "resnet18",
                                                          ((3, 4, 6, 3), True): "resnet34",
                                                          ((3, 4, 6, 3), False): "resnet50"}
        arch = known.get((blocks, basic))
        if arch is not None:
            return net, arch
    raise CheckpointError(f"only torchvision backbones can be stored in a classifier file, got {type(net).__name__}; "
                          "use radaraug.training.TorchvisionClassifier, or save the network yourself")


def save_checkpoint(data: dict[str, Any], path: str | os.PathLike) -> Path:
    """Write ``data`` (tensors and plain values) as a classifier file, atomically.

    Raises:
        CheckpointError: ``data`` holds an object a weights-only load would refuse.
    """
    import io

    buf = io.BytesIO()
    torch.save({"format": FORMAT, "format_version": FORMAT_VERSION, **data}, buf)
    try:  # what cannot be loaded back safely is not written
        torch.load(io.BytesIO(buf.getvalue()), map_location="cpu", weights_only=True)
    except pickle.UnpicklingError as e:
        raise CheckpointError(f"{path}: the classifier holds objects a weights-only load refuses ({e})") from None
    path = Path(path)
    atomic_write_bytes(path, buf.getvalue())
    return path


def load_checkpoint(path: str | os.PathLike) -> dict[str, Any]:
    """The dict of a classifier file, loaded without running code from it.

    Raises:
        CheckpointError: missing, not a torch file, truncated or damaged, holding objects other than
            tensors and plain values (refused unread: loading them would run code), not a radaraug
            classifier, or of a newer format version.
    """
    path = Path(path)
    regular_file_size(path, error=CheckpointError, what="classifier file")
    if not zipfile.is_zipfile(path):
        raise CheckpointError(f"{path}: not a classifier file (not a torch zip archive; truncated, or another format)")
    try:
        data = torch.load(path, map_location="cpu", weights_only=True)
    except pickle.UnpicklingError as e:
        first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise CheckpointError(f"{path}: refused: it holds objects other than tensors and plain values, and loading "
                              f"them could run code ({first})") from None
    except (RuntimeError, EOFError, zipfile.BadZipFile, KeyError, OSError) as e:
        raise CheckpointError(f"{path}: damaged or truncated classifier file ({type(e).__name__}: {e})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        what = data.get("format") if isinstance(data, dict) else type(data).__name__
        hint = " (a Lightning checkpoint: `radaraug train fit` writes classifier.pt beside it)" \
            if isinstance(data, dict) and "pytorch-lightning_version" in data else ""
        raise CheckpointError(f"{path}: not a radaraug classifier (format {what!r}){hint}")
    version = data.get("format_version")
    if not isinstance(version, int) or version > FORMAT_VERSION:
        raise CheckpointError(f"{path}: classifier format version {version!r}; this radaraug reads up to "
                              f"{FORMAT_VERSION} (upgrade radaraug)")
    return data
