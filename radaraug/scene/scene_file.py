"""Scene files: reading, validating and writing the YAML/JSON description of a :class:`Scene`.

Format: ``docs/scenes.md``. Relative paths resolve against the file's folder; every error is a
:class:`~radaraug.errors.SceneError` naming the file and the key.
"""

from __future__ import annotations

import contextlib
import glob
import inspect
import json
import math
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import torch
import yaml

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, SceneError
from radaraug.files import atomic_write_text, load_json
from radaraug.scene.geometry import RadarPose, SceneGeometry
from radaraug.scene.materials import MATERIALS, Material, get_material, register_material
from radaraug.scene.people._rotations import axis_rotation
from radaraug.scene.people.person import PERSON_TYPES
from radaraug.scene.room import (
    CORRIDOR_SURFACES,
    corridor,
    load_mesh,
    merge,
    placed_box,
    placed_cylinder,
    placed_mesh,
)
from radaraug.scene.scattering import DiffuseScattering, as_scattering

if TYPE_CHECKING:
    from radaraug.scene.people.person import Person
    from radaraug.scene.scene import Scene

_SUFFIXES = (".yaml", ".yml", ".json")

_SCENES_DIR = Path(__file__).resolve().parent.parent / "data" / "scenes"
_TOP_KEYS = {"name", "description", "radar", "room", "people", "materials", "objects"}
_OBJECT_KEYS = {
    "box": ({"type", "size", "position", "yaw_deg", "material", "max_edge", "name"}, {"size", "position", "material"}),
    "cylinder": ({"type", "radius", "height", "position", "material", "sections", "max_edge", "name"},
                 {"radius", "height", "position", "material"}),
    "mesh": ({"type", "file", "scale", "position", "yaw_deg", "material", "name"}, {"file", "position", "material"}),
}
_RADAR_KEYS = {"config", "position", "look_at", "up", "rotation", "yaw_pitch_roll_deg", "mounting"}
_ROOM_KEYS = {
    "corridor": {"type", "length", "width", "height", "materials", "thickness", "end_walls", "max_edge"},
    "mesh": {"type", "file", "material", "materials", "scale", "transform"},
    "inline": {"type", "vertices", "faces", "materials", "face_material", "object_id"},
}
# Short file keys -> constructor keywords of the people classes.
_PERSON_ALIASES = {"height": "height_m", "speed": "speed_m_s", "file": "path", "files": "files_or_meshes"}


def builtin_scene(name: str) -> Path:
    """Path of a scene file shipped with radaraug (``"corridor"``, ``"corridor_one_walker"``, ...).

    Raises:
        SceneError: unknown name (the message lists the available ones).
    """
    stem = name.removesuffix(".yaml")
    path = _SCENES_DIR / f"{stem}.yaml"
    if not path.is_file():
        known = sorted(p.stem for p in _SCENES_DIR.glob("*.yaml"))
        raise SceneError(f"unknown built-in scene {name!r}; available: {', '.join(known)}")
    return path


