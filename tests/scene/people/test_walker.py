"""Boulic walker: published gait facts and kinematic closed forms."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.errors import InputTensorError, SceneError
from radaraug.scene.people import JOINT_NAMES, SEGMENT_NAMES, Walker, person_from_dict

J = {n: i for i, n in enumerate(JOINT_NAMES)}
S = {n: i for i, n in enumerate(SEGMENT_NAMES)}


def cycle_times(w: Walker, n: int = 400, cycles: int = 1) -> torch.Tensor:
    return torch.arange(n * cycles, dtype=torch.float64) * (w.cycle_duration_s / n)


def test_cycle_duration_matches_boulic_closed_form() -> None:
    w = Walker(height_m=1.8, speed_m_s=1.4)
    rv = 1.4 / (0.491 * 1.8)
    assert w.cycle_duration_s == pytest.approx(1.346 / math.sqrt(rv), rel=1e-12)
    assert w.cycle_duration_s == pytest.approx(1.07, abs=0.01)  # docs/people.md: ~1.07 s
    assert w.stance_fraction == pytest.approx((0.752 * w.cycle_duration_s - 0.143) / w.cycle_duration_s)


def test_pelvis_moves_at_walking_speed() -> None:
    w = Walker(height_m=1.75, speed_m_s=1.2, heading_rad=0.0)
    t = cycle_times(w)
    pos, vel = w.joints(t)
    assert vel[:, J["pelvis"], 0].mean().item() == pytest.approx(1.2, rel=0.02)
    # Periodic oscillations: after a whole cycle the pelvis has advanced exactly V * Dc.
    p_end, _ = w.joints(torch.tensor([w.cycle_duration_s], dtype=torch.float64))
    advance = p_end[0, J["pelvis"]] - pos[0, J["pelvis"]]
    assert advance[0].item() == pytest.approx(1.2 * w.cycle_duration_s, abs=1e-9)
    assert advance[1:].abs().max().item() < 1e-9


def test_torso_and_limb_speeds() -> None:
    v = 1.4
    w = Walker(height_m=1.8, speed_m_s=v)
    e = w.ellipsoids(cycle_times(w))
    speed = e.velocities.norm(dim=-1)  # (T, S)
    torso = speed[:, S["torso"]]
    assert torso.mean().item() == pytest.approx(v, rel=0.1)
    assert 0.7 * v < torso.min().item() and torso.max().item() < 1.3 * v
    for seg in ("left_lower_leg", "right_lower_leg"):
        assert 2.0 * v <= speed[:, S[seg]].max().item() <= 4.0 * v
    for seg in ("left_foot", "right_foot"):
        assert 2.5 * v <= speed[:, S[seg]].max().item() <= 4.5 * v


def test_feet_nearly_stationary_in_stance() -> None:
    v = 1.4
    w = Walker(height_m=1.8, speed_m_s=v)
    n = 400
    e = w.ellipsoids(cycle_times(w, n))
    horiz = e.velocities[..., :2].norm(dim=-1)
    u = torch.arange(n) / n
    mid_stance = (u > 0.1) & (u < 0.45)  # right foot flat on the ground (heel strike at u = 0)
    assert horiz[mid_stance, S["right_foot"]].max().item() < 0.4 * v  # ~0.49 m/s: the model slides
    left_mid = ((u + 0.5) % 1 > 0.1) & ((u + 0.5) % 1 < 0.45)
    assert horiz[left_mid, S["left_foot"]].max().item() < 0.4 * v
    assert horiz[~mid_stance, S["right_foot"]].max().item() > 3.0 * v  # swing


@pytest.mark.parametrize("phase", [0.0, 0.37])
def test_segments_connected_and_rigid(phase: float) -> None:
    h = 1.7
    w = Walker(height_m=h, speed_m_s=1.1, phase=phase, heading_rad=1.0)
    t = cycle_times(w, 97)
    pos, vel = w.joints(t)
    e = w.ellipsoids(t)
    axis = e.rotations[..., :, 2]
    ends_a = e.centers - axis * e.semi_axes[..., 2:]
    ends_b = e.centers + axis * e.semi_axes[..., 2:]
    from radaraug.scene.people.skeleton import _SEGMENT_TABLE

    for s, (_, parent, child, _) in enumerate(_SEGMENT_TABLE):
        assert (ends_a[:, s] - pos[:, J[parent]]).norm(dim=-1).max().item() < 1e-6
        assert (ends_b[:, s] - pos[:, J[child]]).norm(dim=-1).max().item() < 1e-6
    lengths = {"left_upper_leg": 0.245, "right_lower_leg": 0.246, "left_upper_arm": 0.188,
               "right_lower_arm": 0.152, "torso": 0.288, "head": 0.130}
    for seg, frac in lengths.items():
        assert torch.allclose(2 * e.semi_axes[:, S[seg], 2], torch.full_like(t, frac * h), atol=1e-9)
    rot = e.rotations
    eye = torch.eye(3, dtype=rot.dtype).expand_as(rot)
    assert torch.allclose(rot.mT @ rot, eye, atol=1e-9)
    assert torch.allclose(torch.linalg.det(rot), torch.ones(rot.shape[:-2], dtype=rot.dtype), atol=1e-9)


@pytest.mark.parametrize(
    ("height", "speed", "phase", "max_gap"), [(1.8, 1.4, 0.0, 0.06), (1.6, 0.5, 0.2, 0.06), (1.9, 2.2, 0.7, 0.12)]
)
def test_feet_on_ground(height: float, speed: float, phase: float, max_gap: float) -> None:
    w = Walker(height_m=height, speed_m_s=speed, phase=phase, heading_rad=2.0)
    e = w.ellipsoids(cycle_times(w, 500, cycles=2) + 0.123)
    # Lowest point of an ellipsoid (closed form): c_z - sqrt(sum_i (R[z, i] a_i)^2).
    bottom = e.centers[..., 2] - ((e.rotations[..., 2, :] * e.semi_axes) ** 2).sum(-1).sqrt()
    assert bottom.min().item() > -0.01
    assert bottom.min().item() < 0.01  # and it does touch the ground
    feet = bottom[:, [S["left_foot"], S["right_foot"]]].min(dim=1).values
    # One foot is always near the floor (the pelvis bob is prescribed, not contact-driven, so
    # the stance foot lifts a few cm; more at fast walks).
    assert feet.max().item() < max_gap


def test_heading_and_start_rotate_and_translate_everything() -> None:
    t = torch.linspace(0, 2, 50, dtype=torch.float64)
    base = Walker(speed_m_s=1.3)
    th = 2.2
    turned = Walker(speed_m_s=1.3, heading_rad=th, start=(3.0, -1.5))
    p0, v0 = base.joints(t)
    p1, v1 = turned.joints(t)
    rz = torch.tensor([[math.cos(th), -math.sin(th), 0], [math.sin(th), math.cos(th), 0], [0, 0, 1]],
                      dtype=torch.float64)
    assert torch.allclose(p1, p0 @ rz.T + torch.tensor([3.0, -1.5, 0.0], dtype=torch.float64), atol=1e-9)
    assert torch.allclose(v1, v0 @ rz.T, atol=1e-9)
    assert torch.allclose(p1[0, J["pelvis"], :2], torch.tensor([3.0, -1.5], dtype=torch.float64), atol=1e-12)
    mean_v = v1[:, J["pelvis"], :2].mean(0)
    assert math.atan2(mean_v[1].item(), mean_v[0].item()) == pytest.approx(th, abs=0.03)


def test_velocities_are_derivatives_of_positions() -> None:
    w = Walker(height_m=1.72, speed_m_s=1.5, phase=0.4, heading_rad=0.3)
    t = torch.rand(200, dtype=torch.float64, generator=torch.Generator().manual_seed(0)) * 3
    h = 1e-6
    _, vel = w.joints(t)
    fd = (w.joints(t + h)[0] - w.joints(t - h)[0]) / (2 * h)
    assert (fd - vel).abs().max().item() < 1e-4
    e = w.ellipsoids(t)
    fd_c = (w.ellipsoids(t + h).centers - w.ellipsoids(t - h).centers) / (2 * h)
    assert (fd_c - e.velocities).abs().max().item() < 1e-4


def test_phase_shifts_the_gait_cycle() -> None:
    a = Walker(phase=0.0)
    b = Walker(phase=0.25)
    t = torch.linspace(0, 1, 20, dtype=torch.float64)
    pa, _ = a.joints(t + 0.25 * a.cycle_duration_s)
    pb, _ = b.joints(t)
    rel_a = pa - pa[:, :1]
    rel_b = pb - pb[:, :1]
    assert torch.allclose(rel_a, rel_b, atol=1e-9)  # same pose relative to the pelvis


def test_device_and_dtype(device: torch.device, dtype: torch.dtype) -> None:
    w = Walker()
    t = torch.linspace(0, 0.5, 64, dtype=dtype, device=device)
    e = w.ellipsoids(t)
    for x in (e.centers, e.semi_axes, e.rotations, e.velocities):
        assert x.device.type == device.type and x.dtype == dtype
    assert e.centers.shape == (64, 16, 3) and e.rotations.shape == (64, 16, 3, 3)
    ref = w.ellipsoids(t.cpu().double())
    assert torch.allclose(e.centers.cpu().double(), ref.centers, atol=1e-4)


def test_bad_parameters_raise() -> None:
    with pytest.raises(SceneError, match="relative velocity"):
        Walker(height_m=1.8, speed_m_s=3.0)
    with pytest.raises(SceneError):
        Walker(speed_m_s=0.0)
    with pytest.raises(SceneError, match="phase"):
        Walker(phase=1.0)
    with pytest.raises(InputTensorError):
        Walker().ellipsoids(torch.zeros(2, 2))
    with pytest.raises(InputTensorError):
        Walker().ellipsoids(torch.tensor([float("nan")]))


def test_to_dict_round_trip() -> None:
    w = Walker(height_m=1.65, speed_m_s=1.1, start=(1.0, 2.0), heading_rad=0.5, phase=0.3)
    d = w.to_dict()
    w2 = person_from_dict(d)
    t = torch.linspace(0, 1, 7, dtype=torch.float64)
    assert torch.equal(w.joints(t)[0], w2.joints(t)[0])
    assert d["type"] == "walker"
