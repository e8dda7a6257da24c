"""The tracer tells its diffuse static paths from the specular ones (what the calibration scales)."""

from __future__ import annotations

import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.errors import SceneError
from radaraug.raytrace import cache as static_cache
from radaraug.raytrace import tracer as tracer_module
from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import RadarPose
from radaraug.scene.room import corridor

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16)
POSE = RadarPose.look_at((0.1, 0.0, 1.2), (5.0, 0.0, 1.2))


def _room():
    return corridor(5.0, 2.0, 2.7, max_edge_m=1.0)


def test_parts_partition_the_static_paths(tmp_path):
    tr = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    everything, spec, diff = tr.static_paths(), tr.static_paths("specular"), tr.static_paths("diffuse")
    mask = tr.static_diffuse_mask()
    assert diff.num_paths > 100 and spec.num_paths > 0
    assert int(mask.sum()) == diff.num_paths and spec.num_paths + diff.num_paths == everything.num_paths
    torch.testing.assert_close(torch.cat([spec.amplitude, diff.amplitude]),
                               torch.cat([everything.amplitude[~mask], everything.amplitude[mask]]))
    # The diffuse part is exactly what the diffuse tracer adds: without it, the specular paths
    # are the same reflections but with the smooth surface's full coefficient (sqrt(1 - S^2) undone).
    smooth = RayTracer(_room(), POSE, CFG, cache=False, diffuse=False)
    assert smooth.static_paths("diffuse").num_paths == 0
    assert smooth.static_paths("specular").num_paths == spec.num_paths
    with pytest.raises(SceneError, match="part must be one of"):
        tr.static_paths("rough")


def test_diffuse_gain_scales_only_the_diffuse_part():
    """The tracer's ``diffuse_gain_dB`` is a field factor 10**(g/20) on every diffuse path and
    leaves the specular paths as they are: what the calibration's no-retrace scaling assumes."""
    a = RayTracer(_room(), POSE, CFG, cache=False, dtype=torch.float64)
    b = RayTracer(_room(), POSE, CFG, cache=False, dtype=torch.float64, diffuse_gain_dB=6.0)
    torch.testing.assert_close(b.static_paths("specular").amplitude, a.static_paths("specular").amplitude)
    torch.testing.assert_close(b.static_paths("diffuse").delay_s, a.static_paths("diffuse").delay_s)
    torch.testing.assert_close(b.static_paths("diffuse").amplitude, a.static_paths("diffuse").amplitude * 10 ** (6 / 20))


def test_mask_survives_the_disk_cache_and_old_entries_are_traced_again(tmp_path, monkeypatch):
    ref = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    ref_mask = ref.static_diffuse_mask()
    entry = next(tmp_path.glob("static-*.pt"))
    calls = []
    real = tracer_module.diffuse_paths
    monkeypatch.setattr(tracer_module, "diffuse_paths", lambda *a, **k: calls.append(1) or real(*a, **k))
    loaded = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    assert torch.equal(loaded.static_diffuse_mask(), ref_mask) and calls == []
    # An entry written before the mask existed cannot say which paths are diffuse: traced again.
    data = torch.load(entry, weights_only=True)
    del data["diffuse"]
    del data["version"]
    static_cache.store(tmp_path, ref.cache_key(), data)
    again = RayTracer(_room(), POSE, CFG, cache=tmp_path)
    assert torch.equal(again.static_diffuse_mask(), ref_mask) and calls == [1]
    assert "diffuse" in torch.load(entry, weights_only=True)