class _Reader:
    """Validation helpers that name the file and the key in every error."""

    def __init__(self, source: Path | None) -> None:
        self.source = source
        self.folder = source.parent if source is not None else Path.cwd()

    def fail(self, key: str, msg: str) -> SceneError:
        where = f"scene file {self.source}" if self.source is not None else "scene description"
        return SceneError(f"{where}: key '{key}': {msg}")

    def mapping(self, value: Any, key: str, allowed: set[str] | None = None) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.fail(key, f"must be a mapping, got {type(value).__name__}")
        if allowed is not None:
            unknown = sorted(set(value) - allowed)
            if unknown:
                raise self.fail(key, f"unknown key(s) {unknown}; allowed: {sorted(allowed)}")
        return value

    def require(self, spec: Mapping[str, Any], keys: Iterable[str], prefix: str = "", what: str = "") -> None:
        """Fail on the first of ``keys`` that ``spec`` lacks (named ``prefix + key``; ``what`` ends the message)."""
        for k in keys:
            if k not in spec:
                raise self.fail(prefix + k, f"is required{what}")

    def sequence(self, value: Any, key: str, what: str = "a list") -> Sequence[Any]:
        if not isinstance(value, Sequence) or isinstance(value, str):
            raise self.fail(key, f"must be {what}")
        return value

    def material(self, name: Any, key: str) -> None:
        with self.naming(key):
            get_material(name)

    @contextlib.contextmanager
    def naming(self, key: str) -> Iterator[None]:
        """Re-raise a SceneError that does not name the file yet as one about ``key``."""
        try:
            yield
        except SceneError as err:
            if str(err).startswith(("scene file ", "scene description")):
                raise  # already names the file and key
            raise self.fail(key, str(err)) from None

    def number(self, value: Any, key: str, *, positive: bool = False) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise self.fail(key, f"must be a finite number, got {value!r}")
        if positive and value <= 0:
            raise self.fail(key, f"must be positive, got {value!r}")
        return float(value)

    def vector(self, value: Any, key: str, n: int, *, positive: bool = False) -> list[float]:
        if not isinstance(value, Sequence) or isinstance(value, str) or len(value) != n:
            raise self.fail(key, f"must be a list of {n} numbers, got {value!r}")
        return [self.number(v, f"{key}[{i}]", positive=positive) for i, v in enumerate(value)]

    def matrix(self, value: Any, key: str, rows: Sequence[int], cols: int) -> list[list[float]]:
        if not isinstance(value, Sequence) or isinstance(value, str) or len(value) not in rows:
            raise self.fail(key, f"must be a {'/'.join(map(str, rows))}x{cols} matrix (list of rows)")
        return [self.vector(r, f"{key}[{i}]", cols) for i, r in enumerate(value)]

    def path(self, value: Any, key: str) -> Path:
        if not isinstance(value, (str, os.PathLike)) or not str(value):
            raise self.fail(key, f"must be a file path, got {value!r}")
        p = Path(os.path.expanduser(str(value)))
        return Path(os.path.abspath(p if p.is_absolute() else self.folder / p))

    def mesh_file(self, value: Any, key: str) -> Path:
        path = self.path(value, key)
        if not path.is_file():
            raise self.fail(key, f"mesh file {path} not found")
        return path


def _relative(path: str | os.PathLike, folder: Path | None) -> str:
    """``path`` relative to ``folder`` when one is given (as written into a saved scene file)."""
    if folder is None:
        return str(path)
    try:
        return os.path.relpath(Path(path).resolve(), folder.resolve())
    except ValueError:  # other drive on Windows
        return str(Path(path).resolve())


# --------------------------------------------------------------------------------------- radar
def _yaw_pitch_roll(yaw_deg: float, pitch_deg: float, roll_deg: float) -> torch.Tensor:
    """World-from-radar rotation; (0, 0, 0) looks along +x with the sensor's y up (world z).

    Yaw turns left about world z, pitch raises the boresight, roll turns the sensor clockwise
    as seen from behind it (about the boresight).
    """
    y, p, r = (math.radians(a) for a in (yaw_deg, pitch_deg, roll_deg))
    # Body frame x forward, y left, z up: a rotation of -pitch about +y raises the nose.
    body = axis_rotation("z", y) @ axis_rotation("y", -p) @ axis_rotation("x", r)
    # Radar axes in body coordinates: x (right) = -y_body, y (up) = z_body, z (boresight) = x_body.
    body_from_radar = torch.tensor([[0, 0, 1], [-1, 0, 0], [0, 1, 0]], dtype=torch.float64)
    return body @ body_from_radar


# Portrait mounting: the sensor turned 90 degrees about its boresight so that its x axis (the
# horizontal RX1-RX3 pair in landscape) points up; new x = old y, new y = -old x.
_PORTRAIT = torch.tensor([[0, -1, 0], [1, 0, 0], [0, 0, 1]], dtype=torch.float64)


def _read_config(value: Any, rd: _Reader) -> RadarConfig:
    try:
        if value is None or value == "bgt60tr13c":
            return RadarConfig.bgt60tr13c()
        if isinstance(value, str):
            return RadarConfig.from_json(rd.path(value, "radar.config"))
        if isinstance(value, Mapping):
            data = dict(value)
            preset = data.pop("preset", None)
            if preset is not None:
                if preset != "bgt60tr13c":
                    raise rd.fail("radar.config.preset", f"unknown preset {preset!r} (known: bgt60tr13c)")
                return RadarConfig.bgt60tr13c(**data)
            if "device_config" in data or "fmcw_single_shape" in data:
                return RadarConfig.from_infineon(data, source=str(rd.source))
            return RadarConfig.from_dict(data, source=str(rd.source))
    except (ConfigError, TypeError) as err:
        raise rd.fail("radar.config", str(err)) from None
    raise rd.fail("radar.config", f"must be 'bgt60tr13c', a path or a mapping, got {value!r}")


