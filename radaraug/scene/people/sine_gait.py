"""A sinusoidal gait model written as BVH: a motion source independent of the Boulic walker.

The held-out proxy set must not walk with the training twin's model; this simple, open-loop gait
(sinusoids of the cycle phase, its own cadence law) is played back with ``BVHPerson``. Its
equations: ``docs/people.md``, "Sinusoidal gait".
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import torch

from radaraug.errors import SceneError
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people.bvh_person import UNIT_SCALES
from radaraug.scene.people.bvh_writer import CMUJoint, cmu_hierarchy, write_clip
from radaraug.scene.people.skeleton import ANKLE_HEIGHT_FRACTION, SEGMENT_LENGTH_FRACTIONS

_TWO_PI = 2.0 * math.pi

# Body proportions (fractions of height). Legs, trunk, head, hip and shoulder widths as the
# walker (Drillis-Contini); foot and arms differ.
PROPORTIONS: dict[str, float] = {
    **{k: SEGMENT_LENGTH_FRACTIONS[k] for k in ("upper_leg", "lower_leg", "hip_width", "shoulder_width", "torso", "head")},
    "foot_forward": 0.115,  # ankle to toe, horizontal
    "heel_back": 0.035,  # ankle to heel, horizontal
    "upper_arm": 0.186,
    "forearm": 0.146,
    "hand": 0.05,
    "shoulder_drop": 0.02,  # shoulder joints below the neck joint
}


def _r(x: torch.Tensor) -> torch.Tensor:
    """Raised cosine ``(1 - cos 2 pi x) / 2`` in [0, 1], peak at ``x = 1/2``."""
    return 0.5 - 0.5 * torch.cos(_TWO_PI * x)


@dataclass(frozen=True)
class SineGait:
    """A person walking straight ahead with the sinusoidal gait (see the module doc).

    Args:
        height_m: standing height H, metres (1.2-2.2).
        speed_m_s: walking speed V, m/s (0.3-2.0: walking, not running).
        phase: gait-cycle phase at ``t = 0`` in [0, 1) (0 = right heel strike).
        arm_swing: scale of the arm-swing amplitude (1 = the model's law).
    """

    height_m: float = 1.75
    speed_m_s: float = 1.2
    phase: float = 0.0
    arm_swing: float = 1.0

    def __post_init__(self) -> None:
        checks = (("height_m", self.height_m, 1.2, 2.2), ("speed_m_s", self.speed_m_s, 0.3, 2.0),
                  ("phase", self.phase, 0.0, 1.0), ("arm_swing", self.arm_swing, 0.0, 3.0))
        for name, value, lo, hi in checks:
            if not (isinstance(value, (int, float)) and math.isfinite(value) and lo <= value <= hi):
                raise SceneError(f"SineGait: {name}={value!r} must be a number in [{lo}, {hi}]")

    @property
    def cycle_frequency_Hz(self) -> float:
        """Gait cycles per second: ``0.575 + 0.275 V`` (linear in speed, height-independent)."""
        return 0.575 + 0.275 * self.speed_m_s

    @property
    def cycle_duration_s(self) -> float:
        """Seconds per gait cycle (two steps)."""
        return 1.0 / self.cycle_frequency_Hz

    @property
    def stride_length_m(self) -> float:
        """Distance covered per cycle."""
        return self.speed_m_s * self.cycle_duration_s

    def to_dict(self) -> dict[str, Any]:
        """The parameters (JSON-friendly)."""
        return {"model": "sine_gait", **asdict(self)}

    # ------------------------------------------------------------------ kinematics
    def angles_deg(self, u: torch.Tensor) -> dict[str, torch.Tensor]:
        """Joint angles in degrees at cycle phases ``u`` ``(T,)`` (right side; left = ``u + 0.5``)."""
        v = self.speed_m_s
        return {
            "hip": 6.0 + (12.0 + 7.0 * v) * torch.cos(_TWO_PI * u),
            "knee": 4.0 + (42.0 + 12.0 * v) * _r(u - 0.22) ** 2,
            "ankle": 8.0 * torch.sin(_TWO_PI * (u - 0.15)) - 4.0 * torch.sin(2 * _TWO_PI * (u - 0.03)),
            "shoulder": -self.arm_swing * (8.0 + 14.0 * v) * torch.cos(_TWO_PI * u),
            "elbow": 14.0 + 8.0 * v + (6.0 + 8.0 * v) * _r(u),
            "pelvis_rotation": (3.0 + 4.0 * v) * torch.cos(_TWO_PI * u),
            "pelvis_obliquity": 2.5 * torch.sin(_TWO_PI * u),
        }

    def _lengths(self) -> dict[str, float]:
        return {k: f * self.height_m for k, f in PROPORTIONS.items()}

    def _hierarchy(self) -> list[CMUJoint]:
        """``(joint, parent, offset (BVH axes, m), end-site offset or None)`` in file order."""
        ln = self._lengths()
        return cmu_hierarchy({**ln, "ankle": ANKLE_HEIGHT_FRACTION * self.height_m, "foot": ln["foot_forward"]})

    def channels(self, t: torch.Tensor) -> tuple[torch.Tensor, dict[str, torch.Tensor]]:
        """Root position ``(T, 3)`` and per-joint Euler angles ``(T, 3)`` at times ``t``.

        Positions in BVH axes, m, floor not yet applied; angles in degrees, order ``(Z, X, Y)``
        (``R = Rz Rx Ry``).
        """
        t = t.to(torch.float64)
        v = self.speed_m_s
        u = t / self.cycle_duration_s + self.phase
        right = self.angles_deg(u)
        left = self.angles_deg(u + 0.5)
        zero = torch.zeros_like(t)
        lean = 2.0 + 3.0 * v

        def zxy(z: torch.Tensor, x: torch.Tensor, y: torch.Tensor) -> torch.Tensor:
            return torch.stack([z, x, y], dim=-1)

        eul: dict[str, torch.Tensor] = {
            "Hips": zxy(right["pelvis_obliquity"], zero, right["pelvis_rotation"]),
            "Spine": zxy(zero, zero + lean, -1.3 * right["pelvis_rotation"]),
            "Neck": zxy(zero, zero - 0.6 * lean, zero),
            "Head": zxy(zero, zero, zero),
        }
        abduction = 6.0
        for side, a, sgn in (("Left", left, 1.0), ("Right", right, -1.0)):
            # Rx(+a) turns a hanging segment (0, -1, 0) backward, to (0, -cos a, -sin a): forward
            # flexion of hip, shoulder and elbow, and dorsiflexion (toes up), are negative X rotations.
            eul[f"{side}UpLeg"] = zxy(zero, -a["hip"], zero)
            eul[f"{side}Leg"] = zxy(zero, a["knee"], zero)
            eul[f"{side}Foot"] = zxy(zero, -a["ankle"], zero)
            eul[f"{side}Arm"] = zxy(zero + sgn * abduction, -a["shoulder"], zero)
            eul[f"{side}ForeArm"] = zxy(zero, -a["elbow"], zero)
            eul[f"{side}Hand"] = zxy(zero, zero, zero)
        bob = -(0.010 + 0.012 * v) * torch.cos(2 * _TWO_PI * u)
        sway = -(0.025 - 0.006 * v) * torch.sin(_TWO_PI * u)
        surge = 0.008 * torch.sin(2 * _TWO_PI * (u - 0.1))
        root = torch.stack([sway, bob, v * t + surge], dim=-1)
        return root, eul

    def forward_kinematics(self, t: torch.Tensor, root: torch.Tensor | None = None) -> dict[str, torch.Tensor]:
        """World positions ``(T, 3)`` (BVH axes, m) of every joint, end site and heel at times ``t``.

        End sites are named ``<joint>_end``, heels ``<side>Heel``; ``root`` overrides the root position.
        """
        r0, eul = self.channels(t)
        root = r0 if root is None else root
        pos: dict[str, torch.Tensor] = {}
        wrot: dict[str, torch.Tensor] = {}
        for name, parent, offset, end in self._hierarchy():
            local = rot.matrix_from_euler(torch.deg2rad(eul[name]), "zxy")
            off = torch.tensor(offset, dtype=torch.float64)
            if parent is None:
                pos[name] = root
                wrot[name] = local
            else:
                pos[name] = pos[parent] + wrot[parent] @ off
                wrot[name] = wrot[parent] @ local
            if end is not None:
                pos[f"{name}_end"] = pos[name] + wrot[name] @ torch.tensor(end, dtype=torch.float64)
        ln = self._lengths()
        for side in ("Left", "Right"):
            heel = torch.tensor([0.0, -ANKLE_HEIGHT_FRACTION * self.height_m, -ln["heel_back"]], dtype=torch.float64)
            pos[f"{side}Heel"] = pos[f"{side}Foot"] + wrot[f"{side}Foot"] @ heel
        return pos

    def clip_times(self, fps: float = 100.0) -> torch.Tensor:
        """Frame times of one looping cycle: ``n + 1`` frames, the last one cycle after the first."""
        if not (isinstance(fps, (int, float)) and math.isfinite(fps) and fps > 0):
            raise SceneError(f"SineGait: fps must be a positive number, got {fps!r}")
        n = max(8, int(round(self.cycle_duration_s * fps)))
        return torch.arange(n + 1, dtype=torch.float64) * (self.cycle_duration_s / n)

    def pelvis_height_m(self, fps: float = 100.0) -> float:
        """Constant added to the root height so that the lowest heel/toe point touches the floor."""
        t = self.clip_times(fps)
        pos = self.forward_kinematics(t)
        low = torch.stack([pos[k][:, 1] for k in ("LeftFoot_end", "RightFoot_end", "LeftHeel", "RightHeel")])
        return -float(low.min())


def write_sine_gait_bvh(gait: SineGait, path: str | Path, *, fps: float = 100.0, unit: str = "cm") -> Path:
    """Write one gait cycle of ``gait`` as a looping BVH clip (CMU joint names).

    The last frame is one stride after the first, so ``BVHPerson(..., loop=True)`` walks on seamlessly.

    Args:
        gait: the gait.
        path: output file.
        fps: nominal frames per second.
        unit: length unit of the file, a key of ``UNIT_SCALES`` (``"cm"`` default).

    Returns:
        The path written.
    """
    if unit not in UNIT_SCALES:
        raise SceneError(f"write_sine_gait_bvh: unknown unit {unit!r}; one of {sorted(UNIT_SCALES)}")
    t = gait.clip_times(fps)
    root, eul = gait.channels(t)
    root = root + torch.tensor([0.0, gait.pelvis_height_m(fps), 0.0], dtype=torch.float64)
    return write_clip(path, gait._hierarchy(), root, eul, float(t[1] - t[0]), UNIT_SCALES[unit])


__all__ = ["PROPORTIONS", "SineGait", "write_sine_gait_bvh"]
