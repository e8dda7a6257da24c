"""Classifier files on the third-party BGT60TR13C recordings: every config, the chain and its export."""

from __future__ import annotations

import json

import pytest
import torch

from radaraug.cli import main
from radaraug.inference import ChainSpec, MatmulChain, RadarClassifier
from radaraug.io import open_capture
from radaraug.training.models import resnet18

pytestmark = pytest.mark.real


def _recordings(root):
    return sorted(p.parent.parent for p in root.rglob("RadarIfxAvian_00/config.json"))


def test_predict_and_the_matrix_chain_on_every_recording(real_data, tmp_path, capsys) -> None:
    recordings = _recordings(real_data)
    assert len(recordings) >= 3
    configs = []
    for i, rec in enumerate(recordings):
        with open_capture(rec) as cap:
            config, frames = cap.config, cap.read(0, min(len(cap), 24))
            n = len(cap)
        configs.append(config)
        spec = ChainSpec({}, "floor_relative", 1, (-5.0, 30.0), (64, 32))
        torch.manual_seed(i)
        clf = RadarClassifier(resnet18(2), arch="resnet18", task="occupancy", config=config, chain=spec)
        # the export's matrix chain on measured frames (other sample counts, chirps, ADC offsets)
        eager = spec.eager()(frames)
        mat = MatmulChain(spec, config.num_samples_per_chirp, config.num_chirps_per_frame)(frames)
        diff = (eager - mat).abs()
        assert float(diff.max()) < 0.03 and float((diff > 1e-4).double().mean()) < 0.005, rec.name
        path = clf.save(tmp_path / f"c{i}.pt")
        out = tmp_path / f"rows{i}.jsonl"
        assert main(["predict", str(path), str(rec), "-o", str(out), "--no-progress"]) == 0, capsys.readouterr().err
        rows = [json.loads(line) for line in out.read_text().splitlines()]
        assert [r["frame"] for r in rows] == list(range(n))
    # a recording of another config is refused, naming both configs
    first, other = recordings[0], next(r for r, c in zip(recordings, configs) if c != configs[0])
    assert main(["predict", str(tmp_path / "c0.pt"), str(other), "-o", str(tmp_path / "x.jsonl")]) == 3
    err = capsys.readouterr().err
    assert other.name in err and "this classifier was trained for" in err and first.name not in err.split(":")[0]