def _read_radar(spec: Any, rd: _Reader) -> tuple[RadarPose, RadarConfig]:
    spec = rd.mapping(spec, "radar", _RADAR_KEYS)
    rd.require(spec, ("position",), "radar.")
    position = rd.vector(spec["position"], "radar.position", 3)
    given = [k for k in ("look_at", "rotation", "yaw_pitch_roll_deg") if k in spec]
    if len(given) > 1:
        raise rd.fail("radar", f"give only one of look_at / rotation / yaw_pitch_roll_deg, got {given}")
    if "look_at" in spec:
        up = rd.vector(spec.get("up", [0.0, 0.0, 1.0]), "radar.up", 3)
        try:
            target = rd.vector(spec["look_at"], "radar.look_at", 3)
            pose = RadarPose.look_at((position[0], position[1], position[2]), (target[0], target[1], target[2]),
                                     (up[0], up[1], up[2]))
        except ValueError as e:
            raise rd.fail("radar.look_at", str(e)) from None
        if not torch.isfinite(pose.rotation).all():
            raise rd.fail("radar.look_at", "must differ from radar.position")
        rotation = pose.rotation
    elif "rotation" in spec:
        rotation = torch.tensor(rd.matrix(spec["rotation"], "radar.rotation", (3,), 3), dtype=torch.float64)
        ortho_err = (rotation.T @ rotation - torch.eye(3, dtype=torch.float64)).abs().max()
        # The antenna frame (x right, y up, z boresight) is left-handed, so a valid pose matrix
        # is orthonormal with determinant -1 (RadarPose.look_at gives the same).
        if ortho_err > 1e-6 or torch.linalg.det(rotation) > 0:
            raise rd.fail("radar.rotation", "must be orthonormal with determinant -1 (columns: the radar's "
                          "x right, y up, z boresight in world coordinates, a left-handed frame)")
    else:
        rotation = _yaw_pitch_roll(*rd.vector(spec.get("yaw_pitch_roll_deg", [0.0, 0.0, 0.0]),
                                              "radar.yaw_pitch_roll_deg", 3))
    mounting = spec.get("mounting", "landscape")
    if mounting not in ("landscape", "portrait"):
        raise rd.fail("radar.mounting", f"must be 'landscape' or 'portrait', got {mounting!r}")
    if mounting == "portrait":
        rotation = rotation @ _PORTRAIT
    pose = RadarPose(position=torch.tensor(position, dtype=torch.float64), rotation=rotation)
    return pose, _read_config(spec.get("config"), rd)


# ---------------------------------------------------------------------------------------- room
def _read_room(spec: Any, rd: _Reader) -> tuple[SceneGeometry, dict[str, Any]]:
    """The geometry and a normalised spec (absolute paths) to write back."""
    spec = rd.mapping(spec, "room")
    kind = spec.get("type", "corridor")
    if kind not in _ROOM_KEYS:
        raise rd.fail("room.type", f"must be one of {sorted(_ROOM_KEYS)}, got {kind!r}")
    rd.mapping(spec, "room", _ROOM_KEYS[kind])
    norm: dict[str, Any] = {"type": kind}
    with rd.naming(f"room ({kind})"):
        if kind == "corridor":
            dims = {k: rd.number(spec.get(k, default), f"room.{k}", positive=True)
                    for k, default in (("length", 20.0), ("width", 2.0), ("height", 2.7), ("max_edge", 0.5))}
            norm.update(dims)
            mats = dict(rd.mapping(spec.get("materials", {}), "room.materials", set(CORRIDOR_SURFACES)))
            thick = {s: None if t is None else rd.number(t, f"room.thickness.{s}", positive=True)
                     for s, t in rd.mapping(spec.get("thickness", {}), "room.thickness", set(CORRIDOR_SURFACES)).items()}
            for s, m in mats.items():
                rd.material(m, f"room.materials.{s}")
            end_walls = spec.get("end_walls", True)
            if not isinstance(end_walls, bool):
                raise rd.fail("room.end_walls", f"must be true or false, got {end_walls!r}")
            norm.update(materials=mats, thickness=thick, end_walls=end_walls)
            geom = corridor(dims["length"], dims["width"], dims["height"], materials=mats, thickness_m=thick,
                            end_walls=end_walls, max_edge_m=dims["max_edge"])
        elif kind == "mesh":
            rd.require(spec, ("file",), "room.", " for a mesh room")
            path = rd.mesh_file(spec["file"], "room.file")
            material = spec.get("material", "concrete")
            mats = dict(rd.mapping(spec.get("materials", {}), "room.materials"))
            scale = rd.number(spec.get("scale", 1.0), "room.scale", positive=True)
            transform = spec.get("transform")
            if transform is not None:
                transform = rd.matrix(transform, "room.transform", (3, 4), 4)
            norm.update(file=str(path), material=material, materials=mats, scale=scale, transform=transform)
            geom = load_mesh(path, material=material, face_materials=mats or None, scale=scale,
                             transform=transform)
        else:
            geom = _inline_room(spec, rd)
            norm = _inline_dict(geom)
    return geom, norm


