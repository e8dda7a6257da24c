"""RadarClassifier: its file round-trips and refuses what it must, its stream, its gate and config checks."""

from __future__ import annotations

import os

import pytest
import torch
from torch import nn

from radaraug.detection import StaticChangeDetector
from radaraug.errors import CheckpointError, ConfigError, InputTensorError
from radaraug.inference import RadarClassifier
from radaraug.training.classifier_file import FORMAT, FORMAT_VERSION, load_checkpoint, torchvision_net
from tests.inference.conftest import classifier, room_frames, small_config


def test_file_round_trip_gives_the_same_predictions(tmp_path, clf) -> None:
    x = room_frames(5)
    again = RadarClassifier.load(clf.save(tmp_path / "c.pt"))
    assert torch.equal(again.probabilities(x), clf.probabilities(x))
    assert again.config == clf.config and again.task == clf.task and again.chain.to_dict()["clip_range_db"] == [-5.0, 30.0]
    data = load_checkpoint(tmp_path / "c.pt")
    assert data["format"] == FORMAT and data["format_version"] == FORMAT_VERSION


class _Payload:
    """Unpickling this would run code (it writes a file); a weights-only load must refuse it first."""

    def __init__(self, sentinel: str) -> None:
        self.sentinel = sentinel

    def __reduce__(self):
        return (open, (self.sentinel, "w"))


def test_a_malicious_damaged_or_foreign_file_is_refused_without_running_anything(tmp_path, clf) -> None:
    good = clf.save(tmp_path / "good.pt").read_bytes()
    sentinel = tmp_path / "ran"
    torch.save({"format": FORMAT, "format_version": 1, "x": _Payload(str(sentinel))}, tmp_path / "evil.pt")
    with pytest.raises(CheckpointError, match="evil.pt: refused: it holds objects other than tensors"):
        RadarClassifier.load(tmp_path / "evil.pt")
    assert not sentinel.exists()
    (tmp_path / "cut.pt").write_bytes(good[: len(good) // 2])
    (tmp_path / "text.pt").write_text("not a model")
    torch.save({"state_dict": {}}, tmp_path / "other.pt")
    torch.save({"format": FORMAT, "format_version": FORMAT_VERSION + 1}, tmp_path / "newer.pt")
    cases = {"cut.pt": "not a classifier file|damaged or truncated", "text.pt": "not a classifier file",
             "other.pt": "not a radaraug classifier", "newer.pt": "upgrade radaraug", "missing.pt": "does not exist"}
    for name, why in cases.items():
        with pytest.raises(CheckpointError, match=f"{name}: .*({why})"):
            RadarClassifier.load(tmp_path / name)
    os.mkfifo(tmp_path / "fifo.pt")
    with pytest.raises(CheckpointError, match="not a regular file"):
        RadarClassifier.load(tmp_path / "fifo.pt")
    data = load_checkpoint(tmp_path / "good.pt")
    data["arch"] = "resnet34"  # weights of another network
    torch.save(data, tmp_path / "mixed.pt")
    with pytest.raises(CheckpointError, match="mixed.pt: the classifier file is inconsistent"):
        RadarClassifier.load(tmp_path / "mixed.pt")


def test_frames_of_another_config_or_in_counts_are_refused(clf) -> None:
    other = small_config().replace(num_chirps_per_frame=32)
    with pytest.raises(ConfigError, match="rec.h5 has radar config .*32 chirps.*trained for .*16 chirps"):
        clf.check_config(other, "rec.h5")
    with pytest.raises(InputTensorError, match="do not match the classifier's radar config"):
        clf.predict(torch.zeros(2, 3, 32, 64))
    with pytest.raises(InputTensorError, match="raw ADC counts"):
        clf.predict(torch.full((2, 3, 16, 64), 2048.0))


def test_pushing_frames_in_chunks_equals_pushing_them_at_once(clf) -> None:
    x = room_frames(11)
    whole = clf.predict(x, window=4)
    stream = clf.stream(window=4)
    parts = [stream.push(x[i:i + 3]) for i in range(0, 11, 3)]
    one = clf.stream(window=4)
    singles = [one.push(f) for f in x]
    for got in (parts, singles):
        assert torch.allclose(torch.cat([p.smoothed for p in got]), whole.smoothed, atol=1e-6)
        assert torch.equal(torch.cat([p.decisions for p in got]), whole.decisions)
    # the smoothing is the causal mean of the frame's own probabilities
    assert torch.allclose(whole.smoothed[5], whole.probs[2:6].mean(dim=0), atol=1e-6)
    assert torch.allclose(whole.smoothed[1], whole.probs[:2].mean(dim=0), atol=1e-6)
    assert torch.equal(clf.predict(x, window=1).decisions, whole.classes)
    rows = list(whole.rows(100))
    assert [r["frame"] for r in rows] == list(range(100, 111)) and set(rows[0]) >= {"class", "score", "decision", "p_empty"}


def test_the_gate_raises_nobody_to_one_person_where_the_static_return_changed() -> None:
    empty = room_frames(40, seed=1)
    counts = empty.double() * (small_config().adc_full_scale_counts / 2)  # the gate is fitted on ADC counts
    gate = StaticChangeDetector.fit(counts, small_config())
    clf = classifier(constant=0, gate=gate, context_frames=3)
    x = torch.cat([room_frames(6, seed=2), room_frames(6, seed=3, target=0.02)])
    p = clf.predict(x)
    assert p.gate is not None and not p.gate[:6].any() and p.gate[6:].all()
    assert p.classes.eq(0).all()  # the network alone always says nobody
    # raised once the gate fired on more than half of the 3-frame window: frames 7.. (6 is 1 of 3)
    assert p.decisions.tolist() == [0] * 7 + [1] * 5
    assert clf.predict(x, gate=False).decisions.eq(0).all()


def test_only_torchvision_backbones_go_into_a_file() -> None:
    with pytest.raises(CheckpointError, match="only torchvision backbones"):
        torchvision_net(nn.Linear(3, 2))
    from radaraug.training import TorchvisionClassifier

    net, arch = torchvision_net(TorchvisionClassifier(3, "resnet34"))
    assert arch == "resnet34" and net.fc.out_features == 3
