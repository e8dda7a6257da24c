"""Procedural walker: the Boulic-Magnenat-Thalmann-Thalmann (1990) global walking model.

Trajectories are functions of the relative velocity ``rv = V / leg length`` and the cycle time ``u``
(0 = right heel strike), with analytic velocities. References and deviations: ``docs/people.md``.
"""

from __future__ import annotations

import math
from typing import Any

import torch

from radaraug.errors import SceneError
from radaraug.scene.people import _rotations as rot
from radaraug.scene.people._pchip import PeriodicPchip
from radaraug.scene.people.person import SkeletonPerson, as_times, register_person
from radaraug.scene.people.skeleton import ANKLE_HEIGHT_FRACTION, JOINT_NAMES, SEGMENT_LENGTH_FRACTIONS

_DEG = math.pi / 180.0
_TWO_PI = 2.0 * math.pi


def gait_curves(rv: float, rds: float) -> dict[str, tuple[list[float], list[float]]]:
    """PCHIP control points ``(u, degrees)`` of Boulic's joint-angle trajectories.

    Args:
        rv: relative velocity ``V / Ht`` (1/s).
        rds: relative duration of support (stance fraction of the cycle).

    Returns:
        ``{"hip", "knee", "ankle", "elbow", "thorax"}`` -> ``(u, angle_deg)`` of the right side.
    """
    c = (rv - 1.3) / 1.7  # position inside the fast gait range [1.3, 3]
    b = (rv - 0.5) / 0.8  # position inside the medium range [0.5, 1.3]
    if rv < 0.5:
        hip = ([-0.1, 0.5], [50 * rv, -30 * rv])  # third point (0.9, 50 rv) is the next period's first
        knee = ([0.17, 0.4, 0.75, 1.0], [3, 3, 140 * rv, 3])
        ankle = ([0, 0.08, 0.5, rds, 0.85], [-3, -30 * rv - 3, 22 * rv - 3, -34 * rv - 3, -3])
        elbow = ([0.05, 0.5, 0.9], [6 * rv + 3, 34 * rv + 3, 10 * rv + 3])
    elif rv < 1.3:
        hip = ([-0.1, 0.5], [25, -15])
        knee = ([0.17, 0.4, 0.75, 1.0], [3, 3, 70, 3])
        ankle = ([0, 0.08, 0.5, rds, 0.85], [-3, -18, 8, -20, -3])
        elbow = ([0.05, 0.01 * b + 0.5, 0.9], [8 * b + 6, 24 * b + 20, 9 * b + 8])
    else:
        hip = ([0.2 * c - 0.1, 0.5, 0.9], [5 * c + 25, -15, 6 * c + 25])
        knee = ([-0.05 * c + 0.17, 0.4, -0.05 * c + 0.75, -0.03 * c + 1.0], [22 * c + 3, 3, -5 * c + 70, 3 * c + 3])
        ankle = ([0, 0.08, -0.1 * c + 0.5, rds, 0.85], [5 * c - 3, 4 * c - 18, -3 * c + 8, -8 * c - 20, 5 * c - 3])
        elbow = ([0.05, 0.04 * c + 0.51, -0.1 * c + 0.9], [-6 * c + 14, 26 * c + 44, -6 * c + 17])
    thorax = ([0.1, 0.4, 0.6, 0.9], [4 / 3 * rv, -4.5 / 3 * rv, -4 / 3 * rv, 4.5 / 3 * rv])
    return {"hip": hip, "knee": knee, "ankle": ankle, "elbow": elbow, "thorax": thorax}


_CURVES = ("hip", "knee", "ankle", "elbow", "thorax")


