"""The training chain's inputs: sizes and clip ranges are checked where they are given."""

import math

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.training import CDR, CDRProfile, ImageSpec, RadarDataModule
from radaraug.training.pipeline import floor_texture, image_chain, noise_texture_db


def test_image_size_must_be_height_and_width():
    x = torch.full((2, 3, 8, 4), -90.0)
    assert image_chain(-120.0, -60.0, [6, 5])(x).shape == (2, 3, 6, 5)
    with pytest.raises(ConfigError, match=r"\[H, W\]"):
        image_chain(-120.0, -60.0, [6, 5, 4])


def test_max_resample_shrinks_the_levels_before_the_colour_map():
    # one cell 25 dB over a floor-relative floor of 0: the max keeps its colour, bilinear dims it
    x = torch.zeros(1, 3, 32, 16)
    x[..., 10, 5] = 25.0
    peak = image_chain(0.0, 25.0, [8, 4], resample="max")(x)
    top = image_chain(0.0, 25.0, None)(x)[..., 10, 5]  # the colour of a full-scale cell
    assert torch.allclose(peak[..., 2, 1], top) and peak.shape == (1, 3, 8, 4)
    assert not torch.allclose(image_chain(0.0, 25.0, [8, 4])(x)[..., 2, 1], top, atol=0.1)
    with pytest.raises(ConfigError, match="resample must be one of"):
        image_chain(0.0, 25.0, [8, 4], resample="nearest")
    with pytest.raises(ConfigError, match="resample must be one of"):
        ImageSpec(resample="nearest")  # type: ignore[arg-type]


def test_noise_texture_is_the_chi_square_closed_form_at_any_level():
    # one receiver: 10 log10 of an exponential, std 10/ln10 * pi/sqrt(6) = 5.57 dB; three: trigamma(3)
    assert noise_texture_db(1) == pytest.approx(10 / math.log(10) * math.pi / math.sqrt(6))
    assert noise_texture_db(3) == pytest.approx(10 / math.log(10) * math.sqrt(math.pi ** 2 / 6 - 1.25))
    with pytest.raises(ConfigError, match="rx >= 1"):
        noise_texture_db(0)
    g = torch.Generator().manual_seed(0)
    iq = torch.randn(8, 3, 128, 64, 2, generator=g, dtype=torch.float64)
    db = 10 * torch.log10(iq.square().sum(-1))
    quiet, loud = floor_texture(db - 120.0), floor_texture(db - 60.0)
    assert float(loud["level_db"].mean() - quiet["level_db"].mean()) == pytest.approx(60.0, abs=1e-3)
    for key in ("texture_std_db", "peak_db", "row_spread_db"):  # referenced to the row: the level cancels
        assert torch.allclose(quiet[key], loud[key], atol=1e-3)
    assert float(quiet["texture_std_db"].mean()) == pytest.approx(noise_texture_db(3), abs=0.05)
    # a floor whose rows sit at different levels keeps the same texture: the rows' spread moves instead
    tilted = db + torch.linspace(0, 20, 128, dtype=torch.float64)[:, None]
    assert torch.allclose(floor_texture(tilted)["texture_std_db"], quiet["texture_std_db"], atol=1e-3)
    assert float(floor_texture(tilted)["row_spread_db"].mean()) > 5.0


def test_clip_range_must_be_two_values_and_setup_must_run_first():
    with pytest.raises(ConfigError, match=r"\[vmin, vmax\]"):
        ImageSpec(clip_range=[-120.0])
    dm = RadarDataModule(image=ImageSpec(clip_range=[-120.0, -60.0]))
    assert dm.clip == (-120.0, -60.0)
    with pytest.raises(ConfigError, match="setup"):
        dm.images(torch.zeros(1, 3, 8, 4))
    dm.load_state_dict({"clip_range": [-110.0, -50.0], "interference_db": 6.0})
    assert dm.clip == (-110.0, -50.0)
    assert dm.state_dict() == {"clip_range": [-110.0, -50.0], "excise": None, "excise_shape": None,
                               "interference_db": 6.0, "resample": dm.image_spec.resample}
    # a checkpoint trained without the interference excision (or from before it) is not tested with it
    with pytest.raises(ConfigError, match="excise_interference_db: None"):
        dm.load_state_dict({"clip_range": [-110.0, -50.0]})
    old = RadarDataModule(image=ImageSpec(excise_interference_db=None, resample="bilinear"))
    old.load_state_dict({"clip_range": [-110.0, -50.0]})  # a checkpoint of before the resample option: bilinear
    assert old.clip == (-110.0, -50.0)
    with pytest.raises(ConfigError, match="resample: max"):
        old.load_state_dict({"clip_range": [-110.0, -50.0], "resample": "max"})


def test_cdr_floor_reaches_the_dr_and_is_checked(captures, tmp_path):
    from radaraug.transforms import CalibratedDR

    cal, _ = captures
    fitted = CalibratedDR.fit(cal, progress=False)
    assert CDR(floor=None).dr(fitted, seed=0).floor == "normal"  # the calibration's own (a capture: normal)
    emp = CDR(floor="empirical").dr(fitted, seed=1)
    assert emp.floor == "empirical" and torch.equal(emp.quantiles_db, fitted.quantiles_db)
    assert CDR().dr(fitted, seed=1).floor == "empirical"  # matched: empirical, then matched by the data module
    path = tmp_path / "cdr.json"
    CalibratedDR.fit(cal, progress=False, floor="empirical").save(path)
    assert CDR(floor=None).dr(str(path), seed=0).floor == "empirical"  # a JSON keeps its floor
    assert CDRProfile(floor="normal").dr(str(path), seed=0).floor == "normal"
    with pytest.raises(ConfigError, match="CDR floor must be one of"):
        CDR(floor="gaussian")  # type: ignore[arg-type]
