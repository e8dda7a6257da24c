"""Diffuse clutter (effective-roughness model) against closed forms and its statistics."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import IsotropicAntenna
from radaraug.raytrace.diffuse import diffuse_paths, occluder_faces, surface_cells
from radaraug.raytrace.radar import RadarGeometry
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.scene.geometry import SceneGeometry
from radaraug.scene.scattering import DiffuseScattering, directive_norm, specular_reduction

F0 = 60e9
LAM = SPEED_OF_LIGHT / F0
DT = torch.float64


def _radar() -> RadarGeometry:
    o = torch.zeros(3, dtype=DT)
    return RadarGeometry(o, o[None].clone(), o.clone(), torch.eye(3, dtype=DT),
                         torch.tensor([0.0, 1.0, 0.0], dtype=DT), LAM)


def _rect(origin, u, v, nu: int, nv: int, material: str = "concrete") -> SceneGeometry:
    """Rectangle ``origin + s u + t v`` split into ``2 nu nv`` triangles."""
    o, u, v = (torch.tensor(x, dtype=DT) for x in (origin, u, v))
    s = torch.linspace(0, 1, nu + 1, dtype=DT)
    t = torch.linspace(0, 1, nv + 1, dtype=DT)
    ss, tt = torch.meshgrid(s, t, indexing="ij")
    verts = (o + ss[..., None] * u + tt[..., None] * v).reshape(-1, 3)
    idx = torch.arange((nu + 1) * (nv + 1)).reshape(nu + 1, nv + 1)
    a, b, c, d = idx[:-1, :-1].flatten(), idx[1:, :-1].flatten(), idx[1:, 1:].flatten(), idx[:-1, 1:].flatten()
    faces = torch.cat([torch.stack([a, b, c], 1), torch.stack([a, c, d], 1)])
    n = faces.shape[0]
    return SceneGeometry(verts, faces, torch.zeros(n, dtype=torch.long), (material,), None,
                         torch.zeros(n, dtype=torch.long))


def _expected_per_bin(rect: tuple, prm: DiffuseScattering, edges: torch.Tensor, material: str = "concrete",
                      fine: int = 400) -> torch.Tensor:
    """Closed form on a fine midpoint grid of the rectangle ``(origin, u, v)``: the sum of
    ``lambda^2 sigma0(theta) dA / ((4 pi)^3 r^4)`` per range bin (isotropic antennas)."""
    o, u, v = (torch.tensor(x, dtype=DT) for x in rect)
    s = (torch.arange(fine, dtype=DT) + 0.5) / fine
    ss, tt = torch.meshgrid(s, s, indexing="ij")
    pts = (o + ss[..., None] * u + tt[..., None] * v).reshape(-1, 3)
    nrm = torch.linalg.cross(u, v)
    da = nrm.norm() / fine**2
    nrm = nrm / nrm.norm()
    r = pts.norm(dim=-1)
    k = -pts / r[:, None]
    cos = (k @ nrm).abs()
    refl = FaceReflectivity((material,), F0, torch.device("cpu"), DT)
    gamma2 = refl(torch.zeros(len(pts), dtype=torch.long), cos, -k, nrm.expand_as(pts),
                  torch.tensor([0.0, 1.0, 0.0], dtype=DT)).abs() ** 2
    p = LAM**2 * prm.sigma0(gamma2, cos) * da / ((4 * math.pi) ** 3 * r**4)
    b = (torch.bucketize(r, edges) - 1).clamp(0, len(edges) - 2)
    return torch.zeros(len(edges) - 1, dtype=DT).index_add_(0, b, p)


def _powers(room, seeds, prm, cell_m, bvh=None, edges=None):
    """Per-seed total (or per-range-bin) diffuse power, unmerged cells."""
    out = []
    for seed in seeds:
        paths, verts = diffuse_paths(room, _radar(), IsotropicAntenna(), bvh, frequency_Hz=F0, seed=seed,
                                     scattering={room.materials[0]: prm}, cell_m=cell_m, merge_bin_m=None)
        p = paths.amplitude[:, 0].abs() ** 2
        if edges is None:
            out.append(p.sum())
        else:
            r = verts[:, 1].norm(dim=-1)
            b = (torch.bucketize(r, edges) - 1).clamp(0, len(edges) - 2)
            out.append(torch.zeros(len(edges) - 1, dtype=DT).index_add_(0, b, p))
    return torch.stack(out)


def _cell_weights(room, prm, cell_m):
    """Expected power of each cell (its |z|^2 replaced by 1) for the tolerance."""
    paths, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, frequency_Hz=F0, seed=0,
                             scattering={room.materials[0]: prm}, cell_m=cell_m, merge_bin_m=None)
    # Var of an exponential with mean w is w^2: the relative std of the sum is sqrt(sum w^2) / sum w.
    # |a|^2 = w |z|^2; E over seeds of w |z|^2 ~ w, so estimate sum w^2 by sum |a|^4 / 2 (E|z|^4 = 2).
    p = paths.amplitude[:, 0].abs() ** 2
    return float((p.square().sum() / 2).sqrt() / p.sum())


@pytest.mark.parametrize("prm", [DiffuseScattering(0.5), DiffuseScattering(0.5, "directive", 4)],
                         ids=["lambertian", "directive"])
def test_plate_mean_power_matches_radar_equation(prm):
    # A 0.6 m x 0.6 m concrete plate 3 m in front of the radar, facing it.
    rect = ((-0.3, -0.3, 3.0), (0.6, 0.0, 0.0), (0.0, 0.6, 0.0))
    room = _rect(*rect, 1, 1)
    seeds = range(24)
    got = _powers(room, seeds, prm, 0.03).mean()
    want = _expected_per_bin(rect, prm, torch.tensor([0.0, 100.0], dtype=DT))[0]
    rel_std = _cell_weights(room, prm, 0.03) / math.sqrt(len(seeds))
    assert abs(float(got / want) - 1) < 5 * rel_std + 0.01, (float(got / want), rel_std)


def test_monostatic_sigma0_closed_forms():
    c = torch.tensor([1.0, 0.8, 0.3], dtype=DT)
    g2 = torch.tensor(0.25, dtype=DT)
    lam = DiffuseScattering(0.4)
    torch.testing.assert_close(lam.sigma0(g2, c), 4 * 0.16 * 0.25 * c**2)
    # Directive at normal incidence: F = 2 pi (2^(a+1) - 1) / ((a + 1) 2^a), sigma0 = 4 pi S^2 |G|^2 / F.
    a = 3
    d = DiffuseScattering(0.4, "directive", a)
    f0 = 2 * math.pi * (2 ** (a + 1) - 1) / ((a + 1) * 2**a)
    torch.testing.assert_close(d.sigma0(g2, torch.tensor(1.0, dtype=DT)),
                               torch.tensor(4 * math.pi * 0.16 * 0.25 / f0, dtype=DT))


@pytest.mark.parametrize("prm", [DiffuseScattering(1.0), *(DiffuseScattering(1.0, "directive", a) for a in (1, 2, 4, 7))])
@pytest.mark.parametrize("theta_deg", [0.0, 30.0, 60.0, 85.0])
def test_pattern_integrates_to_one_over_hemisphere(prm, theta_deg):
    # Midpoint quadrature in (theta_s, phi) over the hemisphere z > 0; specular direction at theta_i.
    n = 400
    th = (torch.arange(n, dtype=DT) + 0.5) / n * (math.pi / 2)
    ph = (torch.arange(2 * n, dtype=DT) + 0.5) / (2 * n) * (2 * math.pi)
    tt, pp = torch.meshgrid(th, ph, indexing="ij")
    s = torch.stack([tt.sin() * pp.cos(), tt.sin() * pp.sin(), tt.cos()], -1)
    ti = math.radians(theta_deg)
    spec = torch.tensor([math.sin(ti), 0.0, math.cos(ti)], dtype=DT)
    f = prm.pattern_value(s[..., 2], s @ spec, torch.tensor(math.cos(ti), dtype=DT))
    total = (f * tt.sin()).sum() * (math.pi / 2 / n) * (2 * math.pi / (2 * n))
    assert abs(float(total) - 1) < 2e-3


def test_directive_norm_matches_numeric_integral():
    for a in (1, 3, 6):
        for ti in (0.0, 0.7, 1.4):
            n = 300
            th = (torch.arange(n, dtype=DT) + 0.5) / n * (math.pi / 2)
            ph = (torch.arange(2 * n, dtype=DT) + 0.5) / (2 * n) * (2 * math.pi)
            tt, pp = torch.meshgrid(th, ph, indexing="ij")
            cpsi = tt.sin() * pp.cos() * math.sin(ti) + tt.cos() * math.cos(ti)
            num = (((1 + cpsi) / 2) ** a * tt.sin()).sum() * (math.pi / 2 / n) * (math.pi / n)
            assert abs(float(directive_norm(torch.tensor(math.cos(ti), dtype=DT), a) / num) - 1) < 2e-3


def test_specular_reduction_and_energy_balance():
    names = ["concrete", "plasterboard@0.0125", "absorber"]
    red = specular_reduction(names, {"plasterboard": {"S": 0.6}}, dtype=DT)
    torch.testing.assert_close(red[1], torch.tensor(0.8, dtype=DT))
    assert float(red[2]) == 1.0
    prm = DiffuseScattering(0.45)
    assert abs(prm.S**2 + prm.specular_reduction**2 - 1) < 1e-12


def test_rayleigh_statistics():
    # A small plate far away: every cell has the same expected power, so the normalized cell
    # powers are the |z|^2 draws: exponential, mean 1, dB std 10/ln(10) * pi/sqrt(6) = 5.57 dB.
    room = _rect((-0.05, -0.05, 20.0), (0.1, 0.0, 0.0), (0.0, 0.1, 0.0), 1, 1)
    paths, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, frequency_Hz=F0, seed=3,
                             scattering={"concrete": 0.5}, cell_m=0.001, merge_bin_m=None)
    p = paths.amplitude[:, 0].abs() ** 2
    assert p.numel() > 5000
    paths1, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, frequency_Hz=F0, seed=4,
                              scattering={"concrete": 0.5}, cell_m=0.001, merge_bin_m=None)
    mean = (paths1.amplitude[:, 0].abs() ** 2).mean()
    x = p / mean
    assert abs(float(x.mean()) - 1) < 0.05
    db = 10 * torch.log10(x)
    assert abs(float(db.std()) - 10 / math.log(10) * math.pi / math.sqrt(6)) < 0.2
    phase = torch.angle(paths.amplitude[:, 0])
    assert abs(float(torch.cos(phase).mean())) < 0.05 and abs(float(torch.sin(phase).mean())) < 0.05


def test_deterministic_for_a_seed():
    room = _rect((1.0, 1.0, 0.0), (3.0, 0.0, 0.0), (0.0, 0.0, 1.0), 3, 2)
    kw = dict(frequency_Hz=F0, scattering={"concrete": 0.5})
    a, va = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=7, **kw)
    b, vb = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=7, **kw)
    c, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=8, **kw)
    assert torch.equal(a.amplitude, b.amplitude) and torch.equal(a.delay_s, b.delay_s) and torch.equal(va, vb)
    assert a.amplitude.shape != c.amplitude.shape or not torch.equal(a.amplitude, c.amplitude)
    assert va.shape == (a.num_paths, 3, 3)
    assert torch.equal(va[:, 0], _radar().centre.expand(a.num_paths, 3)) and torch.equal(va[:, 2], va[:, 0])
    assert a.kind is not None and int(a.kind.abs().sum()) == 0


def test_cells_tile_the_faces():
    room = _rect((0.0, 0.0, 0.0), (1.3, 0.0, 0.0), (0.0, 0.7, 0.0), 1, 3)
    pts, face, area = surface_cells(room, 0.1, torch.Generator().manual_seed(0))
    torch.testing.assert_close(area.sum(), torch.tensor(1.3 * 0.7, dtype=DT))
    assert float(area.max()) <= 0.01 + 1e-12
    assert bool((pts[:, 0] >= 0).all() and (pts[:, 0] <= 1.3).all() and (pts[:, 1] >= 0).all()
                and (pts[:, 1] <= 0.7).all() and (pts[:, 2] == 0).all())


def test_independent_of_triangulation():
    # A side wall seen obliquely (range 1.1..4.1 m), split into 2 or 200 triangles: the same mean
    # power per 0.5 m range bin, both equal to the closed form.
    prm = DiffuseScattering(0.5)
    edges = torch.tensor([1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.5], dtype=DT)
    rect = ((1.0, 0.5, -0.5), (3.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    coarse = _rect(*rect, 1, 1)
    fine = _rect(*rect, 20, 5)
    want = _expected_per_bin(rect, prm, edges)
    seeds = range(8)
    for room in (coarse, fine):
        got = _powers(room, seeds, prm, 0.05, edges=edges).mean(0)
        # Tolerance: ~200 cells per bin, 8 seeds -> relative std ~2.5 %: 12 % is about 5 sigma.
        assert torch.allclose(got, want, rtol=0.12), (got / want)


def test_occluded_cells_give_nothing():
    wall = _rect((-1.0, -1.0, 5.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), 2, 2)
    # A 4 m x 4 m absorber screen (no diffuse scattering of its own) at 2 m hides the whole wall.
    screen = _rect((-2.0, -2.0, 2.0), (4.0, 0.0, 0.0), (0.0, 4.0, 0.0), 1, 1, material="absorber")
    from radaraug.scene.room import merge

    room = merge([wall, screen])
    bvh = TriangleBVH(room.triangles)
    occ = occluder_faces(room.triangles, _radar().centre)
    assert bool(occ[wall.num_faces:].all()) and not bool(occ[: wall.num_faces].any())
    blocked, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), bvh, frequency_Hz=F0, seed=0, merge_bin_m=None)
    assert blocked.num_paths == 0
    free, _ = diffuse_paths(wall, _radar(), IsotropicAntenna(), TriangleBVH(wall.triangles), frequency_Hz=F0,
                            seed=0, merge_bin_m=None)
    assert free.num_paths > 100
    # A screen over half the wall (x < 0) keeps only cells with x > 0.
    half = _rect((-2.0, -2.0, 2.0), (2.0, 0.0, 0.0), (0.0, 4.0, 0.0), 1, 1, material="absorber")
    room = merge([wall, half])
    _, verts = diffuse_paths(room, _radar(), IsotropicAntenna(), TriangleBVH(room.triangles), frequency_Hz=F0,
                             seed=0, merge_bin_m=None)
    assert verts.shape[0] > 50 and bool((verts[:, 1, 0] > 0).all())


def test_merge_keeps_power_statistics_and_geometry():
    room = _rect((1.0, 1.0, -1.0), (4.0, 0.0, 0.0), (0.0, 0.0, 2.0), 4, 2)
    kw = dict(frequency_Hz=F0, scattering={"concrete": 0.5})
    cells, vc = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=1, merge_bin_m=None, **kw)
    tiny, vt = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=1, merge_bin_m=1e-9,
                             merge_voxel_m=1e-6, **kw)
    # Bins too small to merge anything: the same set of paths (order aside).
    assert tiny.num_paths == cells.num_paths
    torch.testing.assert_close((tiny.amplitude.abs() ** 2).sum(), (cells.amplitude.abs() ** 2).sum())
    merged, vm = diffuse_paths(room, _radar(), IsotropicAntenna(), None, seed=1, **kw)
    assert merged.num_paths < cells.num_paths
    # Centroids stay on the wall (y = 1) inside its extent.
    assert torch.allclose(vm[:, 1, 1], torch.ones_like(vm[:, 1, 1]), atol=1e-9)
    assert bool((vm[:, 1, 0] >= 1.0).all() and (vm[:, 1, 0] <= 5.0).all())


def test_gain_db_scales_power():
    room = _rect((1.0, 1.0, -1.0), (2.0, 0.0, 0.0), (0.0, 0.0, 2.0), 1, 1)
    a, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, frequency_Hz=F0, seed=0, merge_bin_m=None)
    b, _ = diffuse_paths(room, _radar(), IsotropicAntenna(), None, frequency_Hz=F0, seed=0, merge_bin_m=None,
                         gain_dB=10.0)
    torch.testing.assert_close(b.amplitude.abs() ** 2, 10 * a.amplitude.abs() ** 2)


def test_same_clutter_on_every_device(device):
    room = _rect((1.0, 1.0, -1.0), (3.0, 0.0, 0.0), (0.0, 0.0, 2.0), 3, 2)
    r = _radar()
    moved = RadarGeometry(*(x.to(device) for x in (r.tx, r.rx, r.centre, r.rotation, r.polarization)), r.wavelength)
    a, va = diffuse_paths(room, r, IsotropicAntenna(), None, frequency_Hz=F0, seed=5)
    b, vb = diffuse_paths(room.to(device), moved, IsotropicAntenna(), TriangleBVH(room.triangles.to(device)),
                          frequency_Hz=F0, seed=5)
    assert b.amplitude.device.type == device.type
    torch.testing.assert_close(b.amplitude.cpu(), a.amplitude)
    torch.testing.assert_close(vb.cpu(), va)
