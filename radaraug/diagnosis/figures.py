"""Figures of a diagnosis: every view, capture vs twin before and after, and the RD residual."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import torch

from radaraug.diagnosis.views import ADC_QUANTILES, RD_QUANTILES, _db
from radaraug.files import atomic_savefig

if TYPE_CHECKING:
    from radaraug.diagnosis.diagnose import Diagnosis


def view_figures(diag: Diagnosis, out: Path) -> list[str]:
    """Write one PNG per view plus ``rd_residual.png``; returns the file names."""
    from radaraug._optional import pyplot

    plt = pyplot()

    cfg = diag.config
    rng = torch.tensor(cfg.range_axis_m())
    vel = torch.tensor(cfg.velocity_axis_m_s())
    cap, before, after = diag.capture_views, diag.result.before.twin, diag.result.after.twin
    series = (("capture (held-out)", cap, "k-"), ("twin before", before, "C3--"), ("twin after", after, "C0-"))
    nr = cap["noise_floor"].numel()
    names: list[str] = []

    def save(fig, name: str) -> None:
        fig.tight_layout()
        atomic_savefig(fig, out / name, dpi=90)
        plt.close(fig)
        names.append(name)

    def curve(view: str, x: torch.Tensor, xlabel: str, ylabel: str, sl: slice = slice(None)) -> None:
        fig, ax = plt.subplots(figsize=(6, 3.4))
        for label, v, style in series:
            ax.plot(x.tolist(), v[view][sl].tolist(), style, label=label, lw=1.2)
        ax.set(xlabel=xlabel, ylabel=ylabel, title=view)
        ax.legend(fontsize=8)
        save(fig, f"view_{view}.png")

    curve("rd_histogram", torch.tensor(RD_QUANTILES), "quantile", "RD cell (dBFS)")
    curve("noise_floor", rng, "range (m)", "median off-zero-Doppler power (dBFS)")
    curve("range_profile", rng, "range (m)", "mean zero-Doppler power (dBFS)")
    curve("doppler_profile", vel, "velocity (m/s)", "mean power (dBFS)")
    curve("static_ratio", rng, "range (m)", "zero-Doppler / total (dB)")
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    for label, v, style in series:
        axes[0].plot(rng.tolist(), v["lines"][:nr].tolist(), style, label=label, lw=1)
        axes[1].plot(vel.tolist(), v["lines"][nr:].tolist(), style, label=label, lw=1)
    axes[0].set(xlabel="range (m)", ylabel="peak / median (dB)", title="lines per range row")
    axes[1].set(xlabel="velocity (m/s)", ylabel="peak / median (dB)", title="lines per Doppler column")
    axes[0].legend(fontsize=8)
    save(fig, "view_lines.png")
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    R = cfg.num_rx
    for j, (label, v, _style) in enumerate(series):
        x = [k + 0.25 * (j - 1) for k in range(R)]
        axes[0].bar(x, v["rx_balance"][:R].tolist(), width=0.25, label=label)
        axes[1].bar(x, v["rx_balance"][R:].tolist(), width=0.25, label=label)
    axes[0].set(xlabel="RX", ylabel="noise floor - mean (dB)", title="rx_balance: noise")
    axes[1].set(xlabel="RX", ylabel="static level - mean (dB)", title="rx_balance: static")
    axes[0].legend(fontsize=8)
    save(fig, "view_rx_balance.png")
    fig, ax = plt.subplots(figsize=(6, 3.4))
    for label, v, style in series:
        for r in range(R):
            ax.plot(ADC_QUANTILES, v["adc_histogram"][r, :-1].tolist(), style, lw=1, label=label if r == 0 else None)
    ax.set(xscale="logit", xlabel="quantile", ylabel="ADC code", title="adc_histogram (per RX)")
    ax.legend(fontsize=8)
    save(fig, "view_adc_histogram.png")
    fig, ax = plt.subplots(figsize=(8, 3.4))
    lab = ["median frame\npower (dB)", "frame power\nspread (dB)", "chirp-to-chirp\nnoise (dB c^2)",
           "frame-to-frame\nnoise (dB c^2)", "chirp q90\n- q50", "chirp q97\n- q50", "chirp q99\n- q50",
           "chirp q99.9\n- q50"]
    for j, (label, v, _) in enumerate(series):
        ax.bar([k + 0.25 * (j - 1) for k in range(len(lab))], v["frame_power"].tolist(), width=0.25, label=label)
    ax.set_xticks(range(len(lab)), lab, fontsize=6)
    ax.set(title="frame_power")
    ax.legend(fontsize=8)
    save(fig, "view_frame_power.png")
    ex = _db(cap.stats.power.mean(dim=0)) - _db(after.stats.power.mean(dim=0))
    fig, ax = plt.subplots(figsize=(6, 4))
    im = ax.imshow(ex.numpy(), aspect="auto", origin="lower", cmap="RdBu_r", vmin=-15, vmax=15,
                   extent=(float(vel[0]), float(vel[-1]), float(rng[0]), float(rng[-1])))
    for u in diag.unexplained:
        if u["view"] == "rd_map":
            ax.plot(u["velocity_m_s"], u["range_m"], "ko", mfc="none")
    fig.colorbar(im, ax=ax, label="capture - twin after (dB)")
    ax.set(xlabel="velocity (m/s)", ylabel="range (m)", title="RD residual after the search (circles: unexplained)")
    save(fig, "rd_residual.png")
    names += signature_figures(diag, out)
    return names


#: The view in which each signature's effect shows (what its small figure plots).
SIGNATURE_VIEWS = {
    "adc_clipping": "adc_histogram", "phase_noise": "doppler_profile", "spur_tone": "lines",
    "if_highpass": "noise_floor", "rx_gain_phase_mismatch": "rx_balance", "tx_rx_leakage": "range_profile",
    "interference": "frame_power", "vibrating_clutter": "lines", "frame_drift": "frame_power",
}


def signature_figures(diag: Diagnosis, out: Path) -> list[str]:
    """One small figure per signature found (``signature_<effect>.png``): its view, capture vs twin, and the evidence."""
    from radaraug._optional import pyplot

    plt = pyplot()
    names: list[str] = []
    cap, before, after = diag.capture_views, diag.result.before.twin, diag.result.after.twin
    for name, ev in diag.evidence.items():
        if not ev.present:
            continue
        view = SIGNATURE_VIEWS[name]
        fig, ax = plt.subplots(figsize=(5, 3.0))
        for label, v, style in (("capture", cap, "k-"), ("twin before", before, "C3--"), ("twin after", after, "C0-")):
            y = v[view].reshape(-1)
            ax.plot(range(y.numel()), y.tolist(), style, lw=1, label=label)
        ax.set(title=f"{name}: signature present (view {view})", xlabel=f"{view} element", ylabel="dB / code")
        ax.legend(fontsize=7)
        fig.text(0.01, 0.01, ev.reason[:150], fontsize=6)
        fig.tight_layout(rect=(0, 0.06, 1, 1))
        fname = f"signature_{name}.png"
        atomic_savefig(fig, out / fname, dpi=80)
        plt.close(fig)
        names.append(fname)
    return names
