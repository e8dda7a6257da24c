"""The common interface of every person model, and the ellipsoid tessellation shared by them."""

from __future__ import annotations

import inspect
import math
from abc import ABC, abstractmethod
from functools import lru_cache
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import
from radaraug.errors import InputTensorError, SceneError
from radaraug.scene.geometry import Ellipsoids, SceneGeometry

MESH_VELOCITY_DT_S = 1e-4
"""Half-step of the central differences that give mesh vertex velocities (seconds)."""


def as_times(t: torch.Tensor | float | Any, name: str = "t") -> torch.Tensor:
    """Validate a time argument: a 0-D or 1-D finite tensor/number -> ``(T,)`` float tensor."""
    if not isinstance(t, torch.Tensor):
        try:
            t = torch.as_tensor(t, dtype=torch.float64)
        except (TypeError, ValueError, RuntimeError) as exc:
            raise InputTensorError(f"{name}: expected a tensor of times in seconds, got {type(t).__name__}") from exc
    if not torch.is_floating_point(t):
        t = t.to(torch.get_default_dtype())
    if t.ndim == 0:
        t = t.reshape(1)
    if t.ndim != 1:
        raise InputTensorError(f"{name}: expected shape (T,) of times in seconds, got {tuple(t.shape)}")
    if not bool(torch.isfinite(t).all()):
        raise InputTensorError(f"{name}: times must be finite (found NaN/Inf)")
    return t


@lru_cache(maxsize=8)
def _unit_icosphere(subdivisions: int) -> tuple[np.ndarray, np.ndarray]:
    trimesh = lazy_import("trimesh", feature="meshes")

    s = trimesh.creation.icosphere(subdivisions=subdivisions, radius=1.0)
    return np.asarray(s.vertices, dtype=np.float64), np.asarray(s.faces, dtype=np.int64)


def icosphere_level(faces_per_segment: int) -> int:
    """Largest icosphere subdivision level whose face count ``20 * 4**k`` fits the budget."""
    if int(faces_per_segment) < 20:
        raise SceneError(f"faces_per_segment={faces_per_segment}: at least 20 (an icosahedron)")
    return int(math.floor(math.log(int(faces_per_segment) / 20.0, 4) + 1e-9))


def tessellate(ell: Ellipsoids, faces_per_segment: int = 320) -> tuple[torch.Tensor, torch.Tensor]:
    """Triangulate ellipsoids: an icosphere through each ellipsoid's affine map (faces stay outward).

    Args:
        ell: ellipsoids with shapes ``(..., S, ...)``.
        faces_per_segment: triangle budget per ellipsoid (20, 80, 320, 1280, ...; rounded down).

    Returns:
        ``vertices (..., S*V, 3)`` and ``faces (S*F, 3)`` (long, on the same device).
    """
    uv, uf = _unit_icosphere(icosphere_level(faces_per_segment))
    c = ell.centers
    u = torch.as_tensor(uv, dtype=c.dtype, device=c.device)
    local = u * ell.semi_axes.unsqueeze(-2)  # (..., S, V, 3)
    verts = c.unsqueeze(-2) + local @ ell.rotations.transpose(-1, -2)
    s, v = verts.shape[-3], verts.shape[-2]
    offs = torch.arange(s, device=c.device).view(s, 1, 1) * v
    faces = (torch.as_tensor(uf, device=c.device).unsqueeze(0) + offs).reshape(-1, 3)
    return verts.reshape(*verts.shape[:-3], s * v, 3), faces


