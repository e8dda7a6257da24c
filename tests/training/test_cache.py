"""The simulate-once cache: a change of any input re-simulates, an unchanged one does not."""

import h5py
import numpy as np
import pytest
import torch
from data import small_config

from radaraug.errors import CaptureError
from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.scenarios import ScenarioSampler
from radaraug.training.cache import CachedMaps, build_map_cache, cache_key, cache_spec
from radaraug.training.pipeline import rd_db_chain

TWIN = {"tracer_options": {"rays": 16}}


def _ds(scene="corridor", **kw):
    args = {"length": 6, "seed": 0, "config": small_config(), "twin_options": TWIN} | kw
    return SimulatedRadarDataset(scene, **args)


def test_key_changes_with_every_input():
    base = cache_key(cache_spec(_ds(), range(4)))
    assert cache_key(cache_spec(_ds(), range(4))) == base
    changed = [
        cache_spec(_ds(seed=1), range(4)),
        cache_spec(_ds(), range(5)),
        cache_spec(_ds(), [0, 2, 4, 6]),
        cache_spec(_ds(config=small_config().replace(if_gain_dB=38)), range(4)),
        cache_spec(_ds(sampler=ScenarioSampler(speed_m_s=(0.5, 1.0))), range(4)),
        cache_spec(_ds(scene="corridor_two_walkers"), range(4)),
        cache_spec(_ds(twin_options={"tracer_options": {"rays": 32}}), range(4)),
        cache_spec(_ds(), range(4), interference_db=6.0),  # the maps' chain
    ]
    keys = {cache_key(s) for s in changed}
    assert base not in keys and len(keys) == len(changed)


def test_build_reuses_and_matches_the_twin(tmp_path):
    ds = _ds()
    path = build_map_cache(ds, range(4), tmp_path, progress=False, batch_size=3)
    mtime = path.stat().st_mtime_ns
    again = build_map_cache(_ds(), range(4), tmp_path, progress=False)
    assert again == path and path.stat().st_mtime_ns == mtime  # not re-simulated
    other = build_map_cache(_ds(seed=3), range(4), tmp_path, progress=False)
    assert other != path and len(list(tmp_path.glob("*.h5"))) == 2
    cached = CachedMaps(path)
    assert len(cached) == 4 and cached.indices.tolist() == [0, 1, 2, 3]
    x, count = ds[2]
    assert count == int(cached.counts[2])
    expect = rd_db_chain()(x)
    got, _ = cached[2]
    assert got.shape == expect.shape
    # float16 storage: 0.06 dB steps at -100 dB
    assert torch.allclose(got, expect.clamp(-300, 300), atol=0.07)


def test_killed_build_leaves_no_trusted_file(tmp_path, monkeypatch):
    ds = _ds()
    import radaraug.training.cache as cache_mod

    real_chain = cache_mod.rd_db_chain
    calls = []

    class Dies:
        def __init__(self, interference_db=None):
            self.interference_db = interference_db

        def chain_spec(self):
            return real_chain(self.interference_db).chain_spec()

        def __call__(self, x):
            calls.append(1)
            raise KeyboardInterrupt  # stands in for a kill after the file was opened

    monkeypatch.setattr(cache_mod, "rd_db_chain", Dies)
    with pytest.raises(KeyboardInterrupt):
        build_map_cache(ds, range(2), tmp_path, progress=False)
    assert calls and list(tmp_path.iterdir()) == []


def test_not_a_cache_is_a_clear_error(tmp_path):
    p = tmp_path / "x.h5"
    with h5py.File(p, "w") as f:
        f["maps"] = np.zeros((1, 1, 2, 2))
    with pytest.raises(CaptureError, match="not a radaraug simulated-map cache"):
        CachedMaps(p)
    with pytest.raises(CaptureError, match="cannot read"):
        CachedMaps(tmp_path / "missing.h5")


def test_sigkill_during_build_leaves_no_trusted_file(tmp_path):
    """A separate process killed with SIGKILL mid-build: no cache file, and the next build is whole."""
    import os
    import signal
    import subprocess
    import sys
    import time
    from pathlib import Path

    script = (
        f"import sys; sys.path.insert(0, {str(Path(__file__).parent)!r})\n"
        "from data import small_config\n"
        "from radaraug.sim.dataset import SimulatedRadarDataset\n"
        "from radaraug.training.cache import build_map_cache\n"
        "ds = SimulatedRadarDataset('corridor', length=4000, seed=0, config=small_config(),"
        " twin_options={'tracer_options': {'rays': 16}})\n"
        f"build_map_cache(ds, range(4000), {str(tmp_path)!r}, progress=False, batch_size=2)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", script])
    try:
        deadline = time.time() + 120
        while not list(tmp_path.glob(".sim-*.tmp")) and time.time() < deadline:
            time.sleep(0.2)
        time.sleep(1.0)  # let it write some items
        assert proc.poll() is None, "the build finished before it could be killed"
    finally:
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
    assert list(tmp_path.glob("sim-*.h5")) == []  # only the hidden temporary: nothing a later run trusts
    from radaraug.training.cache import _remove_dead_partials

    big = SimulatedRadarDataset("corridor", length=4000, seed=0, config=small_config(), twin_options=TWIN)
    dead = tmp_path / f"sim-{cache_key(cache_spec(big, range(4000)))}.h5"
    assert len(list(tmp_path.glob(f".{dead.name}.*.tmp"))) == 1  # the _files convention's temporary
    _remove_dead_partials(dead)  # what the next build of that key does first
    assert list(tmp_path.glob(".*.tmp")) == []
    # the next build (here a smaller one of another key) cleans the dead partial of its own key only
    ds = _ds()
    path = build_map_cache(ds, range(2), tmp_path, progress=False)
    assert len(CachedMaps(path)) == 2


def test_maps_by_index_list_read_from_the_file(tmp_path):
    """``maps([i, j])`` of a cache not held in memory indexed a ``range`` with a list (TypeError)."""
    path = build_map_cache(_ds(), range(3), tmp_path, progress=False)
    disk, memory = CachedMaps(path, in_memory=False), CachedMaps(path)
    assert torch.equal(disk.maps([2, 0]), memory.maps([2, 0]))
    assert torch.equal(disk.maps(slice(1, 3)), memory.maps(slice(1, 3)))


def test_splits_built_in_one_pass_equal_separate_builds(tmp_path):
    from radaraug.training.cache import build_map_caches

    one = build_map_caches(_ds(), {"train": range(0, 4), "val": range(4, 6)}, tmp_path / "a", progress=False,
                           batch_size=3)  # a batch straddles the two splits
    sep = {"train": build_map_cache(_ds(), range(0, 4), tmp_path / "b", name="train", progress=False),
           "val": build_map_cache(_ds(), range(4, 6), tmp_path / "b", name="val", progress=False)}
    for name in ("train", "val"):
        assert one[name].name == sep[name].name  # same keys
        a, b = CachedMaps(one[name]), CachedMaps(sep[name])
        assert torch.equal(a.maps(), b.maps()) and torch.equal(a.counts, b.counts)
        assert a.indices.tolist() == b.indices.tolist()
    mtime = one["val"].stat().st_mtime_ns
    assert build_map_caches(_ds(), {"train": range(0, 4), "val": range(4, 6)}, tmp_path / "a",
                            progress=False)["val"].stat().st_mtime_ns == mtime  # reused
