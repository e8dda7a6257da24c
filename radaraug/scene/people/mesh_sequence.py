"""A person given as an animated mesh: one mesh per animation frame (e.g. exported from Mixamo)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import, missing_dependency
from radaraug.errors import SceneError
from radaraug.scene.geometry import Ellipsoids
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people._interp import FrameTrack
from radaraug.scene.people.person import Person, as_times, register_person
from radaraug.scene.people.simplify import simplify_mesh

_Y_UP_TO_Z_UP = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
NUM_CLUSTERS = 16


def _load(item: Any, k: int) -> tuple[np.ndarray, np.ndarray, str]:
    trimesh = lazy_import("trimesh", feature="meshes")

    label = str(item) if isinstance(item, (str, Path)) else f"mesh #{k}"
    if isinstance(item, (str, Path)):
        if not Path(item).is_file():
            raise SceneError(f"{item}: mesh file not found")
        try:
            item = trimesh.load(str(item), force="mesh", process=False)
        except ModuleNotFoundError as exc:  # some formats need packages trimesh imports on demand
            raise missing_dependency(exc, f"reading mesh file {label}") from None
        except Exception as exc:  # trimesh raises many types for bad files
            raise SceneError(f"{label}: cannot read mesh: {exc}") from exc
    if isinstance(item, trimesh.Scene):
        item = item.to_geometry() if hasattr(item, "to_geometry") else item.dump(concatenate=True)
    if not isinstance(item, trimesh.Trimesh) or len(item.faces) == 0:
        raise SceneError(f"{label}: not a triangle mesh (got {type(item).__name__})")
    return np.asarray(item.vertices, dtype=np.float64), np.asarray(item.faces, dtype=np.int64), label


def _kmeans_labels(points: np.ndarray, k: int, iters: int = 20) -> np.ndarray:
    """Deterministic k-means (farthest-point initialization from the lowest vertex)."""
    k = min(k, len(points))
    centers = [points[np.argmin(points[:, 2])]]
    dist = np.linalg.norm(points - centers[0], axis=1)
    for _ in range(1, k):
        centers.append(points[np.argmax(dist)])
        dist = np.minimum(dist, np.linalg.norm(points - centers[-1], axis=1))
    c = np.stack(centers)
    for _ in range(iters):
        labels = np.argmin(((points[:, None, :] - c[None]) ** 2).sum(-1), axis=1)
        for j in range(k):
            members = points[labels == j]
            if len(members):
                c[j] = members.mean(0)
    return np.argmin(((points[:, None, :] - c[None]) ** 2).sum(-1), axis=1)


def _attach(points: torch.Tensor, vertices: torch.Tensor, faces: torch.Tensor,
            candidates: int = 16, chunk: int = 2048) -> tuple[torch.Tensor, torch.Tensor]:
    """Nearest triangle and barycentric coordinates of each point on a reference mesh.

    Among the ``candidates`` triangles with the nearest centroids, the point is projected on
    each triangle's plane, its barycentric coordinates are clipped to the triangle and
    renormalized, and the closest result wins (weights always sum to 1, so rigid motions of
    the reference are reproduced exactly).
    """
    tri_v = vertices[faces]  # (F, 3, 3)
    cent = tri_v.mean(1)
    k = min(candidates, faces.shape[0])
    tri_out, bary_out = [], []
    for i in range(0, points.shape[0], chunk):
        p = points[i:i + chunk]
        cand = torch.cdist(p, cent).topk(k, largest=False).indices  # (P, k)
        a, b, c = tri_v[cand].unbind(-2)  # (P, k, 3)
        v0, v1, v2 = b - a, c - a, p[:, None] - a
        d00, d01, d11 = (v0 * v0).sum(-1), (v0 * v1).sum(-1), (v1 * v1).sum(-1)
        d20, d21 = (v2 * v0).sum(-1), (v2 * v1).sum(-1)
        den = (d00 * d11 - d01 * d01).clamp_min(1e-30)
        w1 = (d11 * d20 - d01 * d21) / den
        w2 = (d00 * d21 - d01 * d20) / den
        w = torch.stack([1 - w1 - w2, w1, w2], -1).clamp_min(0.0)
        w = w / w.sum(-1, keepdim=True)
        q = w[..., :1] * a + w[..., 1:2] * b + w[..., 2:] * c
        best = (q - p[:, None]).norm(dim=-1).argmin(-1)
        rows = torch.arange(p.shape[0])
        tri_out.append(cand[rows, best])
        bary_out.append(w[rows, best])
    return torch.cat(tri_out), torch.cat(bary_out)


@register_person
class MeshSequencePerson(Person):
    """An animated triangle mesh, one mesh per frame, every frame with the same vertices.

    The sequence is cyclic (period ``N / fps``); vertices follow a Catmull-Rom spline through the
    frames, with exact velocities. Placement and conventions: ``docs/people.md``.

    Args:
        files_or_meshes: mesh files (anything trimesh reads; vertex order kept) or
            ``trimesh.Trimesh`` objects, one per frame.
        fps: animation frames per second.
        start: ``(x, y)`` of the body centroid at ``t = 0``.
        heading_rad: facing / walking direction in the x-y plane.
        scale: metres per file unit.
        max_faces: triangle budget; frame 0 is decimated once and the other frames follow it.
        up_axis: ``"y"`` (default, OBJ/GLB/Mixamo) or ``"z"``.
        speed_m_s: root motion along the heading (m/s), added to the animation.
    """

    type_name = "mesh_sequence"
    _FIELDS = ("files", "fps", "start", "heading_rad", "scale", "max_faces", "up_axis", "speed_m_s")

    def __init__(
        self,
        files_or_meshes: Sequence[Any],
        *,
        fps: float,
        start: tuple[float, float] = (0.0, 0.0),
        heading_rad: float = 0.0,
        scale: float = 1.0,
        max_faces: int | None = None,
        up_axis: str = "y",
        speed_m_s: float = 0.0,
    ) -> None:
        items = list(files_or_meshes)
        if not items:
            raise SceneError("MeshSequencePerson: no frames given")
        if not float(fps) > 0:
            raise SceneError(f"MeshSequencePerson: fps must be positive, got {fps}")
        if up_axis not in ("y", "z"):
            raise SceneError(f"MeshSequencePerson: up_axis must be 'y' or 'z', got {up_axis!r}")
        if not float(scale) > 0:
            raise SceneError(f"MeshSequencePerson: scale must be positive, got {scale}")
        self.files = [str(i) for i in items] if all(isinstance(i, (str, Path)) for i in items) else None
        self.fps, self.scale, self.up_axis = float(fps), float(scale), up_axis
        self.start = (float(start[0]), float(start[1]))
        self.heading_rad, self.speed_m_s = float(heading_rad), float(speed_m_s)
        self.max_faces = None if max_faces is None else int(max_faces)

        frames, faces = [], None
        for k, item in enumerate(items):
            v, f, label = _load(item, k)
            if faces is None:
                faces, label0 = f, label
            elif len(v) != len(frames[0]):
                raise SceneError(
                    f"{label}: frame {k} has {len(v)} vertices but frame 0 ({label0}) has {len(frames[0])}; "
                    "per-vertex velocities need the same vertices in every frame"
                )
            frames.append(v)
        assert faces is not None
        x = np.stack(frames) * self.scale
        if up_axis == "y":
            x = x @ _Y_UP_TO_Z_UP.T
        rz = rot.axis_rotation("z", float(self.heading_rad)).numpy()
        c, s = rz[0, 0], rz[1, 0]
        centroid = np.array([*x[0].mean(0)[:2], 0.0])
        x = (x - centroid) @ rz.T + np.array([*self.start, 0.0])

        if self.max_faces is not None and len(faces) > self.max_faces:
            x, faces = self._decimate(x, faces, self.max_faces)
        self.faces = torch.as_tensor(faces, dtype=torch.long)
        self.num_frames = x.shape[0]
        frames_t = torch.as_tensor(x, dtype=torch.float64)
        self._track = FrameTrack(torch.cat([frames_t, frames_t[:1]]), 1.0 / self.fps, loop=True)
        self.duration_s = self.num_frames / self.fps
        self._direction = torch.tensor([c, s, 0.0], dtype=torch.float64)
        self._labels = torch.as_tensor(_kmeans_labels(x[0], NUM_CLUSTERS), dtype=torch.long)

    @staticmethod
    def _decimate(x: np.ndarray, faces: np.ndarray, max_faces: int) -> tuple[np.ndarray, np.ndarray]:
        v_s, f_s = simplify_mesh(x[0], faces, max_faces)
        tri, bary = _attach(torch.as_tensor(v_s), torch.as_tensor(x[0]), torch.as_tensor(faces))
        corners = faces[tri.numpy()]  # (Vs, 3)
        return np.einsum("fvkd,vk->fvd", x[:, corners], bary.numpy()), f_s

    def vertices(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Vertex positions ``(T, V, 3)`` m and velocities ``(T, V, 3)`` m/s at ``t`` ``(T,)``."""
        t = as_times(t)
        pos, vel = self._track(t)
        d = self._direction.to(pos)
        return pos + t[:, None, None] * self.speed_m_s * d, vel + self.speed_m_s * d

    def _surface(self, t0: float, faces_per_segment: int) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """The animated mesh at ``t0`` with exact per-vertex velocities (``faces_per_segment`` unused)."""
        pos, vel = self.vertices(torch.tensor([t0], dtype=torch.float64))
        return pos[0], self.faces, vel[0]

    def ellipsoids(self, t: torch.Tensor) -> Ellipsoids:
        """A coarse 16-ellipsoid decomposition: one per vertex cluster (k-means on frame 0).

        Semi-axes ``sqrt(3 * variance)`` along the cluster's principal axes; not the skeleton's segment order.
        """
        pos, vel = self.vertices(as_times(t))
        ids = self._labels.to(pos.device)
        s = int(ids.max()) + 1
        count = torch.zeros(s, dtype=pos.dtype, device=pos.device).index_add_(0, ids, torch.ones_like(ids, dtype=pos.dtype))
        shape = (pos.shape[0], s, 3)
        mean = torch.zeros(shape, dtype=pos.dtype, device=pos.device).index_add_(1, ids, pos) / count[:, None]
        mvel = torch.zeros(shape, dtype=pos.dtype, device=pos.device).index_add_(1, ids, vel) / count[:, None]
        d = pos - mean[:, ids]
        outer = d.unsqueeze(-1) * d.unsqueeze(-2)
        cov = torch.zeros(*shape, 3, dtype=pos.dtype, device=pos.device).index_add_(1, ids, outer)
        cov = cov / count[:, None, None]
        evals, evecs = torch.linalg.eigh(cov)
        flip = torch.linalg.det(evecs) < 0
        evecs = torch.where(flip[..., None, None], evecs * evecs.new_tensor([1.0, 1.0, -1.0]), evecs)
        semi = (3.0 * evals.clamp_min(0.0)).sqrt().clamp_min(1e-3)
        return Ellipsoids(centers=mean, semi_axes=semi, rotations=evecs, velocities=mvel, material=self.material)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Person:
        """Inverse of :meth:`to_dict` (needs ``files``)."""
        if not d.get("files"):
            raise SceneError("mesh_sequence person: 'files' is missing (meshes given as objects cannot be saved)")
        return super().from_dict({"files_or_meshes" if k == "files" else k: v for k, v in d.items()})

    def __repr__(self) -> str:
        return f"MeshSequencePerson({self.num_frames} frames, {self.faces.shape[0]} faces, fps={self.fps})"
