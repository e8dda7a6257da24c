"""Antenna pattern normalization and the scalar reflection coefficient."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.raytrace.antenna import IsotropicAntenna, PatchAntenna
from radaraug.raytrace.reflect import FaceReflectivity, te_weight
from radaraug.scene.materials import get_material


def test_patch_pattern_radiates_unit_power():
    """Lossless pattern: (1 / 4 pi) * integral of G over the sphere = 1 (+ the -30 dB back-lobe floor)."""
    ant = PatchAntenna(gain_dBi=6.0)
    n = 2000
    th = (torch.arange(n, dtype=torch.float64) + 0.5) * math.pi / n
    dirs = torch.stack([torch.sin(th), torch.zeros_like(th), torch.cos(th)], -1)
    g = ant.gain(dirs)
    total = float((g * torch.sin(th)).sum() * (math.pi / n) * 2 * math.pi / (4 * math.pi))
    assert total == pytest.approx(1.0 + 0.5 * ant.peak_gain * 1e-3, rel=2e-3)
    assert float(g[0]) == pytest.approx(10 ** 0.6, rel=1e-3)  # boresight (theta ~ 0)


def test_isotropic_and_bad_gain():
    assert torch.equal(IsotropicAntenna().gain(torch.randn(4, 3)), torch.ones(4))
    with pytest.raises(ConfigError):
        PatchAntenna(gain_dBi=1.0)


def test_metal_is_minus_one_and_normal_incidence_is_gamma_te():
    f = 60e9
    refl = FaceReflectivity(("metal", "concrete"), f, torch.device("cpu"), torch.float64)
    n = torch.tensor([0.0, 0.0, 1.0], dtype=torch.float64)
    th = torch.linspace(0.01, 1.5, 7, dtype=torch.float64)
    d = torch.stack([torch.sin(th), torch.zeros_like(th), -torch.cos(th)], -1)
    pol = torch.tensor([0.3, 0.8, 0.52], dtype=torch.float64)
    pol = pol / pol.norm()
    g_metal = refl(torch.zeros(7, dtype=torch.long), torch.cos(th), d, n.expand(7, 3), pol)
    torch.testing.assert_close(g_metal, torch.full_like(g_metal, -1.0), atol=1e-2, rtol=0)  # sigma = 1e7 S/m, not PEC
    eps = get_material("concrete").permittivity(f)
    g0 = refl(torch.ones(1, dtype=torch.long), torch.ones(1, dtype=torch.float64), -n[None], n[None], pol)
    expected = (1 - eps**0.5) / (1 + eps**0.5)
    assert abs(complex(g0[0]) - expected) < 1e-9
    assert 10 * math.log10(abs(expected) ** 2) == pytest.approx(-8.1, abs=0.1)  # ITU-R P.2040 table


def test_te_weight():
    n = torch.tensor([0.0, 0.0, 1.0])
    d = torch.tensor([[1.0, 0.0, -1.0]]) / math.sqrt(2)  # plane of incidence x-z: TE along y
    assert float(te_weight(d, n, torch.tensor([0.0, 1.0, 0.0]))) == pytest.approx(1.0)
    assert float(te_weight(d, n, torch.tensor([1.0, 0.0, 0.0]))) == pytest.approx(0.0)
