import json

import torch

from radaraug.transforms import (
    ClipNormalize,
    Colormap,
    CombineRx,
    RadarCompose,
    RandomDR,
    RangeDoppler,
    ToDecibels,
)


def test_compose_chain_spec_is_json_and_ordered():
    pipe = RadarCompose(
        [RangeDoppler(), ToDecibels(), RandomDR(), CombineRx(db=True), ClipNormalize(-110, -40)]
    )
    spec = pipe.chain_spec()
    assert [s["name"] for s in spec] == [
        "RangeDoppler",
        "ToDecibels",
        "RandomDR",
        "CombineRx",
        "ClipNormalize",
    ]
    assert json.loads(json.dumps(spec)) == spec
    assert spec[2]["random"] is True and spec[2]["mean_db"] == [-120.0, -90.0]


def test_compose_end_to_end_image_and_eval():
    pipe = RadarCompose(
        [
            RangeDoppler(),
            ToDecibels(),
            RandomDR(seed=0),
            CombineRx(db=True),
            ClipNormalize(-110, -40),
            Colormap(),
        ]
    )
    x = 0.01 * torch.randn(4, 3, 16, 64)
    y, label = pipe(x, 2)
    assert y.shape == (4, 3, 32, 16) and label == 2
    assert float(y.min()) >= 0 and float(y.max()) <= 1
    pipe.eval()
    assert not pipe[2].training
