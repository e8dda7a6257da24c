"""Optional cross-check of radaraug's specular geometry and Fresnel model against Sionna RT.

Skipped unless Sionna RT (``pip install sionna-rt``) is importable; see the section
"Cross-check against Sionna RT" of docs/raytracer.md.

Scene: radaraug's box corridor (20 m x 2 m x 2.7 m), every wall a 0.1 m slab of its default
material (or all metal), TX and RX at the same point inside, 60 GHz. Sionna traces specular
reflections only (no line of sight, refraction, diffraction or diffuse scattering), up to two
bounces, with isotropic dual-polarized (V/H) antennas.

Reference on the radaraug side, per path: the image method over the corridor's mirror planes
(:class:`radaraug.raytrace.targets.MirrorPlanes`), every leg confirmed by radaraug's ray-triangle
intersection (first hit on the expected wall, return leg clear), and the amplitude from
radaraug's slab reflection coefficients (:meth:`radaraug.scene.materials.Material.reflection`)
chained as a Jones operator. Compared per path (matched by the sequence of walls hit): delay to
1e-3 ns and polarization-summed power ``sum |a|^2`` over the 2 x 2 ports to 0.5 dB.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest
import torch

sionna_rt = pytest.importorskip("sionna.rt")

from radaraug.config import SPEED_OF_LIGHT  # noqa: E402
from radaraug.raytrace.intersect import intersect  # noqa: E402
from radaraug.raytrace.targets import MirrorPlanes  # noqa: E402
from radaraug.scene.materials import get_material, parse_material_key  # noqa: E402
from radaraug.scene.room import CORRIDOR_SURFACES, corridor  # noqa: E402

FREQ_HZ = 60e9
THICKNESS_M = 0.1
POINT = (1.0, 0.25, 1.2)  # TX = RX: 19 m from the far wall, off-centre so path delays differ
MAX_DEPTH = 2

MATERIAL_SETS = {
    "paper_slabs": None,  # the corridor's default materials
    "metal": dict.fromkeys(CORRIDOR_SURFACES, "metal"),
}


def _write_ply(path: Path, vertices: np.ndarray, faces: np.ndarray) -> None:
    """Binary little-endian PLY with float32 vertices and int32 triangle indices."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(vertices)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    face_rec = np.zeros(len(faces), dtype=[("n", "u1"), ("idx", "<i4", (3,))])
    face_rec["n"] = 3
    face_rec["idx"] = faces
    with open(path, "wb") as fh:
        fh.write(header.encode("ascii"))
        fh.write(np.ascontiguousarray(vertices, dtype="<f4").tobytes())
        fh.write(face_rec.tobytes())


def _mirror(p: np.ndarray, n: np.ndarray, off: float) -> np.ndarray:
    return p - 2.0 * (n @ p - off) * n


def _bounce_operator(d_in: np.ndarray, n: np.ndarray, key: str) -> tuple[np.ndarray, np.ndarray]:
    """``(3x3 complex field operator, outgoing direction)`` of one specular reflection.

    ``E_out = Gamma_TE (E.s) s + Gamma_TM (E.p_in) p_out``: the sign conventions of the p axes do
    not change the Frobenius norm of a chain of such operators, which is all that is compared.
    """
    cos = abs(float(d_in @ n))
    d_out = d_in - 2.0 * (d_in @ n) * n
    s = np.cross(d_in, n)
    if np.linalg.norm(s) < 1e-9:  # normal incidence: any transverse axis (|Gamma_TE| = |Gamma_TM|)
        s = np.cross(d_in, [1.0, 0.0, 0.0] if abs(d_in[0]) < 0.9 else [0.0, 1.0, 0.0])
    s = s / np.linalg.norm(s)
    p_in, p_out = np.cross(s, d_in), np.cross(s, d_out)
    g_te, g_tm = get_material(key).reflection(torch.tensor(cos, dtype=torch.float64), FREQ_HZ)
    op = complex(g_te) * np.outer(s, s) + complex(g_tm) * np.outer(p_out, p_in)
    return op, d_out


