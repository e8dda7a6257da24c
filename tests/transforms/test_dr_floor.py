"""CalibratedDR's empirical floor against the closed form of a receiver's noise in dB.

Noise power in an RD cell is exponential (``|X|**2`` of a complex Gaussian), so its dB value has
quantiles ``q(p) = 10 log10(-P0 ln(1 - p))``: the test maps below are drawn from that law, with
static clutter at zero Doppler, and the fitted quantiles and the floor's draws are checked against
it (not against radaraug's own output).
"""

from __future__ import annotations

import json
import math

import pytest
import torch

from radaraug.cli import main
from radaraug.errors import CalibrationError, InputTensorError
from radaraug.transforms import CalibratedDR, InterferenceExcision, RadarCompose, RangeDoppler, ToDecibels
from radaraug.transforms import functional as F
from radaraug.transforms.floor_fit import QUANTILES

P0_DB = -100.0  # mean noise power per cell, dB
CLUTTER_DB = -40.0


def closed_form_db(p: float) -> float:
    """The p-quantile of 10 log10 of exponential power with mean P0."""
    return P0_DB + 10 * math.log10(-math.log1p(-p))


def noise_maps(frames: int = 60, seed: int = 0) -> torch.Tensor:
    """(frames, rx, range, doppler) dB maps: exponential noise, static clutter at zero Doppler."""
    g = torch.Generator().manual_seed(seed)
    power = torch.empty(frames, 2, 64, 32, dtype=torch.float64).exponential_(generator=g)
    maps = P0_DB + 10 * torch.log10(power)
    maps[..., 16] = CLUTTER_DB  # zero Doppler (centred), what the twin simulates itself
    return maps


@pytest.fixture(scope="module")
def fitted() -> CalibratedDR:
    return CalibratedDR.fit(noise_maps(), input="db", floor="empirical", seed=0)


def test_the_fitted_quantiles_are_the_noise_law_and_leave_the_clutter_out(fitted) -> None:
    q = fitted.quantiles_db
    assert q.shape == (QUANTILES,) and bool((q.diff() >= 0).all())
    for k in (10, 102, 512, 922, 1014, 1023):  # probability k / 1024: 0.01 ... 0.999
        assert float(q[k]) == pytest.approx(closed_form_db(k / (QUANTILES - 1)), abs=0.15), k
    assert float(q[-1]) < CLUTTER_DB - 30  # the zero-Doppler clutter is not in the floor
    # the paper's statistics are unchanged: mean and std of all values, clutter included
    maps = noise_maps()
    assert fitted.mean_db == pytest.approx(float(maps.mean()), abs=1e-9)


def test_the_empirical_floor_has_the_noise_tail_the_normal_one_does_not(fitted) -> None:
    low = torch.full((40, 2, 64, 32), -300.0, dtype=torch.float64)
    empirical = fitted(low).flatten()
    # the noise law's own mean and std in dB: -10 gamma / ln 10 and (10 / ln 10) pi / sqrt 6
    mean, std = P0_DB - 10 * 0.5772156649 / math.log(10), 10 / math.log(10) * math.pi / math.sqrt(6)
    normal = CalibratedDR(mean, std, seed=0)(low).flatten()
    probs = torch.tensor([0.5, 0.99, 0.999], dtype=torch.float64)
    e = torch.quantile(empirical[::3], probs).tolist()
    for got, p in zip(e, probs.tolist(), strict=True):
        assert got == pytest.approx(closed_form_db(p), abs=0.3), p
    # a normal with the same mean and std (5.57 dB) puts the 99.9th percentile 6.3 dB higher
    # (closed forms: -102.5 + 3.09 * 5.57 = -85.3 dB vs -91.6 dB): the spikes a classifier trained on
    # the paper's CDR learns to call floor
    n999 = float(torch.quantile(normal[::3], torch.tensor(0.999, dtype=torch.float64)))
    assert n999 == pytest.approx(mean + 3.0902 * std, abs=0.5)
    assert n999 - closed_form_db(0.999) > 5.5


def test_draws_are_reproducible_and_stay_within_the_table(fitted) -> None:
    x = torch.full((4, 2, 64, 32), -300.0)
    g1, g2 = torch.Generator().manual_seed(7), torch.Generator().manual_seed(7)
    f1 = F.empirical_floor(x.shape, fitted.quantiles_db, like=x, generator=g1)
    f2 = F.empirical_floor(x.shape, fitted.quantiles_db, like=x, generator=g2)
    assert torch.equal(f1, f2) and f1.dtype == torch.float32
    q = fitted.quantiles_db
    assert float(f1.min()) >= float(q[0]) - 1e-4 and float(f1.max()) <= float(q[-1]) + 1e-4
    with pytest.raises(InputTensorError, match="1-D"):
        F.empirical_floor(x.shape, q.reshape(5, -1), like=x)


