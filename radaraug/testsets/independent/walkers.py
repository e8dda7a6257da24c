"""People as a handful of moving point scatterers, written from gait physics in NumPy.

Nothing of the twin's people model: a person is :data:`NUM_POINTS` points on a sinusoidal gait
(walking a racetrack, or standing, breathing and swaying) whose RCS splits a drawn whole-body
RCS and fluctuates from frame to frame. Room frame: metres, ``x`` along the room, ``y`` across,
``z`` up. Randomness comes from generators the caller seeds. Model: docs/heldout_worlds.md ("People").
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np

POINT_NAMES: tuple[str, ...] = (
    "pelvis", "waist", "chest", "head", "shoulder_l", "shoulder_r",
    "elbow_l", "elbow_r", "hand_l", "hand_r", "knee_l", "knee_r", "foot_l", "foot_r",
)
"""The scatterers of one person, in the order of every ``(points, ...)`` array."""
NUM_POINTS = len(POINT_NAMES)

RCS_FRACTIONS: dict[str, float] = {
    "pelvis": 0.14, "waist": 0.14, "chest": 0.17, "head": 0.07, "shoulder_l": 0.05, "shoulder_r": 0.05,
    "elbow_l": 0.04, "elbow_r": 0.04, "hand_l": 0.03, "hand_r": 0.03, "knee_l": 0.07, "knee_r": 0.07,
    "foot_l": 0.04, "foot_r": 0.04,
}
"""Share of the whole-body RCS per point (normalized to 1 when used): the torso is the largest
and flattest surface; limbs are thin cylinders."""

HEIGHT_M = (1.5, 1.95)
SPEED_M_S = (0.4, 1.6)
RCS_DBSM = (-5.0, 3.0)
FLUCTUATION_DB = (2.5, 4.5)
FLUCTUATION_CORRELATION = 0.5
"""Frame-to-frame correlation of each point's RCS fluctuation (in dB)."""
TURN_RADIUS_M = 0.35
SWING_FRACTION = (0.50, 0.60)
FOOT_CLEARANCE_M = (0.04, 0.09)
BOB_M = (0.015, 0.03)
SWAY_M = (0.01, 0.03)
ARM_SWING_SCALE = (0.7, 1.3)
STANCE_FOOT_HEIGHT_M = 0.04
"""Height of a foot scatterer standing on the floor (the shoe's upper, not the sole)."""
DERIVATIVE_STEP_S = 2e-4
"""Half-step of the central difference that gives each point's range rate."""


@dataclass(frozen=True)
class Person:
    """One person's drawn parameters (everything :func:`positions` and :func:`rcs_per_frame` need).

    Attributes:
        standing: True for a standing (breathing, swaying) person, False for a walker.
        height_m: body height.
        speed_m_s: walking speed along the path (0 when standing).
        lane_y_m: walker: centre line of the racetrack; standing: the person's ``y``.
        x_near_m, x_far_m: walker: the racetrack's straight part (the turns reach
            ``TURN_RADIUS_M`` beyond); standing: ``x_near_m`` is the person's ``x``.
        start_m: walker: arc length along the racetrack at the person's time 0.
        facing_rad: standing: facing direction (0 = +x, away from the radar).
        step_hz: walker: step frequency; standing: breathing frequency.
        gait_phase: walker: gait phase (strides) at time 0; standing: breathing phase (cycles).
        swing_fraction: walker: fraction of a stride a foot swings.
        clearance_m: walker: foot lift mid-swing.
        bob_m: walker: vertical torso bob; standing: chest breathing displacement.
        sway_m: lateral torso sway (walker) or whole-body sway (standing).
        sway_hz: standing: sway frequency (walker: 0, the sway follows the stride).
        sway_phase: standing: sway phase (cycles).
        arm_swing_rad: walker: arm swing amplitude.
        rcs_dBsm: mean whole-body RCS.
        fluctuation_dB: standard deviation of each point's per-frame RCS fluctuation.
        point_phase_rad: constant scattering phase of each point (``NUM_POINTS`` values).
        track_yaw_rad: walker: rotation of the racetrack about the room's origin (0: the
            straight lanes run along ``x``, toward and away from a radar looking along ``+x``;
            ``pi / 2``: they run along ``y``, across its beam). The racetrack's ``x``, lane and
            start are then given in the rotated frame.
    """

    standing: bool
    height_m: float
    speed_m_s: float
    lane_y_m: float
    x_near_m: float
    x_far_m: float
    start_m: float
    facing_rad: float
    step_hz: float
    gait_phase: float
    swing_fraction: float
    clearance_m: float
    bob_m: float
    sway_m: float
    sway_hz: float
    sway_phase: float
    arm_swing_rad: float
    rcs_dBsm: float
    fluctuation_dB: float
    point_phase_rad: tuple[float, ...]
    track_yaw_rad: float = 0.0

    def to_dict(self, digits: int = 5) -> dict[str, object]:
        """JSON-friendly parameters, floats rounded to ``digits`` significant digits."""
        def r(v: float) -> float:
            return float(f"{v:.{digits}g}")

        out: dict[str, object] = {k: r(v) if isinstance(v, float) else v for k, v in asdict(self).items()}
        out["point_phase_rad"] = [r(float(x)) for x in self.point_phase_rad]  # the one tuple field
        return out

    @property
    def perimeter_m(self) -> float:
        """Length of the walker's racetrack."""
        return 2.0 * (self.x_far_m - self.x_near_m) + 2.0 * math.pi * TURN_RADIUS_M


