"""Samples like torchvision v2: tuples, lists and dicts (pytrees) through every transform."""

import numpy as np
import pytest
import torch
from torch import nn
from torch.utils.data import DataLoader, Dataset
from torchvision.transforms import v2

from radaraug.errors import InputTensorError
from radaraug.transforms import (
    CalibratedDR,
    ClipNormalize,
    Colormap,
    CombineRx,
    RadarCompose,
    RandomDR,
    RangeDoppler,
    ToDecibels,
)
from tests.transforms.test_base import CASES, IDS, make


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_tuple_and_dict_samples_in_torchvision_v2_compose(case):
    x = case[2](2, torch.float32, "cpu")
    ref = make(case, seed=5)[0](x)
    label = torch.tensor(1)
    # One argument holding the sample, as a torchvision Dataset hands it over.
    out, lab = v2.Compose([make(case, seed=5)[0]])((x, label))
    assert torch.equal(out, ref) and lab is label
    d = v2.Compose([make(case, seed=5)[0]])({"image": x, "label": label, "name": "frame 0"})
    assert list(d) == ["image", "label", "name"]
    assert torch.equal(d["image"], ref) and d["label"] is label and d["name"] == "frame 0"
    # radaraug's own compose, and the transform called directly, give the same.
    assert torch.equal(RadarCompose([make(case, seed=5)[0]])({"image": x, "label": label})["image"], ref)
    assert torch.equal(make(case, seed=5)[0]([x, label])[0], ref)


@pytest.mark.parametrize("make_t", [lambda: RandomDR(seed=3), lambda: CalibratedDR(-100, 3, seed=3)],
                         ids=["RandomDR", "CalibratedDR"])
def test_plain_tensors_draw_exactly_the_documented_stream(make_t):
    # The tensor path is unchanged: the output is the clamp with the floor drawn, in this order,
    # from a generator seeded 3 -- recomputed here by hand.
    x = torch.randn(4, 3, 8, 6, dtype=torch.float64) * 10 - 100
    t = make_t()
    y = t(x)
    g = torch.Generator().manual_seed(3)
    if isinstance(t, RandomDR):
        (mlo, mhi), (slo, shi) = t.mean_db, t.std_db
        m = mlo + (mhi - mlo) * torch.empty(4, dtype=x.dtype).uniform_(0, 1, generator=g)
        s = slo + (shi - slo) * torch.empty(4, dtype=x.dtype).uniform_(0, 1, generator=g)
        z = torch.empty(x.shape, dtype=x.dtype).normal_(0, 1, generator=g)
        floor = m[:, None, None, None] + z * s[:, None, None, None]
    else:
        floor = torch.empty(x.shape, dtype=x.dtype).normal_(-100, 3, generator=g)
    torch.testing.assert_close(y, torch.maximum(x, floor), rtol=0, atol=1e-12)
    # ... and a tuple or dict sample gives bit for bit what the tensor gives.
    assert torch.equal(make_t()((x, 7))[0], y)
    assert torch.equal(make_t()({"rd": x})["rd"], y)


def test_every_radar_leaf_gets_the_same_random_params_and_the_rest_passes_through():
    x = torch.randn(4, 3, 8, 6) * 10 - 100
    other_shape = torch.randn(4, 3, 8, 5) * 10 - 100
    arr = np.zeros(3)
    sample = {
        "label": torch.tensor([1, 0, 2, 1]),          # integer: a label
        "a": x,
        "meta": {"b": x.clone(), "snr": torch.tensor([3.0, 4.0]), "name": "run1", "none": None},
        "other": other_shape,                         # a float tensor of another shape
        "arr": arr,
    }
    t = RandomDR(seed=0, p=0.5)
    out = t(sample)
    assert torch.equal(out["a"], out["meta"]["b"])    # one floor for both radar leaves
    assert torch.equal(out["a"], t(x, params=t.last_params))
    assert not torch.equal(out["a"], x)
    for key in ("label", "other", "arr"):
        assert out[key] is sample[key]
    assert out["meta"]["snr"] is sample["meta"]["snr"] and out["meta"]["name"] == "run1"
    assert out["meta"]["none"] is None
    # replaying on a sample, and eval() returning the very sample
    replay = t(sample, params=t.last_params)
    assert torch.equal(replay["a"], out["a"])
    t.eval()
    assert t(sample) is sample and t.last_params is None


