"""Physical-optics facet integrals and RCS against closed forms."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.po import parallelogram_integral, plane_wave_rcs, triangle_integral

LAM = SPEED_OF_LIGHT / 60e9
K = 2 * math.pi / LAM


def _plate(side: float, dtype=torch.float64) -> torch.Tensor:
    h = side / 2
    v = torch.tensor([[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]], dtype=dtype)
    return torch.stack([v[[0, 1, 2]], v[[0, 2, 3]]])


def test_plate_normal_incidence(dtype):
    """Square PEC plate, normal incidence: sigma = 4 pi A^2 / lambda^2 (10 cm at 60 GHz: 17.02 dBsm)."""
    side = 0.1
    k_inc = torch.tensor([0.0, 0.0, -1.0], dtype=dtype)
    sigma = plane_wave_rcs(_plate(side, dtype), k_inc, -k_inc, LAM, two_sided=True)
    expected = 4 * math.pi * side**4 / LAM**2
    assert abs(10 * math.log10(float(sigma) / expected)) < 0.01


@pytest.mark.parametrize("theta_deg", [0.3, 1.0, 2.0, 3.5, 7.0])
def test_plate_sinc_pattern(theta_deg):
    """Plate rotated about an edge-parallel axis: sigma = 4 pi A^2/lambda^2 cos^2 th sinc^2(k L sin th)."""
    side = 0.1
    th = math.radians(theta_deg)
    k_inc = torch.tensor([math.sin(th), 0.0, -math.cos(th)], dtype=torch.float64)
    sigma = float(plane_wave_rcs(_plate(side), k_inc, -k_inc, LAM, two_sided=True))
    x = K * side * math.sin(th)
    expected = 4 * math.pi * side**4 / LAM**2 * math.cos(th) ** 2 * (math.sin(x) / x) ** 2
    assert abs(10 * math.log10(sigma / expected)) < 0.05


def test_unlit_side_and_one_sided_plate():
    """A one-sided plate seen from behind scatters nothing; two-sided it scatters as from the front."""
    k_back = torch.tensor([0.0, 0.0, 1.0], dtype=torch.float64)  # travelling +z: hits the back
    assert float(plane_wave_rcs(_plate(0.1), k_back, -k_back, LAM)) == 0.0
    assert float(plane_wave_rcs(_plate(0.1), k_back, -k_back, LAM, two_sided=True)) > 1.0


def test_sphere_rcs_pi_a2():
    """Tessellated PEC sphere, a = 5 cm = 10 lambda (icosphere, 5120 facets): sigma = pi a^2 within 1 dB."""
    trimesh = pytest.importorskip("trimesh")
    a = 0.05
    m = trimesh.creation.icosphere(4, a)
    tri = torch.tensor(m.vertices[m.faces])
    k_inc = torch.tensor([0.3, -0.2, -1.0], dtype=torch.float64)
    k_inc = k_inc / k_inc.norm()
    sigma = float(plane_wave_rcs(tri, k_inc, -k_inc, LAM))
    err = 10 * math.log10(sigma / (math.pi * a * a))
    assert abs(err) < 1.0


def test_triangle_integral_vs_quadrature():
    """Gordon's closed form vs a dense midpoint-rule quadrature of exp(j w.r) over a triangle."""
    g = torch.Generator().manual_seed(3)
    tri = torch.rand(3, 3, generator=g, dtype=torch.float64) * 0.02
    n = 400
    i, j = torch.meshgrid(torch.arange(n), torch.arange(n), indexing="ij")
    keep = i + j < n - 1  # cells fully inside: the lower-left sub-triangles ...
    u = (i[keep] + 1 / 3) / n
    v = (j[keep] + 1 / 3) / n
    u2 = (i[keep] + 2 / 3) / n
    v2 = (j[keep] + 2 / 3) / n
    # ... and the upper-right ones (each cell of the unit square split into two triangles).
    diag = i + j == n - 1
    uu = torch.cat([u, u2, (i[diag] + 1 / 3) / n]).double()
    vv = torch.cat([v, v2, (j[diag] + 1 / 3) / n]).double()
    pts = tri[0] + uu[:, None] * (tri[1] - tri[0]) + vv[:, None] * (tri[2] - tri[0])
    area = 0.5 * torch.linalg.cross(tri[1] - tri[0], tri[2] - tri[0]).norm()
    for w in (torch.tensor([300.0, -150.0, 80.0]), torch.tensor([1e-3, 0.0, 2.0]), torch.tensor([0.0, 900.0, 0.0])):
        w = w.double()
        quad = torch.exp(1j * (pts @ w)).sum() * area / (n * n)
        exact = triangle_integral(tri, w, torch.zeros(3, dtype=torch.float64))
        assert abs(complex(exact) - complex(quad)) < 2e-3 * float(area)


def test_parallelogram_equals_two_triangles():
    e1 = torch.tensor([0.03, 0.01, 0.0], dtype=torch.float64)
    e2 = torch.tensor([-0.005, 0.02, 0.004], dtype=torch.float64)
    c = torch.zeros(3, dtype=torch.float64)
    p0 = c - (e1 + e2) / 2
    tris = torch.stack([torch.stack([p0, p0 + e1, p0 + e1 + e2]), torch.stack([p0, p0 + e1 + e2, p0 + e2])])
    for w in (torch.tensor([200.0, 50.0, -30.0]), torch.tensor([0.0, 0.0, 500.0])):
        w = w.double()
        two = triangle_integral(tris, w.expand(2, 3), c.expand(2, 3)).sum()
        torch.testing.assert_close(parallelogram_integral(e1, e2, w), two, atol=1e-9, rtol=1e-6)
