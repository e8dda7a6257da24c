"""Corridor builder, mesh import and merging."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import torch
import trimesh

from radaraug.errors import SceneError
from radaraug.scene.geometry import SceneGeometry
from radaraug.scene.materials import Material, get_material
from radaraug.scene.room import PAPER_CORRIDOR_MATERIALS, corridor, load_mesh, merge


def _normals_areas(g: SceneGeometry) -> tuple[torch.Tensor, torch.Tensor]:
    tri = g.triangles.double()
    n = torch.linalg.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    return n / n.norm(dim=-1, keepdim=True), n.norm(dim=-1) / 2


def test_corridor_box_closed_form(device: torch.device) -> None:
    L, W, H = 20.0, 2.0, 2.7
    g = corridor(L, W, H, device=device)
    assert g.vertices.device.type == device.type
    v = g.vertices.double()
    torch.testing.assert_close(v.min(0).values.cpu(), torch.tensor([0.0, -W / 2, 0.0], dtype=torch.float64))
    torch.testing.assert_close(v.max(0).values.cpu(), torch.tensor([L, W / 2, H], dtype=torch.float64))
    n, area = _normals_areas(g)
    # Total inner surface area of the box.
    assert area.sum().item() == pytest.approx(2 * (L * W + L * H + W * H), rel=1e-5)
    # Every normal points into the corridor: toward the box centre and axis-aligned.
    centre = torch.tensor([L / 2, 0.0, H / 2], dtype=torch.float64, device=device)
    c = g.triangles.double().mean(1)
    assert ((n * (centre - c)).sum(-1) > 0).all()
    assert torch.allclose(n.abs().max(-1).values, torch.ones_like(area))
    assert (g.object_id == 0).all() and g.vertex_velocity is None


def test_corridor_surfaces_have_their_materials() -> None:
    g = corridor(materials={"left_wall": "glass"})
    n, _ = _normals_areas(g)
    c = g.triangles.double().mean(1)
    names = [g.materials[i] for i in g.face_material.tolist()]
    expect = {
        "floor": (torch.tensor([0, 0, 1.0]), "floorboard"),
        "ceiling": (torch.tensor([0, 0, -1.0]), "ceiling_board"),
        "left_wall": (torch.tensor([0, -1.0, 0]), "glass"),  # at y = +W/2, facing -y
        "right_wall": (torch.tensor([0, 1.0, 0]), "plasterboard"),
        "near_wall": (torch.tensor([1.0, 0, 0]), "concrete"),
        "far_wall": (torch.tensor([-1.0, 0, 0]), "concrete"),
    }
    for surface, (normal, material) in expect.items():
        sel = torch.isclose(n, normal.double()).all(-1)
        assert sel.any(), surface
        assert {names[i] for i in sel.nonzero().flatten().tolist()} == {material}, surface
    assert (c[torch.isclose(n, torch.tensor([0, -1.0, 0], dtype=torch.float64)).all(-1), 1] == 1.0).all()


def test_corridor_defaults_and_thickness() -> None:
    assert PAPER_CORRIDOR_MATERIALS["ceiling"] == "ceiling_board"
    g = corridor(thickness_m={"ceiling": 0.1}, materials={"floor": "wood@0.02"})
    assert "ceiling_board@0.1" in g.materials and "wood@0.02" in g.materials
    assert get_material("ceiling_board@0.1").thickness_m == 0.1


@pytest.mark.parametrize("max_edge", [0.3, 0.5, 1.0, 5.0])
def test_corridor_max_edge(max_edge: float) -> None:
    g = corridor(10.0, 2.0, 2.5, max_edge_m=max_edge)
    tri = g.triangles.double()
    edges = torch.stack([tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 1], tri[:, 0] - tri[:, 2]], 1).norm(dim=-1)
    assert edges.max().item() <= max_edge + 1e-6
    _, area = _normals_areas(g)
    assert area.sum().item() == pytest.approx(2 * (10 * 2 + 10 * 2.5 + 2 * 2.5), rel=1e-5)
    assert (area > 0).all()


def test_corridor_without_end_walls() -> None:
    g = corridor(8.0, 2.0, 2.0, end_walls=False, max_edge_m=1.0)
    n, area = _normals_areas(g)
    assert (n[:, 0].abs() < 1e-12).all()
    assert area.sum().item() == pytest.approx(2 * (8 * 2 + 8 * 2), rel=1e-6)
    assert "concrete" not in g.materials


def test_corridor_bad_input() -> None:
    with pytest.raises(SceneError, match="length_m"):
        corridor(-1.0)
    with pytest.raises(SceneError, match="surface"):
        corridor(materials={"roof": "metal"})
    with pytest.raises(SceneError, match="unknown material"):
        corridor(materials={"floor": "lava"})
    with pytest.raises(SceneError, match="faces"):
        corridor(max_edge_m=1e-4)
    with pytest.raises(SceneError, match="not registered"):
        corridor(materials={"floor": Material("unregistered_x", 2.0, 0, 0, 0)})


def _write_obj(path: Path) -> None:
    """Two OBJ groups: a unit floor square (2 triangles) and a wall triangle."""
    path.write_text(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
        "g floor\nf 1 2 3\nf 1 3 4\n"
        "g wall_a\nf 1 5 2\n"
    )


def test_load_mesh_obj_groups(tmp_path: Path) -> None:
    f = tmp_path / "room.obj"
    _write_obj(f)
    g = load_mesh(f, material="concrete", face_materials={"floor": "wood", "wall*": "metal"})
    assert g.num_faces == 3
    names = sorted(g.materials[i] for i in g.face_material.tolist())
    assert names == ["metal", "wood", "wood"]
    _, area = _normals_areas(g)
    assert area.sum().item() == pytest.approx(1.5)
    # Unmapped groups take the default material.
    g = load_mesh(f, material="glass", face_materials={"floor": "wood"})
    assert sorted(g.materials[i] for i in g.face_material.tolist()) == ["glass", "wood", "wood"]


def test_load_mesh_scale_transform_and_callable(tmp_path: Path) -> None:
    f = tmp_path / "room.obj"
    _write_obj(f)
    shift = np.eye(4)
    shift[:3, 3] = [10.0, 0.0, 0.0]
    g = load_mesh(f, scale=2.0, transform=shift, dtype=torch.float64,
                  face_materials=lambda c, n, grp: ["metal" if abs(nn[2]) > 0.9 else "glass" for nn in n])
    assert g.vertices[:, 0].min().item() == pytest.approx(10.0)
    assert g.vertices[:, 0].max().item() == pytest.approx(12.0)
    _, area = _normals_areas(g)
    assert area.sum().item() == pytest.approx(4 * 1.5)
    names = [g.materials[i] for i in g.face_material.tolist()]
    assert sorted(names) == ["glass", "metal", "metal"]


@pytest.mark.parametrize("suffix", ["ply", "stl", "glb"])
def test_load_mesh_other_formats(tmp_path: Path, suffix: str) -> None:
    box = trimesh.creation.box(extents=(1.0, 2.0, 3.0))
    f = tmp_path / f"box.{suffix}"
    box.export(f)
    g = load_mesh(f, material="wood")
    assert g.num_faces == 12 and g.materials == ("wood",)
    _, area = _normals_areas(g)
    assert area.sum().item() == pytest.approx(2 * (2 + 3 + 6), rel=1e-6)


def test_load_mesh_bad_files(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="missing.obj"):
        load_mesh(tmp_path / "missing.obj")
    bad = tmp_path / "garbage.glb"
    bad.write_bytes(b"\x00\x01not a mesh at all")
    with pytest.raises(SceneError, match="garbage.glb"):
        load_mesh(bad)
    empty = tmp_path / "empty.obj"
    empty.write_text("# nothing\n")
    with pytest.raises(SceneError, match="empty.obj"):
        load_mesh(empty)
    good = tmp_path / "room.obj"
    _write_obj(good)
    with pytest.raises(SceneError, match="room.obj"):
        load_mesh(good, face_materials={"floor": "lava"})
    with pytest.raises(SceneError, match="3 faces"):
        load_mesh(good, face_materials=lambda c, n, g: ["wood", "wood"])
    with pytest.raises(SceneError, match="transform"):
        load_mesh(good, transform=np.eye(3))


def test_merge_keeps_materials_and_ids(tmp_path: Path) -> None:
    room = corridor(4.0, 2.0, 2.0, max_edge_m=2.0)
    f = tmp_path / "room.obj"
    _write_obj(f)
    obj = load_mesh(f, material="metal", face_materials={"floor": "plasterboard"})
    moving = SceneGeometry(
        vertices=torch.zeros(3, 3), faces=torch.tensor([[0, 1, 2]]), face_material=torch.tensor([0]),
        materials=("skin",), vertex_velocity=torch.ones(3, 3), object_id=torch.tensor([0]),
    )
    m = merge([room, obj, moving])
    assert m.num_faces == room.num_faces + obj.num_faces + 1
    assert len(set(m.materials)) == len(m.materials)
    # Materials survive by name, face by face.
    names = [m.materials[i] for i in m.face_material.tolist()]
    expect = ([room.materials[i] for i in room.face_material.tolist()]
              + [obj.materials[i] for i in obj.face_material.tolist()] + ["skin"])
    assert names == expect
    # Geometry survives.
    torch.testing.assert_close(m.triangles, torch.cat([room.triangles, obj.triangles, moving.triangles]))
    # Object ids: room 0, then one distinct id per following object.
    ids = m.object_id.tolist()
    assert set(ids[: room.num_faces]) == {0}
    assert set(ids[room.num_faces: room.num_faces + obj.num_faces]) == {1}
    assert ids[-1] == 2
    # Velocities: zeros for static parts, kept for the moving one.
    assert m.vertex_velocity is not None
    assert (m.vertex_velocity[: room.vertices.shape[0] + obj.vertices.shape[0]] == 0).all()
    assert (m.vertex_velocity[-3:] == 1).all()
    with pytest.raises(SceneError):
        merge([])


def test_corridor_float64_and_face_count() -> None:
    g = corridor(2.0, 1.0, 1.0, max_edge_m=math.sqrt(2), dtype=torch.float64)
    assert g.vertices.dtype == torch.float64
    # 1 m cells: floor/ceiling/side walls 2 cells each, end walls 1 cell each -> 2 triangles per cell.
    assert g.num_faces == 2 * (2 + 2 + 2 + 2 + 1 + 1)
