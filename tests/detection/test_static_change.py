"""The zero-Doppler change detector against closed forms: noise statistics, a static point target, Doppler."""

from __future__ import annotations

import math

import pytest
import torch

from radaraug.config import RadarConfig
from radaraug.detection import StaticChangeDetector, zero_doppler_profile
from radaraug.errors import ConfigError

CFG = RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16)
SIGMA = 2.0  # ADC noise, counts RMS per sample


def noise(frames: int, g: torch.Generator) -> torch.Tensor:
    shape = (frames, CFG.num_rx, CFG.num_chirps_per_frame, CFG.num_samples_per_chirp)
    return 2048 + SIGMA * torch.randn(shape, generator=g, dtype=torch.float64)


def tone(range_m: float, amplitude: float, doppler_bins: float = 0.0) -> torch.Tensor:
    """A point target's beat tone on every RX: f_b = 2 R slope / c, chirp phase 2 pi k doppler_bins / chirps."""
    fs, n, c = CFG.sample_rate_Hz, CFG.num_samples_per_chirp, CFG.num_chirps_per_frame
    t = torch.arange(n, dtype=torch.float64) / fs
    k = torch.arange(c, dtype=torch.float64)[:, None]
    x = amplitude * torch.cos(2 * math.pi * CFG.beat_Hz_per_m * range_m * t + 2 * math.pi * doppler_bins * k / c + 0.3)
    return x.expand(CFG.num_rx, c, n)


def test_empty_frames_exceed_the_calibrations_largest_with_probability_one_over_n_plus_one() -> None:
    """Exchangeable empty frames: P(a new score > the largest of n leave-one-out scores) = 1 / (n + 1)."""
    g = torch.Generator().manual_seed(0)
    n, trials, tests = 19, 150, 20
    hits = 0
    for _ in range(trials):
        det = StaticChangeDetector.fit(noise(n, g), CFG, margin_db=0.0)
        hits += int(det.detect(noise(tests, g)).sum())
    rate = hits / (trials * tests)
    assert rate == pytest.approx(1 / (n + 1), abs=0.015)  # 0.05; binomial sd 0.004, trials share a fit


def test_noise_change_per_cell_follows_the_gamma_law_of_a_mean_over_receivers() -> None:
    """White noise: each RX's |change|^2 / spread is ~Exp(1) x (1 + 1/n) (the reference's own noise), and
    their mean over R receivers Gamma(R, 1/R). (Hann-windowed bins are correlated, so the largest over
    range has no closed form; the threshold's law is the distribution-free test above.)"""
    g = torch.Generator().manual_seed(1)
    n = 400
    det = StaticChangeDetector.fit(noise(n, g), CFG, margin_db=0.0)
    p = zero_doppler_profile(noise(1000, g))
    z = ((p - det.reference).abs().square() / det.spread).mean(1) / (1 + 1 / n)  # (frames, range)
    z = z[:, det.first_bin:-1].flatten()  # the last bin sits next to Nyquist's real-valued one
    r = CFG.num_rx
    for t in (0.3, 1.0, 2.0, 3.0):
        # Gamma(R, 1/R) CDF at t for integer R: 1 - exp(-R t) sum_{k<R} (R t)^k / k!
        cdf = 1 - math.exp(-r * t) * sum((r * t) ** k / math.factorial(k) for k in range(r))
        assert float((z <= t).double().mean()) == pytest.approx(cdf, abs=0.01)
    # the frame's score is the largest over range of that cell statistic, in dB
    s = det.score(noise(5, g))
    assert s.shape == (5,) and bool((s > 0).all())


def test_a_static_target_scores_its_snr_at_its_range_bin_and_a_moving_one_nothing() -> None:
    """A tone of amplitude a at zero Doppler adds a * sum(w) / 2 to its bin of the chirp-mean profile,
    against noise of variance sigma^2 sum(w^2) / chirps per bin: the score is that ratio (+1, the noise),
    at bin f_b / (fs / samples). At an integer Doppler bin the chirp mean cancels the tone (Dirichlet zero)."""
    g = torch.Generator().manual_seed(2)
    det = StaticChangeDetector.fit(noise(200, g), CFG, margin_db=0.0)
    w = torch.hann_window(CFG.num_samples_per_chirp, periodic=False, dtype=torch.float64)
    a, k = 1.5, 9  # counts; range bin
    range_on_bin = k * CFG.sample_rate_Hz / CFG.num_samples_per_chirp / CFG.beat_Hz_per_m  # f_b on bin k
    frames = noise(300, g) + tone(range_on_bin, a)
    p = zero_doppler_profile(frames)
    change = (p - det.reference).abs().square().mean(1).mean(0)  # mean over RX and frames, per range bin
    assert int(change[det.first_bin:].argmax()) + det.first_bin == k
    snr = (a * float(w.sum()) / 2) ** 2 / (SIGMA**2 * float(w.square().sum()) / CFG.num_chirps_per_frame)
    expected = snr + 1  # + the noise's own mean spread
    measured = float(change[k] / det.spread[:, k].mean())
    assert 10 * math.log10(measured) == pytest.approx(10 * math.log10(expected), abs=0.5)
    assert bool(det.detect(frames).all())
    moving = noise(300, g) + tone(range_on_bin, a, doppler_bins=3.0)
    assert float(det.detect(moving).double().mean()) < 0.2  # noise-only false alarms, not the target


def test_bad_inputs_raise_a_config_error() -> None:
    g = torch.Generator().manual_seed(3)
    with pytest.raises(ConfigError, match="at least 3"):
        StaticChangeDetector.fit(noise(2, g), CFG)
    with pytest.raises(ConfigError, match="do not match"):
        StaticChangeDetector.fit(noise(5, g)[..., :32], CFG)
    det = StaticChangeDetector.fit(noise(5, g), CFG)
    with pytest.raises(ConfigError, match="do not match"):
        det.score(noise(2, g)[:, :2])
    with pytest.raises(ConfigError, match="no range bin"):
        StaticChangeDetector.fit(noise(5, g), CFG, min_range_m=1e3)
    with pytest.raises(ConfigError, match="margin_db"):
        StaticChangeDetector.fit(noise(5, g), CFG, margin_db=float("nan"))


def test_from_and_over_a_capture_a_chunk_at_a_time(tmp_path, monkeypatch) -> None:
    """A capture file gives what its frames give, read in chunks (a long recording is never held whole)."""
    import radaraug.detection.static_change as sc
    from radaraug.io import write_capture

    g = torch.Generator().manual_seed(4)
    empty, test = noise(11, g).round(), (noise(9, g) + tone(3.0, 4.0)).round()
    write_capture(tmp_path / "empty.h5", empty.to(torch.int32), CFG)
    write_capture(tmp_path / "test.h5", test.to(torch.int32), CFG)
    monkeypatch.setattr(sc, "CHUNK_FRAMES", 4)
    det = StaticChangeDetector.from_capture(tmp_path / "empty.h5")
    ref = StaticChangeDetector.fit(empty, CFG)
    assert det.threshold_db == pytest.approx(ref.threshold_db, abs=1e-9)
    assert torch.equal(det.detect_capture(tmp_path / "test.h5"), ref.detect(test))
    assert len(StaticChangeDetector.from_capture(tmp_path / "empty.h5", max_frames=5).calibration_scores_db) == 5
