"""The torchvision-style battery every transform must pass, plus seeding and DataLoader use."""

import pickle

import pytest
import torch
from torch.utils.data import DataLoader, Dataset
from torchvision.transforms import v2

from radaraug.errors import RadarAugError
from radaraug.transforms import (
    CalibratedDR,
    ClipNormalize,
    Colormap,
    CombineRx,
    DopplerFFT,
    FloorRelative,
    InterferenceExcision,
    RadarCompose,
    RandomDR,
    RangeDoppler,
    RangeFFT,
    RemoveMean,
    Resize,
    StaticClutterRemoval,
    ToDecibels,
)


def raw(b, dtype, device):
    return torch.randn(b, 3, 8, 16, dtype=dtype, device=device) * 0.1 + 0.2


def profiles(b, dtype, device):
    return torch.fft.rfft(raw(b, dtype, device), dim=-1)


def db_maps(b, dtype, device):
    return torch.randn(b, 3, 8, 6, dtype=dtype, device=device) * 10 - 100


def unit_maps(b, dtype, device):
    return torch.rand(b, 1, 8, 6, dtype=dtype, device=device)


# (id, factory of a transform (seeded when random), input maker)
CASES = [
    ("RemoveMean", lambda **k: RemoveMean(), raw),
    ("StaticClutterRemoval", lambda **k: StaticClutterRemoval(), raw),
    ("RangeFFT", lambda **k: RangeFFT("blackmanharris"), raw),
    ("DopplerFFT", lambda **k: DopplerFFT(), profiles),
    ("RangeDoppler", lambda **k: RangeDoppler(static_clutter=True), raw),
    ("ToDecibels", lambda **k: ToDecibels(), profiles),
    ("CombineRx", lambda **k: CombineRx(), profiles),
    ("ClipNormalize", lambda **k: ClipNormalize(-110, -90), db_maps),
    ("FloorRelative", lambda **k: FloorRelative(), db_maps),
    ("Colormap", lambda **k: Colormap(), unit_maps),
    ("Resize", lambda **k: Resize((5, 9)), unit_maps),
    ("RandomDR", lambda **k: RandomDR((-105, -95), (1, 4), **k), db_maps),
    ("CalibratedDR", lambda **k: CalibratedDR(-100, 3, **k), db_maps),
    ("CalibratedDR-empirical",
     lambda **k: CalibratedDR(-100, 3, floor="empirical", quantiles_db=torch.linspace(-110, -90, 33), **k), db_maps),
    # the compose's clamp sits at the level of these maps, so it is active
    (
        "RadarCompose",
        lambda **k: RadarCompose([RangeDoppler(), ToDecibels(), RandomDR((-30, -20), **k)]),
        raw,
    ),
]
RANDOM = {"RandomDR", "CalibratedDR", "CalibratedDR-empirical"}
SEEDED = RANDOM | {"RadarCompose"}
IDS = [c[0] for c in CASES]


def make(case, seed=0, **kw):
    name, factory, maker = case
    if name in SEEDED:
        return factory(seed=seed, **kw), maker
    return factory(), maker


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_no_inplace_dtype_device_kept(case, dtype, device):
    t, maker = make(case)
    x = maker(4, dtype, device)
    before = x.clone()
    y = t(x)
    assert torch.equal(x, before)
    assert y.device == x.device
    real = y.real.dtype if y.is_complex() else y.dtype
    assert real == (x.real.dtype if x.is_complex() else x.dtype)


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_leading_batch_dims_and_batched_equals_per_sample(case):
    kw = {"same_on_batch": True} if case[0] in SEEDED else {}
    t, maker = make(case, **kw)
    x = maker(6, torch.float64, "cpu").reshape(2, 3, *maker(1, torch.float64, "cpu").shape[1:])
    y = t(x)
    if case[0] in SEEDED:
        clean = t.transforms[1](t.transforms[0](x)) if case[0] == "RadarCompose" else x
        assert not torch.equal(y, clean)  # the clamp is active
    for i in range(2):
        for j in range(3):
            ts, _ = make(case, **kw)
            torch.testing.assert_close(y[i, j], ts(x[i, j]))


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_pickle_round_trip_continues_the_stream(case):
    t, maker = make(case, seed=3)
    x = maker(2, torch.float32, "cpu")
    t(x)  # advance any generator first
    t2 = pickle.loads(pickle.dumps(t))
    torch.testing.assert_close(t2(x), t(x))


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_works_inside_torchvision_v2_compose(case):
    x = case[2](2, torch.float32, "cpu")
    ref = make(case, seed=5)[0](x)
    got = v2.Compose([make(case, seed=5)[0]])(x)
    torch.testing.assert_close(got, ref)
    # A (tensor, label) sample: only the first tensor is transformed, like torchvision v2.
    label = torch.tensor(1)
    y, lab = v2.Compose([make(case, seed=5)[0]])(x, label)
    torch.testing.assert_close(y, ref)
    assert lab is label


