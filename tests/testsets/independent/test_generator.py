"""The independent held-out generator: files, labels, manifest, determinism, physics, isolation."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError
from radaraug.io import open_capture
from radaraug.testsets.generated import GeneratedTestSet
from radaraug.testsets.independent import load_independent_set, make_independent_set, walkers
from radaraug.testsets.independent import room as room_mod
from radaraug.testsets.independent.generator import _chirp_times, plan_episodes, resolve_effects

ROOT = Path(__file__).resolve().parents[2]
FRAMES, CAL_FRAMES, SEED = 6, 4, 7


def small_config() -> RadarConfig:
    """A non-paper config: 128 samples, 32 chirps, IF gain 38 dB."""
    return RadarConfig.bgt60tr13c(num_samples_per_chirp=128, num_chirps_per_frame=32, if_gain_dB=38)


@pytest.fixture(scope="module")
def made(tmp_path_factory: pytest.TempPathFactory) -> GeneratedTestSet:
    out = tmp_path_factory.mktemp("heldout")
    return make_independent_set(out, config=small_config(), frames_per_count=FRAMES, calibration_frames=CAL_FRAMES,
                                  seed=SEED, progress=False)


def read(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray] | None, RadarConfig]:
    with open_capture(path) as cap:
        return cap.read(as_float=False).numpy(), cap.labels, cap.config


def test_files_frames_labels_and_config(made: GeneratedTestSet) -> None:
    cfg = small_config()
    assert made.config == cfg and not made.reused
    assert [c for _, c in made.tests] == [0, 1, 2]
    counts, labels, c_cfg = read(made.calibration)
    assert counts.shape == (CAL_FRAMES, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    assert c_cfg == cfg and labels is not None and set(np.unique(labels["count"])) == {0}
    for path, c in made.tests:
        counts, labels, c_cfg = read(path)
        assert c_cfg == cfg
        assert counts.shape == (FRAMES, 3, 32, 128)
        assert labels is not None
        assert np.array_equal(labels["count"], np.full(FRAMES, c))
        assert np.array_equal(labels["occupancy"], np.full(FRAMES, int(c > 0)))
        # Raw ADC codes around the DC levels, nowhere near clipping.
        assert 0 < counts.min() and counts.max() < cfg.adc_full_scale_counts
    assert made.test_specs()[1].endswith("test_count1.h5:1")
    d = made.to_dict()
    assert set(d) == {"calibration", "tests", "config", "manifest", "reused"}
    assert RadarConfig.from_dict(d["config"]) == cfg


def test_manifest_and_reuse(made: GeneratedTestSet) -> None:
    assert made.manifest is not None and made.manifest.name == "manifest.json"
    m = json.loads(made.manifest.read_text())
    assert m["format"] == "radaraug-heldout-independent" and m["seed"] == SEED
    assert RadarConfig.from_dict(m["config"]) == small_config()
    names = {e["name"] for e in m["receiver"]["effects"]}
    assert {"adc_noise", "phase_noise", "spur_tone", "frame_drift", "vibrating_clutter"} <= names
    assert len(m["room"]["scatterers"]) > 20
    assert [t["count"] for t in m["files"]["tests"]] == [0, 1, 2]
    people = m["files"]["tests"][2]["episodes"][0]["people"]
    assert len(people) == 2 and all(1.5 <= p["height_m"] <= 1.95 for p in people)
    assert m["settings"]["generator_version"] == m["generator_version"]
    mtime = made.calibration.stat().st_mtime_ns
    again = make_independent_set(made.calibration.parent, config=small_config(), frames_per_count=FRAMES,
                                   calibration_frames=CAL_FRAMES, seed=SEED, progress=False)
    assert again.reused and again.tests == made.tests and made.calibration.stat().st_mtime_ns == mtime
    assert load_independent_set(made.calibration.parent).tests == made.tests


def test_deterministic_per_seed_and_count(made: GeneratedTestSet, tmp_path: Path) -> None:
    """The file of a count depends on (seed, count, ...) only, not on the other counts generated."""
    kw = dict(config=small_config(), frames_per_count=FRAMES, calibration_frames=CAL_FRAMES, progress=False)
    alone = make_independent_set(tmp_path / "a", seed=SEED, counts=(1,), **kw)
    assert np.array_equal(read(alone.tests[0][0])[0], read(made.tests[1][0])[0])
    assert np.array_equal(read(alone.calibration)[0], read(made.calibration)[0])
    other = make_independent_set(tmp_path / "b", seed=SEED + 1, counts=(1,), **kw)
    assert not np.array_equal(read(other.tests[0][0])[0], read(alone.tests[0][0])[0])


def test_a_person_shows_up_at_their_range(made: GeneratedTestSet) -> None:
    from radaraug.transforms import RangeDoppler, ToDecibels

    cfg = small_config()
    chain = torch.nn.Sequential(RangeDoppler(), ToDecibels())
    with open_capture(made.calibration) as cap:
        empty = chain(cap.read()).numpy()
    with open_capture(made.tests[1][0]) as cap:
        one = chain(cap.read()).numpy()
    m = cfg.num_chirps_per_frame
    moving = np.abs(np.arange(m) - m // 2) > 1
    ep = plan_episodes(1, FRAMES, SEED, cfg)[0]
    t = _chirp_times(cfg, np.arange(FRAMES) * cfg.frame_repetition_time_s)[:, m // 2]
    r_torso, _ = room_mod.look(walkers.positions(ep["people"][0], t)[2])  # chest
    gains = []
    for f in range(FRAMES):
        k = int(round(r_torso[f] / cfg.range_resolution_m))
        near = slice(max(k - 3, 0), k + 4)
        gains.append(one[f, :, near][..., moving].max() - empty[:, :, near][..., moving].max())
    # At the torso's range, the person's echo stands well above the empty room's (every empty frame).
    assert np.median(gains) > 6.0, gains


def test_walker_kinematics() -> None:
    rng = np.random.default_rng(np.random.SeedSequence(3))
    p = walkers.draw_person(rng, x_range_m=(1.12, 8.5), lane_range_m=(1.15, 2.55))
    t = np.arange(0.0, 4.0, 1e-3)
    pos = walkers.positions(p, t)
    assert pos.shape == (walkers.NUM_POINTS, t.size, 3)
    speed = np.linalg.norm(np.diff(pos[..., :2], axis=1), axis=-1) / 1e-3
    v = p.speed_m_s
    assert np.median(speed[0]) == pytest.approx(v, rel=0.1)  # the pelvis walks at the body speed
    feet = speed[12:14]
    assert 2.3 * v < feet.max() < 3.4 * v  # feet swing at ~2.6-3.1x the body speed
    assert np.mean(feet < 0.05 * v) > 0.3  # ... and stand still during stance
    assert 0.9 * p.height_m < pos[3, :, 2].max() < p.height_m  # head height
    assert (pos[..., 0] > 0.7).all() and (pos[..., 0] < 8.6).all()
    rcs = walkers.rcs_per_frame(p, rng, 4000).sum(axis=0)
    assert 10 * math.log10(rcs.mean()) == pytest.approx(p.rcs_dBsm, abs=0.5)
    standing = walkers.draw_person(rng, x_range_m=(1.12, 8.5), lane_range_m=(1.15, 2.55), standing=True)
    sp = walkers.positions(standing, t)
    assert np.ptp(sp[2, :, :2], axis=0).max() < 0.06  # breathing and sway only


def test_bad_arguments() -> None:
    with pytest.raises(ConfigError):
        resolve_effects("loud", small_config())
    with pytest.raises(ConfigError):
        resolve_effects([{"name": "spur_tone", "freq_Hz": 1e5}], small_config())
    with pytest.raises(ConfigError):
        make_independent_set("unused", counts=(3,), progress=False)
    with pytest.raises(ConfigError):
        make_independent_set("unused", frames_per_count=0, progress=False)
    assert [e["name"] for e in resolve_effects("none", small_config())] == ["adc_noise"]


def test_imports_none_of_the_twin() -> None:
    code = ("import radaraug.testsets.independent, sys; bad=[m for m in sys.modules if m.split('.')[:2] in "
            "(['radaraug','sim'],['radaraug','raytrace'],['radaraug','sensor'],['radaraug','scene'])]; "
            "assert not bad, bad")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]


def test_receiver_track_matches_a_moving_target() -> None:
    """A track sampled from a constant-speed trajectory synthesizes what ``moving_target`` does."""
    from radaraug.testsets.independent.receiver import generate

    cfg = small_config()
    quiet = dict(noise_figure_dB=-np.inf, leakage_coupling_dB=-np.inf, seed=0)
    r0, v, level = 3.0, -0.8, -80.0
    target = generate(cfg, 2, effects=[{"name": "moving_target", "range_m": r0, "speed_m_s": v, "level_dB": level}],
                      **quiet)
    t = _chirp_times(cfg, np.arange(2) * cfg.frame_repetition_time_s)
    track = {"range_m": r0 + v * t, "rate_m_s": np.full_like(t, v), "level_dB": level}
    tracked = generate(cfg, 2, tracks=[track], **quiet)
    assert np.abs(tracked.astype(int) - target.astype(int)).max() <= 1
