"""Moving targets: ellipsoid RCS, radar equation, delay / Doppler, occlusion and wall ghosts."""

from __future__ import annotations

import math

import pytest
import torch
from raytrace_scenes import carrier_sum, monostatic_config, quad, soup

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.raytrace.antenna import IsotropicAntenna
from radaraug.raytrace.targets import ellipsoid_rcs, slot_segments
from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry

CFG = monostatic_config()
LAM = CFG.wavelength_m


def _empty_room() -> SceneGeometry:
    return SceneGeometry(torch.zeros(0, 3), torch.zeros(0, 3, dtype=torch.long), torch.zeros(0, dtype=torch.long),
                         ("metal",))


def _spheres(centres, radius, velocities=None, material="metal", dtype=torch.float64) -> Ellipsoids:
    c = torch.as_tensor(centres, dtype=dtype)
    n = c.shape[:-1]
    v = torch.zeros_like(c) if velocities is None else torch.as_tensor(velocities, dtype=dtype)
    return Ellipsoids(c, torch.full_like(c, radius), torch.eye(3, dtype=dtype).expand(*n, 3, 3), v, material)


def _tracer(room=None, config=CFG, **kw) -> RayTracer:
    pose = RadarPose.look_at((0.0, 0.0, 0.0), (1.0, 0.0, 0.0))
    return RayTracer(room if room is not None else _empty_room(), pose, config,
                     antenna=kw.pop("antenna", IsotropicAntenna()), dtype=torch.float64, **kw)


def test_ellipsoid_rcs_closed_forms():
    """a = b = c: sigma = pi a^2 from every direction; along a principal axis z: pi a^2 b^2 / c^2."""
    g = torch.Generator().manual_seed(0)
    dirs = torch.randn(20, 3, generator=g, dtype=torch.float64)
    dirs = dirs / dirs.norm(dim=1, keepdim=True)
    sigma, h = ellipsoid_rcs(torch.full((20, 3), 0.2, dtype=torch.float64), dirs)
    torch.testing.assert_close(sigma, torch.full_like(sigma, math.pi * 0.04))
    torch.testing.assert_close(h, torch.full_like(h, 0.2))
    sigma_z, h_z = ellipsoid_rcs(torch.tensor([0.1, 0.2, 0.3]).double(), torch.tensor([0.0, 0.0, 1.0]).double())
    assert float(sigma_z) == pytest.approx(math.pi * 0.1**2 * 0.2**2 / 0.3**2)
    assert float(h_z) == pytest.approx(0.3)


@pytest.mark.parametrize("rng", [1.0, 2.5, 5.0, 10.0])
def test_radar_equation_r4_and_delay(rng):
    """PEC sphere a = 10 cm: P_r/P_t = G_t G_r lambda^2 sigma / ((4 pi)^3 R^4) with sigma = pi a^2 (exact),
    R = distance to the specular point (centre - a), delay 2 R / c, delay_rate 2 v_radial / c."""
    a, v_rad = 0.1, 1.3
    ell = _spheres([[rng, 0.0, 0.0]], a, velocities=[[v_rad, 0.4, -0.2]])
    paths = _tracer().target_paths(ell, multipath=False)
    r = rng - a
    gamma_metal = abs(complex(RayTracerMetalGamma.value))
    expected = LAM**2 * math.pi * a * a * gamma_metal**2 / ((4 * math.pi) ** 3 * r**4)
    assert float(paths.amplitude[0, 0].abs() ** 2) == pytest.approx(expected, rel=1e-9)
    assert float(paths.delay_s[0, 0]) == pytest.approx(2 * r / SPEED_OF_LIGHT, rel=1e-12)
    assert float(paths.delay_rate[0, 0]) == pytest.approx(2 * v_rad / SPEED_OF_LIGHT, rel=1e-9)
    assert bool(paths.mask[0]) and int(paths.kind[0]) == 0


