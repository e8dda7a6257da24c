"""Mesh repair and decimation to a triangle budget with pymeshlab."""

from __future__ import annotations

from typing import overload

import numpy as np
import torch

from radaraug._optional import lazy_import
from radaraug.errors import SceneError


@overload
def simplify_mesh(
    vertices: torch.Tensor, faces: torch.Tensor | np.ndarray, target_faces: int
) -> tuple[torch.Tensor, torch.Tensor]: ...


@overload
def simplify_mesh(
    vertices: np.ndarray, faces: torch.Tensor | np.ndarray, target_faces: int
) -> tuple[np.ndarray, np.ndarray]: ...


def simplify_mesh(
    vertices: torch.Tensor | np.ndarray,
    faces: torch.Tensor | np.ndarray,
    target_faces: int,
) -> tuple[torch.Tensor | np.ndarray, torch.Tensor | np.ndarray]:
    """Repair a triangle mesh and decimate it to at most ``target_faces`` triangles.

    Repair merges duplicates and drops degenerate faces; decimation is a quadric edge collapse
    keeping normals and topology (``docs/people.md``).

    Args:
        vertices: ``(V, 3)`` float positions.
        faces: ``(F, 3)`` integer vertex indices.
        target_faces: triangle budget (>= 4). A mesh already within budget is only repaired.

    Returns:
        ``(vertices, faces)`` of the same kind (torch on the input's device/dtype, or numpy).
    """
    v = (vertices.detach().cpu().double().numpy() if isinstance(vertices, torch.Tensor)
         else np.asarray(vertices, dtype=np.float64))
    f = faces.detach().cpu().numpy() if isinstance(faces, torch.Tensor) else np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise SceneError(f"simplify_mesh: expected vertices (V, 3) and faces (F, 3), got {v.shape} and {f.shape}")
    if len(f) == 0 or not np.isfinite(v).all():
        raise SceneError("simplify_mesh: empty mesh or non-finite vertices")
    if f.min() < 0 or f.max() >= len(v):
        raise SceneError(f"simplify_mesh: face indices out of range [0, {len(v)})")
    if int(target_faces) < 4:
        raise SceneError(f"simplify_mesh: target_faces={target_faces} must be >= 4")
    pymeshlab = lazy_import("pymeshlab", feature="mesh simplification")

    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f.astype(np.int32)))
    ms.meshing_remove_duplicate_vertices()
    ms.meshing_remove_duplicate_faces()
    ms.meshing_remove_null_faces()
    ms.meshing_remove_unreferenced_vertices()
    if ms.current_mesh().face_number() > int(target_faces):
        ms.meshing_decimation_quadric_edge_collapse(
            targetfacenum=int(target_faces), preservenormal=True, preservetopology=True,
            planarquadric=True, autoclean=True,
        )
    m = ms.current_mesh()
    v_out, f_out = m.vertex_matrix(), m.face_matrix().astype(np.int64)
    if isinstance(vertices, torch.Tensor):
        dev, dt = vertices.device, vertices.dtype
        fdev = faces.device if isinstance(faces, torch.Tensor) else dev
        return torch.as_tensor(v_out, dtype=dt, device=dev), torch.as_tensor(f_out, dtype=torch.long, device=fdev)
    return v_out.astype(np.asarray(vertices).dtype if np.asarray(vertices).dtype.kind == "f" else np.float64), f_out