def draw_person(
    rng: np.random.Generator,
    *,
    x_range_m: tuple[float, float],
    lane_range_m: tuple[float, float],
    standing: bool = False,
    rcs_dBsm: tuple[float, float] = RCS_DBSM,
    speed_m_s: tuple[float, float] = SPEED_M_S,
    track_yaw_rad: float = 0.0,
    min_straight_m: float = 3.0,
) -> Person:
    """Draw one person.

    Args:
        rng: the random generator (seeded by the caller).
        x_range_m: ``(near, far)`` limits of the walkable floor along ``x``; the racetrack's
            turns (or a standing person) stay inside it. For a rotated racetrack
            (``track_yaw_rad``) both ranges are in the rotated frame.
        lane_range_m: ``(low, high)`` limits of the racetrack's centre line (or a standing
            person's ``y``); the lanes lie ``TURN_RADIUS_M`` on either side.
        standing: draw a standing person instead of a walker.
        rcs_dBsm: range of the mean whole-body RCS (uniform, dBsm).
        speed_m_s: range of the walking speed (uniform).
        track_yaw_rad: the walker's racetrack rotation (:class:`Person`).
        min_straight_m: shortest straight part of the racetrack (the walkable floor permitting).

    Returns:
        The :class:`Person`.
    """
    u = rng.uniform
    near, far = x_range_m
    height = u(*HEIGHT_M)
    rcs = u(*rcs_dBsm)
    fluct = u(*FLUCTUATION_DB)
    phases = tuple(float(v) for v in u(0.0, 2.0 * math.pi, NUM_POINTS))
    lane = u(*lane_range_m)
    if standing:
        return Person(
            standing=True, height_m=height, speed_m_s=0.0, lane_y_m=lane, x_near_m=u(near + 0.5, far - 0.5),
            x_far_m=0.0, start_m=0.0, facing_rad=u(-math.pi, math.pi), step_hz=u(0.2, 0.35),
            gait_phase=u(0.0, 1.0), swing_fraction=0.0, clearance_m=0.0, bob_m=u(0.002, 0.006),
            sway_m=u(0.005, 0.02), sway_hz=u(0.15, 0.5), sway_phase=u(0.0, 1.0), arm_swing_rad=0.0,
            rcs_dBsm=rcs, fluctuation_dB=fluct, point_phase_rad=phases,
        )
    speed = u(*speed_m_s)
    # The straight part: turns near both ends of the walkable floor ("turning at the room's ends"),
    # at least min_straight_m long so most of a file is straight walking (toward or away from the
    # radar unless the racetrack is rotated).
    x_near = u(near + TURN_RADIUS_M, near + TURN_RADIUS_M + 0.7)
    x_far = u(min(max(far - TURN_RADIUS_M - 1.0, x_near + min_straight_m), far - TURN_RADIUS_M), far - TURN_RADIUS_M)
    step_hz = 1.8 * math.sqrt(speed / 1.3) * math.sqrt(1.75 / height) * u(0.95, 1.05)
    person = Person(
        standing=False, height_m=height, speed_m_s=speed, lane_y_m=lane, x_near_m=x_near, x_far_m=x_far,
        start_m=0.0, facing_rad=0.0, step_hz=step_hz, gait_phase=u(0.0, 1.0),
        swing_fraction=u(*SWING_FRACTION), clearance_m=u(*FOOT_CLEARANCE_M), bob_m=u(*BOB_M), sway_m=u(*SWAY_M),
        sway_hz=0.0, sway_phase=0.0, arm_swing_rad=u(*ARM_SWING_SCALE) * (0.15 + 0.25 * speed),
        rcs_dBsm=rcs, fluctuation_dB=fluct, point_phase_rad=phases, track_yaw_rad=float(track_yaw_rad),
    )
    return replace(person, start_m=u(0.0, person.perimeter_m))


