"""Levels of the generated test sets against the training twin (benchmarks/testset_levels_cpu.json).

For the twin (default corridor and receiver), the held-out proxy and the independent set (each at
its defaults): RD maps from ``RangeDoppler() -> ToDecibels()`` (dBFS), RX power-combined, "off zero"
meaning more than 2 Doppler bins from zero. Per source: the empty room's median cell, the strongest
off-zero cell of its frame-averaged map (and where it is), and each people count's per-frame
off-zero peak (median, 10th and 90th percentiles). docs/proxy.md quotes the record.

    python scripts/testset_levels.py -o benchmarks/testset_levels_cpu.json
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import torch

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from radaraug.config import RadarConfig  # noqa: E402
from radaraug.io import open_capture  # noqa: E402
from radaraug.sim import SimulatedRadarDataset  # noqa: E402
from radaraug.testsets.independent import make_independent_set  # noqa: E402
from radaraug.testsets.proxy import make_proxy  # noqa: E402
from radaraug.transforms import RangeDoppler, ToDecibels  # noqa: E402

OFF_ZERO_BINS = 2
TWIN_ITEMS = 240


def combined_db(frames: torch.Tensor) -> torch.Tensor:
    """``(F, range, Doppler)`` dBFS maps, the RX power-combined."""
    db = ToDecibels()(RangeDoppler()(frames.to(torch.float32)))
    return 10 * torch.log10((10 ** (db.double() / 10)).mean(dim=1))


def off_zero(maps: torch.Tensor) -> torch.Tensor:
    """Mask of the Doppler bins more than :data:`OFF_ZERO_BINS` from zero."""
    M = maps.shape[-1]
    return (torch.arange(M) - M // 2).abs() > OFF_ZERO_BINS


def levels(by_count: dict[int, torch.Tensor], config: RadarConfig) -> dict[str, object]:
    """The record's figures for one source, from its maps per people count."""
    empty = by_count[0]
    keep = off_zero(empty)
    mean_map = 10 * torch.log10((10 ** (empty / 10)).mean(dim=0))
    masked = mean_map.masked_fill(~keep[None, :], -torch.inf)
    k = int(masked.argmax())
    r, d = divmod(k, masked.shape[1])
    out: dict[str, object] = {
        "empty_median_cell_dB": round(float(empty.median()), 1),
        "empty_strongest_off_zero_dB": round(float(masked.max()), 1),
        "empty_strongest_off_zero_range_m": round(r * config.range_resolution_m, 2),
        "empty_strongest_off_zero_doppler_bins": d - masked.shape[1] // 2,
    }
    for count, maps in sorted(by_count.items()):
        peaks = maps[..., keep].flatten(1).max(dim=1).values
        q = torch.quantile(peaks, torch.tensor([0.1, 0.5, 0.9], dtype=peaks.dtype))
        out[f"count_{count}_peak_dB"] = {"p10": round(float(q[0]), 1), "median": round(float(q[1]), 1),
                                         "p90": round(float(q[2]), 1), "frames": int(peaks.numel())}
    return out


def from_set(gen: object) -> tuple[dict[int, torch.Tensor], RadarConfig]:
    """Maps per count of a generated set (its empty-room capture is count 0)."""
    out = {}
    for path, count in [(gen.calibration, 0), *[(p, c) for p, c in gen.tests if c > 0]]:
        with open_capture(path) as reader:
            out[count] = combined_db(reader.read(0, reader.num_frames))
    return out, gen.config


def from_twin(items: int) -> tuple[dict[int, torch.Tensor], RadarConfig]:
    """Maps per count of the twin's first ``items`` items (default corridor and receiver)."""
    ds = SimulatedRadarDataset("corridor", length=items, seed=0)
    frames: dict[int, list[torch.Tensor]] = {}
    for i in range(items):
        x, count = ds[i]
        frames.setdefault(int(count), []).append(x.reshape(-1, *x.shape[-3:]))
    return {c: combined_db(torch.cat(v)) for c, v in frames.items()}, ds.config


def main() -> None:
    """Measure the three sources and write the record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    record: dict[str, object] = {
        "benchmark": "testset_levels",
        "what": "RD maps RangeDoppler() -> ToDecibels() (dBFS), RX power-combined; off zero = more than "
                f"{OFF_ZERO_BINS} Doppler bins from zero; peaks per frame over the off-zero cells",
        "command": "python scripts/testset_levels.py -o benchmarks/testset_levels_cpu.json",
    }
    t = time.perf_counter()
    with tempfile.TemporaryDirectory() as d:
        proxy = make_proxy(Path(d) / "proxy", progress=False)
        record["proxy"] = levels(*from_set(proxy))
        independent = make_independent_set(Path(d) / "independent", progress=False)
        record["independent"] = levels(*from_set(independent))
    record["twin"] = {**levels(*from_twin(TWIN_ITEMS)), "items": TWIN_ITEMS,
                      "source": "SimulatedRadarDataset('corridor', seed=0): default receiver, no randomization"}
    record["wall_s"] = round(time.perf_counter() - t, 1)
    Path(args.output).write_text(json.dumps(record, indent=1) + "\n")
    print(json.dumps(record, indent=1))


if __name__ == "__main__":
    main()