def _turning_segment(t: float, omega: torch.Tensor, v: torch.Tensor) -> Ellipsoids:
    """A 0.45 x 0.06 x 0.05 m segment (a lower leg) at 3 m, moving at ``v`` and turning at ``omega``."""
    w = omega.norm()
    k = omega / w
    kx = torch.tensor([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]], dtype=torch.float64)
    turn = torch.eye(3, dtype=torch.float64) + torch.sin(w * t) * kx + (1 - torch.cos(w * t)) * kx @ kx  # Rodrigues
    base = torch.tensor([[0.3, 0.9, 0.1], [-0.9, 0.3, 0.2], [0.15, -0.15, 0.97]], dtype=torch.float64)
    base = torch.linalg.qr(base)[0]
    centre = torch.tensor([3.0, 0.4, -0.3], dtype=torch.float64) + v * t
    return Ellipsoids(centre[None], torch.tensor([[0.06, 0.05, 0.45]], dtype=torch.float64), (turn @ base)[None],
                      v[None].clone(), "skin", omega[None].clone())


def test_a_turning_segments_delay_rate_is_the_derivative_of_its_delay():
    """The echo of an elongated segment sits at its specular point, which slides as the segment turns: the
    traced ``delay_rate`` must be the time derivative of the traced ``delay_s`` (a central difference of
    two traces, the outside reference), not the centre's radial velocity; before the angular
    velocity was used the two differed by ~1.3 m/s here, several Doppler bins."""
    omega = torch.tensor([0.8, -5.0, 2.0], dtype=torch.float64)  # a swinging lower leg: ~5 rad/s
    v = torch.tensor([1.2, 0.3, 0.0], dtype=torch.float64)
    tracer = _tracer()
    dt = 1e-5
    for t in (0.0, 0.07, 0.19):
        at = tracer.target_paths(_turning_segment(t, omega, v), multipath=False)
        before = tracer.target_paths(_turning_segment(t - dt, omega, v), multipath=False)
        after = tracer.target_paths(_turning_segment(t + dt, omega, v), multipath=False)
        derivative = (after.delay_s - before.delay_s) / (2 * dt)
        # to 10 um/s (the finite difference's own error; measured < 1e-7 m/s)
        torch.testing.assert_close(at.delay_rate, derivative, rtol=0, atol=1e-5 * 2 / SPEED_OF_LIGHT)
        centre_rate = 2 * float((v * torch.nn.functional.normalize(_turning_segment(t, omega, v).centers[0], dim=0)).sum())
        assert abs(float(at.delay_rate[0, 0]) * SPEED_OF_LIGHT - centre_rate) > 0.05  # the turn matters here
    # without the angular velocity the rate is the centre's (the rule before)
    still = _turning_segment(0.07, omega, v)
    still.angular_velocities = None
    assert float(tracer.target_paths(still, multipath=False).delay_rate[0, 0]) * SPEED_OF_LIGHT == pytest.approx(
        2 * float((v * torch.nn.functional.normalize(still.centers[0], dim=0)).sum()), rel=1e-9)


class RayTracerMetalGamma:
    """|Gamma| of 'metal' at normal incidence (sigma = 1e7 S/m: 1 - 1e-3 or so)."""

    from radaraug.scene.materials import get_material as _gm

    _eps = _gm("metal").permittivity(monostatic_config().center_frequency_Hz)
    value = (1 - _eps**0.5) / (1 + _eps**0.5)


def test_per_rx_delays_follow_array_geometry():
    """Far target at azimuth phi: RX delays differ by (x_rx . u) / c (plane-wave array phase)."""
    cfg = RadarConfig.bgt60tr13c()
    phi = math.radians(20)
    rng = 50.0
    # Radar frame: x right, z boresight; look along world +x with world z up -> radar x = world -y.
    ell = _spheres([[rng * math.cos(phi), -rng * math.sin(phi), 0.0]], 0.05)
    paths = _tracer(config=cfg).target_paths(ell, multipath=False)
    rx = torch.tensor(cfg.rx_positions, dtype=torch.float64)
    u_radar = torch.tensor([math.sin(phi), 0.0, math.cos(phi)], dtype=torch.float64)
    expected = -(rx @ u_radar) / SPEED_OF_LIGHT
    got = paths.delay_s[0] - paths.delay_s[0, 2]
    # Plane-wave closed form; the spherical wavefront adds d^2 / (2 R c) ~ 2e-16 s at 50 m.
    torch.testing.assert_close(got, expected - expected[2], atol=5e-16, rtol=1e-4)