def track_xy(p: Person, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position ``(..., 2)`` and unit heading ``(..., 2)`` at arc lengths ``s`` on ``p``'s racetrack.

    Arc length 0 is the near end of the right-hand lane (smaller ``y``), walking away (+x).
    """
    w = TURN_RADIUS_M
    length = p.x_far_m - p.x_near_m
    s = np.mod(s, p.perimeter_m)
    a1, a2, a3 = length, length + math.pi * w, 2.0 * length + math.pi * w
    seg = np.select([s < a1, s < a2, s < a3], [0, 1, 2], 3)
    alpha_far = (s - a1) / w
    alpha_near = (s - a3) / w
    x = np.choose(seg, [p.x_near_m + s, p.x_far_m + w * np.sin(alpha_far), p.x_far_m - (s - a2),
                        p.x_near_m - w * np.sin(alpha_near)])
    y = np.choose(seg, [np.full_like(s, p.lane_y_m - w), p.lane_y_m - w * np.cos(alpha_far),
                        np.full_like(s, p.lane_y_m + w), p.lane_y_m + w * np.cos(alpha_near)])
    hx = np.choose(seg, [np.ones_like(s), np.cos(alpha_far), -np.ones_like(s), -np.cos(alpha_near)])
    hy = np.choose(seg, [np.zeros_like(s), np.sin(alpha_far), np.zeros_like(s), -np.sin(alpha_near)])
    return np.stack([x, y], axis=-1), np.stack([hx, hy], axis=-1)


def _foot_arc(p: Person, t: np.ndarray, offset: float) -> tuple[np.ndarray, np.ndarray]:
    """Arc length of a foot and its swing progress (0 in stance) at times ``t``.

    ``offset`` (strides) shifts the foot's cycle (0.5 for the second foot). Over a stride of
    period ``T`` the foot stands still for ``(1 - w) T`` and then moves one stride ``v T`` with a
    ``(1 - cos(pi u)) / 2`` profile (``u`` 0..1 the swing progress), so on average it keeps up
    with the body; at mid-stance it is under the hip.
    """
    period = 2.0 / p.step_hz  # a stride = two steps
    stride = p.speed_m_s * period
    w = p.swing_fraction
    cyc = t / period + p.gait_phase + offset
    k = np.floor(cyc)
    ph = cyc - k
    u = np.clip((ph - (1.0 - w)) / w, 0.0, 1.0)
    c = 0.5 * (1.0 - np.cos(math.pi * u))
    # Body arc at mid-stance of cycle k: start + v (k + (1 - w) / 2 - phase - offset) T.
    base = p.start_m + stride * (k + (1.0 - w) / 2.0 - p.gait_phase - offset)
    return base + stride * c, u


def positions(p: Person, t: np.ndarray) -> np.ndarray:
    """Positions ``(NUM_POINTS, *t.shape, 3)`` (room frame, m) of ``p``'s scatterers at times ``t`` (s)."""
    t = np.asarray(t, dtype=np.float64)
    if p.standing:
        return _standing_positions(p, t)
    out = _walker_positions(p, t)
    if p.track_yaw_rad:  # the racetrack's frame -> the room's (a rotation about the origin)
        c, s = math.cos(p.track_yaw_rad), math.sin(p.track_yaw_rad)
        x, y = out[..., 0].copy(), out[..., 1].copy()
        out[..., 0], out[..., 1] = c * x - s * y, s * x + c * y
    return out


def _walker_positions(p: Person, t: np.ndarray) -> np.ndarray:
    H = p.height_m
    s_body = p.start_m + p.speed_m_s * t
    xy, head = track_xy(p, s_body)
    left = np.stack([-head[..., 1], head[..., 0]], axis=-1)
    ph = p.gait_phase + t * p.step_hz / 2.0  # strides
    bob = p.bob_m * np.cos(4.0 * math.pi * ph)
    sway = p.sway_m * np.sin(2.0 * math.pi * ph)
    out = np.empty((NUM_POINTS, *t.shape, 3))

    def put(i: int, fwd: float | np.ndarray, lat: float | np.ndarray, z: float | np.ndarray,
            base: np.ndarray = xy, h: np.ndarray = head, n: np.ndarray = left) -> None:
        fwd_a = np.asarray(fwd)[..., None]
        lat_a = np.asarray(lat)[..., None]
        out[i, ..., :2] = base + fwd_a * h + lat_a * n
        out[i, ..., 2] = z

    put(0, 0.0, sway, 0.52 * H + bob)             # pelvis
    put(1, 0.02 * H, sway, 0.62 * H + bob)        # waist / abdomen (front)
    put(2, 0.03 * H, sway, 0.73 * H + bob)        # chest (front)
    put(3, 0.01 * H, 1.2 * sway, 0.93 * H + bob)  # head
    shoulder_z = 0.82 * H + bob
    for side, i_sh, i_el, i_ha, leg_offset in ((+1, 4, 6, 8, 0.5), (-1, 5, 7, 9, 0.0)):
        # Each arm swings with the opposite leg: forward while that leg is forward.
        theta = p.arm_swing_rad * np.sin(2.0 * math.pi * (ph + leg_offset))
        lat = side * 0.115 * H + sway
        put(i_sh, 0.0, lat, shoulder_z)
        put(i_el, 0.19 * H * np.sin(theta), lat, shoulder_z - 0.19 * H * np.cos(theta))
        put(i_ha, 0.40 * H * np.sin(1.15 * theta), lat, shoulder_z - 0.40 * H * np.cos(1.15 * theta))
    hip_z = 0.52 * H + bob
    for side, i_kn, i_ft, offset in ((+1, 10, 12, 0.0), (-1, 11, 13, 0.5)):
        s_foot, swing = _foot_arc(p, t, offset)
        fxy, fh = track_xy(p, s_foot)
        fn = np.stack([-fh[..., 1], fh[..., 0]], axis=-1)
        lift = p.clearance_m * np.sin(math.pi * swing)
        put(i_ft, 0.0, side * 0.055 * H, STANCE_FOOT_HEIGHT_M + lift, base=fxy, h=fh, n=fn)
        hip = xy + (side * 0.055 * H + sway)[..., None] * left
        knee_xy = 0.5 * (hip + out[i_ft, ..., :2]) + (0.05 * H * np.sin(math.pi * swing))[..., None] * head
        out[i_kn, ..., :2] = knee_xy
        out[i_kn, ..., 2] = 0.5 * (hip_z + out[i_ft, ..., 2]) + 0.5 * lift
    return out


def _standing_positions(p: Person, t: np.ndarray) -> np.ndarray:
    H = p.height_m
    head = np.array([math.cos(p.facing_rad), math.sin(p.facing_rad)])
    left = np.array([-head[1], head[0]])
    sway = p.sway_m * np.sin(2.0 * math.pi * (p.sway_hz * t + p.sway_phase))  # sideways, grows with height
    breath = p.bob_m * np.sin(2.0 * math.pi * (p.step_hz * t + p.gait_phase))  # chest wall, forward
    base = np.array([p.x_near_m, p.lane_y_m])
    # (forward m, lateral m, height fraction, sway weight, breathing weight) per point
    layout = (
        (0.0, 0.0, 0.52, 0.5, 0.3), (0.02, 0.0, 0.62, 0.7, 0.8), (0.03, 0.0, 0.73, 0.8, 1.0),
        (0.01, 0.0, 0.93, 2.0, 0.0), (0.0, 0.115, 0.82, 0.9, 0.2), (0.0, -0.115, 0.82, 0.9, 0.2),
        (0.02, 0.13, 0.63, 0.8, 0.0), (0.02, -0.13, 0.63, 0.8, 0.0), (0.04, 0.12, 0.42, 0.6, 0.0),
        (0.04, -0.12, 0.42, 0.6, 0.0), (0.02, 0.055, 0.28, 0.2, 0.0), (0.02, -0.055, 0.28, 0.2, 0.0),
        (0.05, 0.055, 0.0, 0.0, 0.0), (0.05, -0.055, 0.0, 0.0, 0.0),
    )
    out = np.empty((NUM_POINTS, *t.shape, 3))
    for i, (fwd, lat, zf, w_sway, w_breath) in enumerate(layout):
        f = fwd * H + w_breath * breath
        side = lat * H + w_sway * sway
        out[i, ..., :2] = base + np.multiply.outer(f, head) + np.multiply.outer(side, left)
        out[i, ..., 2] = zf * H if zf > 0 else STANCE_FOOT_HEIGHT_M
    return out


def rcs_per_frame(p: Person, rng: np.random.Generator, frames: int) -> np.ndarray:
    """Linear RCS ``(NUM_POINTS, frames)`` in m^2: the mean split plus the per-frame fluctuation."""
    frac = np.array([RCS_FRACTIONS[n] for n in POINT_NAMES])
    mean = 10.0 ** (p.rcs_dBsm / 10.0) * frac / frac.sum()
    rho = FLUCTUATION_CORRELATION
    xi = np.empty((NUM_POINTS, frames))
    z = rng.standard_normal((NUM_POINTS, frames))
    xi[:, 0] = z[:, 0]
    for f in range(1, frames):  # AR(1) with unit variance
        xi[:, f] = rho * xi[:, f - 1] + math.sqrt(1.0 - rho * rho) * z[:, f]
    sd = p.fluctuation_dB
    # A log-normal factor of mean 1: E[10^(X/10)] = 1 for X ~ N(-sd^2 ln10 / 20, sd^2).
    xi_dB = sd * xi - sd * sd * math.log(10.0) / 20.0
    return mean[:, None] * 10.0 ** (xi_dB / 10.0)


__all__ = [
    "NUM_POINTS", "POINT_NAMES", "RCS_FRACTIONS", "Person", "draw_person", "positions", "rcs_per_frame", "track_xy",
]