def _inline_room(spec: Mapping[str, Any], rd: _Reader) -> SceneGeometry:
    rd.require(spec, ("vertices", "faces", "materials", "face_material"), "room.", " for an inline room")
    try:
        vertices = torch.tensor(spec["vertices"], dtype=torch.get_default_dtype())
        faces = torch.tensor(spec["faces"], dtype=torch.long)
        face_material = torch.tensor(spec["face_material"], dtype=torch.long)
        object_id = torch.tensor(spec["object_id"], dtype=torch.long) if "object_id" in spec else None
    except (TypeError, ValueError, RuntimeError) as err:
        raise rd.fail("room", f"inline arrays are malformed: {err}") from None
    for k in ("faces", "face_material", "object_id"):
        # torch.tensor(..., dtype=long) truncates 1.5 to 1 silently: indices must be integers.
        if k in spec and not _all_integers(spec[k]):
            raise rd.fail(f"room.{k}", "must contain integers only")
    materials = rd.sequence(spec["materials"], "room.materials", "a list of material names")
    if vertices.ndim != 2 or vertices.shape[1] != 3 or faces.ndim != 2 or faces.shape[1] != 3:
        raise rd.fail("room", "vertices and faces must be lists of 3-element lists")
    if not bool(torch.isfinite(vertices).all()):
        raise rd.fail("room.vertices", "must be finite numbers (found NaN or inf)")
    if face_material.shape != faces.shape[:1] or (object_id is not None and object_id.shape != faces.shape[:1]):
        raise rd.fail("room.face_material", "needs one entry per face")
    if faces.numel() and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise rd.fail("room.faces", "vertex index out of range")
    if face_material.numel() and (face_material.min() < 0 or face_material.max() >= len(materials)):
        raise rd.fail("room.face_material", "material index out of range")
    for i, m in enumerate(materials):
        rd.material(m, f"room.materials[{i}]")
    return SceneGeometry(vertices, faces, face_material, tuple(materials), None,
                         object_id if object_id is not None else torch.zeros(len(faces), dtype=torch.long))


def _all_integers(value: Any) -> bool:
    """True when every leaf of a nested list is an int (bools are not)."""
    if isinstance(value, Sequence) and not isinstance(value, str):
        return all(_all_integers(v) for v in value)
    return isinstance(value, int) and not isinstance(value, bool)


def _inline_dict(geom: SceneGeometry) -> dict[str, Any]:
    return {
        "type": "inline",
        "vertices": geom.vertices.detach().cpu().double().tolist(),
        "faces": geom.faces.cpu().tolist(),
        "materials": list(geom.materials),
        "face_material": geom.face_material.cpu().tolist(),
        **({"object_id": geom.object_id.cpu().tolist()} if geom.object_id is not None else {}),
    }


