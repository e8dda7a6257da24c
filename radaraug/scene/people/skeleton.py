"""The 16-segment body model shared by every skeleton-driven person (walker, BVH).

A person is 17 joints; each of the 16 segments is an ellipsoid spanning a parent and a child
joint (V.C. Chen's and MATLAB ``backscatterPedestrian``'s body model, same segment order).
Segment lengths come from the joints; thicknesses are fractions of the body height (values in
the table below, from anthropometric tables for a 1.8 m adult, scaled linearly with height).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.errors import SceneError
from radaraug.scene.geometry import Ellipsoids

JOINT_NAMES: tuple[str, ...] = (
    "pelvis", "neck", "head_top",
    "left_shoulder", "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist",
    "left_hip", "right_hip", "left_knee", "right_knee", "left_ankle", "right_ankle",
    "left_toe", "right_toe",
)
"""The 17 joints, in the order of the ``J`` axis of joint tensors."""

JOINT_INDEX: dict[str, int] = {n: i for i, n in enumerate(JOINT_NAMES)}

# (segment, parent joint, child joint, body-frame reference for the cross-section axes)
# "low"/"up": the lateral axis of the hips/shoulders; "vertical": world up (for lateral bones).
_SEGMENT_TABLE: tuple[tuple[str, str, str, str], ...] = (
    ("left_foot", "left_ankle", "left_toe", "low"),
    ("right_foot", "right_ankle", "right_toe", "low"),
    ("left_lower_leg", "left_knee", "left_ankle", "low"),
    ("right_lower_leg", "right_knee", "right_ankle", "low"),
    ("left_upper_leg", "left_hip", "left_knee", "low"),
    ("right_upper_leg", "right_hip", "right_knee", "low"),
    ("left_hip", "pelvis", "left_hip", "vertical"),
    ("right_hip", "pelvis", "right_hip", "vertical"),
    ("left_lower_arm", "left_elbow", "left_wrist", "up"),
    ("right_lower_arm", "right_elbow", "right_wrist", "up"),
    ("left_upper_arm", "left_shoulder", "left_elbow", "up"),
    ("right_upper_arm", "right_shoulder", "right_elbow", "up"),
    ("left_shoulder", "neck", "left_shoulder", "vertical"),
    ("right_shoulder", "neck", "right_shoulder", "vertical"),
    ("head", "neck", "head_top", "up"),
    ("torso", "pelvis", "neck", "up"),
)

SEGMENT_NAMES: tuple[str, ...] = tuple(s[0] for s in _SEGMENT_TABLE)
"""The 16 segments, in the order of the ``S`` axis of :class:`Ellipsoids`."""

# Cross-section semi-axes (local x, local y) as fractions of body height. Local z runs along the
# bone (semi-axis = half the joint distance); local y is the body's lateral axis (for the hips
# and shoulders, which are lateral bones: world up), local x completes a right-handed frame
# (forward for upright segments, down for the feet). Metres for a 1.8 m adult in comments.
SEMI_AXIS_FRACTIONS: dict[str, tuple[float, float]] = {
    "foot": (0.040 / 1.8, 0.045 / 1.8),       # 4 cm thick, 9 cm wide
    "lower_leg": (0.055 / 1.8, 0.055 / 1.8),  # calf, 11 cm across
    "upper_leg": (0.075 / 1.8, 0.075 / 1.8),  # thigh, 15 cm across
    "hip": (0.080 / 1.8, 0.080 / 1.8),        # buttock/hip mass
    "lower_arm": (0.040 / 1.8, 0.040 / 1.8),
    "upper_arm": (0.050 / 1.8, 0.050 / 1.8),
    "shoulder": (0.060 / 1.8, 0.060 / 1.8),
    "head": (0.095 / 1.8, 0.080 / 1.8),       # 19 cm deep, 16 cm wide
    "torso": (0.110 / 1.8, 0.160 / 1.8),      # 22 cm deep, 32 cm wide
}

# Boulic / Chen segment lengths as fractions of height (also used to size a BVH figure).
SEGMENT_LENGTH_FRACTIONS: dict[str, float] = {
    "head": 0.130, "torso": 0.288, "shoulder_width": 0.259, "hip_width": 0.191,
    "upper_leg": 0.245, "lower_leg": 0.246, "foot": 0.143, "upper_arm": 0.188, "lower_arm": 0.152,
}
LEG_LENGTH_FRACTION = SEGMENT_LENGTH_FRACTIONS["upper_leg"] + SEGMENT_LENGTH_FRACTIONS["lower_leg"]
ANKLE_HEIGHT_FRACTION = 0.039
"""Height of the ankle joint above the sole (Winter's anthropometric table)."""

_MIN_SEMI_AXIS_M = 1e-3
_CACHE: dict[tuple, Any] = {}  # small per-device constant tensors


def _kind(segment: str) -> str:
    return segment.replace("left_", "").replace("right_", "")


@dataclass(frozen=True)
class Skeleton:
    """The 16-ellipsoid body for a person of a given height.

    Args:
        height_m: standing height, metres; sets the segment thicknesses.
    """

    height_m: float = 1.8

    def __post_init__(self) -> None:
        if not (0.3 <= float(self.height_m) <= 3.0):
            raise SceneError(f"Skeleton: height_m={self.height_m} m is not a human height (0.3-3 m)")

    @property
    def num_segments(self) -> int:
        """``S`` = 16."""
        return len(SEGMENT_NAMES)

    def _indices(self, device: torch.device) -> tuple[torch.Tensor, torch.Tensor]:
        key = ("idx", device)
        if key not in _CACHE:
            _CACHE[key] = (
                torch.tensor([JOINT_INDEX[s[1]] for s in _SEGMENT_TABLE], device=device),
                torch.tensor([JOINT_INDEX[s[2]] for s in _SEGMENT_TABLE], device=device),
            )
        return _CACHE[key]

    def cross_section(self, like: torch.Tensor) -> torch.Tensor:
        """``(S, 2)`` cross-section semi-axes (local x, y) in metres, on ``like``'s device/dtype."""
        key = ("cs", float(self.height_m), like.device, like.dtype)
        if key not in _CACHE:
            vals = [SEMI_AXIS_FRACTIONS[_kind(s)] for s in SEGMENT_NAMES]
            _CACHE[key] = torch.tensor(vals, dtype=like.dtype, device=like.device) * float(self.height_m)
        return _CACHE[key]

    def segment_frames(
        self, joints: torch.Tensor, fallback: torch.Tensor | None = None
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """World-from-local rotations of the segments (local z along the bone).

        Cross-section axes follow a body reference (hip or shoulder line; world up for lateral bones),
        or a second one for a bone within ~12 degrees of it; ``fallback`` returns that choice so that
        nearby instants can reuse it (continuous finite differences).

        Args:
            joints: ``(..., 17, 3)`` joint positions.
            fallback: ``(..., S)`` bool, which segments use the second reference; None = decide.

        Returns:
            ``(rotations (..., S, 3, 3), fallback (..., S))``.
        """
        parent, child = self._indices(joints.device)
        return self._frames(joints, joints[..., child, :] - joints[..., parent, :], fallback)

    def _frames(
        self, joints: torch.Tensor, bone: torch.Tensor, fallback: torch.Tensor | None
    ) -> tuple[torch.Tensor, torch.Tensor]:
        j = JOINT_INDEX
        length = bone.norm(dim=-1, keepdim=True)
        up = torch.zeros_like(bone[..., 0, :])
        up[..., 2] = 1.0
        d = torch.where(length > 1e-9, bone / length.clamp_min(1e-12), up.unsqueeze(-2))

        def unit(v: torch.Tensor) -> torch.Tensor:
            return v / v.norm(dim=-1, keepdim=True).clamp_min(1e-12)

        lat_low = unit(joints[..., j["left_hip"], :] - joints[..., j["right_hip"], :])
        lat_up = unit(joints[..., j["left_shoulder"], :] - joints[..., j["right_shoulder"], :])
        fwd = unit(torch.linalg.cross(lat_low, up, dim=-1))
        refs = {"low": (lat_low, up), "up": (lat_up, up), "vertical": (up, fwd)}
        r1 = torch.stack([refs[s[3]][0] for s in _SEGMENT_TABLE], dim=-2)
        r2 = torch.stack([refs[s[3]][1] for s in _SEGMENT_TABLE], dim=-2)

        def perp(r: torch.Tensor) -> torch.Tensor:
            return r - (r * d).sum(-1, keepdim=True) * d

        y1, y2 = perp(r1), perp(r2)
        if fallback is None:
            fallback = y1.norm(dim=-1) < 0.2
        y = unit(torch.where(fallback.unsqueeze(-1), y2, y1))
        x = torch.linalg.cross(y, d, dim=-1)
        return torch.stack([x, y, d], dim=-1), fallback

    def ellipsoids(
        self,
        joints: torch.Tensor,
        velocities: torch.Tensor,
        fallback: torch.Tensor | None = None,
        material: str = "skin",
    ) -> Ellipsoids:
        """Segment ellipsoids from joint positions and velocities.

        Centres are bone midpoints moving with the mean joint velocity (exact for a rigid bone);
        angular velocities come from the segment frames a short step ahead (``docs/people.md``).

        Args:
            joints: ``(..., 17, 3)`` positions, metres.
            velocities: ``(..., 17, 3)`` m/s.
            fallback: see :meth:`segment_frames`.
            material: surface material name.
        """
        parent, child = self._indices(joints.device)
        s = parent.shape[0]
        # One gather for both ends of every bone, positions and velocities together.
        ends = torch.cat([joints, velocities], dim=-1)[..., torch.cat([parent, child]), :]
        pa, ch = ends[..., :s, :3], ends[..., s:, :3]
        centers = 0.5 * (pa + ch)
        vel = 0.5 * (ends[..., :s, 3:] + ends[..., s:, 3:])
        bone = ch - pa
        half = (0.5 * bone.norm(dim=-1, keepdim=True)).clamp_min(_MIN_SEMI_AXIS_M)
        cs = self.cross_section(joints).expand(*half.shape[:-1], 2)
        semi = torch.cat([cs, half], dim=-1)
        rot, _ = self._frames(joints, bone, fallback)
        # The segment frames a short step ahead along the joints' velocities: R(t + dt) R(t)^T = I + [omega]x dt,
        # the whole turn (the bone's, and the twist the hip and shoulder lines give the cross-section).
        step = 1e-4
        ahead = joints + step * velocities
        ends2 = ahead[..., torch.cat([parent, child]), :]
        rot2, _ = self._frames(ahead, ends2[..., s:, :] - ends2[..., :s, :], fallback)
        w = (rot2 @ rot.transpose(-1, -2) - rot @ rot2.transpose(-1, -2)) / (2 * step)
        omega = torch.stack([w[..., 2, 1], w[..., 0, 2], w[..., 1, 0]], dim=-1)
        return Ellipsoids(centers=centers, semi_axes=semi, rotations=rot, velocities=vel, material=material,
                          angular_velocities=omega)


@contextmanager
def without_turn() -> Iterator[None]:
    """Inside, skeleton people give no angular velocities: echoes move with their segments' centres.

    Reproduces twin model version 1 (``docs/people.md``). Not thread-safe: it replaces :meth:`Skeleton.ellipsoids`.
    """
    with_turn = Skeleton.ellipsoids

    def centre_only(self: Skeleton, *args: Any, **kwargs: Any) -> Ellipsoids:
        return dataclasses.replace(with_turn(self, *args, **kwargs), angular_velocities=None)

    Skeleton.ellipsoids = centre_only  # type: ignore[method-assign]
    try:
        yield
    finally:
        Skeleton.ellipsoids = with_turn  # type: ignore[method-assign]
