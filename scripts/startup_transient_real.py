"""The chirp start of the public recordings against the twin's, with and without the high-pass start-up.

For each recording: the chirp-mean profile (ADC counts, every chirp of the first 100 frames, per RX) of its
first samples and its tail (samples 24 on), and the same of the default receiver for the recording's config
(an empty room: the declared leakage and DC only) in steady state and with ``IFHighPass(startup=1)``
(docs/receiver.md, "The high-pass' start-up transient").

    python scripts/startup_transient_real.py REAL_DIR [-o benchmarks/startup_transient_real_cpu.json]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import torch

from radaraug.config import RadarConfig
from radaraug.io import open_capture
from radaraug.sensor.effects import IFHighPass
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver

FIRST = 8  # samples shown at the chirp start
TAIL = 24  # the tail's mean from this sample on


def twin_profile(config: RadarConfig, startup: int) -> torch.Tensor:
    """``(RX, N)`` the default receiver's chirp-mean profile, in counts, for an empty room (seeded noise)."""
    effects = [IFHighPass(cutoff_Hz=e.cutoff_Hz, order=int(e.order), startup=startup) if e.name == "if_highpass" else e
               for e in FMCWReceiver(config).effects]
    z = torch.zeros(1, 0, config.num_rx, dtype=torch.float64)
    x = FMCWReceiver(config, effects=effects)(Paths(z, z.clone(), z.to(torch.complex128)),
                                              generator=torch.Generator().manual_seed(0))
    return (x * config.adc_full_scale_counts / 2 + config.adc_full_scale_counts / 2).mean(dim=(0, 2))


def summary(profile: torch.Tensor) -> dict[str, list]:
    """The first samples and the tail's mean per RX, rounded to counts."""
    return {"first": [[round(float(v)) for v in row[:FIRST]] for row in profile],
            "tail_mean": [round(float(row[TAIL:].mean())) for row in profile]}


def main() -> None:
    """Measure every Infineon recording under REAL_DIR and write the record."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("real_dir", type=Path)
    ap.add_argument("-o", "--output", type=Path, default=None)
    args = ap.parse_args()
    out: dict[str, dict] = {}
    for radar in sorted(args.real_dir.glob("**/RadarIfxAvian_00/radar.npy")):
        folder = radar.parent.parent
        with open_capture(folder) as cap:
            counts = cap.read(0, min(len(cap), 100), as_float=False).double()
            config = cap.config
        out[folder.name] = {"path": str(folder.relative_to(args.real_dir)), "if_gain_dB": config.if_gain_dB,
                            "frames": int(counts.shape[0]), "recording": summary(counts.mean(dim=(0, 2))),
                            "twin_steady_state": summary(twin_profile(config, 0)),
                            "twin_startup": summary(twin_profile(config, 1))}
    record = {"benchmark": "chirp-start profile of the public recordings vs the twin's (counts)",
              "command": "python scripts/startup_transient_real.py REAL_DIR -o benchmarks/startup_transient_real_cpu.json",
              "first_samples": FIRST, "tail_from_sample": TAIL, "recordings": out}
    text = json.dumps(record, indent=1)
    print(text)
    if args.output:
        args.output.write_text(text + "\n")


if __name__ == "__main__":
    main()