def test_occlusion_by_ellipsoid_and_room():
    """A big sphere in front hides a small one behind it; a wall between hides everything."""
    ell = _spheres([[3.0, 0.0, 0.0], [6.0, 0.0, 0.0], [6.0, 2.0, 0.0]], 0.3)
    paths = _tracer().target_paths(ell, multipath=False)
    assert paths.mask.tolist() == [True, False, True]
    assert float(paths.amplitude[1].abs().max()) == 0.0
    c = torch.tensor([1.5, 0.0, 0.0], dtype=torch.float64)
    wall = soup(quad(c + torch.tensor([0.0, -5.0, -5.0]).double(), torch.tensor([0.0, 10.0, 0.0]).double(),
                     torch.tensor([0.0, 0.0, 10.0]).double()))
    assert not _tracer(wall).target_paths(ell, multipath=False).mask.any()


def test_paths_of_some_segments_are_theirs_among_all_and_every_segment_still_occludes():
    """``targets``: the slots of just those segments, equal to their slots of the full trace (direct and
    wall ghosts), with a segment left out still hiding the one behind it."""
    wall = soup(quad(torch.tensor([-2.0, -0.5, -5.0]).double(), torch.tensor([0.0, 0.0, 10.0]).double(),
                     torch.tensor([20.0, 0.0, 0.0]).double()))
    ell = _spheres([[[3.0, 0.0, 0.0], [6.0, 0.0, 0.0], [6.0, 2.0, 0.0], [4.0, 0.5, 0.3]]] * 2, 0.3,
                   velocities=[[[0.5, 0.0, 0.0], [-1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.1]]] * 2)
    tracer = _tracer(wall)
    full = tracer.target_paths(ell, multipath=True)
    for targets in ([1], [0, 2], [1, 3]):
        t = torch.tensor(targets)
        some = tracer.target_paths(ell, multipath=True, targets=t)
        where = torch.isin(slot_segments(4, full.num_paths), t).nonzero()[:, 0]
        assert some.num_paths == len(targets) * full.num_paths // 4
        for name in ("kind", "mask"):
            assert torch.equal(getattr(some, name), getattr(full, name)[:, where]), name
        for name in ("delay_s", "delay_rate", "amplitude"):  # vector kernels may round the last bit otherwise
            torch.testing.assert_close(getattr(some, name), getattr(full, name)[:, where], rtol=1e-12, atol=0)
    # segment 1 sits behind segment 0: traced alone it is still hidden
    assert not bool(tracer.target_paths(ell, multipath=True, targets=torch.tensor([1])).mask[:, 0].any())
    # the layout: S direct slots, then three blocks of S K wall slots, segment-major (S = 2, K = 2 here)
    assert slot_segments(2, 14).tolist() == [0, 1] + [0, 0, 1, 1] * 3