@pytest.mark.parametrize("case", [c for c in CASES if c[0] in RANDOM], ids=sorted(RANDOM))
def test_random_replay_p0_eval_and_per_sample_p(case):
    t, maker = make(case, p=1.0)
    x = maker(8, torch.float64, "cpu")
    y = t(x)
    assert not torch.equal(y, x)
    torch.testing.assert_close(t(x, params=t.last_params), y)
    torch.testing.assert_close(t(x, t.last_params), y)  # positional params
    # p = 0: identity
    t0, _ = make(case, p=0.0)
    assert torch.equal(t0(x), x)
    # eval(): identity, no params; explicit params still replay
    params = t.last_params
    t.eval()
    assert t(x) is x and t.last_params is None
    torch.testing.assert_close(t(x, params=params), y)
    t.train()
    # p per sample
    tp, _ = make(case, p=0.5)
    xb = maker(64, torch.float64, "cpu")
    yb = tp(xb)
    apply = tp.last_params["apply"]
    assert 10 < int(apply.sum()) < 54
    changed = (yb != xb).flatten(1).any(1)
    assert torch.equal(changed, apply)


def test_random_params_shapes_and_ranges():
    t = RandomDR((-110, -100), (1, 2), seed=0)
    x = db_maps(500, torch.float64, "cpu")
    t(x)
    prm = t.last_params
    assert prm["mean_db"].shape == (500,) and prm["noise_db"].shape == x.shape
    assert prm["mean_db"].min() >= -110 and prm["mean_db"].max() <= -100
    assert prm["std_db"].min() >= 1 and prm["std_db"].max() <= 2
    # the noise of each frame is Normal(m, s^2) with that frame's m, s
    z = (prm["noise_db"] - prm["mean_db"][:, None, None, None]) / prm["std_db"][:, None, None, None]
    assert abs(z.mean().item()) < 0.02 and abs(z.std().item() - 1) < 0.02


def test_same_seed_same_output_generator_seed_and_global():
    x = db_maps(4, torch.float32, "cpu")
    a = RandomDR(generator=torch.Generator().manual_seed(9))(x)
    b = RandomDR(generator=torch.Generator().manual_seed(9))(x)
    assert torch.equal(a, b)
    assert torch.equal(RandomDR(seed=9)(x), RandomDR(seed=9)(x))
    assert not torch.equal(RandomDR(seed=9)(x), RandomDR(seed=10)(x))
    torch.manual_seed(4)
    c = RandomDR()(x)
    torch.manual_seed(4)
    assert torch.equal(c, RandomDR()(x))
    with pytest.raises(RadarAugError):
        RandomDR(generator=torch.Generator(), seed=1)
    with pytest.raises(RadarAugError):
        RandomDR(p=1.5)


class Maps(Dataset):
    """Identical dB maps, so any difference between items is the transform's noise."""

    def __init__(self, transform):
        self.transform = transform

    def __len__(self):
        return 8

    def __getitem__(self, i):
        return self.transform(torch.full((1, 4, 4), -200.0)), i


def run_loader(transform, seed=0):
    loader = DataLoader(
        Maps(transform), batch_size=1, num_workers=2, generator=torch.Generator().manual_seed(seed)
    )
    return torch.cat([x for x, _ in loader])


@pytest.mark.parametrize("kind", ["seed", "generator", "global"])
def test_dataloader_workers_reproducible_and_distinct(kind):
    def make_t(**kw):
        if kind == "seed":
            return RandomDR(seed=11, **kw)
        if kind == "generator":
            return RandomDR(generator=torch.Generator().manual_seed(11), **kw)
        return RandomDR(**kw)

    a, b = run_loader(make_t()), run_loader(make_t())
    assert torch.equal(a, b)  # same seeds -> same output, in workers too
    assert not torch.equal(a[0], a[1])  # items 0 and 1 come from different workers
    assert not torch.equal(run_loader(make_t(), seed=1), a)  # another loader seed / epoch differs
    if kind != "global":
        same = run_loader(make_t(reseed_in_workers=False))
        assert torch.equal(same[0], same[1])  # asked for: every worker replays one stream


def test_shapes_and_devices_follow_the_input_on_the_meta_device():
    # Meta tensors carry shape/dtype/device but no data: every step must keep its tensors on the
    # input's device, and the default p=1 path must not read values back to the host
    # (before: "Tensor.item() cannot be called on meta tensors").
    x = torch.empty(2, 3, 8, 16, device="meta")
    pipeline = RadarCompose(
        [InterferenceExcision(), RangeDoppler(), ToDecibels(),
         CalibratedDR(-100, 3, floor="empirical", quantiles_db=[-110.0, -90.0]),
         RandomDR(), CombineRx("mean_power", db=True),
         ClipNormalize(-120, -40), Colormap(), Resize((5, 7))]
    )
    y = pipeline(x)
    assert y.device.type == "meta" and y.shape == (2, 3, 5, 7) and y.dtype == torch.float32
    for t in (pipeline[3], pipeline[4]):
        assert all(v.device.type == "meta" for v in t.last_params.values())
