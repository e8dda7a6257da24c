"""Shooting and bouncing rays: corner reflectors and a wall's image, against closed forms.

Far-field RCS is read back from the paths with the monostatic radar equation (isotropic
antennas, TX = RX): ``sigma = |sum_p a_p exp(-j 2 pi f tau_p)|^2 (4 pi)^3 R^4 / lambda^2``.
"""

from __future__ import annotations

import math

import torch
from raytrace_scenes import carrier_sum, monostatic_config, quad, rotation_taking, soup

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.antenna import IsotropicAntenna
from radaraug.raytrace.merge import merge_paths
from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import RadarPose

CFG = monostatic_config()
LAM = CFG.wavelength_m
F0 = CFG.center_frequency_Hz
R = 30.0  # beyond the far-field distance 2 D^2 / lambda (~8 m) of 10 cm targets


def _far_rcs(triangles: torch.Tensor, bounces: int, n_rays: int = 200, extent: float = 0.1) -> float:
    scene = soup(triangles)
    pose = RadarPose.look_at((0.0, 0.0, 0.0), (R, 0.0, 0.0))
    tracer = RayTracer(scene, pose, CFG, method="sbr", rays=n_rays, fov_deg=math.degrees(math.atan(extent / R)),
                       antenna=IsotropicAntenna(), max_bounces=bounces, merge_bin_m=None, dtype=torch.float64)
    a = carrier_sum(tracer.static_paths(), F0)
    return abs(a) ** 2 * (4 * math.pi) ** 3 * R**4 / LAM**2


def _db(x: float) -> float:
    return 10 * math.log10(x)


def test_flat_plate_sbr():
    """Square plate facing the radar: sigma = 4 pi A^2 / lambda^2 within 0.5 dB."""
    side = 0.1
    c = torch.tensor([R, 0.0, 0.0], dtype=torch.float64)
    ey, ez = torch.tensor([0.0, 1.0, 0.0]).double(), torch.tensor([0.0, 0.0, 1.0]).double()
    plate = quad(c - side / 2 * (ey + ez), side * ey, side * ez)
    sigma = _far_rcs(plate, bounces=1, extent=0.08)
    assert abs(_db(sigma / (4 * math.pi * side**4 / LAM**2))) < 0.5


def test_dihedral_corner():
    """90-degree PEC dihedral, faces a x b, symmetric incidence: sigma_max = 8 pi a^2 b^2 / lambda^2, within 1 dB."""
    a = b = 0.1  # a: seam length, b: face width
    c = torch.tensor([R, 0.0, 0.0], dtype=torch.float64)
    z = torch.tensor([0.0, 0.0, 1.0], dtype=torch.float64)
    u1 = torch.tensor([-1.0, 1.0, 0.0], dtype=torch.float64) / math.sqrt(2)
    u2 = torch.tensor([-1.0, -1.0, 0.0], dtype=torch.float64) / math.sqrt(2)
    tri = torch.cat([quad(c - a / 2 * z, b * u1, a * z), quad(c - a / 2 * z, b * u2, a * z)])
    sigma = _far_rcs(tri, bounces=2, n_rays=240)
    assert abs(_db(sigma / (8 * math.pi * a**2 * b**2 / LAM**2))) < 1.0
    # With a single bounce the double-bounce return is missing: far below the corner value.
    assert _db(_far_rcs(tri, bounces=1, n_rays=240) / sigma) < -10


def test_square_trihedral_corner():
    """Square trihedral of edge a, looked into along its axis: sigma_max = 12 pi a^4 / lambda^2, within 1 dB."""
    a = 0.1
    c = torch.tensor([R, 0.0, 0.0], dtype=torch.float64)
    axis = torch.ones(3, dtype=torch.float64) / math.sqrt(3)
    rot = rotation_taking(axis, torch.tensor([-1.0, 0.0, 0.0], dtype=torch.float64))
    e = [rot @ v for v in torch.eye(3, dtype=torch.float64)]
    tri = torch.cat([quad(c, a * e[0], a * e[1]), quad(c, a * e[1], a * e[2]), quad(c, a * e[2], a * e[0])])
    sigma = _far_rcs(tri, bounces=3, n_rays=200)
    assert abs(_db(sigma / (12 * math.pi * a**4 / LAM**2))) < 1.0


def test_metal_wall_image_path():
    """Radar facing a large metal wall at D: the sum of the tube paths is the image source,
    |a| = lambda / (4 pi 2 D) (isotropic, Gamma = -1), within 0.5 dB, at delay 2 D / c."""
    d_wall, half = 3.0, 4.0
    c = torch.tensor([d_wall, 0.0, 0.0], dtype=torch.float64)
    ey, ez = torch.tensor([0.0, 1.0, 0.0]).double(), torch.tensor([0.0, 0.0, 1.0]).double()
    wall = soup(quad(c - half * (ey + ez), 2 * half * ey, 2 * half * ez))
    pose = RadarPose.look_at((0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
    tracer = RayTracer(wall, pose, CFG, method="sbr", rays=256, fov_deg=40.0, antenna=IsotropicAntenna(), max_bounces=1,
                       dtype=torch.float64)
    paths = tracer.static_paths()
    a = carrier_sum(paths, F0)
    assert abs(20 * math.log10(abs(a) * 4 * math.pi * 2 * d_wall / LAM)) < 0.5
    strongest = paths.amplitude[:, 0].abs().argmax()
    assert abs(float(paths.delay_s[strongest, 0]) - 2 * d_wall / SPEED_OF_LIGHT) < 0.02 / SPEED_OF_LIGHT
    assert tracer.static_paths() is paths  # traced once, cached


def test_merge_keeps_carrier_sum_and_shrinks():
    d_wall, half = 2.0, 1.0
    c = torch.tensor([d_wall, 0.0, 0.0], dtype=torch.float64)
    ey, ez = torch.tensor([0.0, 1.0, 0.0]).double(), torch.tensor([0.0, 0.0, 1.0]).double()
    wall = soup(quad(c - half * (ey + ez), 2 * half * ey, 2 * half * ez))
    pose = RadarPose.look_at((0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
    tracer = RayTracer(wall, pose, CFG, method="sbr", rays=96, fov_deg=40.0, max_bounces=1, merge_bin_m=None, dtype=torch.float64)
    raw = tracer.static_paths()
    merged = merge_paths(raw, F0, bin_m=0.01, floor_dB=-300)
    assert merged.num_paths < raw.num_paths / 10
    assert abs(carrier_sum(merged, F0) - carrier_sum(raw, F0)) < 1e-9 * abs(carrier_sum(raw, F0))