def test_wall_ghost_at_image_range():
    """Radar beside a metal wall (plane y = -w) and a sphere: a ghost path at the image-method length
    |T - image(radar)| + |T - radar| (closed-form geometry), with |a| from the bistatic radar equation."""
    w, a = 0.5, 0.05
    target = torch.tensor([4.0, 0.5, 0.0], dtype=torch.float64)
    wall = soup(quad(torch.tensor([-2.0, -w, -5.0]).double(), torch.tensor([0.0, 0.0, 10.0]).double(),
                     torch.tensor([20.0, 0.0, 0.0]).double()))
    paths = _tracer(wall).target_paths(_spheres(target[None], a), multipath=True)
    # radar->wall->target->radar and its reverse (the second-order ghost is the third slot)
    ghosts = paths.mask & (paths.kind == 1) & (torch.arange(paths.num_paths) < paths.num_paths - 1)
    assert int(ghosts.sum()) == 2
    image = torch.tensor([0.0, -2 * w, 0.0], dtype=torch.float64)
    u_in = (target - image) / (target - image).norm()
    u_out = -target / target.norm()
    bis = (u_in - u_out) / (u_in - u_out).norm()
    spec = target - a * bis  # specular point of a sphere for that bistatic pair
    length = float((spec - image).norm() + spec.norm())
    got = paths.delay_s[ghosts, 0] * SPEED_OF_LIGHT
    torch.testing.assert_close(got, torch.full_like(got, length), rtol=1e-9, atol=1e-9)
    gamma = abs(complex(RayTracerMetalGamma.value))
    expected = LAM * math.sqrt(math.pi) * a * gamma**2 / ((4 * math.pi) ** 1.5 * float((spec - image).norm() * spec.norm()))
    # |Gamma_metal| at the wall's oblique incidence differs from the normal-incidence value by < 1e-3.
    torch.testing.assert_close(paths.amplitude[ghosts, 0].abs(), torch.full_like(got, expected), rtol=2e-3, atol=0)
    # The direct echo is there too and the ghost is farther.
    direct = paths.mask & (paths.kind == 0)
    assert int(direct.sum()) == 1 and float(paths.delay_s[direct, 0]) < float(got.min()) / SPEED_OF_LIGHT


def test_second_order_wall_target_wall_ghost_is_the_image_radars_echo():
    """Radar beside a metal wall (plane y = -w), a moving sphere: radar -> wall -> sphere -> wall ->
    radar is the sphere's monostatic echo seen from the radar's image (closed form): length
    2 |image - p| with p the sphere's point facing the image, |a| from the radar equation with
    |Gamma_wall|^2 (two bounces) and the sphere's sqrt(pi) a, rate 2 v . u / c along the image's
    line of sight."""
    w, a = 0.5, 0.05
    target = torch.tensor([4.0, 0.5, 0.0], dtype=torch.float64)
    v = torch.tensor([-1.0, 0.7, 0.2], dtype=torch.float64)
    wall = soup(quad(torch.tensor([-2.0, -w, -5.0]).double(), torch.tensor([0.0, 0.0, 10.0]).double(),
                     torch.tensor([20.0, 0.0, 0.0]).double()))
    paths = _tracer(wall).target_paths(_spheres(target[None], a, v[None]), multipath=True)
    assert paths.num_paths == 4 and bool(paths.mask.all())  # direct, two first-order, one second-order
    image = torch.tensor([0.0, -2 * w, 0.0], dtype=torch.float64)
    u = (target - image) / (target - image).norm()
    spec = target - a * u
    r = float((spec - image).norm())
    assert float(paths.delay_s[3, 0] * SPEED_OF_LIGHT) == pytest.approx(2 * r, rel=1e-12)
    gamma = abs(complex(RayTracerMetalGamma.value))
    expected = LAM * math.sqrt(math.pi) * a * gamma**3 / ((4 * math.pi) ** 1.5 * r * r)
    assert float(paths.amplitude[3, 0].abs()) == pytest.approx(expected, rel=2e-3)
    assert float(paths.delay_rate[3, 0]) == pytest.approx(2 * float(v @ u) / SPEED_OF_LIGHT, rel=1e-9)
    assert int(paths.kind[3]) == 1
    # Far enough that the bounce point (a third of the way to the target) lies past the wall's end.
    far = torch.tensor([60.0, 0.5, 0.0], dtype=torch.float64)
    assert not bool(_tracer(wall).target_paths(_spheres(far[None], a), multipath=True).mask[3])


