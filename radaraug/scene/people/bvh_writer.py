"""Export a walker's motion as a BVH file (for other tools, and to test BVH playback)."""

from __future__ import annotations

from pathlib import Path

import torch

from radaraug._files import atomic_write_text
from radaraug.errors import SceneError
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people.bvh_person import _BVH_TO_WORLD, UNIT_SCALES
from radaraug.scene.people.skeleton import ANKLE_HEIGHT_FRACTION
from radaraug.scene.people.walker import Walker


def hierarchy_lines(joints: list[tuple[str, str | None, str, str | None]]) -> tuple[list[str], list[str]]:
    """The ``HIERARCHY`` section of a BVH file and the joint order of its motion channels.

    Args:
        joints: ``(name, parent or None for the root, "x y z" offset, "x y z" end-site offset or
            None)`` in any order with the root first; offsets already in the file's unit.

    Returns:
        ``(lines, order)``: the text lines, and joint names in depth-first channel order (the
        root has 6 channels ``Xposition Yposition Zposition Zrotation Xrotation Yrotation``,
        the others the 3 rotations).
    """
    children: dict[str | None, list[int]] = {}
    for i, j in enumerate(joints):
        children.setdefault(j[1], []).append(i)
    lines = ["HIERARCHY"]
    order: list[str] = []

    def emit(i: int, depth: int) -> None:
        name, parent, offset, end = joints[i]
        pad = "  " * depth
        lines.append(f"{pad}{'ROOT' if parent is None else 'JOINT'} {name}")
        lines.append(f"{pad}{{")
        lines.append(f"{pad}  OFFSET {offset}")
        chans = "Xposition Yposition Zposition " if parent is None else ""
        lines.append(f"{pad}  CHANNELS {6 if parent is None else 3} {chans}Zrotation Xrotation Yrotation")
        order.append(name)
        for c in children.get(name, []):
            emit(c, depth + 1)
        if end is not None:
            lines.extend([f"{pad}  End Site", f"{pad}  {{", f"{pad}    OFFSET {end}", f"{pad}  }}"])
        lines.append(f"{pad}}}")

    emit(0, 0)
    return lines, order

def write_bvh(
    person: Walker,
    path: str | Path,
    fps: float = 120.0,
    duration_s: float | None = None,
    unit: str = "cm",
) -> Path:
    """Write a :class:`Walker`'s motion as BVH (+Y up, ``Zrotation Xrotation Yrotation``).

    The hierarchy uses CMU joint names (Hips, LeftUpLeg, LeftLeg, LeftFoot, Spine, Neck, Head,
    LeftArm, LeftForeArm, LeftHand, ...), so :class:`BVHPerson` maps it back onto the same
    skeleton. World coordinates are written as they are (start and heading included).

    Args:
        person: the walker.
        path: output file.
        fps: frames per second.
        duration_s: clip length; default one gait cycle. ``round(duration_s * fps) + 1`` frames.
        unit: length unit of the file, a key of ``UNIT_SCALES`` (``"cm"``, ``"m"``, ``"inch"``...).

    Returns:
        The path written.
    """
    if not isinstance(person, Walker):
        raise SceneError(f"write_bvh: needs a Walker (joint rotations), got {type(person).__name__}")
    if unit not in UNIT_SCALES:
        raise SceneError(f"write_bvh: unknown unit {unit!r}; one of {sorted(UNIT_SCALES)}")
    if not fps > 0:
        raise SceneError(f"write_bvh: fps must be positive, got {fps}")
    duration = person.cycle_duration_s if duration_s is None else float(duration_s)
    n = int(round(duration * fps)) + 1
    t = torch.arange(n, dtype=torch.float64) / fps
    pose = person.pose(t)
    rots = pose["rotations"]
    h = person.height_m
    lens = person.segment_lengths_m
    m_per_unit = UNIT_SCALES[unit]
    p_mat = _BVH_TO_WORLD

    def off(x: float, y: float, z: float) -> str:
        b = p_mat.T @ torch.tensor([x, y, z], dtype=torch.float64) / m_per_unit
        return " ".join(f"{float(v):.6f}" for v in b)

    # (name, parent, offset in the parent's body frame (m), world rotation, end-site offset)
    hw, sw = lens["hip_width"] / 2, lens["shoulder_width"] / 2
    spec: list[tuple[str, str | None, tuple[float, float, float], torch.Tensor, tuple[float, float, float] | None]]
    spec = [("Hips", None, (0.0, 0.0, 0.0), rots["pelvis"], None)]
    for side, k, sgn in (("Left", 0, 1.0), ("Right", 1, -1.0)):
        spec += [
            (f"{side}UpLeg", "Hips", (0.0, sgn * hw, 0.0), rots["thigh"][k], None),
            (f"{side}Leg", f"{side}UpLeg", (0.0, 0.0, -lens["upper_leg"]), rots["shank"][k], None),
            (f"{side}Foot", f"{side}Leg", (0.0, 0.0, -lens["lower_leg"]), rots["foot"][k],
             (lens["foot"], 0.0, -ANKLE_HEIGHT_FRACTION * h)),
        ]
    spec += [
        ("Spine", "Hips", (0.0, 0.0, 0.0), rots["upper"], None),
        ("Neck", "Spine", (0.0, 0.0, lens["torso"]), rots["upper"], None),
        ("Head", "Neck", (0.0, 0.0, lens["head"] / 2), rots["upper"], (0.0, 0.0, lens["head"] / 2)),
    ]
    for side, k, sgn in (("Left", 0, 1.0), ("Right", 1, -1.0)):
        spec += [
            (f"{side}Arm", "Neck", (0.0, sgn * sw, 0.0), rots["upper_arm"][k], None),
            (f"{side}ForeArm", f"{side}Arm", (0.0, 0.0, -lens["upper_arm"]), rots["forearm"][k], None),
            (f"{side}Hand", f"{side}ForeArm", (0.0, 0.0, -lens["lower_arm"]), rots["forearm"][k],
             (0.0, 0.0, -0.05 * h)),
        ]
    world_rot = {name: r for name, _, _, r, _ in spec}
    lines, order = hierarchy_lines([(name, parent, off(*offset), None if end is None else off(*end))
                                    for name, parent, offset, _, end in spec])
    parent_of = {s[0]: s[1] for s in spec}
    columns = [pose["positions"][:, 0] @ p_mat / m_per_unit]  # the root; world -> bvh: P^T p
    for name in order:
        r_w = world_rot[name]
        parent = parent_of[name]
        local = r_w if parent is None else world_rot[parent].mT @ r_w
        local_bvh = p_mat.T @ local @ p_mat
        columns.append(torch.rad2deg(rot.euler_from_matrix(local_bvh, "zxy")))
    motion = torch.cat(columns, dim=1)
    lines += ["MOTION", f"Frames: {n}", f"Frame Time: {1.0 / fps:.9f}"]
    lines += [" ".join(f"{float(v):.6f}" for v in row) for row in motion]
    out = Path(path)
    atomic_write_text(out, "\n".join(lines) + "\n")
    return out


