"""Figure of the effect variants the signatures tell apart (docs/diagnosis.md, "Physical variants").

Simulates 40 empty-room frames at the paper's config with the twin's receiver and one effect in
each of its forms (a spur locked to absolute time and one unlocked; a vibration of 0.3 mm at
420 Hz and one of 6 mm at 25 Hz; LO phase noise on a return only ~17 dB over the floor), runs the
detector on each and draws the frame-averaged range-Doppler power (moving part, dB over the noise)
with the detector's verdict. The last panel shows why the weak carrier's skirt is still found:
per RX it is under the floor, across the RX (one LO) it is not.

    python scripts/signature_variants_figure.py OUT.png
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import torch

from radaraug._optional import pyplot
from radaraug.config import RadarConfig
from radaraug.diagnosis.signatures import (
    Prepared,
    detect_phase_noise,
    detect_spur_tone,
    detect_vibrating_clutter,
)
from radaraug.files import atomic_savefig
from radaraug.sensor import FMCWReceiver, Paths
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import PhaseNoise, SpurTone, VibratingClutter
from radaraug.sensor.effects.base import insert_in_order

CASES = {
    "spur, locked (a line)": (SpurTone(freq_Hz=187_300.0, amplitude_counts=6.0), detect_spur_tone),
    "spur, unlocked (a ridge)": (SpurTone(freq_Hz=187_300.0, amplitude_counts=6.0, phase_jitter_rad=math.pi),
                                 detect_spur_tone),
    "vibration 0.3 mm at 420 Hz (a pair)": (VibratingClutter(range_m=2.9, level_dB=-75.0, displacement_m=0.3e-3,
                                                             vibration_Hz=420.0), detect_vibrating_clutter),
    "vibration 6 mm at 25 Hz (a band)": (VibratingClutter(range_m=2.9, level_dB=-75.0, displacement_m=6e-3,
                                                          vibration_Hz=25.0), detect_vibrating_clutter),
    "LO phase noise on a weak return (under the floor)": (PhaseNoise(freq_noise_rms_Hz=1.5e6, corner_Hz=100e3),
                                                           detect_phase_noise),
}
WEAK_RETURN_M, WEAK_RETURN_AMPLITUDE = 4.6, 1e-5
"""The phase-noise panel's one static return: range and amplitude (sqrt(W) per W), ~17 dB over the floor."""


def frames_with(cfg: RadarConfig, effect: torch.nn.Module, frames: int = 40) -> torch.Tensor:
    """``frames`` consecutive frames through the default receiver plus ``effect``.

    An empty scene, but one weak static return for LO phase noise (it needs a carrier).
    """
    rx = FMCWReceiver(cfg, effects=insert_in_order(default_effects(cfg), effect))
    n = 1 if isinstance(effect, PhaseNoise) else 0
    a = WEAK_RETURN_AMPLITUDE * torch.tensor([1.0, 1j, -1.0], dtype=torch.complex128)
    paths = Paths(torch.full((n, 3), 2 * WEAK_RETURN_M / 299_792_458.0, dtype=torch.float64),
                  torch.zeros(n, 3, dtype=torch.float64), a[None].expand(n, 3))
    g = torch.Generator().manual_seed(0)
    return torch.stack([rx(paths, generator=g, frame_start_s=i * cfg.frame_repetition_time_s)
                        for i in range(frames)]).float()


def cross_rx_profile(ax, p: Prepared, cfg: RadarConfig) -> None:
    """Per-RX and cross-RX power of the moving part over range (dB over the per-RX floor)."""
    X = p.moving_bh4  # (F, R, M, K): chirps with the frames' static part removed
    auto = X.abs().square().mean(dim=(0, 1, 2))
    i, j = torch.triu_indices(X.shape[1], X.shape[1], 1)
    cross = (X[:, i] * X[:, j].conj()).mean(dim=(0, 2)).abs().mean(dim=0)
    ref = auto.median()
    r = torch.arange(auto.numel()) * cfg.range_resolution_m
    ax.plot(r, 10 * torch.log10(auto / ref), label="per RX: |X_i|^2 (the floor)")
    ax.plot(r, 10 * torch.log10(cross / ref), label="across RX: |<X_i X_j*>| (one LO)")
    # |mean| of independent noise over n = frames x chirps products: sqrt(pi / 4n) of the floor
    n = X.shape[0] * X.shape[2]
    ax.axhline(10 * math.log10(math.sqrt(math.pi / 4 / n)), color="C1", lw=0.8, ls="--",
               label="across RX, noise alone (closed form)")
    ax.axvline(WEAK_RETURN_M, color="k", lw=0.5, ls=":")
    ax.set(title="the same capture over range", xlabel="range (m)", ylabel="dB over the per-RX floor",
           ylim=(-35, 8))
    ax.legend(fontsize=7, loc="lower right")


def main() -> None:
    """Draw the 3 x 2 figure."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    args = ap.parse_args()
    cfg = RadarConfig.bgt60tr13c()
    plt = pyplot()
    fig, axes = plt.subplots(3, 2, figsize=(10, 9.5))
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
    cross_rx_profile(axes.flat[-1], p, cfg)
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, args.out, dpi=90)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
