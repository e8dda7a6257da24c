"""The traced static room is cached on disk per (scene, radar, tracer options, tracer version)."""

from __future__ import annotations

import pytest
import torch
from raytrace_scenes import box_room

from radaraug.config import RadarConfig
from radaraug.raytrace import cache as static_cache
from radaraug.raytrace import tracer as tracer_module
from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import RadarPose

CFG = RadarConfig.bgt60tr13c()
POSE = RadarPose.look_at((0.2, 0.0, 1.5), (20.0, 0.0, 1.5))


def _room(material: str = "metal"):
    return box_room((0.0, -1.0, 0.0), (20.0, 1.0, 3.0), materials=("floorboard", "ceiling_board", "concrete", material))


def test_second_tracer_loads_instead_of_tracing(tmp_path, monkeypatch):
    first = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    ref = first.static_paths()
    assert len(list(tmp_path.glob("static-*.pt"))) == 1

    def boom(*a, **k):
        raise AssertionError("traced again despite a cache entry")

    monkeypatch.setattr(tracer_module, "image_paths", boom)
    again = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    got = again.static_paths()
    torch.testing.assert_close(got.amplitude, ref.amplitude)
    torch.testing.assert_close(got.delay_s, ref.delay_s)
    torch.testing.assert_close(again.static_vertices(), first.static_vertices())


def test_key_follows_what_the_paths_depend_on():
    base = RayTracer(_room(), POSE, CFG, cache=False).cache_key()
    assert RayTracer(_room("wood"), POSE, CFG, cache=False).cache_key() != base
    moved = RadarPose.look_at((0.3, 0.0, 1.5), (20.0, 0.0, 1.5))
    assert RayTracer(_room(), moved, CFG, cache=False).cache_key() != base
    assert RayTracer(_room(), POSE, CFG, cache=False, max_bounces=2).cache_key() != base
    # The IF gain is applied by the receiver, later: same room trace.
    assert RayTracer(_room(), POSE, RadarConfig.bgt60tr13c(if_gain_dB=23), cache=False).cache_key() == base


def test_damaged_entry_is_traced_again(tmp_path):
    ref = RayTracer(_room(), POSE, CFG, cache=tmp_path).static_paths()
    entry = next(tmp_path.glob("static-*.pt"))
    entry.write_bytes(b"not a torch file")
    with pytest.warns(RuntimeWarning, match="unreadable"):
        got = RayTracer(_room(), POSE, CFG, cache=tmp_path).static_paths()
    torch.testing.assert_close(got.amplitude, ref.amplitude)
    assert torch.load(entry, weights_only=True)["version"] == static_cache.TRACER_VERSION


def test_unwritable_folder_warns_and_still_traces(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.warns(RuntimeWarning, match="cannot write the static-room cache"):
        p = RayTracer(_room(), POSE, CFG, cache=blocker / "sub").static_paths()
    assert p.num_paths > 0


def test_default_folder_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("RADARAUG_CACHE_DIR", str(tmp_path))
    assert static_cache.default_cache_dir() == tmp_path
    monkeypatch.delenv("RADARAUG_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert static_cache.default_cache_dir() == tmp_path / "xdg" / "radaraug"


def test_a_killed_writers_temporary_is_removed_by_the_next_write(tmp_path):
    """A writer killed mid-write leaves only its temporary file (never a partial entry); the next
    write of the entry removes it once stale, and leaves a fresh one (a live writer's) alone."""
    import os
    import time

    tracer = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    key = tracer.cache_key()
    stale = tmp_path / f".static-{key}.dead.tmp"
    live = tmp_path / f".static-{key}.live.tmp"
    for f in (stale, live):
        f.write_bytes(b"half a torch file")
    old = time.time() - 2 * static_cache.STALE_TEMPORARY_S
    os.utime(stale, (old, old))
    tracer.static_paths()
    assert not stale.exists() and live.exists()
    assert (tmp_path / f"static-{key}.pt").is_file()