def _radaraug_paths(
    room, planes: MirrorPlanes, point: np.ndarray,
) -> dict[tuple[int, ...], tuple[float, float]]:
    """Image-method specular paths ``{wall sequence: (delay_s, sum|a|^2)}`` with TX = RX = point."""
    tri = room.triangles.to(torch.float64)
    normals = planes.normals.to(torch.float64).numpy()
    offsets = planes.offsets.to(torch.float64).numpy()
    keys = [room.materials[int(m)] for m in planes.plane_material]
    lam = SPEED_OF_LIGHT / FREQ_HZ
    out = {}
    seqs = [s for depth in range(1, MAX_DEPTH + 1)
            for s in itertools.product(range(planes.num_planes), repeat=depth)
            if all(a != b for a, b in itertools.pairwise(s))]
    for seq in seqs:
        images = [point]
        for k in seq:
            images.append(_mirror(images[-1], normals[k], offsets[k]))
        # Bounce points, from the last wall back to the first: the line towards each image.
        pts, target = [], point
        ok = True
        for k, img in zip(reversed(seq), reversed(images[1:])):
            n, off = normals[k], offsets[k]
            denom = n @ (img - target)
            t = (off - n @ target) / denom if abs(denom) > 1e-12 else -1.0
            if not 0.0 < t < 1.0:
                ok = False
                break
            target = target + t * (img - target)
            pts.append(target)
        if not ok:
            continue
        pts = pts[::-1]
        # Visibility with radaraug's intersection: each leg must first meet the expected wall,
        # and the last leg must reach the RX unobstructed.
        nodes = [point, *pts, point]
        for leg in range(len(nodes) - 1):
            a, b = nodes[leg], nodes[leg + 1]
            length = float(np.linalg.norm(b - a))
            hit = intersect(torch.tensor(a[None]), torch.tensor(((b - a) / length)[None]), tri,
                            t_min=1e-6, compiled=False)
            if leg < len(seq):
                face = int(hit.face[0])
                ok &= face >= 0 and int(planes.face_plane[face]) == seq[leg]
                ok &= abs(float(hit.t[0]) - length) < 1e-6
            else:
                ok &= not bool(hit.valid[0]) or float(hit.t[0]) > length - 1e-6
        if not ok:
            continue
        total = sum(float(np.linalg.norm(b - a)) for a, b in itertools.pairwise(nodes))
        op, d = np.eye(3, dtype=complex), (pts[0] - point) / np.linalg.norm(pts[0] - point)
        for k in seq:
            step, d = _bounce_operator(d, normals[k], keys[k])
            op = step @ op
        # Restrict to the transverse plane of the departure direction, then Frobenius norm.
        d0 = (pts[0] - point) / np.linalg.norm(pts[0] - point)
        op = op @ (np.eye(3) - np.outer(d0, d0))
        power = float(np.sum(np.abs(op) ** 2)) * (lam / (4 * math.pi * total)) ** 2
        out[seq] = (total / SPEED_OF_LIGHT, power)
    return out


