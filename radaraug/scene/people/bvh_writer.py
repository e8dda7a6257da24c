"""Export a walker's motion as a BVH file (for other tools, and to test BVH playback)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import torch

from radaraug.errors import SceneError
from radaraug.files import atomic_write_text
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people.bvh_person import _BVH_TO_WORLD, UNIT_SCALES
from radaraug.scene.people.skeleton import ANKLE_HEIGHT_FRACTION
from radaraug.scene.people.walker import Walker

Vec3 = tuple[float, float, float]
CMUJoint = tuple[str, str | None, Vec3, Vec3 | None]
"""``(name, parent or None for the root, offset, end-site offset or None)``."""


def cmu_hierarchy(ln: Mapping[str, float]) -> list[CMUJoint]:
    """The CMU-named joints of a figure in file order, offsets in metres along the BVH axes.

    BVH axes: +x the figure's left, +y up, +z forward. ``ln`` holds the lengths in metres:
    ``hip_width``, ``upper_leg``, ``lower_leg``, ``ankle`` (ankle height), ``foot`` (ankle to
    toe, forward), ``torso``, ``head``, ``shoulder_width``, ``shoulder_drop`` (shoulder joints
    below the neck joint), ``upper_arm``, ``forearm``, ``hand``.
    """
    hw, sw = ln["hip_width"] / 2, ln["shoulder_width"] / 2
    spec: list[CMUJoint] = [("Hips", None, (0.0, 0.0, 0.0), None)]
    for side, sgn in (("Left", 1.0), ("Right", -1.0)):
        spec += [
            (f"{side}UpLeg", "Hips", (sgn * hw, 0.0, 0.0), None),
            (f"{side}Leg", f"{side}UpLeg", (0.0, -ln["upper_leg"], 0.0), None),
            (f"{side}Foot", f"{side}Leg", (0.0, -ln["lower_leg"], 0.0), (0.0, -ln["ankle"], ln["foot"])),
        ]
    spec += [
        ("Spine", "Hips", (0.0, 0.0, 0.0), None),
        ("Neck", "Spine", (0.0, ln["torso"], 0.0), None),
        ("Head", "Neck", (0.0, ln["head"] / 2, 0.0), (0.0, ln["head"] / 2, 0.0)),
    ]
    for side, sgn in (("Left", 1.0), ("Right", -1.0)):
        spec += [
            (f"{side}Arm", "Neck", (sgn * sw, -ln["shoulder_drop"], 0.0), None),
            (f"{side}ForeArm", f"{side}Arm", (0.0, -ln["upper_arm"], 0.0), None),
            (f"{side}Hand", f"{side}ForeArm", (0.0, -ln["forearm"], 0.0), (0.0, -ln["hand"], 0.0)),
        ]
    return spec


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


def write_clip(
    path: str | Path, joints: list[CMUJoint], root: torch.Tensor, euler_deg: Mapping[str, torch.Tensor],
    frame_time_s: float, m_per_unit: float,
) -> Path:
    """Write a BVH clip of ``joints`` (:func:`cmu_hierarchy`); returns ``path``.

    ``root``: ``(T, 3)`` root positions in metres (BVH axes); ``euler_deg``: per joint its
    ``(T, 3)`` Euler angles in degrees, order ``(Z, X, Y)``; ``m_per_unit``: the file's unit.
    """

    def fmt(vec: Vec3) -> str:
        # "+ 0.0" writes a zero offset as "0.000000", never "-0.000000".
        return " ".join(f"{x / m_per_unit + 0.0:.6f}" for x in vec)

    lines, order = hierarchy_lines([(name, parent, fmt(offset), None if end is None else fmt(end))
                                    for name, parent, offset, end in joints])
    motion = torch.cat([root / m_per_unit] + [euler_deg[name] for name in order], dim=1)
    lines += ["MOTION", f"Frames: {motion.shape[0]}", f"Frame Time: {frame_time_s:.9f}"]
    lines += [" ".join(f"{float(x):.6f}" for x in row) for row in motion]
    out = Path(path)
    atomic_write_text(out, "\n".join(lines) + "\n")
    return out


def write_bvh(
    person: Walker,
    path: str | Path,
    fps: float = 120.0,
    duration_s: float | None = None,
    unit: str = "cm",
) -> Path:
    """Write a :class:`Walker`'s motion as BVH (+Y up, ``Zrotation Xrotation Yrotation``, CMU joint names).

    :class:`BVHPerson` maps it back onto the same skeleton; start and heading are kept.

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
    h, lens = person.height_m, person.segment_lengths_m
    joints = cmu_hierarchy({**lens, "ankle": ANKLE_HEIGHT_FRACTION * h, "shoulder_drop": 0.0,
                            "forearm": lens["lower_arm"], "hand": 0.05 * h})
    # World rotation of each joint's segment (limbs: index 0 left, 1 right).
    rots = pose["rotations"]
    world_rot = {"Hips": rots["pelvis"], "Spine": rots["upper"], "Neck": rots["upper"], "Head": rots["upper"]}
    for side, k in (("Left", 0), ("Right", 1)):
        for joint, segment in (("UpLeg", "thigh"), ("Leg", "shank"), ("Foot", "foot"), ("Arm", "upper_arm"),
                               ("ForeArm", "forearm"), ("Hand", "forearm")):
            world_rot[side + joint] = rots[segment][k]
    p_mat = _BVH_TO_WORLD  # world = P bvh
    euler = {}
    for name, parent, _, _ in joints:
        local = world_rot[name] if parent is None else world_rot[parent].mT @ world_rot[name]
        euler[name] = torch.rad2deg(rot.euler_from_matrix(p_mat.T @ local @ p_mat, "zxy"))
    root = pose["positions"][:, 0] @ p_mat  # world -> bvh: P^T p
    return write_clip(path, joints, root, euler, 1.0 / fps, UNIT_SCALES[unit])
