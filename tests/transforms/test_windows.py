import numpy as np
import pytest
import torch
from scipy.signal import windows as sw

from radaraug.errors import InputTensorError
from radaraug.transforms.windows import get_window, noise_power_gain, shifted_doppler_window

REFERENCE = {
    "rect": np.ones,
    "hann": np.hanning,
    "hamming": np.hamming,
    "blackman": np.blackman,
    "blackmanharris": lambda n: sw.blackmanharris(n, sym=True),
}


@pytest.mark.parametrize("name", sorted(REFERENCE))
@pytest.mark.parametrize("n", [1, 2, 7, 64])
def test_windows_are_numpy_scipy_symmetric_windows(name, n):
    w = get_window(name, n, torch.float64)
    np.testing.assert_allclose(w.numpy(), REFERENCE[name](n), rtol=0, atol=1e-14)


@pytest.mark.parametrize("n", [2, 3, 16, 64, 255])
def test_blackman_harris_is_the_closed_form_in_float64(n):
    # sum_k (-1)^k a_k cos(2 pi k i / (n - 1)), written out here independently of torch.signal
    a = (0.35875, 0.48829, 0.14128, 0.01168)
    i = np.arange(n)
    ref = sum((-1) ** k * a[k] * np.cos(2 * np.pi * k * i / (n - 1)) for k in range(4))
    np.testing.assert_allclose(get_window("blackmanharris", n, torch.float64).numpy(), ref, rtol=0, atol=1e-12)


def test_noise_power_gain_closed_forms():
    assert noise_power_gain("rect", 50) == pytest.approx(1 / 50)
    # symmetric Hann: sum w = (n-1)/2, sum w^2 = 3(n-1)/8  ->  gain = 3 / (2 (n-1))
    assert noise_power_gain("hann", 65) == pytest.approx(3 / (2 * 64))


def test_window_cache_and_errors():
    assert get_window("hanning", 16) is get_window("hanning", 16)
    with pytest.raises(InputTensorError, match="unknown window"):
        get_window("kaiser", 16)


@pytest.mark.parametrize("m", [8, 9])
def test_shifted_window_is_fftshift(m):
    x = torch.randn(m, dtype=torch.complex128)
    w = get_window("hann", m, torch.float64) / get_window("hann", m, torch.float64).sum()
    ref = torch.fft.fftshift(torch.fft.fft(x * w))
    got = torch.fft.fft(x * shifted_doppler_window("hann", m, torch.float64, torch.device("cpu")))
    torch.testing.assert_close(got, ref)
