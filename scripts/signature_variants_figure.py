"""Figure of the effect variants the signatures tell apart (docs/calibration.md, "Physical variants").

Simulates 40 empty-room frames at the paper's config with the twin's receiver and one effect in
each of its forms (a spur locked to absolute time and one unlocked; a vibration of 0.3 mm at
420 Hz and one of 6 mm at 25 Hz), runs the detector on each and draws the frame-averaged
range-Doppler power (moving part, dB over the noise) with the detector's verdict.

    python scripts/signature_variants_figure.py OUT.png
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import torch

from radaraug._optional import pyplot
from radaraug.calibration.signatures import Prepared, detect_spur_tone, detect_vibrating_clutter
from radaraug.config import RadarConfig
from radaraug.sensor import FMCWReceiver, Paths
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import SpurTone, VibratingClutter
from radaraug.sensor.effects.base import insert_in_order

CASES = {
    "spur, locked (a line)": (SpurTone(freq_Hz=187_300.0, amplitude_counts=6.0), detect_spur_tone),
    "spur, unlocked (a ridge)": (SpurTone(freq_Hz=187_300.0, amplitude_counts=6.0, phase_jitter_rad=math.pi),
                                 detect_spur_tone),
    "vibration 0.3 mm at 420 Hz (a pair)": (VibratingClutter(range_m=2.9, level_dB=-75.0, displacement_m=0.3e-3,
                                                             vibration_Hz=420.0), detect_vibrating_clutter),
    "vibration 6 mm at 25 Hz (a band)": (VibratingClutter(range_m=2.9, level_dB=-75.0, displacement_m=6e-3,
                                                          vibration_Hz=25.0), detect_vibrating_clutter),
}


def frames_with(cfg: RadarConfig, effect: torch.nn.Module, frames: int = 40) -> torch.Tensor:
    """``frames`` consecutive frames of an empty scene through the default receiver plus ``effect``."""
    rx = FMCWReceiver(cfg, effects=insert_in_order(default_effects(cfg), effect))
    empty = Paths(torch.zeros(0, 3, dtype=torch.float64), torch.zeros(0, 3, dtype=torch.float64),
                  torch.zeros(0, 3, dtype=torch.complex128))
    g = torch.Generator().manual_seed(0)
    return torch.stack([rx(empty, generator=g, frame_start_s=i * cfg.frame_repetition_time_s)
                        for i in range(frames)]).float()


def main() -> None:
    """Draw the 2 x 2 figure."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    args = ap.parse_args()
    cfg = RadarConfig.bgt60tr13c()
    plt = pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(10, 6.5))
    for ax, (title, (effect, detect)) in zip(axes.flat, CASES.items()):
        x = frames_with(cfg, effect)
        p = Prepared(x, cfg)
        sig = detect(p, cfg)
        _, pm, _ = p.doppler
        db = 10 * torch.log10(pm / pm.median()).T  # (doppler, range) over the map's median cell
        dv = cfg.wavelength_m / (2 * cfg.num_chirps_per_frame * cfg.chirp_repetition_time_s)
        m = db.shape[0]
        im = ax.imshow(db.numpy(), aspect="auto", origin="lower", vmin=-5, vmax=45, cmap="viridis",
                       extent=(0, db.shape[1] * cfg.range_resolution_m, -m / 2 * dv, m / 2 * dv))
        ax.set(title=title, xlabel="range (m)", ylabel="radial speed (m/s)")
        verdict = ("found: " if sig.present else "not found: ") + sig.detail.split(";")[0]
        ax.text(0.01, 0.02, verdict[:95], transform=ax.transAxes, fontsize=6, color="w")
        fig.colorbar(im, ax=ax, label="dB over the median cell")
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=90)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