# ------------------------------------------------------------------------------------- objects
def _read_object(spec: Any, i: int, rd: _Reader) -> tuple[SceneGeometry, dict[str, Any]]:
    """One ``objects[i]`` entry: its geometry (object id 0, part of the static room) and spec."""
    key = f"objects[{i}]"
    spec = rd.mapping(spec, key)
    kind = spec.get("type")
    if kind not in _OBJECT_KEYS:
        raise rd.fail(f"{key}.type", f"must be one of {sorted(_OBJECT_KEYS)}, got {kind!r}")
    allowed, required = _OBJECT_KEYS[kind]
    rd.mapping(spec, key, allowed)
    rd.require(spec, sorted(required), f"{key}.", f" for a {kind} object")
    material = spec["material"]
    rd.material(material, f"{key}.material")
    norm: dict[str, Any] = {"type": kind}
    if "name" in spec:
        if not isinstance(spec["name"], str):
            raise rd.fail(f"{key}.name", f"must be a string, got {spec['name']!r}")
        norm["name"] = spec["name"]
    position = rd.vector(spec["position"], f"{key}.position", 3)
    norm["position"] = position
    with rd.naming(key):
        if kind == "box":
            size = rd.vector(spec["size"], f"{key}.size", 3, positive=True)
            yaw = rd.number(spec.get("yaw_deg", 0.0), f"{key}.yaw_deg")
            edge = rd.number(spec.get("max_edge", 0.5), f"{key}.max_edge", positive=True)
            norm.update(size=size, yaw_deg=yaw, max_edge=edge)
            geom = placed_box(size, position, material, yaw_deg=yaw, max_edge_m=edge)
        elif kind == "cylinder":
            radius = rd.number(spec["radius"], f"{key}.radius", positive=True)
            height = rd.number(spec["height"], f"{key}.height", positive=True)
            sections = spec.get("sections", 24)
            if isinstance(sections, bool) or not isinstance(sections, int) or sections < 3:
                raise rd.fail(f"{key}.sections", f"must be an integer >= 3, got {sections!r}")
            edge = rd.number(spec.get("max_edge", 0.5), f"{key}.max_edge", positive=True)
            norm.update(radius=radius, height=height, sections=sections, max_edge=edge)
            geom = placed_cylinder(radius, height, position, material, sections=sections, max_edge_m=edge)
        else:
            path = rd.mesh_file(spec["file"], f"{key}.file")
            scale = rd.number(spec.get("scale", 1.0), f"{key}.scale", positive=True)
            yaw = rd.number(spec.get("yaw_deg", 0.0), f"{key}.yaw_deg")
            norm.update(file=str(path), scale=scale, yaw_deg=yaw)
            geom = placed_mesh(path, position, material, scale=scale, yaw_deg=yaw)
    norm["material"] = material
    return geom, norm


def _with_objects(room: SceneGeometry, objects: Sequence[SceneGeometry]) -> SceneGeometry:
    """The room merged with its static objects, every face object id 0 (all static room)."""
    if not objects:
        return room
    merged = merge([room, *objects])
    merged.object_id = torch.zeros_like(merged.face_material)
    return merged


# -------------------------------------------------------------------------------------- people
def _read_person(spec: Any, i: int, rd: _Reader) -> tuple[Person, dict[str, Any]]:
    key = f"people[{i}]"
    spec = dict(rd.mapping(spec, key))
    kind = spec.pop("type", None)
    if kind not in PERSON_TYPES:
        raise rd.fail(f"{key}.type", f"must be one of {sorted(PERSON_TYPES)}, got {kind!r}")
    cls = PERSON_TYPES[kind]
    params = set(inspect.signature(cls).parameters)
    kwargs: dict[str, Any] = {}
    norm: dict[str, Any] = {"type": kind}
    for k, v in spec.items():
        name = _PERSON_ALIASES.get(k, k)
        if k == "heading_deg":
            name, v = "heading_rad", math.radians(rd.number(v, f"{key}.heading_deg"))
        if name not in params:
            allowed = sorted({a for a, b in _PERSON_ALIASES.items() if b in params} | params | {"heading_deg"})
            raise rd.fail(f"{key}.{k}", f"unknown for type {kind!r}; allowed: {allowed}")
        if name in kwargs:
            raise rd.fail(f"{key}.{k}", f"given twice (as {name!r})")
        if name == "path":
            v = rd.path(v, f"{key}.{k}")
            norm[k] = str(v)
        elif name == "files_or_meshes":
            v = _expand_files(v, f"{key}.{k}", rd)
            norm[k] = [str(p) for p in v]
        elif name == "start":
            v = tuple(rd.vector(v, f"{key}.start", 2))
            norm[k] = list(v)
        else:
            norm[k] = spec[k]
        kwargs[name] = v
    try:
        person = cls(**kwargs)
    except SceneError as err:
        raise rd.fail(key, str(err)) from None
    except (TypeError, ValueError) as err:
        raise rd.fail(key, f"cannot build a {kind}: {err}") from None
    return person, norm


