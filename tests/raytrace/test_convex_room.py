"""The convex-room fast path gives exactly the paths of the ray-cast path, and is only used when valid."""

from __future__ import annotations

import torch

from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import Ellipsoids, SceneGeometry
from radaraug.scene.scene import Scene


def _people(scene: Scene, n: int = 8) -> Ellipsoids:
    e = scene.people_ellipsoids(torch.arange(n, dtype=torch.float64) * 0.1)
    return Ellipsoids(e.centers.float(), e.semi_axes.float(), e.rotations.float(), e.velocities.float(), e.material)


def test_convex_fast_path_matches_ray_casting() -> None:
    scene = Scene.builtin("corridor_two_walkers")
    tracer = RayTracer(scene.room, scene.radar, scene.config, rays=16)
    assert tracer.convex_room
    ell = _people(scene)
    fast = tracer.target_paths(ell)
    tracer.convex_room = False
    slow = tracer.target_paths(ell)
    assert torch.equal(fast.mask, slow.mask)
    assert fast.mask[..., 32:].any()  # multipath present
    torch.testing.assert_close(fast.amplitude, slow.amplitude)
    torch.testing.assert_close(fast.delay_s, slow.delay_s)


def test_open_room_is_not_treated_as_convex() -> None:
    scene = Scene.builtin("corridor")
    room = scene.room
    # Remove the faces of the far wall: an opening, so the room no longer encloses anything.
    centroid_x = room.triangles[..., 0].mean(-1)
    keep = centroid_x < centroid_x.max() - 1e-6
    open_room = SceneGeometry(room.vertices, room.faces[keep], room.face_material[keep], room.materials)
    assert not RayTracer(open_room, scene.radar, scene.config, rays=16).convex_room


def test_degenerate_point_sets_are_not_closed_rooms() -> None:
    """Too few or coplanar triangles are "not a closed convex room" (Qhull's own error is caught,
    nothing else: a missing dependency must not silently turn the fast path off)."""
    import torch

    from radaraug.raytrace.targets import _is_closed_convex

    one = torch.tensor([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    assert _is_closed_convex(one, torch.tensor([0.5])) is False
    line = torch.tensor([[[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]])
    assert _is_closed_convex(line, torch.tensor([0.0])) is False