def test_batched_frames_shapes_and_values():
    """Leading (T,) dims carry through; each frame equals tracing that frame alone."""
    g = torch.Generator().manual_seed(0)
    c = torch.rand(4, 5, 3, generator=g, dtype=torch.float64) * torch.tensor([5.0, 2.0, 1.0]).double() + torch.tensor(
        [2.0, -1.0, -0.5]).double()
    ell = Ellipsoids(c, torch.rand(4, 5, 3, generator=g, dtype=torch.float64) * 0.1 + 0.05,
                     torch.eye(3, dtype=torch.float64).expand(4, 5, 3, 3), torch.randn(4, 5, 3, generator=g).double())
    tracer = _tracer()
    batched = tracer.target_paths(ell, multipath=False)
    assert batched.delay_s.shape == (4, 5, 1) and batched.mask.shape == (4, 5)
    one = tracer.target_paths(Ellipsoids(c[2], ell.semi_axes[2], ell.rotations[2], ell.velocities[2]), multipath=False)
    torch.testing.assert_close(batched.amplitude[2], one.amplitude)
    torch.testing.assert_close(batched.delay_rate[2], one.delay_rate)


def test_mesh_po_sphere_and_doppler():
    """PO on a moving tessellated PEC sphere (a = 5 cm) at 30 m: coherent sum of the facet paths gives
    sigma = pi a^2 within 1 dB; every facet path has delay_rate = 2 v_radial / c."""
    trimesh = pytest.importorskip("trimesh")
    a, rng, v = 0.05, 30.0, 0.8
    m = trimesh.creation.icosphere(4, a)
    verts = torch.tensor(m.vertices) + torch.tensor([rng, 0.0, 0.0]).double()
    vel = torch.tensor([[v, 0.0, 0.0]], dtype=torch.float64).expand_as(verts)
    mesh = SceneGeometry(verts, torch.as_tensor(m.faces), torch.zeros(len(m.faces), dtype=torch.long), ("metal",),
                         vertex_velocity=vel)
    paths = _tracer().target_paths(meshes=[mesh])
    s = carrier_sum(paths, CFG.center_frequency_Hz)
    sigma = abs(s) ** 2 * (4 * math.pi) ** 3 * (rng - a) ** 4 / LAM**2
    assert abs(10 * math.log10(sigma / (math.pi * a * a))) < 1.0
    torch.testing.assert_close(paths.delay_rate, torch.full_like(paths.delay_rate, 2 * v / SPEED_OF_LIGHT),
                               rtol=1e-3, atol=0)


def test_multipath_inputs_that_cannot_work_are_scene_errors():
    """Multipath needs the room's reflectivity, and the convex fast path one material per mirror
    plane: without them ``ellipsoid_paths`` raised a bare TypeError / AttributeError."""
    from radaraug.errors import SceneError
    from radaraug.raytrace.targets import ellipsoid_paths
    from radaraug.scene.scene import Scene

    scene = Scene.builtin("corridor")
    tracer = RayTracer(scene.room, scene.radar, scene.config, rays=16)
    assert tracer.convex_room and tracer.mirrors is not None
    ell = scene.people_ellipsoids(torch.zeros(1, dtype=torch.float64))
    if ell.centers.shape[-2] == 0:  # an empty corridor: one sphere in front of the radar
        ell = _spheres(torch.tensor([[3.0, 0.0, 1.0]], dtype=torch.float64), 0.1)
    common = {"room_bvh": tracer.bvh, "room_face_material": tracer.face_material, "mirrors": tracer.mirrors,
              "frequency_Hz": tracer.frequency_Hz}
    ok = ellipsoid_paths(ell, tracer.radar, tracer.antenna, room_reflectivity=tracer.reflectivity,
                         convex_room=True, **common)
    assert ok.mask.any()
    with pytest.raises(SceneError, match="needs room_reflectivity"):
        ellipsoid_paths(ell, tracer.radar, tracer.antenna, room_reflectivity=None, **common)
    tracer.mirrors.plane_material = None
    with pytest.raises(SceneError, match="one material each"):
        ellipsoid_paths(ell, tracer.radar, tracer.antenna, room_reflectivity=tracer.reflectivity,
                        convex_room=True, **common)
