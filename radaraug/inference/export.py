"""Export a classifier with its test chain: TorchScript and ONNX, checked against the eager model.

Both exports take raw frames (SDK floats) and return class probabilities; the chain inside is
:class:`~radaraug.inference.chain.MatmulChain` (DFTs as matrices, no complex tensors). docs/predict.md.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import torch
from torch import nn

from radaraug._optional import lazy_import
from radaraug.errors import ConfigError
from radaraug.files import atomic_save, atomic_write_json
from radaraug.inference.chain import MatmulChain
from radaraug.inference.classifier import RadarClassifier

FORMATS = ("torchscript", "onnx", "torch_export")
"""TorchScript (``.ts``: C++ and mobile runtimes load it; torch marks it deprecated), ONNX (``.onnx``),
``torch.export`` (``.pt2``: torch's successor to TorchScript, for AOTInductor and ExecuTorch)."""
FILES = {"torchscript": "classifier.ts", "onnx": "classifier.onnx", "torch_export": "classifier.pt2"}
#: Largest difference in any class probability between an export and the eager classifier on the
#: check frames before :func:`export` refuses the export (float32 rounding in the DFTs moves a
#: colormap index now and then; measured ~1e-4, docs/predict.md).
PROB_TOLERANCE = 2e-3
ONNX_OPSET = 18


class ExportedClassifier(nn.Module):
    """Raw frames ``(B, rx, chirps, samples)`` -> class probabilities ``(B, classes)``, export-friendly."""

    def __init__(self, classifier: RadarClassifier) -> None:
        super().__init__()
        cfg = classifier.config
        self.chain = MatmulChain(classifier.chain, cfg.num_samples_per_chirp, cfg.num_chirps_per_frame)
        self.net = classifier.net
        self.eval()

    def forward(self, frames: torch.Tensor) -> torch.Tensor:
        """Class probabilities of raw frames in SDK floats."""
        return torch.softmax(self.net(self.chain(frames)), dim=1)


def check_frames(classifier: RadarClassifier, n: int = 8, seed: int = 0) -> torch.Tensor:
    """``(n, rx, chirps, samples)`` frames to check an export on: noise, a DC offset and a few beat tones."""
    cfg = classifier.config
    g = torch.Generator().manual_seed(seed)
    shape = (n, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    t = torch.arange(cfg.num_samples_per_chirp, dtype=torch.float32)
    c = torch.arange(cfg.num_chirps_per_frame, dtype=torch.float32)[:, None]
    x = 0.002 * torch.randn(shape, generator=g) + 0.05
    for k in range(3):  # a return at a random range bin moving at a random Doppler bin
        f = torch.rand(n, 1, 1, 1, generator=g) * 0.45
        v = (torch.rand(n, 1, 1, 1, generator=g) - 0.5) * 0.9
        x = x + 0.02 / (k + 1) * torch.cos(2 * torch.pi * (f * t + v * c))
    return x.clamp(-1, 1)


def export(classifier: RadarClassifier, out_dir: str | os.PathLike, *, formats: Sequence[str] = FORMATS,
           frames: torch.Tensor | None = None, overwrite: bool = False) -> dict[str, Any]:
    """Write the classifier as TorchScript, ONNX and/or a ``torch.export`` program (:data:`FILES`), checked.

    Each export is run on ``frames`` (default: :func:`check_frames`) and compared with the eager
    classifier; ``export.json`` records the differences, the input layout and the class names.

    Args:
        classifier: the classifier.
        out_dir: folder to write into (created).
        formats: any of :data:`FORMATS`.
        frames: check frames in SDK floats (a capture's, ideally).
        overwrite: replace existing export files.

    Returns:
        The ``export.json`` record.

    Raises:
        ConfigError: an unknown format, an existing file without ``overwrite``, or an export that differs
            from the eager classifier by more than :data:`PROB_TOLERANCE`.
        DependencyNotFoundError: ONNX asked for without the ``onnx``/``onnxscript``/``onnxruntime`` packages.
    """
    unknown = sorted(set(formats) - set(FORMATS))
    if unknown or not formats:
        raise ConfigError(f"export formats must be among {FORMATS}, got {list(formats)}")
    out = Path(out_dir)
    for f in formats:
        if (out / FILES[f]).exists() and not overwrite:
            raise ConfigError(f"{out / FILES[f]}: exists; pass overwrite=True (--overwrite) to replace it")
    out.mkdir(parents=True, exist_ok=True)
    x = check_frames(classifier) if frames is None else frames.float()
    model = ExportedClassifier(classifier)
    eager = classifier.probabilities(x)
    cfg = classifier.config
    record: dict[str, Any] = {
        "input": {"name": "frames", "layout": "(batch, rx, chirps, samples)", "dtype": "float32",
                  "units": "SDK floats 2*counts/(2**adc_bits-1) - 1",
                  "shape": [None, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp]},
        "output": {"name": "probabilities", "layout": "(batch, classes)", "classes": list(classifier.class_names)},
        "chain": ("interference excision, " if classifier.chain.interference_db is not None else "")
                 + "range-Doppler (DFT matrices), dB, RX mean power, floor-relative map, excision, clip, "
                 + ("max resize, viridis" if classifier.chain.resample == "max" else "viridis, resize")
                 + ": all inside the export",
        "not_inside": "the causal smoothing over frames and the static-change gate (run them on the host: "
                      "docs/predict.md)",
        "context_frames": classifier.context_frames, "config": cfg.to_dict(), "check_frames": len(x),
        "tolerance": PROB_TOLERANCE, "exports": {}}
    for f in formats:
        path = out / FILES[f]
        probs = {"torchscript": _torchscript, "onnx": _onnx, "torch_export": _torch_export}[f](model, x, path)
        diff = float((probs - eager).abs().max())
        agree = float((probs.argmax(1) == eager.argmax(1)).double().mean())
        record["exports"][f] = {"file": path.name, "max_abs_prob_diff": diff, "class_agreement": agree}
        if not diff <= PROB_TOLERANCE:
            path.unlink(missing_ok=True)
            raise ConfigError(f"{f} export differs from the eager classifier by {diff:.3g} in a class probability "
                              f"(tolerance {PROB_TOLERANCE}); not written")
    atomic_write_json(out / "export.json", record, newline=False, indent=2)
    return record


def _torchscript(model: nn.Module, x: torch.Tensor, path: Path) -> torch.Tensor:
    with warnings.catch_warnings(), torch.no_grad():
        warnings.simplefilter("ignore")  # torch.jit's deprecation notice: TorchScript is still what C++ and mobile load
        traced = torch.jit.trace(model, x[:1], check_trace=False)
        atomic_save(path, lambda fh: torch.jit.save(traced, fh))
        loaded = torch.jit.load(str(path))
        return loaded(x).float()


def _torch_export(model: nn.Module, x: torch.Tensor, path: Path) -> torch.Tensor:
    batch = torch.export.Dim("batch", min=1)
    with torch.no_grad():
        program = torch.export.export(model, (x[:2],), dynamic_shapes=({0: batch},))
        atomic_save(path, lambda fh: torch.export.save(program, fh))
        loaded = torch.export.load(str(path))
        return loaded.module()(x).float()


def _onnx(model: nn.Module, x: torch.Tensor, path: Path) -> torch.Tensor:
    for module in ("onnx", "onnxscript"):
        lazy_import(module, feature="ONNX export")
    ort = lazy_import("onnxruntime", feature="checking the ONNX export")
    batch = torch.export.Dim("batch", min=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        program = torch.onnx.export(model, (x[:2],), dynamo=True, opset_version=ONNX_OPSET, input_names=["frames"],
                                    output_names=["probabilities"], dynamic_shapes=({0: batch},), verbose=False)
    assert program is not None
    atomic_save(path, lambda fh: fh.write(program.model_proto.SerializeToString()))
    session = ort.InferenceSession(str(path), providers=["CPUExecutionProvider"])
    return torch.from_numpy(session.run(None, {"frames": x.numpy()})[0]).float()
