"""Fitting the twin's noise figure to a capture's floor, checked against the radiometer law."""

import pytest
import torch

from radaraug.diagnosis.noise_fit import fit_noise_figure, noise_fit_receiver
from radaraug.errors import CalibrationError
from radaraug.io.summary import noise_floor_db
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import ADC_NOISE_RMS_COUNTS
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.twin import DigitalTwin
from radaraug.transforms import RangeDoppler, ToDecibels

FAST = {"rays": 16}


def _floor(twin, nf, adc=None):
    rx = FMCWReceiver(twin.config, noise_figure_dB=nf, adc_noise_rms_counts=adc)
    g = torch.Generator().manual_seed(3)
    times = twin.frame_times(range(6))
    x = rx(twin.paths([], times), generator=g, frame_start_s=times, static_signal=twin.static_signal())
    return noise_floor_db(ToDecibels()(RangeDoppler()(x)))


@pytest.fixture(scope="module")
def twin():
    scene = Scene.builtin("corridor")
    return DigitalTwin(scene, tracer_options=FAST)


def test_fit_recovers_a_known_noise_offset(twin):
    # the target is the floor of the same twin with both noise sources 6.5 dB up (not the 0 dB start)
    target = _floor(twin, 18.5, ADC_NOISE_RMS_COUNTS * 10 ** (6.5 / 20))
    fit = fit_noise_figure(twin.scene, twin.config, target, twin=twin)
    assert fit["noise_offset_dB"] == pytest.approx(6.5, abs=0.3)
    assert fit["noise_figure_dB"] == pytest.approx(18.5, abs=0.3)
    assert fit["adc_noise_rms_counts"] == pytest.approx(ADC_NOISE_RMS_COUNTS * 10 ** (6.5 / 20), rel=0.05)
    assert abs(fit["twin_floor_db"] - target) <= 0.15
    rx = noise_fit_receiver(twin.config, fit)
    assert float(rx.effect("adc_noise").rms_counts) == pytest.approx(fit["adc_noise_rms_counts"], rel=1e-5)
    # kT0 F B: +6 dB of noise figure is +6 dB of floor (thermal noise alone, well above quantization)
    assert _floor(twin, 36.0, 0.0) - _floor(twin, 30.0, 0.0) == pytest.approx(6.0, abs=0.3)


def test_unreachable_floor_is_a_clear_error(twin):
    with pytest.raises(CalibrationError, match="noise figure"):
        fit_noise_figure(twin.scene, twin.config, -20.0, twin=twin)
