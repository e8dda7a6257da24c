"""Held-out worlds: each prior varies what it claims, worlds are reproducible, suites are disjoint."""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np
import pytest

from radaraug.errors import ConfigError
from radaraug.io import open_capture
from radaraug.testsets.independent import room as room_mod
from radaraug.testsets.independent import walkers
from radaraug.testsets.independent.generator import PeoplePriors, plan_episodes
from radaraug.testsets.independent.worlds import (
    DISTURBANCES,
    SPENT_SUITES,
    SUITES,
    World,
    draw_world,
    load_world,
    make_suite,
    make_world,
    world_seed,
)

N_DRAWN = 40


@pytest.fixture(scope="module")
def drawn() -> list[World]:
    return [draw_world("design", i) for i in range(N_DRAWN)]


def digest(paths: list[Path]) -> str:
    h = hashlib.sha256()
    for p in paths:
        with open_capture(p) as cap:
            h.update(cap.read(as_float=False).numpy().tobytes())
    return h.hexdigest()


def test_a_world_is_a_pure_function_of_suite_and_index() -> None:
    assert draw_world("design", 3).to_dict() == draw_world("design", 3).to_dict()
    assert draw_world("design", 3).to_dict() != draw_world("design", 4).to_dict()
    assert draw_world("design", 3).to_dict() != draw_world("report", 3).to_dict()


def test_suites_are_disjoint_by_seed() -> None:
    seeds = {s: {world_seed(s, i) for i in range(500)} for s in SUITES}
    assert all(len(v) == 500 for v in seeds.values())
    names = sorted(seeds)
    assert {"design", "report", *SPENT_SUITES} <= set(names)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            assert not seeds[a] & seeds[b], (a, b)


def test_config_prior_varies_samples_chirps_bandwidth_chirp_time_and_gain(drawn: list[World]) -> None:
    cfgs = [w.config for w in drawn]
    assert {c.num_samples_per_chirp for c in cfgs} == {128, 256}
    assert {c.num_chirps_per_frame for c in cfgs} == {32, 64}
    assert {c.sample_rate_Hz for c in cfgs} == {1e6, 2e6}
    assert len({c.if_gain_dB for c in cfgs}) >= 5
    assert len({c.hp_cutoff_Hz for c in cfgs}) >= 3
    bw = [c.bandwidth_Hz for c in cfgs]
    assert max(bw) / min(bw) > 2.0
    prt = [c.chirp_repetition_time_s for c in cfgs]
    assert max(prt) - min(prt) > 100e-6
    for c in cfgs:  # inside the BGT60's band and long enough for the room
        assert 58e9 <= c.start_frequency_Hz < c.end_frequency_Hz <= 63.5e9
        assert 9.5 <= c.max_range_m <= 25.0


def test_room_and_mount_priors_vary_and_fit_the_range(drawn: list[World]) -> None:
    lengths = [w.room.size_m[0] for w in drawn]
    widths = [w.room.size_m[1] for w in drawn]
    heights = [w.room.mount.position_m[2] for w in drawn]
    tilts = [w.room.mount.tilt_down_deg for w in drawn]
    assert max(lengths) - min(lengths) > 3.0 and max(widths) - min(widths) > 2.5
    assert min(heights) < 1.2 and max(heights) > 2.0
    assert min(tilts) < 3.0 and max(tilts) > 15.0
    assert len({len(w.room.objects) for w in drawn}) >= 4
    for w in drawn:
        assert w.room.size_m[0] <= 0.7 * w.config.max_range_m + 0.5
        (x0, x1), (y0, y1) = w.room.walk_x_m, w.room.walk_y_m
        assert x0 >= w.room.mount.position_m[0] + 1.0 and x1 <= w.room.size_m[0] and 0 < y0 < y1 < w.room.size_m[1]


def test_a_high_tilted_mount_looks_down() -> None:
    flat = room_mod.Mount(position_m=(0.0, 0.0, 2.5), tilt_down_deg=0.0)
    down = room_mod.Mount(position_m=(0.0, 0.0, 2.5), tilt_down_deg=30.0)
    target = np.array([3.0, 0.0, 2.5 - 3.0 * math.tan(math.radians(30.0))])
    assert room_mod.look(target, down)[1][2] == pytest.approx(1.0)  # on boresight
    assert room_mod.look(target, flat)[1][2] == pytest.approx(math.cos(math.radians(30.0)))
    yawed = room_mod.Mount(position_m=(0.0, 0.0, 0.0), tilt_down_deg=0.0, yaw_deg=90.0)
    assert room_mod.look(np.array([0.0, 2.0, 0.0]), yawed)[1][2] == pytest.approx(1.0)


def test_people_prior_varies_strength_speed_and_posture(drawn: list[World]) -> None:
    lows = [w.people.rcs_dBsm[0] for w in drawn]
    assert min(lows) < -10.0 and max(lows) > -3.0  # much weaker and about as strong as the office's
    assert max(w.people.rcs_dBsm[1] for w in drawn) > 4.0
    speeds = [w.people.speed_m_s for w in drawn]
    assert min(s[0] for s in speeds) < 0.35 and max(s[1] for s in speeds) > 1.5
    assert max(w.people.crossing_probability for w in drawn) > 0.5
    assert max(w.people.standing_probability for w in drawn) > 0.3