def _sionna_paths(room, planes: MirrorPlanes, point: np.ndarray, tmp_path: Path):
    """Sionna RT specular paths ``{wall sequence: (delay_s, sum|a|^2)}`` and the Sionna materials."""
    rt = sionna_rt
    verts = room.vertices.to(torch.float64).numpy()
    faces = room.faces.numpy()
    objects, obj_plane, mats = [], {}, {}
    for k in range(planes.num_planes):
        f = faces[(planes.face_plane == k).numpy()]
        used, f_local = np.unique(f, return_inverse=True)
        fname = tmp_path / f"wall{k}.ply"
        _write_ply(fname, verts[used], f_local.reshape(-1, 3))
        name, thickness = parse_material_key(room.materials[int(planes.plane_material[k])])
        mat = rt.ITURadioMaterial(name=f"wall{k}-{name}", itu_type=name, thickness=thickness)
        mats[k] = (mat, room.materials[int(planes.plane_material[k])])
        objects.append(rt.SceneObject(fname=str(fname), name=f"wall{k}", radio_material=mat))
    scene = rt.load_scene()
    scene.frequency = FREQ_HZ  # before adding materials: floorboard is defined for 50-100 GHz only
    scene.edit(add=objects)
    for k in range(planes.num_planes):
        obj_plane[int(scene.objects[f"wall{k}"].object_id)] = k
    array = dict(num_rows=1, num_cols=1, vertical_spacing=0.5, horizontal_spacing=0.5, pattern="iso",
                 polarization="VH")
    scene.tx_array = rt.PlanarArray(**array)
    scene.rx_array = rt.PlanarArray(**array)
    scene.add(rt.Transmitter(name="tx", position=[float(x) for x in point]))
    scene.add(rt.Receiver(name="rx", position=[float(x) for x in point]))
    paths = rt.PathSolver()(scene, max_depth=MAX_DEPTH, los=False, specular_reflection=True,
                            diffuse_reflection=False, refraction=False, diffraction=False,
                            synthetic_array=True)
    a_re, a_im = (np.asarray(x, dtype=np.float64) for x in paths.a)  # (1, 2, 1, 2, P)
    power = (a_re**2 + a_im**2).sum(axis=(0, 1, 2, 3))
    tau = np.asarray(paths.tau, dtype=np.float64).reshape(-1)
    valid = np.asarray(paths.valid).reshape(-1, tau.size).any(0)
    inter = np.asarray(paths.interactions).reshape(MAX_DEPTH, -1)
    objs = np.asarray(paths.objects).reshape(MAX_DEPTH, -1)
    out = {}
    for i in np.nonzero(valid)[0]:
        depth = int((inter[:, i] != rt.constants.InteractionType.NONE).sum())
        assert (inter[:depth, i] == rt.constants.InteractionType.SPECULAR).all()
        seq = tuple(obj_plane[int(o)] for o in objs[:depth, i])
        assert seq not in out, f"Sionna returned wall sequence {seq} twice"
        out[seq] = (float(tau[i]), float(power[i]))
    return out, mats


@pytest.mark.parametrize("material_set", sorted(MATERIAL_SETS))
def test_specular_paths_match_sionna(material_set: str, tmp_path: Path) -> None:
    room = corridor(materials=MATERIAL_SETS[material_set],
                    thickness_m=dict.fromkeys(CORRIDOR_SURFACES, THICKNESS_M), dtype=torch.float64)
    planes = MirrorPlanes(room, min_area_m2=1.0, device=torch.device("cpu"), dtype=torch.float64)
    assert planes.num_planes == 6 and planes.plane_material is not None
    point = np.asarray(POINT, dtype=np.float64)

    ref = _radaraug_paths(room, planes, point)
    got, mats = _sionna_paths(room, planes, point, tmp_path)

    # Same material parameters on both sides (both use ITU-R P.2040 Table 3).
    for mat, key in mats.values():
        m = get_material(key)
        assert float(mat.thickness[0]) == pytest.approx(m.thickness_m)
        assert float(mat.relative_permittivity[0]) == pytest.approx(m.permittivity(FREQ_HZ).real, rel=1e-5)
        assert float(mat.conductivity[0]) == pytest.approx(m.conductivity(FREQ_HZ), rel=1e-5)

    # With TX = RX the specular paths are the 6 single bounces at normal incidence and the 6 double
    # bounces between parallel walls. The 24 double bounces via two perpendicular walls degenerate:
    # the unfolded ray runs through the shared edge, both bounce points coincide on it (a corner /
    # diffraction case), and neither side returns them as specular paths.
    assert len(ref) == 6 + 6
    assert all(len(s) == 1 or abs(float(planes.normals[s[0]] @ planes.normals[s[1]])) > 0.999 for s in ref)
    assert sorted(got) == sorted(ref)
    delay_err = max(abs(got[s][0] - ref[s][0]) for s in ref)
    power_err = max(abs(10 * math.log10(got[s][1] / ref[s][1])) for s in ref)
    print(f"{material_set}: {len(ref)} paths, max delay error {delay_err * 1e9:.2e} ns, "
          f"max power error {power_err:.2e} dB")
    assert delay_err < 1e-12, f"max delay error {delay_err * 1e9:.2e} ns"
    assert power_err < 0.5, f"max power error {power_err:.3f} dB"