def test_save_load_keeps_the_floor_and_an_older_reader_refuses_it(fitted, tmp_path) -> None:
    path = tmp_path / "cdr.json"
    fitted.save(path)
    data = json.loads(path.read_text())
    # A calibration record: radaraug before it read only "radaraug.CalibratedDR" files, so it refuses this one
    # rather than draw a normal floor from it.
    assert data["format"] == "radaraug-calibration" and data["format"] != "radaraug.CalibratedDR"
    assert data["cdr"]["floor"] == "empirical" and len(data["cdr"]["quantiles_db"]) == QUANTILES
    back = CalibratedDR.load(path, seed=3)
    assert back.floor == "empirical"
    assert torch.allclose(back.quantiles_db, fitted.quantiles_db, atol=1e-4)
    x = torch.full((2, 2, 64, 32), -300.0)
    assert torch.equal(back(x), CalibratedDR.load(path, seed=3)(x))
    normal = CalibratedDR.load(path, floor="normal")  # the file's floor can be overridden
    normal.save(tmp_path / "n.json")
    assert json.loads((tmp_path / "n.json").read_text())["cdr"]["floor"] == "normal"


def test_bad_floor_arguments_are_refused(tmp_path) -> None:
    with pytest.raises(CalibrationError, match="floor must be one of"):
        CalibratedDR(-100, 5, floor="gaussian")
    with pytest.raises(CalibrationError, match="needs the floor's quantiles"):
        CalibratedDR(-100, 5, floor="empirical")
    for bad in ([-90.0, -100.0], [float("nan"), 1.0], [1.0], "abc", [[1.0, 2.0]]):
        with pytest.raises(CalibrationError, match="quantiles_db"):
            CalibratedDR(-100, 5, floor="empirical", quantiles_db=bad)
    old = tmp_path / "old.json"  # a calibration written before the empirical floor existed
    old.write_text(json.dumps({"format": "radaraug.CalibratedDR", "format_version": 1, "mean_db": -100, "std_db": 5}))
    with pytest.raises(CalibrationError, match=f"{old}.*refit"):
        CalibratedDR.load(old, floor="empirical")


def test_fit_cdr_cli_writes_the_floor_it_is_asked_for(tmp_path, capsys, cfg) -> None:
    from radaraug.io import write_capture
    from radaraug.units import counts_to_float, float_to_counts

    g = torch.Generator().manual_seed(1)
    counts = float_to_counts(1e-3 * torch.randn(20, 3, 32, 128, generator=g, dtype=torch.float64))
    write_capture(tmp_path / "empty.h5", counts.numpy().astype("uint16"), cfg)
    assert main(["fit-cdr", str(tmp_path / "empty.h5"), "-o", str(tmp_path / "cdr.json"), "--floor", "empirical"]) == 0
    assert "empirical floor" in capsys.readouterr().out
    cdr = CalibratedDR.load(tmp_path / "cdr.json")
    assert cdr.floor == "empirical" and cdr.quantiles_db.shape == (QUANTILES,)
    # fitted on the recipes' maps (bursts excised first): it composes after that chain, and refuses another
    low = RadarCompose([InterferenceExcision(), RangeDoppler(), ToDecibels(), cdr])(counts_to_float(counts))
    assert low.shape == (20, 3, 64, 32)
    with pytest.raises(CalibrationError, match="InterferenceExcision"):
        RadarCompose([RangeDoppler(), ToDecibels(), cdr])
    # --excise-interference-db off: the paper's chain
    assert main(["fit-cdr", str(tmp_path / "empty.h5"), "-o", str(tmp_path / "plain.json"),
                 "--excise-interference-db", "off"]) == 0
    plain = CalibratedDR.load(tmp_path / "plain.json")
    assert RadarCompose([RangeDoppler(), ToDecibels(), plain])(counts_to_float(counts)).shape == (20, 3, 64, 32)


@pytest.mark.real
def test_on_real_static_recordings_the_normal_floor_overshoots_the_measured_tail(real_data) -> None:
    # The two recordings without motion (below the warning threshold; 23 and 38 dB IF gain)
    static = [
        next((real_data / "ssalehi152431__Beamforming-with-Infineon-BGT60TR13C/Beamforming/beamforming_data")
             .glob("2_reflectors*")),
        real_data / "jjustin__ec-international-2022/recordings/recording_2022_05_25_18_53_49",
    ]
    for folder in static:
        cdr = CalibratedDR.fit(folder, floor="empirical")
        assert cdr.motion is not None and cdr.motion < 1e-3, folder  # no motion warning
        measured = float(cdr.quantiles_db[1023])  # p = 0.999, off zero Doppler
        normal = cdr.mean_db + 3.0902 * cdr.std_db
        # measured: 10.4 dB (23 dB IF gain) and 11.7 dB (38 dB) below the paper's normal floor
        assert normal - measured > 8.0, (folder.name, normal, measured)
