"""A standing person: upright rest pose, breathing and postural sway (analytic, exact velocities).

Why: standing still is outside Boulic's walker, and is the case a one-frame range-Doppler classifier
finds hardest (the whole return sits at zero Doppler). Model: ``docs/people.md``, "Standing person".
"""

from __future__ import annotations

import math

import torch

from radaraug.errors import SceneError
from radaraug.scene.people.person import SkeletonPerson, as_times, register_person
from radaraug.scene.people.skeleton import (
    ANKLE_HEIGHT_FRACTION,
    JOINT_INDEX,
    JOINT_NAMES,
    SEGMENT_LENGTH_FRACTIONS,
)

_TWO_PI = 2.0 * math.pi
_UPPER_BODY = ("neck", "head_top", "left_shoulder", "right_shoulder", "left_elbow", "right_elbow",
               "left_wrist", "right_wrist")
"""Joints that move with the chest (twice the chest displacement: the torso centre moves by it)."""


@register_person
class StandingPerson(SkeletonPerson):
    """A person standing still: rest pose, breathing (along the facing direction) and sway about the ankles.

    Args:
        height_m: body height, metres (0.5-2.5).
        position: ``(x, y)`` of the pelvis, metres.
        facing_rad: direction the person faces in the x-y plane (0 = +x).
        breathing_m: peak chest displacement, metres (0-0.03).
        breathing_Hz: breathing rate, Hz (0-1).
        breathing_phase: breathing phase at ``t = 0``, cycles in [0, 1).
        sway_rad: peak sway angle about the ankles, radians (0-0.05; 0.01 rad moves the pelvis ~1 cm).
        sway_Hz: sway frequency, Hz (0-2).
        sway_phase: sway phase at ``t = 0``, cycles in [0, 1).
        sway_direction_rad: sway direction relative to the facing direction (0 = fore-aft).
    """

    type_name = "standing"
    _FIELDS = ("height_m", "position", "facing_rad", "breathing_m", "breathing_Hz", "breathing_phase", "sway_rad",
               "sway_Hz", "sway_phase", "sway_direction_rad")

    def __init__(
        self,
        height_m: float = 1.75,
        position: tuple[float, float] = (0.0, 0.0),
        facing_rad: float = 0.0,
        breathing_m: float = 0.006,
        breathing_Hz: float = 0.25,
        breathing_phase: float = 0.0,
        sway_rad: float = 0.008,
        sway_Hz: float = 0.3,
        sway_phase: float = 0.0,
        sway_direction_rad: float = 0.0,
    ) -> None:
        checks = {
            "height_m": (height_m, 0.5, 2.5), "breathing_m": (breathing_m, 0.0, 0.03),
            "breathing_Hz": (breathing_Hz, 0.0, 1.0), "sway_rad": (sway_rad, 0.0, 0.05),
            "sway_Hz": (sway_Hz, 0.0, 2.0),
        }
        for name, (value, lo, hi) in checks.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not lo <= float(value) <= hi:
                raise SceneError(f"StandingPerson: {name}={value!r} must be a number in [{lo}, {hi}]")
        for name, value in (("breathing_phase", breathing_phase), ("sway_phase", sway_phase)):
            if not 0.0 <= float(value) < 1.0:
                raise SceneError(f"StandingPerson: {name}={value} must be in [0, 1)")
        if len(tuple(position)) != 2:
            raise SceneError(f"StandingPerson: position must be (x, y), got {position!r}")
        super().__init__(height_m)
        self.height_m = float(height_m)
        self.position = (float(position[0]), float(position[1]))
        self.facing_rad = float(facing_rad)
        self.breathing_m, self.breathing_Hz = float(breathing_m), float(breathing_Hz)
        self.breathing_phase = float(breathing_phase)
        self.sway_rad, self.sway_Hz, self.sway_phase = float(sway_rad), float(sway_Hz), float(sway_phase)
        self.sway_direction_rad = float(sway_direction_rad)
        self._rest = self._rest_pose()

    def _rest_pose(self) -> torch.Tensor:
        """Joint positions ``(17, 3)`` in the body frame (x forward, y left, z up; feet on z = 0)."""
        h = self.height_m
        f = SEGMENT_LENGTH_FRACTIONS
        ankle = ANKLE_HEIGHT_FRACTION * h
        knee = ankle + f["lower_leg"] * h
        hip = knee + f["upper_leg"] * h
        neck = hip + f["torso"] * h
        hw, sw = f["hip_width"] * h / 2, f["shoulder_width"] * h / 2
        elbow = neck - f["upper_arm"] * h
        pos = {"pelvis": (0.0, 0.0, hip), "neck": (0.0, 0.0, neck), "head_top": (0.0, 0.0, neck + f["head"] * h)}
        for side, arm_y, leg_y in (("left", sw, hw), ("right", -sw, -hw)):
            pos |= {
                f"{side}_shoulder": (0.0, arm_y, neck), f"{side}_elbow": (0.0, arm_y, elbow),
                f"{side}_wrist": (0.0, arm_y, elbow - f["lower_arm"] * h), f"{side}_hip": (0.0, leg_y, hip),
                f"{side}_knee": (0.0, leg_y, knee), f"{side}_ankle": (0.0, leg_y, ankle),
                f"{side}_toe": (f["foot"] * h, leg_y, 0.0),
            }
        return torch.tensor([pos[n] for n in JOINT_NAMES], dtype=torch.float64)

    def joints(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Joint positions ``(T, 17, 3)`` m and analytic velocities ``(T, 17, 3)`` m/s."""
        t = as_times(t)
        dev, dt = t.device, t.dtype
        rest = self._rest.to(device=dev, dtype=dt)
        # Body-frame displacement per joint = breathing(t) * chest_weight + sway(t) * lever.
        wb = _TWO_PI * self.breathing_Hz
        arg_b = wb * t + _TWO_PI * self.breathing_phase
        b, db = self.breathing_m * torch.sin(arg_b), self.breathing_m * wb * torch.cos(arg_b)
        ws = _TWO_PI * self.sway_Hz
        arg_s = ws * t + _TWO_PI * self.sway_phase
        s, ds = self.sway_rad * torch.sin(arg_s), self.sway_rad * ws * torch.cos(arg_s)
        chest = torch.zeros(len(JOINT_NAMES), dtype=dt, device=dev)
        chest[[JOINT_INDEX[n] for n in _UPPER_BODY]] = 2.0
        lever = (rest[:, 2] - ANKLE_HEIGHT_FRACTION * self.height_m).clamp_min(0.0)  # (17,) m above the ankles
        cd, sd = math.cos(self.sway_direction_rad), math.sin(self.sway_direction_rad)
        sway_dir = torch.tensor([cd, sd, 0.0], dtype=dt, device=dev)
        fwd = torch.tensor([1.0, 0.0, 0.0], dtype=dt, device=dev)
        disp = (b[:, None, None] * chest[None, :, None] * fwd
                + s[:, None, None] * lever[None, :, None] * sway_dir)  # (T, 17, 3)
        vel = (db[:, None, None] * chest[None, :, None] * fwd
               + ds[:, None, None] * lever[None, :, None] * sway_dir)
        c, si = math.cos(self.facing_rad), math.sin(self.facing_rad)
        rot = torch.tensor([[c, -si, 0.0], [si, c, 0.0], [0.0, 0.0, 1.0]], dtype=dt, device=dev)
        origin = torch.tensor([self.position[0], self.position[1], 0.0], dtype=dt, device=dev)
        pos = (rest + disp) @ rot.T + origin
        return pos, vel @ rot.T

    @property
    def peak_speed_m_s(self) -> float:
        """Upper bound of any joint's speed (breathing plus sway at the head), m/s."""
        lever = self.height_m * (1.0 - ANKLE_HEIGHT_FRACTION)
        return 2.0 * self.breathing_m * _TWO_PI * self.breathing_Hz + self.sway_rad * _TWO_PI * self.sway_Hz * lever
