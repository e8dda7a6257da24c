"""Rooms as triangle soups: the paper's box corridor, any mesh file trimesh reads, and merging.

All builders return a :class:`~radaraug.scene.geometry.SceneGeometry` in the world frame
(metres, right-handed, ``z`` up) with a material name per face (see
:mod:`radaraug.scene.materials`; ``"name@thickness_m"`` makes a face a slab).
"""

from __future__ import annotations

import fnmatch
import functools
import math
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import, missing_dependency
from radaraug.errors import SceneError
from radaraug.scene.geometry import SceneGeometry
from radaraug.scene.materials import Material, get_material
from radaraug.scene.people._rotations import axis_rotation

CORRIDOR_SURFACES = ("floor", "ceiling", "left_wall", "right_wall", "near_wall", "far_wall")
"""Surface names of :func:`corridor`. Left/right as seen looking down the corridor (+x)."""

PAPER_CORRIDOR_MATERIALS: dict[str, str] = {
    "floor": "floorboard",
    "ceiling": "ceiling_board",
    "left_wall": "plasterboard",
    "right_wall": "plasterboard",
    "near_wall": "concrete",
    "far_wall": "concrete",
}
"""Default corridor materials: a guess for a typical office corridor (the paper names none)."""

MAX_FACES = 5_000_000  # a guard against a typo in max_edge_m eating all memory


def _material_key(value: str | Material, thickness: float | None, where: str) -> str:
    """Validate a material given as a name or a :class:`Material` and return its scene key."""
    try:
        mat = value if isinstance(value, Material) else get_material(value)
    except SceneError as err:
        raise SceneError(f"{where}: {err}") from None
    if isinstance(value, Material):
        # Custom materials must be registered so the ray tracer can find them by name.
        try:
            known = get_material(value.name)
        except SceneError:
            raise SceneError(f"{where}: material {value.name!r} is not registered "
                             f"(radaraug.scene.materials.register_material)") from None
        if known.with_thickness(value.thickness_m) != value:
            raise SceneError(f"{where}: material {value.name!r} differs from the registered one")
    if thickness is not None:
        mat = mat.with_thickness(thickness)
    return mat.key


def _geometry(
    v: np.ndarray, f: np.ndarray, face_material: np.ndarray, keys: Sequence[str],
    dtype: torch.dtype | None = None, device: torch.device | str | None = None,
) -> SceneGeometry:
    """A static geometry of ``object_id`` 0 from numpy arrays (vertices at ``dtype``, default torch's)."""
    return SceneGeometry(
        vertices=torch.as_tensor(v, dtype=dtype or torch.get_default_dtype(), device=device),
        faces=torch.as_tensor(f, dtype=torch.long, device=device),
        face_material=torch.as_tensor(face_material, dtype=torch.long, device=device),
        materials=tuple(keys),
        object_id=torch.zeros(len(f), dtype=torch.long, device=device),
    )


def _rectangle(
    origin: Sequence[float], u: Sequence[float], v: Sequence[float], max_edge_m: float,
) -> tuple[np.ndarray, np.ndarray]:
    """A rectangle ``origin + s u + t v`` (s, t in [0, 1]) as a grid of triangles.

    The normal ``u x v`` is the side the faces are counter-clockwise from. Cells are sized so
    that every triangle edge, including the cell diagonal, is at most ``max_edge_m``.
    """
    o, du, dv = (np.asarray(x, dtype=np.float64) for x in (origin, u, v))
    cell = max_edge_m / math.sqrt(2.0)
    nu = max(1, math.ceil(np.linalg.norm(du) / cell - 1e-9))
    nv = max(1, math.ceil(np.linalg.norm(dv) / cell - 1e-9))
    s = np.linspace(0.0, 1.0, nu + 1)
    t = np.linspace(0.0, 1.0, nv + 1)
    ss, tt = np.meshgrid(s, t, indexing="ij")  # (nu+1, nv+1)
    verts = o + ss[..., None] * du + tt[..., None] * dv
    idx = np.arange((nu + 1) * (nv + 1)).reshape(nu + 1, nv + 1)
    p00, p10 = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    p11, p01 = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    faces = np.concatenate([np.stack([p00, p10, p11], 1), np.stack([p00, p11, p01], 1)])
    return verts.reshape(-1, 3), faces


