"""ITU-R P.2040 materials and Fresnel / slab reflection against closed forms."""

from __future__ import annotations

import math
import warnings

import pytest
import torch

from radaraug.config import SPEED_OF_LIGHT
from radaraug.errors import SceneError
from radaraug.scene.materials import (
    MATERIALS,
    Material,
    fresnel_coefficients,
    get_material,
    material_table,
    parse_material_key,
    reflection_coefficients,
    register_material,
    slab_reflection,
    slab_transmission,
)

F_C = 60e9

# ITU-R P.2040 table: |Gamma|^2 at normal incidence, 60 GHz, half-space.
NORMAL_INCIDENCE_DB = {
    "concrete": -8.1,
    "plasterboard": -12.2,
    "wood": -15.3,
    "glass": -7.3,
    "ceiling_board": -20.2,
    "chipboard": -12.6,
    "floorboard": -10.0,
    "metal": -0.01,
}


def _complex(dtype: torch.dtype) -> torch.dtype:
    return torch.complex128 if dtype == torch.float64 else torch.complex64


@pytest.mark.parametrize("name", sorted(NORMAL_INCIDENCE_DB))
def test_normal_incidence_power_matches_table(name: str) -> None:
    te, tm = get_material(name).reflection(torch.tensor(1.0, dtype=torch.float64), F_C)
    db = 10 * math.log10(abs(te.item()) ** 2)
    assert db == pytest.approx(NORMAL_INCIDENCE_DB[name], abs=0.1)
    assert abs(tm.item()) == pytest.approx(abs(te.item()), rel=1e-12)


def test_permittivity_closed_form() -> None:
    concrete = get_material("concrete")
    eps = concrete.permittivity(F_C)
    sigma = 0.0462 * 60 ** 0.7822
    assert eps.real == pytest.approx(5.24)
    assert eps.imag == pytest.approx(-17.98 * sigma / 60)
    assert concrete.conductivity(F_C) == pytest.approx(sigma)


def test_skin_and_absorber() -> None:
    assert get_material("skin").permittivity(60e9) == complex(7.98, -10.90)
    assert get_material("skin").permittivity(57e9) == complex(7.98, -10.90)
    # Absorber = free space: exactly no reflection at any angle.
    cos = torch.linspace(0.0, 1.0, 11, dtype=torch.float64)
    te, tm = get_material("absorber").reflection(cos, F_C)
    assert te.abs().max() < 1e-12 and tm.abs().max() < 1e-12