def test_first_radar_leaf_wins_and_leaves_of_lower_rank_pass():
    cube, rd = torch.randn(2, 3, 8, 16), torch.randn(3, 8, 4)   # rd: other shape, passes
    vec = torch.randn(16)                                         # float target, 1 dim
    out = RangeDoppler()((vec, cube, rd))
    assert out[0] is vec and out[2] is rd
    assert torch.equal(out[1], RangeDoppler()(cube))


@pytest.mark.parametrize(
    "sample, match",
    [
        ((torch.zeros(2, 3, 8, 16, dtype=torch.uint16), 1), "counts_to_float"),
        ({"target": torch.tensor(1.0)}, "at least 3 dims"),
        ({"label": 1, "name": "x"}, "no tensor"),
        ((torch.zeros(2, 3, 8, 16), float("nan")), None),   # fine: the number passes through
    ],
)
def test_a_sample_without_a_radar_tensor_is_an_error(sample, match):
    if match is None:
        RangeDoppler()(sample)
        return
    with pytest.raises(InputTensorError, match=match):
        RangeDoppler()(sample)


def test_a_nan_radar_leaf_and_a_wrong_channel_count_are_still_refused():
    with pytest.raises(InputTensorError, match="NaN"):
        ToDecibels()((torch.full((1, 2, 2), float("nan")), 0))
    with pytest.raises(InputTensorError, match="CombineRx"):
        Colormap()({"image": torch.zeros(3, 4, 4), "label": 1})


def test_plain_module_in_radar_compose_gets_the_radar_tensor_only():
    seen = []

    class Spy(nn.Module):
        def forward(self, x):
            seen.append(x)
            return x * 2

    pipe = RadarCompose([RangeDoppler(), ToDecibels(), Spy(), CombineRx(db=True)])
    cube, label = 0.01 * torch.randn(2, 3, 8, 16), torch.tensor([0, 1])
    y, lab = pipe(cube, label)
    assert lab is label and len(seen) == 1 and seen[0].shape == (2, 3, 8, 8)
    assert torch.equal(y, RadarCompose([RangeDoppler(), ToDecibels(), Spy(), CombineRx(db=True)])(cube))
    # nn.Sequential of radaraug steps takes the whole sample, like the steps themselves
    seq = nn.Sequential(ClipNormalize(-120, -40), Colormap())
    d = RadarCompose([seq])({"image": torch.zeros(2, 1, 4, 4) - 80, "label": label})
    assert d["image"].shape == (2, 3, 4, 4) and d["label"] is label


class DictMaps(Dataset):
    def __init__(self, transform):
        self.transform = transform

    def __len__(self):
        return 8

    def __getitem__(self, i):
        return self.transform({"image": torch.full((1, 4, 4), -200.0), "label": i})


def test_dict_samples_in_a_dataloader_with_workers():
    def run(seed):
        tf = v2.Compose([RandomDR(seed=11), ClipNormalize(-130, -70)])
        loader = DataLoader(DictMaps(tf), batch_size=2, num_workers=2,
                            generator=torch.Generator().manual_seed(seed))
        return list(loader)

    a, b = run(0), run(0)
    assert [batch["label"].tolist() for batch in a] == [[0, 1], [2, 3], [4, 5], [6, 7]]
    assert all(batch["image"].shape == (2, 1, 4, 4) for batch in a)
    assert all(torch.equal(p["image"], q["image"]) for p, q in zip(a, b))   # reproducible
    assert not torch.equal(a[0]["image"], a[1]["image"])                   # workers differ