class Person(ABC):
    """A moving person: ellipsoid segments for fast scattering, a triangle mesh for ray tracing.

    World frame: metres, ``z`` up, ground at ``z = 0``. A concrete person type registers itself
    with :func:`register_person` under its :attr:`type_name`, the ``type`` of scene files.
    """

    material: str = "skin"
    type_name: str = ""
    """The ``type`` that names this kind of person in scene files and :meth:`to_dict`."""
    _FIELDS: tuple[str, ...] = ()
    """Constructor keywords that :meth:`to_dict` writes, each read from the attribute of that name."""

    @abstractmethod
    def ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        """Body segments at times ``t`` ``(T,)`` s: centres ``(T, S, 3)`` etc., velocities in m/s."""

    def to_dict(self) -> dict[str, Any]:
        """The constructor parameters, JSON-serializable (for scene files): ``type`` and :attr:`_FIELDS`."""
        out: dict[str, Any] = {"type": self.type_name}
        for k in self._FIELDS:
            value = getattr(self, k)
            out[k] = list(value) if isinstance(value, tuple) else value
        return out

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Person:
        """Rebuild a person from :meth:`to_dict` output (its keys are constructor keywords).

        Raises:
            SceneError: this type cannot be rebuilt from a dict, unknown parameters, or values
                the constructor refuses.
        """
        if not cls._FIELDS:
            raise SceneError(f"person type {cls.__name__} cannot be rebuilt from a scene file")
        unknown = sorted(set(d) - {"type"} - set(inspect.signature(cls).parameters))
        if unknown:
            raise SceneError(f"{cls.type_name}: unknown parameters {unknown} in {d!r}")
        # JSON/YAML give lists; the constructors take (x, y) tuples.
        kwargs = {k: tuple(v) if isinstance(v, list) else v for k, v in d.items() if k != "type"}
        try:
            return cls(**kwargs)
        except SceneError:
            raise
        except (TypeError, ValueError) as exc:
            raise SceneError(f"{cls.type_name}: bad parameters {d!r}: {exc}") from exc

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={getattr(self, k)!r}" for k in self._FIELDS)
        return f"{type(self).__name__}({args})"

    def _ellipsoids_for_mesh(self, t: torch.Tensor) -> Ellipsoids:
        """Ellipsoids at ``t`` ``(3,)`` with frames chosen consistently across the three instants."""
        return self.ellipsoids(t)

    def _surface(self, t0: float, faces_per_segment: int) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Float64 vertices ``(V, 3)``, faces ``(F, 3)`` and vertex velocities ``(V, 3)`` at ``t0``.

        The tessellated ellipsoids, velocities by central differences over ``t0 +- MESH_VELOCITY_DT_S``.
        """
        dt = MESH_VELOCITY_DT_S
        times = torch.tensor([t0 - dt, t0, t0 + dt], dtype=torch.float64)
        verts, faces = tessellate(self._ellipsoids_for_mesh(times), faces_per_segment)
        return verts[1], faces, (verts[2] - verts[0]) / (2.0 * dt)

    def mesh(
        self,
        t: float,
        *,
        faces_per_segment: int = 320,
        dtype: torch.dtype = torch.float32,
        device: torch.device | str | None = None,
    ) -> SceneGeometry:
        """Triangle mesh of the body at time ``t`` with per-vertex velocities (rotation included).

        Args:
            t: time in seconds.
            faces_per_segment: triangles per ellipsoid (rounded down to ``20 * 4**k``).
            dtype: float dtype of the output.
            device: output device (default CPU).

        Returns:
            :class:`SceneGeometry` with material ``"skin"`` on every face, ``object_id`` None
            (the scene assigns object ids).
        """
        verts, faces, vel = self._surface(float(as_times(t)[0]), faces_per_segment)
        dev = torch.device("cpu") if device is None else torch.device(device)
        return SceneGeometry(
            vertices=verts.to(device=dev, dtype=dtype),
            faces=faces.to(dev),
            face_material=torch.zeros(faces.shape[0], dtype=torch.long, device=dev),
            materials=(self.material,),
            vertex_velocity=vel.to(device=dev, dtype=dtype),
            object_id=None,
        )


PERSON_TYPES: dict[str, type[Person]] = {}
"""Person types by their scene-file ``type`` (filled by :func:`register_person`; the built-in
ones are registered when ``radaraug.scene.people`` is imported, which importing any of its
modules does first)."""


def register_person(cls: type[Person]) -> type[Person]:
    """Class decorator: add ``cls`` to :data:`PERSON_TYPES` under ``cls.type_name``.

    Raises:
        ValueError: no ``type_name``, or the name is taken by another class.
    """
    if not cls.type_name or PERSON_TYPES.get(cls.type_name, cls) is not cls:
        raise ValueError(f"person type {cls.__name__}: type_name {cls.type_name!r} is empty or taken")
    PERSON_TYPES[cls.type_name] = cls
    return cls


def person_type(name: Any) -> type[Person]:
    """The registered person class for a scene-file ``type``.

    Raises:
        SceneError: an unknown type (the message lists the known ones).
    """
    if not isinstance(name, str) or name not in PERSON_TYPES:
        raise SceneError(f"person: unknown or missing 'type' {name!r}; expected one of {sorted(PERSON_TYPES)}")
    return PERSON_TYPES[name]


def person_from_dict(d: dict[str, Any]) -> Person:
    """Rebuild a person from :meth:`Person.to_dict` output."""
    if not isinstance(d, dict) or d.get("type") not in PERSON_TYPES:
        raise SceneError(f"person: unknown or missing 'type' in {d!r}; expected one of {sorted(PERSON_TYPES)}")
    return PERSON_TYPES[d["type"]].from_dict(d)


class SkeletonPerson(Person):
    """A person driven by the 17 joints of :class:`~radaraug.scene.people.Skeleton`.

    Subclasses implement :meth:`joints`; ellipsoids and meshes follow from it.
    """

    def __init__(self, height_m: float) -> None:
        from radaraug.scene.people.skeleton import Skeleton

        self.skeleton = Skeleton(height_m=float(height_m))

    @abstractmethod
    def joints(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Joint positions and velocities at ``t`` ``(T,)``: both ``(T, 17, 3)`` (m, m/s)."""

    def ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        """The 16 segment ellipsoids at ``t`` ``(T,)`` seconds (see :class:`Skeleton`)."""
        pos, vel = self.joints(as_times(t))
        return self.skeleton.ellipsoids(pos, vel, material=self.material)

    def _ellipsoids_for_mesh(self, t: torch.Tensor) -> Ellipsoids:
        pos, vel = self.joints(t)
        _, fallback = self.skeleton.segment_frames(pos[1])
        return self.skeleton.ellipsoids(pos, vel, fallback=fallback.expand(3, -1), material=self.material)