def test_brick_warns_above_40_GHz() -> None:
    with pytest.warns(UserWarning, match="brick"):
        get_material("brick").permittivity(60e9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        get_material("brick").permittivity(30e9)


def test_required_materials_present() -> None:
    for name in ("concrete", "brick", "plasterboard", "wood", "glass", "ceiling_board", "chipboard",
                 "floorboard", "metal", "skin", "absorber"):
        assert name in MATERIALS


def test_unknown_material_lists_names() -> None:
    with pytest.raises(SceneError, match="concrete"):
        get_material("unobtainium")
    with pytest.raises(SceneError, match="thickness"):
        get_material("concrete@abc")
    with pytest.raises(SceneError):
        get_material("concrete@-1")


def test_thickness_key_round_trip() -> None:
    m = get_material("plasterboard@0.0125")
    assert m.thickness_m == 0.0125 and m.name == "plasterboard"
    assert get_material(m.key) == m
    assert parse_material_key("wood") == ("wood", None)
    assert parse_material_key("wood@0.02m") == ("wood", 0.02)


def test_register_material() -> None:
    custom = Material("test_only_foam", 1.1, 0.0, 0.0, 0.0)
    register_material(custom)
    try:
        assert get_material("test_only_foam") is custom
        with pytest.raises(SceneError, match="exists"):
            register_material(custom)
        with pytest.raises(SceneError, match="thickness"):
            register_material(Material("x_slab", 2.0, 0, 0, 0, thickness_m=0.1))
    finally:
        del MATERIALS["test_only_foam"]


def test_brewster_angle_lossless(device: torch.device, dtype: torch.dtype) -> None:
    for eps_r in (2.0, 4.0, 6.31):
        theta_b = math.atan(math.sqrt(eps_r))
        cos = torch.tensor([math.cos(theta_b)], dtype=dtype, device=device)
        eps = torch.tensor([eps_r], dtype=_complex(dtype), device=device)
        te, tm = fresnel_coefficients(eps, cos)
        assert te.dtype == _complex(dtype) and te.device.type == device.type
        assert tm.abs().item() < (1e-5 if dtype == torch.float32 else 1e-12)
        # TE closed form at Brewster: (cos - sqrt(eps - sin^2)) / (cos + ...).
        c, s2 = math.cos(theta_b), math.sin(theta_b) ** 2
        expected = (c - math.sqrt(eps_r - s2)) / (c + math.sqrt(eps_r - s2))
        assert te.real.item() == pytest.approx(expected, rel=1e-5)


def test_grazing_goes_to_minus_one(device: torch.device, dtype: torch.dtype) -> None:
    eps, _ = material_table(list(NORMAL_INCIDENCE_DB), F_C, device=device, dtype=dtype)
    cos = torch.zeros(len(NORMAL_INCIDENCE_DB), dtype=dtype, device=device)
    te, tm = fresnel_coefficients(eps, cos)
    torch.testing.assert_close(te, torch.full_like(te, -1), atol=1e-4, rtol=0)
    # Metal's enormous eps keeps TM away from -1 until extremely close to grazing; dielectrics only.
    torch.testing.assert_close(tm[:-1], torch.full_like(tm[:-1], -1), atol=1e-4, rtol=0)


@pytest.mark.filterwarnings("ignore:material .brick.")
def test_normal_incidence_te_equals_minus_tm(dtype: torch.dtype) -> None:
    eps, _ = material_table(list(MATERIALS), F_C, dtype=dtype)
    te, tm = fresnel_coefficients(eps, torch.ones(len(MATERIALS), dtype=dtype))
    torch.testing.assert_close(te, -tm)
    expected = (1 - torch.sqrt(eps)) / (1 + torch.sqrt(eps))
    torch.testing.assert_close(te, expected)


def test_oblique_closed_form_snell() -> None:
    # Lossless eps = 4 (n = 2) at 30 degrees via Snell's law and the textbook Fresnel formulas.
    n, th = 2.0, math.radians(30)
    th_t = math.asin(math.sin(th) / n)
    rs = (math.cos(th) - n * math.cos(th_t)) / (math.cos(th) + n * math.cos(th_t))
    rp = (n * math.cos(th) - math.cos(th_t)) / (n * math.cos(th) + math.cos(th_t))
    te, tm = fresnel_coefficients(torch.tensor(4.0 + 0j, dtype=torch.complex128),
                                  torch.tensor(math.cos(th), dtype=torch.float64))
    assert te.real.item() == pytest.approx(rs, rel=1e-12)
    assert tm.real.item() == pytest.approx(rp, rel=1e-12)


def test_lossy_has_no_exact_brewster_zero_and_magnitude_below_one() -> None:
    eps, _ = material_table(["concrete", "glass"], F_C, dtype=torch.float64)
    cos = torch.linspace(0, 1, 1001, dtype=torch.float64)[:, None]
    te, tm = fresnel_coefficients(eps, cos)
    assert (te.abs() <= 1).all() and (tm.abs() <= 1).all()
    assert tm.abs().min() > 1e-3


def test_slab_half_wave_zero_and_energy(dtype: torch.dtype) -> None:
    eps_r = 2.73
    lam = SPEED_OF_LIGHT / F_C
    d = lam / (2 * math.sqrt(eps_r))
    eps = torch.tensor(eps_r + 0j, dtype=_complex(dtype))
    te, tm = slab_reflection(eps, d, F_C, torch.tensor(1.0, dtype=dtype))
    assert te.abs().item() < 1e-5 and tm.abs().item() < 1e-5
    # Energy conservation over angles and thicknesses for a lossless slab.
    cos = torch.linspace(0.05, 1.0, 20, dtype=dtype)[:, None]
    thick = torch.tensor([0.001, 0.0125, 0.05, 0.1], dtype=dtype)
    r_te, r_tm = slab_reflection(eps, thick, F_C, cos)
    t_te, t_tm = slab_transmission(eps, thick, F_C, cos)
    tol = 1e-5 if dtype == torch.float32 else 1e-12
    torch.testing.assert_close(r_te.abs() ** 2 + t_te.abs() ** 2, torch.ones_like(cos * thick), atol=tol, rtol=0)
    torch.testing.assert_close(r_tm.abs() ** 2 + t_tm.abs() ** 2, torch.ones_like(cos * thick), atol=tol, rtol=0)


def test_slab_lossy_energy_below_one() -> None:
    eps = torch.tensor(get_material("concrete").permittivity(F_C), dtype=torch.complex128)
    cos = torch.linspace(0.05, 1.0, 20, dtype=torch.float64)
    r, _ = slab_reflection(eps, 0.01, F_C, cos)
    t, _ = slab_transmission(eps, 0.01, F_C, cos)
    assert ((r.abs() ** 2 + t.abs() ** 2) < 1).all()


def test_thick_lossy_slab_is_half_space() -> None:
    eps = torch.tensor(get_material("concrete").permittivity(F_C), dtype=torch.complex128)
    cos = torch.linspace(0.1, 1.0, 10, dtype=torch.float64)
    s_te, s_tm = slab_reflection(eps, 0.5, F_C, cos)
    h_te, h_tm = fresnel_coefficients(eps, cos)
    torch.testing.assert_close(s_te, h_te, atol=1e-9, rtol=0)
    torch.testing.assert_close(s_tm, h_tm, atol=1e-9, rtol=0)


def test_ceiling_board_slab_vs_half_space() -> None:
    # A 10 cm ceiling board is thin and low-loss: its back face matters at the 0.1-1 dB level.
    cb = get_material("ceiling_board")
    half = 20 * math.log10(abs(cb.reflection(torch.tensor(1.0, dtype=torch.float64), F_C)[0].item()))
    slab = 20 * math.log10(abs(cb.with_thickness(0.1).reflection(torch.tensor(1.0, dtype=torch.float64),
                                                                  F_C)[0].item()))
    assert 0.05 < abs(slab - half) < 1.0


def test_reflection_coefficients_selects_per_face(device: torch.device, dtype: torch.dtype) -> None:
    names = ["concrete", "plasterboard@0.0125", "metal", "ceiling_board@0.1"]
    eps, thick = material_table(names, F_C, device=device, dtype=dtype)
    assert torch.isnan(thick[0]) and thick[1].item() == pytest.approx(0.0125)
    face = torch.tensor([[0, 1], [2, 3], [1, 0]], device=device)
    cos = torch.tensor([[1.0, 0.7], [0.3, 0.9], [0.5, 0.2]], dtype=dtype, device=device)
    te, tm = reflection_coefficients(eps, thick, face, cos, F_C)
    assert te.shape == (3, 2) and te.dtype == _complex(dtype) and te.device.type == device.type
    for i in range(3):
        for j in range(2):
            m = get_material(names[face[i, j].item()])
            e_te, e_tm = m.reflection(cos[i, j].cpu(), F_C)
            torch.testing.assert_close(te[i, j].cpu(), e_te.to(te.dtype))
            torch.testing.assert_close(tm[i, j].cpu(), e_tm.to(tm.dtype))
    # thickness 0 also means half-space
    te0, _ = reflection_coefficients(eps, torch.zeros_like(thick), face, cos, F_C)
    torch.testing.assert_close(te0[0, 0], fresnel_coefficients(eps[0], cos[0, 0])[0])


def test_gradients_finite_and_correct() -> None:
    names = ["concrete", "plasterboard@0.0125", "absorber", "metal"]
    eps, thick = material_table(names, F_C, dtype=torch.float64)
    face = torch.tensor([0, 1, 2, 3, 2])
    cos = torch.tensor([0.9, 0.5, 0.0, 0.2, 1.0], dtype=torch.float64, requires_grad=True)
    te, tm = reflection_coefficients(eps, thick, face, cos, F_C)
    (te.abs() ** 2 + tm.abs() ** 2).sum().backward()
    assert torch.isfinite(cos.grad).all()
    # d|Gamma_TE|^2/dcos for lossless eps = 4 by finite differences of the closed form.
    eps4 = torch.tensor(4.0 + 0j, dtype=torch.complex128, requires_grad=True)
    c = torch.tensor(0.6, dtype=torch.float64, requires_grad=True)
    torch.autograd.gradcheck(lambda e, x: fresnel_coefficients(e, x)[0], (eps4, c))
    torch.autograd.gradcheck(lambda e, x: slab_reflection(e, 0.01, F_C, x)[1], (eps4, c))


def test_material_validation() -> None:
    with pytest.raises(SceneError):
        Material("bad@name", 1, 0, 0, 0)
    with pytest.raises(SceneError):
        Material("slab", 2, 0, 0, 0, thickness_m=-0.1)
    with pytest.raises(SceneError):
        get_material("concrete").permittivity(-1.0)