def _expand_files(value: Any, key: str, rd: _Reader) -> list[Path]:
    """A glob pattern (sorted) or an explicit list of files, relative to the scene folder."""
    if isinstance(value, str):
        pattern = str(rd.path(value, key))
        files = sorted(Path(p) for p in glob.glob(pattern))
        if not files:
            raise rd.fail(key, f"pattern {pattern!r} matches no file")
        return files
    if isinstance(value, Sequence) and value:
        return [rd.path(v, f"{key}[{i}]") for i, v in enumerate(value)]
    raise rd.fail(key, f"must be a glob pattern or a non-empty list of files, got {value!r}")


def _read_materials(spec: Any, rd: _Reader, scattering: dict[str, DiffuseScattering]) -> dict[str, dict[str, Any]]:
    """Register the scene's own materials (``name: {a, b, c, d}`` or ``name: {eps: [re, im]}``).

    Any entry may carry ``diffuse: {S, pattern, alpha_R}`` (collected into ``scattering``); an
    entry with only ``diffuse`` sets the diffuse parameters of a known material.
    """
    spec = rd.mapping(spec, "materials")
    out = {}
    for name, m in spec.items():
        key = f"materials.{name}"
        m = dict(rd.mapping(m, key, {"a", "b", "c", "d", "eps", "diffuse"}))
        if "diffuse" in m:
            try:
                scattering[str(name)] = as_scattering(m["diffuse"], f"{key}.diffuse")
            except SceneError as err:
                raise rd.fail(f"{key}.diffuse", str(err).split(": ", 1)[-1]) from None
            if len(m) == 1:
                # Only the diffuse parameters of an existing material.
                try:
                    get_material(str(name))
                except SceneError as err:
                    raise rd.fail(key, f"sets only 'diffuse' but {err}") from None
                out[str(name)] = dict(m)
                continue
        full = dict(m)
        m.pop("diffuse", None)
        if "eps" in m:
            if len(m) != 1:
                raise rd.fail(key, "give either eps or a, b, c, d")
            re, im = rd.vector(m["eps"], f"{key}.eps", 2)
            kwargs: dict[str, Any] = {"a": re, "b": 0.0, "c": 0.0, "d": 0.0, "eps_complex_override": complex(re, im)}
        else:
            kwargs = {k: rd.number(m.get(k, 0.0), f"{key}.{k}") for k in "abcd"}
            rd.require(m, ("a",), f"{key}.")
        with rd.naming(key):
            mat = Material(str(name), **kwargs)
        existing = MATERIALS.get(str(name))
        if existing is not None and existing != mat:
            raise rd.fail(key, "redefines a different material with this name")
        if existing is None:
            register_material(mat)
        out[str(name)] = full
    return out


# ------------------------------------------------------------------------------ whole files
def _check_suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in _SUFFIXES:
        raise SceneError(f"scene file {path}: suffix must be .yaml, .yml or .json")
    return suffix


def read_scene_data(path: str | os.PathLike) -> Any:
    """The parsed content of a ``.yaml``/``.yml`` or ``.json`` scene file (``{}`` for an empty file).

    Raises:
        SceneError: unknown suffix, missing or unreadable file, or a parse error (the message
            names the file).
    """
    path = Path(path)
    suffix = _check_suffix(path)
    if suffix == ".json":
        data = load_json(path, error=SceneError, what="scene file")
    else:
        try:
            text = path.read_text()
        except OSError as err:
            raise SceneError(f"scene file {path}: cannot be read ({err.strerror or err})") from None
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as err:
            raise SceneError(f"scene file {path}: not valid {suffix[1:].upper()}: {err}") from None
    return data if data is not None else {}