def test_drawn_people_follow_the_priors() -> None:
    room = room_mod.Room(size_m=(8.0, 5.0, 3.0), walk_x_m=(1.12, 7.5), walk_y_m=(0.75, 4.25))
    priors = PeoplePriors(rcs_dBsm=(-12.0, -8.0), speed_m_s=(0.3, 0.5), standing_probability=0.3,
                          crossing_probability=0.6)
    people = [p for c in (1, 2) for e in plan_episodes(c, 600, 5, draw_world("design", 0).config, room=room,
                                                        people=priors) for p in e["people"]]
    assert all(-12.0 <= p.rcs_dBsm <= -8.0 for p in people)
    walking = [p for p in people if not p.standing]
    assert all(0.3 <= p.speed_m_s <= 0.5 for p in walking)
    crossing = [p for p in walking if p.track_yaw_rad]
    assert 0.1 < len([p for p in people if p.standing]) / len(people) < 0.5
    assert 0.3 < len(crossing) / len(walking) < 0.9
    t = np.linspace(0.0, 20.0, 400)
    for p in crossing[:5] + [q for q in walking if not q.track_yaw_rad][:5]:
        pelvis = walkers.positions(p, t)[0]
        dx, dy = np.ptp(pelvis[:, 0]), np.ptp(pelvis[:, 1])
        assert (dy > 2 * dx) if p.track_yaw_rad else (dx > 2 * dy)  # across the beam vs toward/away
        assert room.walk_x_m[0] - 0.01 <= pelvis[:, 0].min() and pelvis[:, 0].max() <= room.walk_x_m[1] + 0.01
        assert room.walk_y_m[0] - 0.01 <= pelvis[:, 1].min() and pelvis[:, 1].max() <= room.walk_y_m[1] + 0.01


def test_disturbances_are_drawn_as_subsets(drawn: list[World]) -> None:
    seen = {name: sum(name in w.disturbances for w in drawn) for name in DISTURBANCES}
    assert all(0 < n < N_DRAWN for n in seen.values()), seen
    assert len({w.disturbances for w in drawn}) > N_DRAWN // 2
    for w in drawn:
        names = [e["name"] for e in w.effects]
        assert names[0] == "adc_noise"
        assert ("spur_tone" in names) == ("spur_tone" in w.disturbances)
        assert ("vibrating_clutter" in names) == ("fan" in w.disturbances) == (w.room.fan is not None)
        assert ("static_clutter" in names) == ("clipping" in w.disturbances)


def test_clipping_world_hits_the_rails_and_a_quiet_one_does_not(tmp_path: Path) -> None:
    clip = next(w for w in (draw_world("design", i) for i in range(N_DRAWN))
                if "clipping" in w.disturbances and w.config.num_samples_per_chirp == 128)
    quiet = next(w for w in (draw_world("design", i) for i in range(N_DRAWN))
                 if "clipping" not in w.disturbances and w.config.if_gain_dB <= 33)
    for w, clipped in ((clip, True), (quiet, False)):
        s = make_world(tmp_path / w.name, w, frames_per_count=4, calibration_frames=2, counts=(0,), progress=False)
        with open_capture(s.calibration) as cap:
            x = cap.read(as_float=False).numpy()
        at_rails = float(((x == 0) | (x == 4095)).mean())
        assert (at_rails > 0.01) if clipped else (at_rails == 0.0), (w.name, at_rails)


def test_make_world_is_reproducible_and_reused(tmp_path: Path) -> None:
    w = draw_world("report", 1)
    a = make_world(tmp_path / "a", w, frames_per_count=6, calibration_frames=2, progress=False)
    b = make_world(tmp_path / "b", draw_world("report", 1), frames_per_count=6, calibration_frames=2, progress=False)
    files = lambda s: [s.calibration, *(p for p, _ in s.tests)]  # noqa: E731
    assert digest(files(a)) == digest(files(b))
    assert [c for _, c in a.tests] == [0, 1, 2]
    with open_capture(a.tests[1][0]) as cap:
        assert cap.config == w.config
        assert cap.read(as_float=False).shape == (6, *w.config.frame_shape)
        assert set(cap.labels["count"].tolist()) == {1}
    again = make_world(tmp_path / "a", w, frames_per_count=6, calibration_frames=2, progress=False)
    assert again.reused and load_world(tmp_path / "a").tests == a.tests


def test_make_suite_names_worlds_and_refuses_bad_input(tmp_path: Path) -> None:
    got = make_suite(tmp_path, "design", worlds=2, frames_per_count=3, calibration_frames=1, progress=False)
    assert [w.name for w, _ in got] == ["design-w00", "design-w01"]
    assert all((tmp_path / w.name / "manifest.json").is_file() for w, _ in got)
    with pytest.raises(ConfigError, match="suite"):
        make_suite(tmp_path, "validation")
    with pytest.raises(ConfigError):
        draw_world("design", -1)
    with pytest.raises(ConfigError):
        make_suite(tmp_path, "design", worlds=0)
