"""A person driven by a BVH motion-capture clip, on the walker's 16-segment skeleton."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import torch

from radaraug.errors import SceneError
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people._interp import FrameTrack
from radaraug.scene.people.bvh import BVHSkeleton, read_bvh
from radaraug.scene.people.person import SkeletonPerson, as_times, register_person
from radaraug.scene.people.skeleton import JOINT_INDEX, JOINT_NAMES, LEG_LENGTH_FRACTION

# Metres per file unit of common BVH sources. CMU's BVH conversions keep the ASF unit
# "(1/0.45) inch"; Mixamo / MotionBuilder export centimetres.
UNIT_SCALES: dict[str, float] = {
    "m": 1.0, "cm": 0.01, "mm": 0.001, "inch": 0.0254, "cmu": 0.0254 / 0.45,
}
_TYPICAL_FIGURE_HEIGHT_M = 1.7

# Normalized names (lower case, namespace and punctuation removed) per joint, best first.
# Right-side names are derived by swapping left -> right and a leading l -> r.
_ALIASES: dict[str, list[str]] = {
    "pelvis": ["hips", "pelvis", "hip", "root"],
    "neck": ["neck", "neck1", "neck01"],
    "head_top": ["headend", "headtopend", "headtop", "headsiteend", "head"],
    "left_shoulder": ["leftarm", "leftupperarm", "leftuparm", "lupperarm", "luparm", "larm", "lhumerus"],
    "left_elbow": ["leftforearm", "leftlowerarm", "leftlowarm", "lforearm", "lelbow", "leftelbow", "lradius"],
    "left_wrist": ["lefthand", "leftwrist", "lhand", "lwrist"],
    "left_hip": ["leftupleg", "leftupperleg", "leftthigh", "lthigh", "lupleg", "lhip", "lefthip", "lfemur"],
    "left_knee": ["leftleg", "leftlowerleg", "leftlowleg", "leftshin", "lshin", "lknee", "leftknee", "ltibia"],
    "left_ankle": ["leftfoot", "leftankle", "lfoot", "lankle"],
    "left_toe": ["lefttoebase", "lefttoe", "lefttoes", "ltoes", "ltoe", "lefttoebaseend", "leftfootend", "lfootend"],
}


def _normalize(name: str) -> str:
    return re.sub(r"[^a-z0-9]", "", name.split(":")[-1].lower())


def _right(alias: str) -> str:
    if alias.startswith("left"):
        return "right" + alias[4:]
    return "r" + alias[1:]


def map_joints(sk: BVHSkeleton) -> list[int]:
    """Index into the BVH joints for each of the 17 skeleton joints.

    Raises:
        SceneError: a required joint is missing (lists the names tried).
    """
    lookup: dict[str, int] = {}
    for i, n in enumerate(sk.names):
        lookup.setdefault(_normalize(n), i)
    out = []
    for joint in JOINT_NAMES:
        base = joint.replace("right_", "left_")
        names = _ALIASES[base] if joint == base else [_right(a) for a in _ALIASES[base]]
        found = next((lookup[a] for a in names if a in lookup), None)
        if found is None:
            raise SceneError(
                f"{sk.path}: no joint for {joint!r} (tried {', '.join(names)}; file has {', '.join(sk.names)})"
            )
        out.append(found)
    return out


def detect_scale(sk: BVHSkeleton) -> float:
    """Metres per file unit: the :data:`UNIT_SCALES` entry giving the most human height.

    The rest-pose figure's height closest in ratio to ~1.7 m.
    """
    rest = sk.rest_positions()
    extent = float(rest[:, 1].max() - rest[:, 1].min())
    if not extent > 0:
        raise SceneError(f"{sk.path}: the rest pose has no height; pass scale= explicitly")
    return min(UNIT_SCALES.values(), key=lambda s: abs(math.log(extent * s / _TYPICAL_FIGURE_HEIGHT_M)))


# BVH is +Y up; world is +Z up: (x, y, z)_world = (z, x, y)_bvh, a proper rotation.
_BVH_TO_WORLD = torch.tensor([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], dtype=torch.float64)


@register_person
class BVHPerson(SkeletonPerson):
    """A BVH clip (e.g. CMU motion capture) on the 16-segment skeleton.

    Joints are mapped by name (CMU, Mixamo and common aliases) and placed with the pelvis at ``start``
    and the clip's net travel along ``heading_rad``; joints follow a Catmull-Rom spline between
    frames, with exact velocities. Details: ``docs/people.md``, "BVH motion capture".

    Args:
        path: BVH file.
        start: ``(x, y)`` of the pelvis at ``t = 0``, metres.
        heading_rad: travel direction in the x-y plane.
        scale: metres per file unit; None = detect (see :func:`detect_scale`).
        loop: repeat the clip, carrying its root displacement over (period = ``(F-1)`` frames);
            else hold the first/last pose outside the clip.
    """

    type_name = "bvh"
    _FIELDS = ("path", "start", "heading_rad", "scale", "loop")

    def __init__(
        self,
        path: str | Path,
        *,
        start: tuple[float, float] = (0.0, 0.0),
        heading_rad: float = 0.0,
        scale: float | None = None,
        loop: bool = True,
    ) -> None:
        self.path = str(path)
        sk = read_bvh(path)
        self.bvh = sk
        if scale is not None and not float(scale) > 0:
            raise SceneError(f"{self.path}: scale must be positive (metres per file unit), got {scale}")
        self.scale = detect_scale(sk) if scale is None else float(scale)
        self.scale_given = scale is not None
        if len(tuple(start)) != 2:
            raise SceneError(f"{self.path}: start must be (x, y), got {start!r}")
        self.start = (float(start[0]), float(start[1]))
        self.heading_rad = float(heading_rad)
        self.loop = bool(loop)

        world = sk.forward_kinematics() @ _BVH_TO_WORLD.T * self.scale  # (F, J, 3)
        joints = world[:, map_joints(sk)]  # (F, 17, 3)
        legs = [("left_hip", "left_knee", "left_ankle"), ("right_hip", "right_knee", "right_ankle")]
        leg = sum(
            (joints[0, JOINT_INDEX[a]] - joints[0, JOINT_INDEX[b]]).norm()
            + (joints[0, JOINT_INDEX[b]] - joints[0, JOINT_INDEX[c]]).norm()
            for a, b, c in legs
        ) / 2
        self.estimated_height_m = float(leg) / LEG_LENGTH_FRACTION
        try:
            super().__init__(self.estimated_height_m)
        except SceneError as exc:
            raise SceneError(
                f"{self.path}: figure height {self.estimated_height_m:.2f} m at scale {self.scale} m/unit "
                "is not human; pass scale= (metres per file unit)"
            ) from exc

        pelvis0 = joints[0, JOINT_INDEX["pelvis"], :2]
        travel = joints[-1, JOINT_INDEX["pelvis"], :2] - pelvis0
        if float(travel.norm()) >= 0.2:
            direction = math.atan2(float(travel[1]), float(travel[0]))
        else:
            lat = joints[0, JOINT_INDEX["left_hip"], :2] - joints[0, JOINT_INDEX["right_hip"], :2]
            direction = math.atan2(-float(lat[0]), float(lat[1]))  # forward = lateral x up
        self.clip_direction_rad = direction
        a = self.heading_rad - direction
        rz = rot.axis_rotation("z", a)
        origin = torch.cat([pelvis0, torch.zeros(1, dtype=torch.float64)])
        placed = (joints - origin) @ rz.T + torch.tensor([self.start[0], self.start[1], 0.0], dtype=torch.float64)
        shift = placed[-1, JOINT_INDEX["pelvis"]] - placed[0, JOINT_INDEX["pelvis"]]
        shift[2] = 0.0
        self._track = FrameTrack(placed, sk.frame_time_s, self.loop, shift)
        self.duration_s = self._track.period_s

    @property
    def frame_time_s(self) -> float:
        """Seconds per mocap frame."""
        return self.bvh.frame_time_s

    def joints(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Joint positions ``(T, 17, 3)`` m and velocities (m/s) at ``t`` ``(T,)`` s."""
        return self._track(as_times(t))

    def to_dict(self) -> dict[str, Any]:
        """Parameters for scene files (``scale`` only when it was given)."""
        return {**super().to_dict(), "scale": self.scale if self.scale_given else None}
