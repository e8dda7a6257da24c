"""RayTracer end to end in a box corridor: shapes, caching, JSON summary, input errors."""

from __future__ import annotations

import json
import math

import pytest
import torch
from raytrace_scenes import box_room

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.errors import SceneError
from radaraug.raytrace.tracer import RayTracer, paths_to_json
from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry

CFG = RadarConfig.bgt60tr13c()


def _corridor_tracer(device=None, dtype=torch.float32, **kw) -> RayTracer:
    room = box_room((0.0, -1.0, 0.0), (20.0, 1.0, 3.0))
    pose = RadarPose.look_at((0.2, 0.0, 1.5), (20.0, 0.0, 1.5))
    return RayTracer(room, pose, CFG, rays=kw.pop("rays", 96), device=device, dtype=dtype, **kw)


def _walkers(t: int, s: int, dtype=torch.float32) -> Ellipsoids:
    g = torch.Generator().manual_seed(0)
    c = torch.rand(t, s, 3, generator=g, dtype=dtype) * torch.tensor([10.0, 1.4, 1.8], dtype=dtype) + torch.tensor(
        [3.0, -0.7, 0.1], dtype=dtype)
    ax = torch.rand(t, s, 3, generator=g, dtype=dtype) * 0.1 + 0.03
    return Ellipsoids(c, ax, torch.eye(3, dtype=dtype).expand(t, s, 3, 3), torch.randn(t, s, 3, generator=g, dtype=dtype))


def test_corridor_end_to_end(device):
    tracer = _corridor_tracer(device)
    static = tracer.static_paths()
    assert static.delay_s.ndim == 2 and static.delay_s.shape[1] == 3 and static.num_paths > 10
    assert static.delay_s.device.type == device.type
    assert (static.delay_rate == 0).all()
    # Nothing in a closed 20 m corridor is farther than its longest 2-bounce path.
    assert float(static.delay_s.max()) * SPEED_OF_LIGHT < 2 * 2 * math.dist((0.2, 0, 1.5), (20, 1, 3)) + 0.1
    ell = _walkers(8, 32).to(device)
    full = tracer.trace(ell)
    targets = tracer.target_paths(ell)
    assert full.delay_s.shape == (8, static.num_paths + targets.num_paths, 3)
    assert full.mask.shape == (8, full.num_paths) and full.kind.shape == (8, full.num_paths)
    torch.testing.assert_close(full.amplitude[3, : static.num_paths], static.amplitude)
    # The two walls (y = +-1), floor, ceiling and the two end walls are the mirror planes.
    assert tracer.mirrors.num_planes == 6
    assert targets.num_paths == 32 + 3 * 32 * 6  # direct, two first-order and one second-order per plane


def test_scene_without_people_traces():
    """Zero segments (``Scene.people_ellipsoids`` of an empty scene) keep the frame dim: (T, P_static, RX)."""
    tracer = _corridor_tracer(rays=16)
    empty = _walkers(4, 0)
    targets = tracer.target_paths(empty)
    assert targets.delay_s.shape == (4, 0, 3) and targets.mask.shape == (4, 0) and targets.kind.shape == (4, 0)
    full = tracer.trace(empty)
    assert full.delay_s.shape == (4, tracer.static_paths().num_paths, 3)


def test_end_wall_return_is_there():
    """The metal end wall at 19.8 m gives the strongest static returns near range 19.8 m."""
    static = _corridor_tracer(rays=128).static_paths()
    rng = static.delay_s.mean(-1) * SPEED_OF_LIGHT / 2
    p = (static.amplitude.abs() ** 2).mean(-1)
    near_end = (rng - 19.8).abs() < 0.3
    assert float(p[near_end].sum()) > float(p[(rng > 5) & (rng < 19.0)].sum())


def test_paths_to_json():
    tracer = _corridor_tracer(dtype=torch.float64)
    ell = Ellipsoids(torch.tensor([[5.0, 0.0, 1.5]], dtype=torch.float64), torch.full((1, 3), 0.2).double(),
                     torch.eye(3).double()[None], torch.tensor([[-1.0, 0.0, 0.0]]).double())
    doc = paths_to_json(tracer.trace(ell), CFG)
    json.dumps(doc)  # serializable
    rows = doc["paths"]
    assert doc["num_paths"] == len(rows) > 0
    assert set(rows[0]) == {"delay_ns", "range_m", "radial_velocity_m_s", "power_dB", "rx_phase_deg", "kind"}
    person = [r for r in rows if r["kind"] == "los" and abs(r["radial_velocity_m_s"] + 1.0) < 0.01]
    assert len(person) == 1 and person[0]["range_m"] == pytest.approx(4.8 - 0.2, abs=0.01)
    batched = paths_to_json(tracer.target_paths(_walkers(2, 3, torch.float64)), CFG)
    assert batched["batch_shape"] == [2] and len(batched["snapshots"]) == 2


def test_bad_inputs():
    room = box_room((0.0, -1.0, 0.0), (5.0, 1.0, 3.0))
    pose = RadarPose.look_at((0.2, 0.0, 1.5), (5.0, 0.0, 1.5))
    with pytest.raises(SceneError, match="max_bounces"):
        RayTracer(room, pose, CFG, max_bounces=0)
    bad = SceneGeometry(room.vertices, room.faces + 100, room.face_material, room.materials)
    with pytest.raises(SceneError, match="face indices"):
        RayTracer(bad, pose, CFG)
    bad_mat = SceneGeometry(room.vertices, room.faces, room.face_material + 10, room.materials)
    with pytest.raises(SceneError, match="materials"):
        RayTracer(bad_mat, pose, CFG)
    tracer = RayTracer(room, pose, CFG, rays=16)
    with pytest.raises(SceneError, match="semi_axes"):
        tracer.target_paths(Ellipsoids(torch.ones(1, 3), -torch.ones(1, 3), torch.eye(3)[None], torch.zeros(1, 3)))
