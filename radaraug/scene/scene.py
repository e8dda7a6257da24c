"""`Scene`: a room, a radar (pose + configuration) and people.

Scene files (YAML or JSON, documented in ``docs/scenes.md``) are read, validated and written by
:mod:`radaraug.scene.scene_file`; :meth:`Scene.from_file`, :meth:`Scene.save` and the other
methods here call it.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import torch

from radaraug.config import RadarConfig
from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry
from radaraug.scene.room import merge
from radaraug.scene.scattering import DiffuseScattering
from radaraug.scene.scene_file import (
    builtin_scene,
    parse_scene,
    read_scene_data,
    scene_to_dict,
    write_scene_file,
)

if TYPE_CHECKING:
    from radaraug.scene.people.person import Person


@dataclass(eq=False)  # tensors inside: compare with to_dict() instead
class Scene:
    """A radar scene: room geometry, radar pose and configuration, and people.

    Attributes:
        room: the static geometry (object id 0).
        radar: where the radar is and where it looks.
        config: the radar configuration.
        people: person objects from :mod:`radaraug.scene.people` (``Walker``, ``BVHPerson``,
            ``MeshSequencePerson``).
        name: scene name.
        source: the file the scene was read from, if any.
        room_spec: the description the room was built from (written back by :meth:`to_dict`);
            None for a room built in Python, which is then written inline (every vertex).
        materials_spec: materials the scene file defined (re-written by :meth:`to_dict`).
        objects_spec: the static objects (``objects:`` of the file) merged into ``room``.
        scattering: per-material diffuse-scattering overrides from the file's ``materials``
            section (see :mod:`radaraug.scene.scattering`), for
            :func:`radaraug.raytrace.diffuse.diffuse_paths` ``(scattering=...)``.
    """

    room: SceneGeometry
    radar: RadarPose
    config: RadarConfig = field(default_factory=RadarConfig.bgt60tr13c)
    people: list[Person] = field(default_factory=list)
    name: str = "scene"
    source: Path | None = None
    room_spec: dict[str, Any] | None = None
    materials_spec: dict[str, Any] = field(default_factory=dict)
    objects_spec: list[dict[str, Any]] = field(default_factory=list)
    scattering: dict[str, DiffuseScattering] = field(default_factory=dict)
    _person_specs: list[tuple[Person, dict[str, Any]]] = field(default_factory=list, repr=False)

    # ------------------------------------------------------------------ reading
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, source: str | os.PathLike | None = None) -> Scene:
        """Build from a parsed scene description; ``source`` (a file) anchors relative paths.

        Raises:
            SceneError: bad content (the message names the file and the key).
        """
        return cls(**parse_scene(data, source=source))

    @classmethod
    def from_file(cls, path: str | os.PathLike) -> Scene:
        """Read a ``.yaml``/``.yml`` or ``.json`` scene file.

        Raises:
            SceneError: missing file, unknown suffix, parse error, or bad content (the message
                names the file and the key).
        """
        return cls.from_dict(read_scene_data(path), source=Path(path))

    @classmethod
    def builtin(cls, name: str) -> Scene:
        """A scene shipped with radaraug, see :func:`builtin_scene`."""
        return cls.from_file(builtin_scene(name))

    @classmethod
    def load(cls, scene: Scene | str | os.PathLike) -> Scene:
        """The one entry point for getting a scene: a Scene, a scene file or a built-in scene name.

        A :class:`Scene` is returned as is; a scene file is ``.yaml``/``.yml``/``.json``, or any existing
        file.

        Raises:
            SceneError: missing or invalid file, or unknown built-in name (the message lists them).
        """
        if isinstance(scene, Scene):
            return scene
        p = Path(scene)
        if p.suffix.lower() in (".yaml", ".yml", ".json") or p.is_file():
            return cls.from_file(p)
        return cls.builtin(str(scene))

    # ------------------------------------------------------------------ writing
    def to_dict(self, *, relative_to: str | os.PathLike | None = None) -> dict[str, Any]:
        """The scene description; file paths relative to ``relative_to`` when given."""
        return scene_to_dict(self, relative_to=relative_to)

    def save(self, path: str | os.PathLike) -> Path:
        """Write the scene as YAML or JSON (by suffix); file paths relative to its folder."""
        return write_scene_file(self, path)

    # ------------------------------------------------------------------ people
    def people_ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        """Every person's body segments at times ``t`` (``(T,)`` seconds), concatenated.

        Returns:
            :class:`Ellipsoids` with shapes ``(T, S, ...)``, ``S`` the total segment count (0 for
            an empty scene).
        """
        t = torch.as_tensor(t)
        if not self.people:
            dtype = t.dtype if t.is_floating_point() else torch.get_default_dtype()
            lead = tuple(t.shape)
            z = torch.zeros(*lead, 0, 3, dtype=dtype, device=t.device)
            return Ellipsoids(z, z.clone(), torch.zeros(*lead, 0, 3, 3, dtype=dtype, device=t.device), z.clone())
        return Ellipsoids.cat([p.ellipsoids(t) for p in self.people])

    def people_meshes(self, t: float) -> list[SceneGeometry]:
        """Every person's mesh at time ``t`` seconds (with vertex velocities)."""
        return [p.mesh(t) for p in self.people]

    def geometry(self, t: float | None = None) -> SceneGeometry:
        """The room merged with the people's meshes at ``t`` (room only when ``t`` is None).

        Object ids: 0 for the room, then one id per person in list order.
        """
        if t is None or not self.people:
            return self.room
        return merge([self.room, *self.people_meshes(t)])


__all__ = ["Scene", "builtin_scene"]
