"""BVH: parser + forward kinematics against closed forms, and walker -> BVH -> BVHPerson."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import torch

from radaraug.errors import SceneError
from radaraug.scene.people import BVHPerson, Walker, person_from_dict, read_bvh, write_bvh
from radaraug.scene.people.bvh_person import detect_scale

TINY = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Knee
  {
    OFFSET 0 -10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 -5 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.1
1 20 3 0 0 0 0 0 0
1 20 3 90 0 0 0 90 0
"""


def test_tiny_bvh_forward_kinematics(tmp_path: Path) -> None:
    p = tmp_path / "tiny.bvh"
    p.write_text(TINY)
    sk = read_bvh(p)
    assert sk.names == ["Hips", "Knee", "Knee_end"]
    assert sk.frame_time_s == pytest.approx(0.1)
    pos = sk.forward_kinematics()
    root = torch.tensor([1.0, 20.0, 3.0], dtype=torch.float64)
    # Frame 0: rest pose hanging down -y.
    assert torch.allclose(pos[0], root + torch.tensor([[0, 0, 0], [0, -10, 0], [0, -15, 0]], dtype=torch.float64))
    # Frame 1: root Rz(90) maps the knee offset (0, -10, 0) to (+10, 0, 0); the knee's Rx(90)
    # turns its child (0, -5, 0) into (0, 0, -5), which the root's Rz(90) leaves alone.
    expect = root + torch.tensor([[0, 0, 0], [10, 0, 0], [10, 0, -5]], dtype=torch.float64)
    assert torch.allclose(pos[1], expect, atol=1e-12)


def _walker_clip(tmp_path: Path, unit: str = "cm") -> tuple[Walker, Path]:
    w = Walker(height_m=1.75, speed_m_s=1.3, start=(2.0, -1.0), heading_rad=0.6, phase=0.3)
    fps = 240 / (2 * w.cycle_duration_s)  # exactly 240 frame intervals per two cycles
    path = write_bvh(w, tmp_path / "walk.bvh", fps=fps, duration_s=2 * w.cycle_duration_s, unit=unit)
    return w, path


def test_walker_round_trip_through_bvh(tmp_path: Path) -> None:
    w, path = _walker_clip(tmp_path)
    b = BVHPerson(path, start=(2.0, -1.0), heading_rad=0.6)
    assert b.scale == pytest.approx(0.01)
    assert b.estimated_height_m == pytest.approx(1.75, rel=1e-6)
    t = torch.linspace(0, 2 * w.cycle_duration_s, 301, dtype=torch.float64)
    pw, vw = w.joints(t)
    pb, vb = b.joints(t)
    assert (pw - pb).norm(dim=-1).max().item() < 0.003
    assert (vw - vb).norm(dim=-1).pow(2).mean().sqrt().item() < 0.05
    # Looping carries the root motion over: the next two cycles match the walker too.
    t2 = t + 2 * w.cycle_duration_s
    assert (w.joints(t2)[0] - b.joints(t2)[0]).norm(dim=-1).max().item() < 0.005
    eb, ew = b.ellipsoids(t), w.ellipsoids(t)
    assert eb.centers.shape == ew.centers.shape
    assert (eb.centers - ew.centers).norm(dim=-1).max().item() < 0.003


def test_bvh_placement_and_units(tmp_path: Path) -> None:
    w, path = _walker_clip(tmp_path, unit="inch")
    assert detect_scale(read_bvh(path)) == pytest.approx(0.0254)
    b = BVHPerson(path, start=(0.0, 5.0), heading_rad=-math.pi / 2, loop=False)
    p, v = b.joints(torch.tensor([0.0, 1.0, 100.0], dtype=torch.float64))
    assert torch.allclose(p[0, 0, :2], torch.tensor([0.0, 5.0], dtype=torch.float64), atol=1e-9)
    assert p[1, 0, 1].item() < 5.0 - 1.0  # walking towards -y
    assert v[2].abs().max().item() == 0.0  # held after the clip ends (loop=False)
    assert b.to_dict()["scale"] is None
    b2 = person_from_dict(BVHPerson(path, scale=0.0254).to_dict())
    assert b2.scale == 0.0254


def test_mixamo_names_are_mapped(tmp_path: Path) -> None:
    _, path = _walker_clip(tmp_path)
    text = path.read_text()
    for name in ("Hips", "LeftUpLeg", "RightUpLeg", "LeftLeg", "RightLeg", "LeftFoot", "RightFoot", "Spine",
                 "Neck", "Head", "LeftArm", "RightArm", "LeftForeArm", "RightForeArm", "LeftHand", "RightHand"):
        text = text.replace(f"JOINT {name}\n", f"JOINT mixamorig:{name}\n").replace(f"ROOT {name}\n", f"ROOT mixamorig:{name}\n")
    p2 = tmp_path / "mixamo.bvh"
    p2.write_text(text)
    a, b = BVHPerson(path), BVHPerson(p2)
    t = torch.linspace(0, 1, 5, dtype=torch.float64)
    assert torch.allclose(a.joints(t)[0], b.joints(t)[0])


@pytest.mark.parametrize(
    ("mutate", "line"),
    [
        (lambda s: s.replace("OFFSET 0 -10 0", "OFFSET 0 -1x0 0"), 8),
        (lambda s: s.replace("Zrotation Xrotation Yrotation\n    End", "Zrotation Xrotation Qrotation\n    End"), 9),
        (lambda s: s.replace("1 20 3 90 0 0 0 90 0\n", "1 20 3 90 0 0 0 90\n"), 20),
        (lambda s: s.replace("MOTION", "MOTON"), 16),
        (lambda s: s.replace("OFFSET 0 -10 0", "OFFSET 0 nan 0"), 8),
        (lambda s: s.replace("Frame Time: 0.1", "Frame Time: inf"), 18),
        (lambda s: s.replace("1 20 3 90 0 0 0 90 0", "1 20 3 90 0 0 0 nan 0"), 20),
    ],
)
def test_malformed_bvh_names_file_and_line(tmp_path: Path, mutate, line: int) -> None:  # noqa: ANN001
    p = tmp_path / "bad.bvh"
    p.write_text(mutate(TINY))
    with pytest.raises(SceneError, match=rf"bad\.bvh: line {line}:"):
        read_bvh(p)


def test_missing_file_and_joints(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="nope.bvh"):
        read_bvh(tmp_path / "nope.bvh")
    p = tmp_path / "tiny.bvh"
    p.write_text(TINY)
    with pytest.raises(SceneError, match="no joint for 'neck'"):
        BVHPerson(p, scale=0.1)
