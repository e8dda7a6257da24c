"""Plain-tensor scene geometry: the interface between scene building and the ray tracer.

World frame: metres, right-handed, ``z`` up. The radar's own frame (the antenna frame of
:class:`radaraug.RadarConfig`): ``x`` to the sensor's right, ``y`` up, ``z`` along boresight.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, TypeVar

import torch

_D = TypeVar("_D", "SceneGeometry", "Ellipsoids")


def _moved(obj: _D, device: torch.device | str) -> _D:
    """A copy of ``obj`` with every tensor field on ``device`` (fields that are None stay None)."""
    values = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
    moved: dict[str, Any] = {k: v.to(device) for k, v in values.items() if isinstance(v, torch.Tensor)}
    return dataclasses.replace(obj, **moved)


@dataclass
class SceneGeometry:
    """A triangle soup with a material per face.

    Attributes:
        vertices: ``(V, 3)`` float vertex positions in the world frame, metres.
        faces: ``(F, 3)`` long vertex indices, counter-clockwise seen from the side the
            outward normal points to.
        face_material: ``(F,)`` long index into ``materials``.
        materials: material names (keys of :data:`radaraug.scene.materials.MATERIALS`).
        vertex_velocity: ``(V, 3)`` float m/s, or None for a static mesh.
        object_id: ``(F,)`` long id of the object each face belongs to (0 = room), or None.
    """

    vertices: torch.Tensor
    faces: torch.Tensor
    face_material: torch.Tensor
    materials: tuple[str, ...]
    vertex_velocity: torch.Tensor | None = None
    object_id: torch.Tensor | None = None

    @property
    def triangles(self) -> torch.Tensor:
        """``(F, 3, 3)`` vertex coordinates per face."""
        return self.vertices[self.faces]

    @property
    def num_faces(self) -> int:
        """Number of triangles."""
        return int(self.faces.shape[0])

    def to(self, device: torch.device | str) -> SceneGeometry:
        """Move every tensor to ``device``."""
        return _moved(self, device)


@dataclass
class RadarPose:
    """Where the radar is and where it looks.

    Attributes:
        position: ``(3,)`` world position of the antenna-frame origin, metres.
        rotation: ``(3, 3)`` world-from-radar rotation; its columns are the radar's x (right),
            y (up) and z (boresight) axes in world coordinates.
    """

    position: torch.Tensor
    rotation: torch.Tensor = field(default_factory=lambda: torch.eye(3))

    @classmethod
    def look_at(
        cls,
        position: tuple[float, float, float],
        target: tuple[float, float, float],
        up: tuple[float, float, float] = (0.0, 0.0, 1.0),
        dtype: torch.dtype = torch.float64,
    ) -> RadarPose:
        """A pose at ``position`` with boresight toward ``target`` and the sensor's y toward ``up``."""
        p = torch.tensor(position, dtype=dtype)
        z = torch.tensor(target, dtype=dtype) - p
        z = z / z.norm()
        u = torch.tensor(up, dtype=dtype)
        x = torch.linalg.cross(z, u)
        if x.norm() < 1e-9:
            raise ValueError("look_at: boresight is parallel to 'up'")
        x = x / x.norm()
        y = torch.linalg.cross(x, z)
        return cls(position=p, rotation=torch.stack([x, y, z], dim=1))


@dataclass
class Ellipsoids:
    """A set of moving ellipsoids (body segments), possibly at several time instants.

    Shapes: ``S`` segments, any leading dims ``...`` (e.g. time instants).

    Attributes:
        centers: ``(..., S, 3)`` world positions of the ellipsoid centres, metres.
        semi_axes: ``(..., S, 3)`` semi-axis lengths along the ellipsoid's local x, y, z, metres.
        rotations: ``(..., S, 3, 3)`` world-from-local rotations (columns: local axes in world).
        velocities: ``(..., S, 3)`` velocity of each centre, m/s.
        material: material name of the surface (for reflectivity), default human skin.
        angular_velocities: ``(..., S, 3)`` world-frame angular velocity of each segment, rad/s (the
            tracer moves each echo with its specular point), or None: every point moves with the centre.
    """

    centers: torch.Tensor
    semi_axes: torch.Tensor
    rotations: torch.Tensor
    velocities: torch.Tensor
    material: str = "skin"
    angular_velocities: torch.Tensor | None = None

    @property
    def num_segments(self) -> int:
        """Number of ellipsoids ``S``."""
        return int(self.centers.shape[-2])

    def to(self, device: torch.device | str) -> Ellipsoids:
        """Move every tensor to ``device``."""
        return _moved(self, device)

    @staticmethod
    def cat(items: list[Ellipsoids]) -> Ellipsoids:
        """Concatenate along the segment axis (same leading dims)."""
        return Ellipsoids(
            torch.cat([e.centers for e in items], dim=-2),
            torch.cat([e.semi_axes for e in items], dim=-2),
            torch.cat([e.rotations for e in items], dim=-3),
            torch.cat([e.velocities for e in items], dim=-2),
            items[0].material,
            None if all(e.angular_velocities is None for e in items) else torch.cat(
                [torch.zeros_like(e.velocities) if e.angular_velocities is None else e.angular_velocities
                 for e in items], dim=-2),
        )
