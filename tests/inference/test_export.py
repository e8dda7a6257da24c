"""Exports with the whole chain inside: each reloaded and compared with the eager classifier."""

from __future__ import annotations

import json

import pytest
import torch

from radaraug.cli import main
from radaraug.errors import ConfigError
from radaraug.inference.export import PROB_TOLERANCE, ExportedClassifier, check_frames, export
from tests.inference.conftest import classifier, room_frames, with_bursts, write_frames


@pytest.mark.parametrize("resample", ["bilinear", "max"])
@pytest.mark.parametrize("fmt", ["torchscript", "torch_export", "onnx"])
def test_each_export_matches_the_eager_classifier(fmt, resample, tmp_path) -> None:
    if fmt == "onnx":
        pytest.importorskip("onnxruntime")
        pytest.importorskip("onnxscript")
    # the excision's sort and masks exported too, and the max resize's gathers
    clf = classifier("counting", seed=1, interference_db=6.0, resample=resample)
    x = with_bursts(room_frames(6, target=0.01))
    rec = export(clf, tmp_path, formats=[fmt], frames=x)
    got = rec["exports"][fmt]
    assert (tmp_path / got["file"]).is_file() and got["max_abs_prob_diff"] <= PROB_TOLERANCE
    assert got["class_agreement"] == 1.0
    saved = json.loads((tmp_path / "export.json").read_text())
    assert saved["output"]["classes"] == ["0", "1", "2"] and saved["input"]["shape"] == [None, 3, 16, 64]


def test_the_exported_module_is_the_classifier_on_raw_frames() -> None:
    clf = classifier(seed=2)
    x = check_frames(clf)
    with torch.no_grad():
        assert torch.allclose(ExportedClassifier(clf)(x), clf.probabilities(x), atol=PROB_TOLERANCE)


def test_export_refuses_unknown_formats_and_existing_files(tmp_path) -> None:
    clf = classifier()
    with pytest.raises(ConfigError, match="export formats"):
        export(clf, tmp_path, formats=["tflite"])
    export(clf, tmp_path, formats=["torchscript"])
    with pytest.raises(ConfigError, match="classifier.ts: exists"):
        export(clf, tmp_path, formats=["torchscript"])


def test_cli_export_checks_on_a_capture(tmp_path, capsys) -> None:
    clf = classifier()
    clf.save(tmp_path / "c.pt")
    write_frames(tmp_path / "room.h5", room_frames(4))
    assert main(["export", str(tmp_path / "c.pt"), "-o", str(tmp_path / "out"), "--format", "torchscript",
                 "--check-capture", str(tmp_path / "room.h5"), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["torchscript"]["class_agreement"] == 1.0
    assert json.loads((tmp_path / "out" / "export.json").read_text())["check_frames"] == 4