def corridor(
    length_m: float = 20.0,
    width_m: float = 2.0,
    height_m: float = 2.7,
    *,
    materials: Mapping[str, str | Material] | None = None,
    thickness_m: Mapping[str, float | None] | None = None,
    end_walls: bool = True,
    max_edge_m: float = 0.5,
    dtype: torch.dtype | None = None,
    device: torch.device | str | None = None,
) -> SceneGeometry:
    """A box corridor along +x: ``x in [0, L]``, ``y in [-W/2, W/2]``, ``z in [0, H]``.

    Normals point into the corridor. Surfaces are split into triangles no longer than
    ``max_edge_m``, so that physical-optics facets stay small compared with the Fresnel zone.

    Args:
        length_m: inner length (along x) in metres.
        width_m: inner width (along y) in metres.
        height_m: inner height (along z) in metres.
        materials: material per surface (keys of :data:`CORRIDOR_SURFACES`); default
            :data:`PAPER_CORRIDOR_MATERIALS`.
        thickness_m: optional slab thickness per surface in metres (None = half-space).
        end_walls: include the walls at ``x = 0`` (near) and ``x = L`` (far).
        max_edge_m: longest triangle edge.
        dtype: vertex dtype (default: torch's default dtype).
        device: device of the tensors.

    Returns:
        The corridor with ``object_id`` 0 (room) on every face and no vertex velocities.

    Raises:
        SceneError: non-positive sizes, unknown surface or material names.
    """
    for label, val in (("length_m", length_m), ("width_m", width_m), ("height_m", height_m),
                       ("max_edge_m", max_edge_m)):
        if not (isinstance(val, (int, float)) and math.isfinite(val) and val > 0):
            raise SceneError(f"corridor: {label} must be a positive number, got {val!r}")
    materials = dict(materials or {})
    thickness_m = dict(thickness_m or {})
    for label, given in (("materials", materials), ("thickness_m", thickness_m)):
        unknown = sorted(set(given) - set(CORRIDOR_SURFACES))
        if unknown:
            raise SceneError(f"corridor: unknown surface(s) {unknown} in {label}; "
                             f"surfaces are {list(CORRIDOR_SURFACES)}")
    L, W, H = float(length_m), float(width_m), float(height_m)
    y0, y1 = -W / 2, W / 2
    # (origin, u, v) with u x v pointing into the corridor.
    rects = {
        "floor": ((0, y0, 0), (L, 0, 0), (0, W, 0)),
        "ceiling": ((0, y0, H), (0, W, 0), (L, 0, 0)),
        "left_wall": ((0, y1, 0), (L, 0, 0), (0, 0, H)),
        "right_wall": ((0, y0, 0), (0, 0, H), (L, 0, 0)),
        "near_wall": ((0, y0, 0), (0, W, 0), (0, 0, H)),
        "far_wall": ((L, y0, 0), (0, 0, H), (0, W, 0)),
    }
    surfaces = [s for s in CORRIDOR_SURFACES if end_walls or s not in ("near_wall", "far_wall")]
    cell = max_edge_m / math.sqrt(2.0)
    n_faces = sum(2 * math.prod(max(1, math.ceil(np.linalg.norm(x) / cell)) for x in rects[s][1:]) for s in surfaces)
    if n_faces > MAX_FACES:
        raise SceneError(f"corridor: max_edge_m={max_edge_m} would make more than {MAX_FACES} faces")
    surface_keys = [_material_key(materials.get(s, PAPER_CORRIDOR_MATERIALS[s]), thickness_m.get(s),
                                  f"corridor surface {s!r}") for s in surfaces]
    v, f, surface_of_face = _join([_rectangle(*rects[s], max_edge_m) for s in surfaces])
    return _geometry(v, f, *_face_keys(surface_keys, surface_of_face), dtype, device)