def parse_scene(data: Mapping[str, Any], *, source: str | os.PathLike | None = None) -> dict[str, Any]:
    """Validate a parsed scene description and build its parts: the keyword arguments of ``Scene``.

    Args:
        data: the description, as :func:`read_scene_data` returns it (anything but a mapping is
            refused with a SceneError).
        source: the file it was read from; anchors relative paths and is named in errors.

    Raises:
        SceneError: bad content (the message names the file and the key).
    """
    rd = _Reader(Path(source) if source is not None else None)
    data = rd.mapping(data, "(top level)", _TOP_KEYS)
    rd.require(data, ("radar", "room"))
    name = data.get("name", rd.source.stem if rd.source is not None else "scene")
    if not isinstance(name, str):
        raise rd.fail("name", f"must be a string, got {name!r}")
    scattering: dict[str, DiffuseScattering] = {}
    materials_spec = _read_materials(data.get("materials", {}), rd, scattering)
    pose, config = _read_radar(data["radar"], rd)
    room, room_spec = _read_room(data["room"], rd)
    objs = [_read_object(o, i, rd) for i, o in enumerate(rd.sequence(data.get("objects") or [], "objects"))]
    room = _with_objects(room, [g for g, _ in objs])
    pairs = [_read_person(p, i, rd) for i, p in enumerate(rd.sequence(data.get("people") or [], "people"))]
    return {"room": room, "radar": pose, "config": config, "people": [p for p, _ in pairs], "name": name,
            "source": rd.source, "room_spec": room_spec, "materials_spec": materials_spec,
            "objects_spec": [o for _, o in objs], "scattering": scattering, "_person_specs": pairs}


def scene_to_dict(scene: Scene, *, relative_to: str | os.PathLike | None = None) -> dict[str, Any]:
    """The description of ``scene`` as a scene file holds it; file paths relative to ``relative_to``."""
    folder = Path(relative_to) if relative_to is not None else None
    rot = scene.radar.rotation.detach().cpu().double()
    out: dict[str, Any] = {"name": scene.name}
    if scene.materials_spec:
        out["materials"] = {k: dict(v) for k, v in scene.materials_spec.items()}
    out["radar"] = {
        "config": "bgt60tr13c" if scene.config == RadarConfig.bgt60tr13c() else scene.config.to_dict(),
        "position": scene.radar.position.detach().cpu().double().tolist(),
        "rotation": rot.tolist(),
    }
    room = scene.room_spec if scene.room_spec is not None else _inline_dict(scene.room)
    out["room"] = _relative_paths(room, folder)
    if scene.objects_spec and scene.room_spec is not None:  # an inline room already holds them
        out["objects"] = [_relative_paths(o, folder) for o in scene.objects_spec]
    specs = scene._person_specs
    out["people"] = [_person_dict(p, next((s for q, s in specs if q is p), None), folder) for p in scene.people]
    return out


def _relative_paths(spec: Mapping[str, Any], folder: Path | None) -> dict[str, Any]:
    """A copy of a room, object or person spec with its file paths made relative to ``folder``."""
    out = dict(spec)
    for k in ("file", "path"):
        if k in out:
            out[k] = _relative(out[k], folder)
    for k in ("files", "files_or_meshes"):
        if k in out:
            out[k] = [_relative(f, folder) for f in out[k]]
    return out


def _person_dict(person: Person, spec: dict[str, Any] | None, folder: Path | None) -> dict[str, Any]:
    """A person as the file gave it (``spec``, paths made relative), else from ``person.to_dict()``."""
    if spec is not None:
        return _relative_paths(spec, folder)
    spec = dict(person.to_dict())
    if "type" not in spec:
        spec["type"] = getattr(person, "type_name", "") or type(person).__name__
    return spec


def write_scene_file(scene: Scene, path: str | os.PathLike) -> Path:
    """Write ``scene`` as YAML or JSON (by suffix), atomically; file paths relative to its folder.

    Raises:
        SceneError: unknown suffix.
    """
    path = Path(path)
    suffix = _check_suffix(path)
    data = scene_to_dict(scene, relative_to=path.parent)
    text = (json.dumps(data, indent=2) + "\n" if suffix == ".json"
            else yaml.safe_dump(data, sort_keys=False, default_flow_style=None))
    atomic_write_text(path, text)
    return path


__all__ = ["builtin_scene", "parse_scene", "read_scene_data", "scene_to_dict", "write_scene_file"]
