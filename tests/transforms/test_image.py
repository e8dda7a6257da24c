import matplotlib
import numpy as np
import pytest
import torch
from torchvision.transforms import v2

from radaraug.errors import ConfigError, InputTensorError, RadarAugError
from radaraug.transforms import ClipNormalize, Colormap, MaxResize, Resize
from radaraug.transforms import functional as F


def test_clip_normalize_maps_range_to_unit_interval(dtype):
    x = torch.tensor([[[-130.0, -110.0, -75.0, -40.0, 0.0]]], dtype=dtype)
    y = ClipNormalize(-110, -40)(x)
    torch.testing.assert_close(y, torch.tensor([[[0.0, 0.0, 0.5, 1.0, 1.0]]], dtype=dtype))
    with pytest.raises(RadarAugError):
        ClipNormalize(-40, -110)


def test_estimate_percentiles_tensor_and_dataset():
    maps = torch.linspace(-120, -20, 1001, dtype=torch.float64).reshape(1, 7, 11, 13)
    values = maps.flatten().numpy()
    cn = ClipNormalize.estimate(maps, low=1.0, high=99.0)
    assert (cn.vmin, cn.vmax) == pytest.approx(tuple(np.percentile(values, [1, 99])))
    dataset = [(m, 0) for m in maps.reshape(7, 1, 11, 13)]
    cn2 = ClipNormalize.estimate(dataset, low=1.0, high=99.0)
    assert (cn2.vmin, cn2.vmax) == pytest.approx((cn.vmin, cn.vmax))
    with pytest.raises(InputTensorError):
        ClipNormalize.estimate(torch.tensor([float("nan"), 1.0]))


@pytest.mark.parametrize("name", ["viridis", "magma"])
def test_colormap_matches_matplotlib(name, dtype, device):
    x = torch.cat(
        [torch.linspace(0, 1, 4097, dtype=torch.float64), torch.tensor([0.5 - 1e-12, 255 / 256, 1.0])]
    )
    x = torch.cat([x, torch.rand(2061, dtype=torch.float64)]).reshape(1, 1, 61, 101)
    ref = matplotlib.colormaps[name](x[0, 0].numpy())[..., :3]  # (H, W, 3)
    y = Colormap(name)(x.to(dtype=dtype, device=device))
    assert y.shape == (1, 3, 61, 101) and y.dtype == dtype and y.device.type == torch.device(device).type
    np.testing.assert_allclose(y[0].permute(1, 2, 0).cpu().double().numpy(), ref, atol=1e-6, rtol=0)


def test_colormap_clips_and_refuses_several_channels():
    y = Colormap()(torch.tensor([[[[-0.5, 1.5]]]]))
    lut = matplotlib.colormaps["viridis"]
    np.testing.assert_allclose(y[0, :, 0, 0].numpy(), lut(0.0)[:3], atol=1e-6)
    np.testing.assert_allclose(y[0, :, 0, 1].numpy(), lut(1.0)[:3], atol=1e-6)
    with pytest.raises(InputTensorError, match="CombineRx"):
        Colormap()(torch.zeros(3, 8, 8))


def test_resize_shape_and_constant():
    x = torch.full((2, 3, 64, 32), 0.25, dtype=torch.float64)
    y = Resize((224, 224))(x)
    assert y.shape == (2, 3, 224, 224)
    torch.testing.assert_close(y, torch.full_like(y, 0.25))
    assert Resize((16, 16))(x).shape == (2, 3, 16, 16)


@pytest.mark.parametrize("size", [16, [16], (16, 0), (16.0, 8), "16", (True, 4)])
def test_resize_refuses_an_int_and_bad_sizes(size):
    # An int means 16 x 16 in radaraug's past and "short side 16" in torchvision: refused.
    with pytest.raises(ConfigError, match=r"\(height, width\)"):
        Resize(size)
    with pytest.raises(ConfigError, match=r"\(height, width\)"):
        F.resize(torch.zeros(1, 4, 4), size)


@pytest.mark.parametrize("size", [(224, 224), (5, 9), (64, 20)])
@pytest.mark.parametrize("antialias", [True, False])
def test_resize_equals_torchvision_v2_resize(size, antialias):
    x = torch.rand(2, 3, 32, 24, dtype=torch.float64, generator=torch.Generator().manual_seed(0))
    ref = v2.functional.resize(x, list(size), antialias=antialias)
    # Equal to float rounding: torchvision interpolates (N, C, H, W), radaraug (N*C, 1, H, W), and
    # with one thread PyTorch's kernel sums in another order for the two layouts (1e-16 apart).
    torch.testing.assert_close(Resize(size, antialias=antialias)(x), ref, rtol=0, atol=1e-12)
    assert torch.equal(v2.Resize(size, antialias=antialias)(x), ref)


@pytest.mark.parametrize("shape,size", [((128, 64), (64, 32)), ((100, 64), (64, 32)), ((32, 16), (64, 32)),
                                        ((7, 5), (3, 4))])
def test_max_resize_equals_adaptive_max_pooling(shape, size, dtype, device):
    # an independent reference: torch's adaptive max pooling has the same windows
    x = torch.randn(2, 3, *shape, dtype=torch.float64, generator=torch.Generator().manual_seed(1)).to(dtype=dtype)
    want = torch.nn.functional.adaptive_max_pool2d(x, size)
    got = MaxResize(size)(x.to(device))
    assert got.shape == (2, 3, *size) and got.device.type == torch.device(device).type
    assert torch.equal(got.cpu(), want)


def test_max_resize_keeps_a_one_cell_peak_that_bilinear_averages():
    # a target one range bin wide, 20 dB over a 0 dB floor, on a 128 x 64 map shrunk to 64 x 32
    x = torch.zeros(1, 128, 64)
    x[0, 41, 17] = 20.0
    assert float(MaxResize((64, 32))(x).max()) == 20.0
    # bilinear with antialias spreads it over about 2 x 2 output pixels at most a quarter each, or less
    assert float(Resize((64, 32))(x).max()) <= 20.0 / 4 + 1e-6
    with pytest.raises(ConfigError, match=r"\(height, width\)"):
        MaxResize(16)


def test_estimate_on_empty_data_is_a_clear_error():
    # before: a bare IndexError from numpy.percentile
    for empty in (torch.ones(0), [torch.ones(0, 4)], []):
        with pytest.raises(InputTensorError, match="no data"):
            ClipNormalize.estimate(empty)