def _join(parts: Sequence[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(vertices, faces, part index per face)`` of several ``(vertices, faces)`` parts put together."""
    offsets = np.cumsum([0] + [len(v) for v, _ in parts[:-1]])
    faces = np.concatenate([f + o for (_, f), o in zip(parts, offsets)])
    part_of_face = np.repeat(np.arange(len(parts)), [len(f) for _, f in parts])
    return np.concatenate([v for v, _ in parts]), faces, part_of_face


def _face_keys(part_keys: Sequence[str], part_of_face: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """Material index per face and the material table (duplicates merged, first-seen order).

    ``part_keys`` holds one material key per part, ``part_of_face`` each face's part.
    """
    keys = list(dict.fromkeys(part_keys))
    return np.asarray([keys.index(k) for k in part_keys], dtype=np.int64)[part_of_face], keys


FaceMaterialFn = Callable[[torch.Tensor, torch.Tensor, Sequence[str]], "str | Sequence[str]"]
"""``f(centroids (F, 3), unit normals (F, 3), group name per face) -> material name(s)``."""


def _read_mesh_parts(path: Path) -> list[tuple[str, str | None, np.ndarray, np.ndarray]]:
    """``(group name, file material name or None, vertices, faces)`` per part, transforms applied."""
    trimesh = lazy_import("trimesh", feature="meshes")

    kwargs: dict[str, Any] = {}
    if path.suffix.lower() == ".obj":
        # Keep OBJ groups/objects apart so their names can select materials.
        kwargs = {"split_groups": True, "split_objects": True, "group_material": False}
    try:
        # force="scene": always a trimesh.Scene (trimesh types it as any Geometry).
        loaded: Any = trimesh.load(str(path), force="scene", process=False, **kwargs)
    except ModuleNotFoundError as err:  # some formats need packages trimesh imports on demand
        raise missing_dependency(err, f"reading mesh file {path}") from None
    except Exception as err:  # noqa: BLE001 - trimesh raises many types (ValueError, KeyError, struct.error...) for bad files
        raise SceneError(f"mesh file {path}: cannot be read ({type(err).__name__}: {err})") from None
    parts = []
    for node in loaded.graph.nodes_geometry:
        transform, geom_name = loaded.graph[node]
        geom = loaded.geometry[geom_name]
        if not isinstance(geom, trimesh.Trimesh) or len(geom.faces) == 0:
            continue
        v = np.asarray(geom.vertices, dtype=np.float64)
        v = v @ np.asarray(transform)[:3, :3].T + np.asarray(transform)[:3, 3]
        mat = getattr(getattr(geom, "visual", None), "material", None)
        mat_name = getattr(mat, "name", None)
        parts.append((str(geom_name), None if mat_name is None else str(mat_name), v,
                      np.asarray(geom.faces, dtype=np.int64)))
    if not parts:
        raise SceneError(f"mesh file {path}: contains no triangles")
    return parts


def _lookup(table: Mapping[str, str | Material], names: Sequence[str | None]) -> str | Material | None:
    """First table entry matching any of ``names`` exactly, else by shell-style pattern."""
    for n in names:
        if n is not None and n in table:
            return table[n]
    for n in names:
        for pattern, value in table.items():
            if n is not None and fnmatch.fnmatchcase(n, pattern):
                return value
    return None


def _call_face_materials(
    fn: FaceMaterialFn, v: np.ndarray, f: np.ndarray, part_names: list[str], part_of_face: np.ndarray,
    where: str,
) -> tuple[np.ndarray, list[str]]:
    """Run a user's per-face material callable once on all faces; ``(index per face, keys)``."""
    tri = v[f]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals = normals / np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-30)
    groups = tuple(np.asarray(part_names, dtype=object)[part_of_face])
    try:
        chosen = fn(torch.as_tensor(tri.mean(axis=1)), torch.as_tensor(normals), groups)
    except SceneError:
        raise
    except Exception as err:  # noqa: BLE001 - a user's callable may raise anything; name the scene file
        raise SceneError(f"{where}: face_materials callable failed ({type(err).__name__}: {err})") from None
    if isinstance(chosen, (str, Material)):
        chosen = [chosen]
    names = np.asarray([c.key if isinstance(c, Material) else str(c) for c in chosen], dtype=object)
    if len(names) == 1:
        names = np.repeat(names, len(f))
    if len(names) != len(f):
        raise SceneError(f"{where}: face_materials returned {len(names)} names for {len(f)} faces")
    uniq, inverse = np.unique(names.astype(str), return_inverse=True)
    # Two spellings of one material (e.g. "wood@0.02" and "wood@0.020") collapse to one key.
    return _face_keys([_material_key(str(u), None, where) for u in uniq], inverse.reshape(-1))


def load_mesh(
    path: str | os.PathLike,
    *,
    material: str | Material = "concrete",
    face_materials: Mapping[str, str | Material] | FaceMaterialFn | None = None,
    scale: float = 1.0,
    transform: Sequence[Sequence[float]] | np.ndarray | torch.Tensor | None = None,
    dtype: torch.dtype | None = None,
    device: torch.device | str | None = None,
) -> SceneGeometry:
    """A room (or object) from any mesh file trimesh reads: OBJ, PLY, STL, GLB/GLTF, OFF, ...

    Args:
        path: mesh file. Coordinates are taken as metres times ``scale``.
        material: material of every face not chosen by ``face_materials``.
        face_materials: a dict from the file's part names (OBJ group/object, GLB node/mesh or MTL
            material; shell patterns allowed) to materials, or a callable
            ``f(centroids, normals, groups) -> name or F names`` run once after scale and transform.
        scale: factor applied to the file's coordinates (e.g. 0.001 for millimetres).
        transform: optional 4x4 (or 3x4) world-from-file matrix applied after ``scale``.
        dtype: vertex dtype (default: torch's default dtype).
        device: device of the tensors.

    Returns:
        The mesh, ``object_id`` 0, no vertex velocities.

    Raises:
        SceneError: missing/unreadable/empty file, bad transform or material names.
    """
    path = Path(path)
    if not path.is_file():
        raise SceneError(f"mesh file {path}: not found")
    if not (isinstance(scale, (int, float)) and math.isfinite(scale) and scale > 0):
        raise SceneError(f"mesh file {path}: scale must be a positive number, got {scale!r}")
    parts = _read_mesh_parts(path)
    v, f, part_of_face = _join([(part_v, part_f) for _, _, part_v, part_f in parts])
    v = v * float(scale)
    if transform is not None:
        m = np.asarray(transform.detach().cpu() if isinstance(transform, torch.Tensor) else transform,
                       dtype=np.float64)
        if m.shape not in ((4, 4), (3, 4)) or not np.isfinite(m).all():
            raise SceneError(f"mesh file {path}: transform must be a finite 4x4 or 3x4 matrix, "
                             f"got shape {m.shape}")
        v = v @ m[:3, :3].T + m[:3, 3]
    where = f"mesh file {path}"
    default_key = _material_key(material, None, where)
    if face_materials is None:
        face_material, keys = np.zeros(len(f), dtype=np.int64), [default_key]
    elif callable(face_materials):
        face_material, keys = _call_face_materials(face_materials, v, f, [p[0] for p in parts],
                                                   part_of_face, where)
    elif isinstance(face_materials, Mapping):
        part_keys = []
        for group, mat_name, _, _ in parts:
            hit = _lookup(face_materials, (group, mat_name))
            part_keys.append(default_key if hit is None else _material_key(hit, None, f"{where} part {group!r}"))
        face_material, keys = _face_keys(part_keys, part_of_face)
    else:
        raise SceneError(f"{where}: face_materials must be a dict or a callable, got {type(face_materials).__name__}")
    return _geometry(v, f, face_material, keys, dtype, device)


def box(
    lo: Sequence[float], hi: Sequence[float], material: str | Material, *, max_edge_m: float = 0.5,
) -> SceneGeometry:
    """An axis-aligned box (a cabinet, a pillar) from corner ``lo`` to ``hi``: outward normals, edges <= ``max_edge_m``.

    Raises:
        SceneError: a corner that is not 3 finite numbers, ``hi <= lo`` on an axis, or an unknown material.
    """
    trimesh = lazy_import("trimesh", feature="meshes")

    lo_a, hi_a = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    if lo_a.shape != (3,) or hi_a.shape != (3,) or not (np.isfinite(lo_a).all() and np.isfinite(hi_a).all()):
        raise SceneError(f"box: corners must be 3 finite numbers each, got {list(lo)} and {list(hi)}")
    if not (hi_a > lo_a).all():
        raise SceneError(f"box: every coordinate of hi must exceed lo's, got {list(lo)} and {list(hi)}")
    mesh = trimesh.creation.box(extents=hi_a - lo_a,
                                transform=trimesh.transformations.translation_matrix((lo_a + hi_a) / 2))
    return _from_trimesh(mesh.vertices, mesh.faces, material, "box", max_edge_m, None)


def _placement(position: Sequence[float], yaw_deg: float, where: str) -> np.ndarray:
    """4x4 world-from-object matrix: a turn about +z, then a translation to ``position`` (checked).

    The turn is ``yaw_deg``, counter-clockwise seen from above.
    """
    m = np.eye(4)
    m[:3, :3] = axis_rotation("z", math.radians(float(yaw_deg))).numpy()
    m[:3, 3] = _check_vec(position, 3, "position", where)
    return m


def _check_vec(value: Sequence[float], n: int, label: str, where: str, positive: bool = False) -> np.ndarray:
    a = np.asarray(value, dtype=np.float64)
    if a.shape != (n,) or not np.isfinite(a).all() or (positive and not (a > 0).all()):
        raise SceneError(f"{where}: {label} must be {n} finite{' positive' if positive else ''} numbers, "
                         f"got {list(np.atleast_1d(value))}")
    return a


def _from_trimesh(v: np.ndarray, f: np.ndarray, material: str | Material, where: str, max_edge_m: float,
                  transform: np.ndarray | None) -> SceneGeometry:
    """A one-material mesh split to ``max_edge_m``, then placed by ``transform`` (None: as it is)."""
    trimesh = lazy_import("trimesh", feature="meshes")

    key = _material_key(material, None, where)
    v, f = trimesh.remesh.subdivide_to_size(v, f, max_edge=max_edge_m)
    v = np.asarray(v)
    if transform is not None:
        v = v @ transform[:3, :3].T + transform[:3, 3]
    return _geometry(v, np.asarray(f), np.zeros(len(f), dtype=np.int64), [key])


def placed_box(
    size: Sequence[float], position: Sequence[float], material: str | Material, *, yaw_deg: float = 0.0,
    max_edge_m: float = 0.5,
) -> SceneGeometry:
    """A box of ``size`` (x, y, z extents before the yaw) standing with its base centre at ``position``.

    ``yaw_deg`` turns it about the vertical. Outward normals, edges no longer than ``max_edge_m``.

    Raises:
        SceneError: bad size/position or unknown material.
    """
    trimesh = lazy_import("trimesh", feature="meshes")

    where = "box object"
    ext = _check_vec(size, 3, "size", where, positive=True)
    mesh = trimesh.creation.box(extents=ext, transform=trimesh.transformations.translation_matrix((0, 0, ext[2] / 2)))
    return _from_trimesh(mesh.vertices, mesh.faces, material, where, max_edge_m, _placement(position, yaw_deg, where))


def placed_cylinder(
    radius: float, height: float, position: Sequence[float], material: str | Material, *,
    sections: int = 24, max_edge_m: float = 0.5,
) -> SceneGeometry:
    """A vertical cylinder (a pillar, a pipe, a bin) with its base centre at ``position``.

    ``sections`` facets around (24 keeps the chords within 0.9 % of the radius).

    Raises:
        SceneError: bad radius/height/position/sections or unknown material.
    """
    trimesh = lazy_import("trimesh", feature="meshes")

    where = "cylinder object"
    r, h = _check_vec([radius, height], 2, "radius and height", where, positive=True)
    if isinstance(sections, bool) or not isinstance(sections, int) or sections < 3:
        raise SceneError(f"{where}: sections must be an integer >= 3, got {sections!r}")
    mesh = trimesh.creation.cylinder(radius=r, height=h, sections=sections,
                                     transform=trimesh.transformations.translation_matrix((0, 0, h / 2)))
    return _from_trimesh(mesh.vertices, mesh.faces, material, where, max_edge_m, _placement(position, 0.0, where))


def placed_mesh(
    path: str | os.PathLike, position: Sequence[float], material: str | Material, *, scale: float = 1.0,
    yaw_deg: float = 0.0,
) -> SceneGeometry:
    """A mesh file as an object: scaled, turned by ``yaw_deg`` about +z, its origin moved to ``position``."""
    return load_mesh(path, material=material, scale=scale, transform=_placement(position, yaw_deg, f"mesh file {path}"))


def merge(geoms: Sequence[SceneGeometry]) -> SceneGeometry:
    """Union of triangle soups: materials merged by name, object ids shifted to stay distinct.

    The first geometry keeps its ids (a room built first keeps id 0); missing ``object_id`` counts as
    zeros and missing velocities as zeros. Tensors end on the first geometry's device.

    Raises:
        SceneError: empty list or a geometry with inconsistent tensor shapes.
    """
    geoms = list(geoms)
    if not geoms:
        raise SceneError("merge: no geometries given")
    device = geoms[0].vertices.device
    dtype = functools.reduce(torch.promote_types, (g.vertices.dtype for g in geoms))
    index: dict[str, int] = {}  # material key -> its index in the merged table
    verts, faces, mats, ids, vels = [], [], [], [], []
    n_vert, next_id = 0, 0
    any_vel = any(g.vertex_velocity is not None for g in geoms)
    for i, g in enumerate(geoms):
        if (g.vertices.ndim != 2 or g.vertices.shape[-1] != 3 or g.faces.ndim != 2 or g.faces.shape[-1] != 3
                or g.face_material.shape != g.faces.shape[:1]):
            raise SceneError(f"merge: geometry {i} has inconsistent shapes (vertices "
                             f"{tuple(g.vertices.shape)}, faces {tuple(g.faces.shape)}, face_material "
                             f"{tuple(g.face_material.shape)})")
        remap = [index.setdefault(name, len(index)) for name in g.materials]
        remap_t = torch.tensor(remap, dtype=torch.long, device=device)
        verts.append(g.vertices.to(device=device, dtype=dtype))
        faces.append(g.faces.to(device) + n_vert)
        mats.append(remap_t[g.face_material.to(device)] if len(remap) else g.face_material.to(device))
        oid = (g.object_id.to(device) if g.object_id is not None
               else torch.zeros(g.num_faces, dtype=torch.long, device=device))
        ids.append(oid + next_id)
        if oid.numel():
            next_id = int(ids[-1].max()) + 1
        if any_vel:
            vels.append(g.vertex_velocity.to(device=device, dtype=dtype) if g.vertex_velocity is not None
                        else torch.zeros_like(verts[-1]))
        n_vert += g.vertices.shape[0]
    return SceneGeometry(
        vertices=torch.cat(verts),
        faces=torch.cat(faces),
        face_material=torch.cat(mats),
        materials=tuple(index),
        vertex_velocity=torch.cat(vels) if any_vel else None,
        object_id=torch.cat(ids),
    )


__all__ = [
    "CORRIDOR_SURFACES", "PAPER_CORRIDOR_MATERIALS", "box", "corridor", "load_mesh", "merge", "placed_box",
    "placed_cylinder", "placed_mesh",
]
