"""A trained classifier's file: the network and its test chain, as tensors and plain values only.

:func:`classifier_record` gathers what a prediction needs from a trained run; :class:`radaraug.inference.RadarClassifier`
runs it. The layout is in docs/predict.md ("The classifier file"). Loading uses torch's weights-only
unpickler, which refuses any object but tensors, numbers, strings, lists and dicts: a file that
holds anything else is refused before it could run code.
"""

from __future__ import annotations

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
FORMAT_VERSION = 1
"""Bumped when the layout changes; a file of a newer version is refused."""

if TYPE_CHECKING:
    from radaraug.detection import StaticChangeDetector


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
    from radaraug import __version__
    from radaraug.transforms import RangeDoppler

    if datamodule.clip is None or datamodule.config is None:
        raise CheckpointError("the data module has not been set up (no clip range or radar config)")
    net, arch = torchvision_net(model.net)
    hp = datamodule.hparams
    rd = RangeDoppler()  # the chain rd_db_chain() builds
    chain = {"range_doppler": rd.extra_spec(), "representation": str(hp["representation"]),
             "blank_zero_doppler": int(hp.get("blank_zero_doppler", 1)),
             "clip_range_db": [float(v) for v in datamodule.clip],
             "image_size": None if hp["image_size"] is None else [int(v) for v in hp["image_size"]],
             "excise": None if datamodule.excise is None else datamodule.excise.to(torch.bool).cpu()}
    gate_record = None if gate is None else {
        "reference": gate.reference, "spread": gate.spread, "first_bin": int(gate.first_bin),
        "threshold_db": float(gate.threshold_db), "calibration_scores_db": gate.calibration_scores_db,
        "margin_db": float(gate.margin_db)}
    info = {"method": datamodule.method, "train_items": int(hp["train_items"]), "sim_seed": int(hp["sim_seed"]),
            "dr_seed": int(hp["dr_seed"]), **(provenance or {})}
    task = str(model.hparams["task"])
    return {"radaraug_version": __version__, "task": task, "classes": list(model.class_names), "arch": arch,
            "state_dict": {k: v.detach().cpu().clone() for k, v in net.state_dict().items()},
            "config": datamodule.config.to_dict(), "chain": chain,
            "context_frames": int(model.hparams.get("context_frames", 1)), "gate": gate_record, "provenance": info}


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
