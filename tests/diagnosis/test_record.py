"""The calibration record: fits cached in tagged, versioned files; anything else is refitted."""

from __future__ import annotations

import json

import pytest

import radaraug.diagnosis.noise_fit as noise_fit_mod
from radaraug.config import RadarConfig
from radaraug.diagnosis.record import NOISE_FIT_FORMAT, NOISE_FIT_VERSION, cached_noise_fit, noise_fit_path


@pytest.fixture
def fake_fit(monkeypatch):
    calls = []

    def fit_noise_figure(scene, config, target, tracer_options=None):
        calls.append(target)
        return {"noise_figure_dB": 14.0, "adc_noise_rms_counts": 1.9, "target_db": target}

    monkeypatch.setattr(noise_fit_mod, "fit_noise_figure", fit_noise_figure)
    monkeypatch.setattr(noise_fit_mod, "capture_noise_floor_db", lambda path: -97.25)
    return calls


def test_noise_fit_is_cached_tagged_and_refitted_when_foreign(tmp_path, fake_fit):
    cfg = RadarConfig.bgt60tr13c()
    kw = {"scene": "corridor", "config": cfg, "cache_dir": tmp_path, "tracer_rays": 16}
    fit = cached_noise_fit("empty.h5", **kw)
    assert fit["format"] == NOISE_FIT_FORMAT and fit["version"] == NOISE_FIT_VERSION and fake_fit == [-97.25]
    path = noise_fit_path(tmp_path, "corridor", cfg, -97.25, 16)
    assert json.loads(path.read_text())["noise_figure_dB"] == 14.0
    assert cached_noise_fit("empty.h5", **kw) == fit and len(fake_fit) == 1  # read back, not refitted
    # An untagged (older) file, another version, or one that does not parse: fitted again and replaced.
    for bad in ('{"noise_figure_dB": 3.0}', json.dumps({**fit, "version": 1}), "{not json"):
        path.write_text(bad)
        assert cached_noise_fit("empty.h5", **kw)["noise_figure_dB"] == 14.0
    assert len(fake_fit) == 4
    # The key covers the radar config: another config is another file.
    other = noise_fit_path(tmp_path, "corridor", RadarConfig.bgt60tr13c(if_gain_dB=43.0), -97.25, 16)
    assert other != path