@register_person
class Walker(SkeletonPerson):
    """A person walking in a straight line with Boulic's gait.

    Args:
        height_m: standing height H, metres.
        speed_m_s: walking speed V, m/s; ``0 < V / (0.491 H) <= 3`` (the model's range; 3 is a
            run at ~2.6 m/s for H = 1.8 m).
        start: ``(x, y)`` of the pelvis at ``t = 0``, metres.
        heading_rad: walking direction in the x-y plane (0 = +x, pi/2 = +y).
        phase: gait-cycle phase at ``t = 0`` in [0, 1) (0 = right heel strike).
    """

    type_name = "walker"
    _FIELDS = ("height_m", "speed_m_s", "start", "heading_rad", "phase")

    def __init__(
        self,
        height_m: float = 1.8,
        speed_m_s: float = 1.4,
        start: tuple[float, float] = (0.0, 0.0),
        heading_rad: float = 0.0,
        phase: float = 0.0,
    ) -> None:
        super().__init__(height_m)
        h, v = float(height_m), float(speed_m_s)
        if len(tuple(start)) != 2:
            raise SceneError(f"Walker: start must be (x, y), got {start!r}")
        if not (0.0 <= float(phase) < 1.0):
            raise SceneError(f"Walker: phase={phase} must be in [0, 1)")
        self.height_m, self.speed_m_s = h, v
        self.start = (float(start[0]), float(start[1]))
        self.heading_rad, self.phase = float(heading_rad), float(phase)
        f = SEGMENT_LENGTH_FRACTIONS
        self.leg_length_m = (f["upper_leg"] + f["lower_leg"]) * h
        self.relative_speed = v / self.leg_length_m
        rv = self.relative_speed
        if not (0.0 < rv <= 3.0):
            raise SceneError(
                f"Walker: speed {v} m/s for height {h} m gives relative velocity {rv:.2f}/s; "
                "Boulic's model covers 0 < V/leg_length <= 3"
            )
        self.relative_cycle_length = 1.346 * math.sqrt(rv)
        self.cycle_duration_s = self.relative_cycle_length / rv
        self.support_duration_s = 0.752 * self.cycle_duration_s - 0.143
        self.stance_fraction = self.support_duration_s / self.cycle_duration_s
        self.segment_lengths_m = {k: f[k] * h for k in f}
        self._ankle_height = ANKLE_HEIGHT_FRACTION * h
        curves = gait_curves(rv, self.stance_fraction)
        self._pchip = PeriodicPchip([curves[k] for k in _CURVES])
        # Amplitudes. Translations are in units of Ht like the rest of Boulic's normalized
        # model. Below rv = 0.5 the published lateral / forward amplitudes change sign; the sign
        # of the rv >= 0.5 branch is kept so both are continuous at rv = 0.5.
        slow = rv < 0.5
        self._a_vert = 0.015 * rv * self.leg_length_m
        self._a_lat = -(0.128 * rv - 0.128 * rv**2 if slow else 0.032) * self.leg_length_m
        self._a_fb = -(0.084 * rv - 0.084 * rv**2 if slow else 0.021) * self.leg_length_m
        self._phi_fb = 0.625 - self.stance_fraction
        self._a_pelvis_flex = -8 * rv**2 + 8 * rv if slow else 2.0
        self._a_pelvis_list = 1.66 * rv
        self._a_torsion = 4.0 * rv
        self._a_shoulder = 9.88 * rv
        self._z0 = 0.0
        self._z0 = self._ground_offset()

    # ------------------------------------------------------------------ kinematics
    def _translations(self, u: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Pelvis oscillation (fb, lateral, vertical) in metres and its d/du, ``(T, 3)``."""
        args = torch.stack([2 * u + 2 * self._phi_fb, u - 0.1, 2 * u - 0.35], dim=-1) * _TWO_PI
        amp = u.new_tensor([self._a_fb, self._a_lat, self._a_vert])
        freq = u.new_tensor([2.0, 1.0, 2.0]) * _TWO_PI
        offset = u.new_tensor([0.0, 0.0, -self._a_vert])
        return amp * torch.sin(args) + offset, (amp * freq) * torch.cos(args)

    def _pelvis_list_arcs(self, u: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
        """Left/right rotation of the pelvis (degrees): four cosine arcs, C1 continuous.

        On each arc ``[u0, u1)`` the angle is ``offset + coef * cos(w (u - u0))``; returns
        ``(offset, coef, w, w (u - u0))`` so that the caller batches the trigonometry.
        """
        a = self._a_pelvis_list
        w1, w2 = _TWO_PI * 10 / 3, _TWO_PI * 10 / 7
        # Arcs (offset, coef, w, u0): [0, .15): (-a, a, w1, 0); [.15, .5): (-a, -a, w2, .15);
        # [.5, .65): (a, -a, w1, .5); [.65, 1): (a, a, w2, .65). Chosen elementwise (no gather:
        # tiny index kernels are slow on a busy multi-core CPU).
        in2, in3, in4 = u >= 0.15, u >= 0.5, u >= 0.65
        one = torch.ones_like(u)
        off = torch.where(in3, a * one, -a * one)
        coef = torch.where(in2 & ~in4, -a * one, a * one)
        w = torch.where((in2 & ~in3) | in4, w2 * one, w1 * one)
        u0 = 0.15 * in2.to(u.dtype) + 0.35 * in3.to(u.dtype) + 0.15 * in4.to(u.dtype)
        return off, coef, w, w * (u - u0)

    def pose(self, t: torch.Tensor) -> dict[str, Any]:
        """Joint positions/velocities and segment rotations (world), for ``t`` ``(T,)``.

        Limb tensors carry a leading side axis (0 = left, 1 = right) so that every
        intermediate stays contiguous (small strided tensors are slow on multi-threaded CPU).
        """
        t = as_times(t)
        dev, dt = t.device, t.dtype
        rate = 1.0 / self.cycle_duration_s  # du/dt
        u = torch.remainder(t * rate + self.phase, 1.0)
        u_sides = torch.stack([torch.remainder(u + 0.5, 1.0), u])  # (2, T); right heel strike at u = 0
        nt = u.shape[0]
        vals, ders = self._pchip(u_sides.reshape(1, 2 * nt).expand(len(_CURVES), -1))
        vals, ders = vals.view(len(_CURVES), 2, nt) * _DEG, ders.view(len(_CURVES), 2, nt) * (_DEG * rate)
        ang = {k: (vals[i], ders[i]) for i, k in enumerate(_CURVES)}  # (2, T) rad, rad/s
        thorax = (vals[4, 1], ders[4, 1])

        # All trigonometry in two batched calls: first the gait-phase sinusoids, then the
        # joint rotations (few large kernels instead of dozens of tiny ones).
        pl_off, pl_coef, pl_w, pl_arg = self._pelvis_list_arcs(u)
        phase_args = torch.cat([
            torch.stack([_TWO_PI * u, _TWO_PI * (2 * u - 0.1), pl_arg]), _TWO_PI * u_sides,
        ])  # (5, T): torsion, pelvis flexion, pelvis list, shoulder left/right
        pc, ps = torch.cos(phase_args), torch.sin(phase_args)
        a_t, a_pf, a_sh = self._a_torsion * _DEG, self._a_pelvis_flex * _DEG, self._a_shoulder * _DEG
        tors = (-a_t * pc[0], (a_t * _TWO_PI * rate) * ps[0])
        pflex = (-a_pf + a_pf * ps[1], (a_pf * 2 * _TWO_PI * rate) * pc[1])
        plist = ((pl_off + pl_coef * pc[2]) * _DEG, (-pl_coef * pl_w * ps[2]) * (_DEG * rate))
        shoulder = (3 * _DEG - a_sh / 2 - a_sh * pc[3:5], (a_sh * _TWO_PI * rate) * ps[3:5])

        # Rotation angles (signs: Boulic's flexion angles are negative rotations about +y).
        single = torch.stack([-tors[0], plist[0], -thorax[0], -pflex[0]])  # (4, T)
        sided = torch.stack([-ang["hip"][0], ang["knee"][0], -ang["ankle"][0], -shoulder[0], -ang["elbow"][0]])
        rc = torch.cos(torch.cat([single, sided.reshape(10, nt)]))
        rs = torch.sin(torch.cat([single, sided.reshape(10, nt)]))
        rc_s, rs_s = rc[4:].view(5, 2, nt), rs[4:].view(5, 2, nt)

        def rot_single(i: int, axis: str, rate_: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
            return rot.rotation_from_cos_sin(axis, rc[i], rs[i], rate_)

        def rot_sided(i: int, rate_: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
            return rot.rotation_from_cos_sin("y", rc_s[i], rs_s[i], rate_)

        # Pelvis origin: oscillations relative to their value at t = 0 (so the pelvis is at
        # `start` at t = 0) plus the steady forward progression.
        osc, osc_d = self._translations(torch.cat([u, u.new_full((1,), self.phase)]))
        osc, osc_d, osc0 = osc[:-1], osc_d[:-1], osc[-1:]
        cst = self._constants(dev, dt)
        origin = osc - osc0 * cst["xy_mask"] + t[:, None] * cst["forward_v"] + cst["z0"]
        origin_d = osc_d * rate + cst["forward_v"]

        def add(base: tuple[torch.Tensor, torch.Tensor], frame: tuple[torch.Tensor, torch.Tensor],
                v: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
            p, pd = rot.apply(frame, v)
            return base[0] + p, base[1] + pd

        # Pelvic list tilts the hip line; the legs hang from the hips in the torsion frame only
        # (Chen / MATLAB rotate the whole legs with the list too, which swings each stance foot
        # sideways by ~5 cm at up to ~1 m/s).
        torsion = rot_single(0, "z", -tors[1])
        lower = rot.compose(torsion, rot_single(1, "x", plist[1]))
        upper = rot.compose(rot_single(2, "z", -thorax[1]), rot_single(3, "y", -pflex[1]))
        o = (origin, origin_d)

        hip = add(o, lower, cst["hip_offsets"])  # (2, T, 3) via broadcasting of (2, 1, 3)
        thigh = rot.compose(torsion, rot_sided(0, -ang["hip"][1]))
        knee = add(hip, thigh, cst["upper_leg"])
        shank = rot.compose(thigh, rot_sided(1, ang["knee"][1]))
        ankle = add(knee, shank, cst["lower_leg"])
        foot = rot.compose(shank, rot_sided(2, -ang["ankle"][1]))
        toe = add(ankle, foot, cst["foot"])

        neck = add(o, upper, cst["torso"])
        head = add(o, upper, cst["torso_head"])
        shoulder_j = add(o, upper, cst["shoulder_offsets"])
        uarm = rot.compose(upper, rot_sided(3, -shoulder[1]))
        elbow = add(shoulder_j, uarm, cst["upper_arm"])
        farm = rot.compose(uarm, rot_sided(4, -ang["elbow"][1]))
        wrist = add(elbow, farm, cst["lower_arm"])

        sided_joints = {"shoulder": shoulder_j, "elbow": elbow, "wrist": wrist,
                        "hip": hip, "knee": knee, "ankle": ankle, "toe": toe}
        single_joints = {"pelvis": o, "neck": neck, "head_top": head}
        pos, vel = [], []
        for name in JOINT_NAMES:
            if name in single_joints:
                p, pd = single_joints[name]
            else:
                k = 0 if name.startswith("left_") else 1
                key = name.split("_", 1)[1]
                p, pd = sided_joints[key][0][k], sided_joints[key][1][k]
            pos.append(p)
            vel.append(pd)
        head_r = cst["heading"]
        pos_w = torch.stack(pos, dim=1) @ head_r.mT + cst["start"]
        vel_w = torch.stack(vel, dim=1) @ head_r.mT
        return {
            "positions": pos_w,
            "velocities": vel_w,
            "heading": head_r,
            "rotations": {
                "pelvis": head_r @ lower[0], "upper": head_r @ upper[0], "thigh": head_r @ thigh[0],
                "shank": head_r @ shank[0], "foot": head_r @ foot[0], "upper_arm": head_r @ uarm[0],
                "forearm": head_r @ farm[0],
            },
        }

    def _constants(self, device: torch.device, dtype: torch.dtype) -> dict[str, torch.Tensor]:
        """Per-device tensors of the body dimensions (cached)."""
        key = (device, dtype, self._z0)
        cache = self.__dict__.setdefault("_const_cache", {})
        if key not in cache:
            L = self.segment_lengths_m  # noqa: N806

            def vec(*x: float) -> torch.Tensor:
                return torch.tensor(x, dtype=dtype, device=device)

            sides = lambda x, y, z: torch.tensor([[[x, y, z]], [[x, -y, z]]], dtype=dtype, device=device)  # noqa: E731
            cache[key] = {
                "xy_mask": vec(1.0, 1.0, 0.0),
                "forward_v": vec(self.speed_m_s, 0.0, 0.0),
                "z0": vec(0.0, 0.0, self._z0),
                "hip_offsets": sides(0.0, L["hip_width"] / 2, 0.0),
                "upper_leg": vec(0.0, 0.0, -L["upper_leg"]),
                "lower_leg": vec(0.0, 0.0, -L["lower_leg"]),
                "foot": vec(L["foot"], 0.0, -self._ankle_height),
                "torso": vec(0.0, 0.0, L["torso"]),
                "torso_head": vec(0.0, 0.0, L["torso"] + L["head"]),
                "shoulder_offsets": sides(0.0, L["shoulder_width"] / 2, L["torso"]),
                "upper_arm": vec(0.0, 0.0, -L["upper_arm"]),
                "lower_arm": vec(0.0, 0.0, -L["lower_arm"]),
                "heading": rot.axis_rotation("z", torch.tensor(self.heading_rad, dtype=dtype, device=device)),
                "start": vec(self.start[0], self.start[1], 0.0),
            }
        return cache[key]

    def joints(self, t: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Joint positions ``(T, 17, 3)`` m and analytic velocities ``(T, 17, 3)`` m/s."""
        p = self.pose(t)
        return p["positions"], p["velocities"]

    def _ground_offset(self) -> float:
        """Pelvis height offset that puts the lowest point of the body over a cycle on z = 0."""
        n = 720
        t = torch.arange(n, dtype=torch.float64) * (self.cycle_duration_s / n)
        e = self.ellipsoids(t)
        # Lowest point of an ellipsoid: centre_z - sqrt(sum_i (R[z, i] a_i)^2).
        bottom = e.centers[..., 2] - ((e.rotations[..., 2, :] * e.semi_axes) ** 2).sum(-1).sqrt()
        return float(-bottom.min())
