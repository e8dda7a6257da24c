"""Figure of the other effect variants the signatures tell apart (docs/diagnosis.md, "Physical variants").

The companion of ``signature_variants_figure.py`` (spur, vibration, weak-carrier phase noise): 40 frames
at the paper's config (IF gain 33 dB unless a panel says 48 dB, the BGT60's highest) through the twin's
default receiver plus one effect in one of its forms, the detector run on each capture, and the view
that detector reads, with its verdict and measured parameters as the panel's title:

* ``rx_gain_phase_mismatch`` of -3/+2 dB on RX2/RX3: the gain re RX1 of the noise floor over range and
  of the static returns, with static returns at 33 and 48 dB and without any at 48 dB;
* ``if_highpass`` of another cutoff or order: the noise floor's spectrum (chirp differences) with the
  detector's Butterworth fit, at 48 and 33 dB;
* ``tx_rx_leakage`` at the declared level, +8 dB and +20 dB: the frames' mean range profile near DC;
  +18 dB with the high-pass start-up on (``IFHighPass(startup=1)``): the mean chirp's first samples;
* ``adc_clipping``: the share of each sample of the chirp on a rail and the samples per code next to the
  rails, for that start-up clipping and for too much gain (a return at 1.4 m at IF 48 dB);
* ``interference`` with one chirp slope (5 us bursts) and several (5, 20 and 60 us, three
  ``Interference`` effects): each chirp's wideband excess over its frame and the burst lengths the
  detector measures;
* ``phase_noise`` on a strong carrier: the moving part's power over range, declared LO noise and 0.5 MHz RMS;
* ``frame_drift`` of the DC (3 counts RMS) and of the gain (0.5 dB RMS): the frame-to-frame series.

    python scripts/signature_variants_more_figure.py OUT.png
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from pathlib import Path

import torch

from radaraug._optional import pyplot
from radaraug.config import RadarConfig
from radaraug.diagnosis.signatures import (
    Prepared,
    Signature,
    butterworth_highpass_power,
    detect_adc_clipping,
    detect_frame_drift,
    detect_if_highpass,
    detect_interference,
    detect_phase_noise,
    detect_rx_gain_phase_mismatch,
    detect_tx_rx_leakage,
)
from radaraug.files import atomic_savefig
from radaraug.sensor import FMCWReceiver, Paths
from radaraug.sensor.defaults import LEAKAGE_COUPLING_DB, default_effects
from radaraug.sensor.effects import (
    Effect,
    FrameDrift,
    IFHighPass,
    Interference,
    PhaseNoise,
    RxGainPhaseMismatch,
    TxRxLeakage,
)
from radaraug.sensor.effects.base import insert_in_order
from radaraug.sensor.effects.filters import section_cutoff

C = 299_792_458.0
FRAMES = 40
ROOM = ((1.4, 1e-4), (2.6, 6e-5), (4.1, 4e-5))
"""Static returns: range (m) and amplitude (sqrt(W) per sqrt(W)), 25-37 dB over the per-chirp floor at 33 dB."""
MISMATCH_DB = (0.0, -3.0, 2.0)
"""The RX gains put in, dB."""
HIGH_IF_GAIN_DB = 48
"""The BGT60's highest IF gain: the thermal floor stands a few dB over the ADC-side floor only there."""
FS_TITLE = 7.5


def capture(cfg: RadarConfig, effects: Sequence[Effect], returns: Sequence[tuple[float, float]] = (),
            seed: int = 0) -> torch.Tensor:
    """:data:`FRAMES` consecutive frames ``(F, rx, chirps, samples)`` of static ``returns`` through ``effects``.

    Each return reaches the RX with the phases ``1, j, -1`` (an angle of arrival); one batched call, one
    seeded generator.
    """
    rx = FMCWReceiver(cfg, effects=effects)
    n, R = len(returns), cfg.num_rx
    delay = torch.tensor([2 * r / C for r, _ in returns], dtype=torch.float64)[:, None].expand(n, R)
    amp = torch.tensor([a for _, a in returns], dtype=torch.complex128)[:, None] \
        * torch.tensor([1.0, 1j, -1.0], dtype=torch.complex128)[:R]
    paths = Paths(delay[None].expand(FRAMES, n, R).contiguous(), torch.zeros(FRAMES, n, R, dtype=torch.float64),
                  amp[None].expand(FRAMES, n, R).contiguous())
    start = torch.arange(FRAMES, dtype=torch.float64) * cfg.frame_repetition_time_s
    return rx(paths, generator=torch.Generator().manual_seed(seed), frame_start_s=start).float()


def chain(cfg: RadarConfig, *extra: Effect) -> list[Effect]:
    """The twin's default chain with ``extra`` effects, each at its hardware place (replacing its namesake)."""
    effects = default_effects(cfg)
    for e in extra:
        effects = insert_in_order(effects, e)
    return effects


def verdict(sig: Signature) -> str:
    """``found`` / ``not found``; ``declared`` for a leakage or skirt within the declared one's tolerance."""
    if sig.present:
        return "found"
    declared = sig.params.get("within_declared") or "of the declared skirt" in sig.detail
    return "declared" if declared else "not found"


def leakage(db: float) -> TxRxLeakage:
    """The default chain's TX->RX leakage, ``db`` dB stronger on every RX."""
    return TxRxLeakage(coupling_dB=[LEAKAGE_COUPLING_DB[a] + db for a in (1, 2, 3)], range_m=0.04)


# --------------------------------------------------------------------------- RX mismatch
def mismatch_panel(ax, cfg: RadarConfig, returns: Sequence[tuple[float, float]], what: str) -> None:
    """Gain re RX1 over range: each RX's noise floor (line) and the static returns (dots)."""
    mm = RxGainPhaseMismatch(gain_dB=list(MISMATCH_DB), phase_rad=[0.0, 0.5, -0.8])
    p = Prepared(capture(cfg, chain(cfg, mm), returns), cfg)
    s = detect_rx_gain_phase_mismatch(p, cfg)
    floor = p.floor_hann  # (R, K)
    K = floor.shape[1]
    r = torch.arange(K) * cfg.range_resolution_m
    ax.axvspan(float(r[K // 4]), float(r[3 * K // 4]), color="0.9", label="band of the noise gain")
    ratio = 10 * torch.log10(floor / floor[:1])
    pc = p.static_hann.mean(dim=0).abs().square()  # (R, K)
    for i in range(1, cfg.num_rx):
        ax.plot(r, ratio[i], color=f"C{i}", lw=0.6, label=f"RX{i + 1} noise floor")
        ax.axhline(MISMATCH_DB[i], color=f"C{i}", lw=0.8, ls="--")
        for rng_m, _ in returns:
            k0 = round(rng_m / cfg.range_resolution_m)
            k = k0 - 1 + int(pc[:, k0 - 1: k0 + 2].mean(dim=0).argmax())
            ax.plot(float(r[k]), float(10 * torch.log10(pc[i, k] / pc[0, k])), "o", color=f"C{i}", ms=5,
                    label=f"RX{i + 1} static returns" if rng_m == returns[0][0] else None)
    pr = s.params
    gains = "/".join(f"{pr[f'noise_gain_dB_rx{i}']:+.2f}" for i in (2, 3))
    if returns:
        got = "returns " + "/".join(f"{pr[f'static_gain_dB_rx{i}']:+.2f}" for i in (2, 3)) + f" dB, noise {gains} dB"
        got += "" if s.present else " (the floor must carry 40 % of what the returns predict for it)"
    else:
        got = f"noise {gains} dB, spread {pr['spread_dB']:.2f} dB"
    ax.set_title(f"rx_gain_phase_mismatch -3/+2 dB (dashed), {what}\n{verdict(s)}: {got}", fontsize=FS_TITLE)
    ax.set(xlabel="range (m)", ylabel="gain re RX1 (dB)", ylim=(-4.5, 3.5))
    ax.legend(fontsize=6, loc="lower right", ncol=2)


# --------------------------------------------------------------------------- IF high-pass
def floor_psd(p: Prepared) -> torch.Tensor:
    """The noise floor as ``detect_if_highpass`` reads it: chirp differences, Blackman-Harris, ``(K,)``.

    Median power over frames and chirps (over ``ln 2``), RX mean, less what is common to the RX.
    """
    F, R, M, N = p.shape
    dd = torch.fft.rfft(p.counts.diff(dim=2) * p.bh4, dim=-1)[..., : N // 2] / p.bh4.sum()
    d = dd.permute(1, 3, 0, 2).reshape(R, N // 2, -1)  # (R, K, pairs)
    pw = d.abs().square()
    psd = pw.median(dim=-1).values.mean(dim=0) / math.log(2)
    i, j = torch.triu_indices(R, R, 1)
    coh = (d[i] * d[j].conj()).mean(dim=-1).abs().mean(dim=0)
    return psd * (1 - (coh / pw.mean(dim=(0, 2))).clamp(0, 0.9))


def hp_model(f: torch.Tensor, psd: torch.Tensor, fc: float, order: float, fs: float) -> torch.Tensor:
    """The detector's model ``|H|^2 (a + c f/fs) + b`` at ``(fc, order)``, ``(a, c, b)`` fitted as it does (1/psd weights)."""
    h = butterworth_highpass_power(f, fc, order)
    A = torch.stack([h, h * f / fs, torch.ones_like(h)], dim=-1) / psd[:, None]
    sol = torch.linalg.lstsq(A, torch.ones_like(psd)[:, None]).solution
    return (A @ sol)[:, 0] * psd


def highpass_panel(ax, cfg: RadarConfig) -> None:
    """Noise-floor spectra of the declared high-pass and two others, with the detector's fits."""
    variants = {"declared (80 kHz, order 1)": None, "20 kHz, order 1": IFHighPass(cutoff_Hz=20e3),
                "-3 dB at 120 kHz, order 2": IFHighPass(cutoff_Hz=section_cutoff(120e3, 2), order=2)}
    fs, N = cfg.sample_rate_Hz, cfg.num_samples_per_chirp
    fmax = min(0.3 * fs, 6 * cfg.effective_hp_cutoff_Hz)
    f_all = torch.arange(N // 2, dtype=torch.float64) * fs / N
    band = (torch.arange(N // 2) >= 2) & (f_all <= fmax)
    f = f_all[band]
    found = []
    for n, (name, hp) in enumerate(variants.items()):
        p = Prepared(capture(cfg, chain(cfg) if hp is None else chain(cfg, hp)), cfg)
        s = detect_if_highpass(p, cfg)
        psd = floor_psd(p)[band]
        ref = psd[-8:].mean()
        pr = s.params
        ax.plot(f / 1e3, 10 * torch.log10(psd / ref), color=f"C{n}", lw=0.8,
                label=f"{name}: {verdict(s)}, fit order {pr['order']:g} at {pr['cutoff_Hz'] / 1e3:.0f} kHz, "
                      f"gain {s.score:.2f} dB")
        model = hp_model(f, psd, pr["cutoff_Hz"], pr["order"], fs)
        ax.plot(f / 1e3, 10 * torch.log10(model / ref), color=f"C{n}", lw=0.8, ls="--")
        found.append((s.present, pr["hp_over_floor_dB"]))
    over = ", ".join(f"{o:+.1f}" if o > -30 else "< -30" for _, o in found)
    ax.set_title(f"if_highpass in the noise floor, IF gain {cfg.if_gain_dB} dB (dashed: the fits)\n"
                 f"{sum(pr for pr, _ in found[1:])} of the 2 other filters found, the declared "
                 f"{'found' if found[0][0] else 'not'}; high-passed floor over the ADC floor {over} dB",
                 fontsize=FS_TITLE)
    ax.set(xlabel="beat frequency (kHz)", ylabel="dB over the band's top 8 bins", xscale="log")
    ax.legend(fontsize=6, loc="lower right")


# --------------------------------------------------------------------------- TX->RX leakage, clipping
def leakage_levels_panel(ax, cfg: RadarConfig) -> None:
    """The frames' mean range profile near DC (RX1, empty room) at the declared leakage, +8 and +20 dB."""
    bins = torch.arange(1, 13)
    r = bins * cfg.range_resolution_m
    ax.axvspan(float(r[0]) - 0.5 * cfg.range_resolution_m, float(r[1]) + 0.5 * cfg.range_resolution_m,
               color="0.9", label="bins 1..2 (the detector's)")
    for n, db in enumerate((0.0, 8.0, 20.0)):
        p = Prepared(capture(cfg, chain(cfg, leakage(db))), cfg)
        s = detect_tx_rx_leakage(p, cfg)
        scale = (2 / p.full) ** 2
        prof = p.static_bh4.mean(dim=0)[0, bins].abs().square() * scale
        v = verdict(s)
        if v == "declared" and abs(s.params["excess_dB"]) >= 3:
            v += " at other parameters (the loop refits it)"
        ax.plot(r, 10 * torch.log10(prof), color=f"C{n}", marker=".", ms=4, lw=0.8,
                label=f"{'declared' if db == 0 else f'{db:+.0f} dB'}: {v}, "
                      f"{s.params['level_dBFS_rx1']:.1f} dBFS, {s.params['excess_dB']:+.1f} dB from the declared")
    noise = p.moving_bh4[:, 0, :, bins].abs().square().mean(dim=(0, 1)) * scale
    ax.plot(r, 10 * torch.log10(noise), color="k", lw=0.6, ls=":", label="per-chirp noise (RX1)")
    ax.set_title("tx_rx_leakage under the rails: the frames' mean range profile near DC (RX1, empty room)\n"
                 "declared: not named; +8 dB: the declared one at another level; +20 dB: found", fontsize=FS_TITLE)
    ax.set(xlabel="range (m)", ylabel="power (dBFS)", ylim=(-135, 5))
    ax.legend(fontsize=6, loc="upper right")


def leakage_startup_panel(ax, cfg: RadarConfig) -> tuple[Prepared, Signature]:
    """The mean chirp's first samples of a leakage 18 dB over the declared, high-pass start-up on and off.

    Returns the start-up capture and its clipping signature (for the clipping panels).
    """
    p = Prepared(capture(cfg, chain(cfg, IFHighPass(startup=1), leakage(18.0))), cfg)
    steady = Prepared(capture(cfg, chain(cfg, leakage(18.0))), cfg)
    s_leak, s_clip = detect_tx_rx_leakage(p, cfg), detect_adc_clipping(p, cfg)
    n = torch.arange(40)
    for i in range(cfg.num_rx):
        ax.plot(n, p.static.mean(dim=0)[i, :40], color=f"C{i}", lw=0.9, marker=".", ms=3,
                label=f"RX{i + 1}, start-up on")
        ax.plot(n, steady.static.mean(dim=0)[i, :40], color=f"C{i}", lw=0.7, ls="--",
                label=f"RX{i + 1}, steady state" if i == 0 else None)
    for rail in (0.0, p.full):
        ax.axhline(rail, color="k", lw=0.6)
    ax.set_title(f"tx_rx_leakage +18 dB, IFHighPass(startup=1): the mean chirp's first samples\n"
                 f"leakage {verdict(s_leak)} ({s_leak.params['excess_dB']:+.1f} dB); adc_clipping {verdict(s_clip)} "
                 f"({100 * s_clip.params['fraction']:.2f} % on the rails, all at the chirp start)",
                 fontsize=FS_TITLE)
    ax.set(xlabel="sample in the chirp", ylabel="ADC code (frame mean)", ylim=(-200, p.full + 200))
    ax.legend(fontsize=6, loc="center right", ncol=2)
    return p, s_clip


def clipping_panels(ax_where, ax_rail, cfg: RadarConfig, startup: tuple[Prepared, Signature]) -> None:
    """Where in the chirp the samples clip, and the codes next to each rail: start-up vs too much gain."""
    hot = cfg.replace(if_gain_dB=HIGH_IF_GAIN_DB)
    p_gain = Prepared(capture(hot, chain(hot), ((1.4, 4e-3), *ROOM[1:])), hot)
    cases = {"leakage +18 dB, start-up (IF 33 dB)": startup,
             "return at 1.4 m, IF 48 dB (too much gain)": (p_gain, detect_adc_clipping(p_gain, hot))}
    N = cfg.num_samples_per_chirp
    ax_where.axvspan(-0.5, max(4, N // 32) - 0.5, color="0.9", label="first 1/32 of the chirp")
    lines = []
    for n, (name, (p, s)) in enumerate(cases.items()):
        share = p.rails.double().mean(dim=(0, 1, 2))
        k = torch.nonzero(share).flatten()
        ax_where.vlines(k + 0.15 * n, 1e-4, share[k], color=f"C{n}", lw=1.2, label=name)
        c = torch.round(p.counts).clamp(0, p.full)
        dist = torch.minimum(c, p.full - c).long().flatten()  # codes from the nearer rail
        counts = torch.bincount(dist, minlength=41)[:41].double()
        ax_rail.step(torch.arange(41), counts.clamp_min(0.5), where="mid", color=f"C{n}", lw=0.9, label=name)
        lines.append(f"{'start-up' if n == 0 else 'gain'}: {verdict(s)}, {100 * s.params['fraction']:.2f} % "
                     f"on the rails, rail code {s.params['pileup']:.0f}x its 4 neighbours")
    ax_where.set_title("adc_clipping: share of each sample of the chirp on a rail\n" + lines[0]
                       + " (all at the chirp start)", fontsize=FS_TITLE)
    ax_where.set(xlabel="sample in the chirp", ylabel="share on a rail (frames, chirps, RX)", yscale="log",
                 ylim=(1e-4, 2), xlim=(-2, N + 1))
    ax_where.legend(fontsize=6, loc="upper right")
    ax_rail.set_title("adc_clipping: samples per code next to the rails (the pile-up the detector tests)\n"
                      + lines[1], fontsize=FS_TITLE)
    ax_rail.set(xlabel="codes from the nearer rail (0: on the rail)", ylabel="samples", yscale="log",
                ylim=(0.3, None))
    ax_rail.legend(fontsize=6, loc="upper right")


# --------------------------------------------------------------------------- interference
def after_if_gain(cfg: RadarConfig, *extra: Effect) -> list[Effect]:
    """The default chain with ``extra`` right after ``if_gain`` (several of one kind allowed)."""
    effects = default_effects(cfg)
    i = [e.name for e in effects].index("if_gain") + 1
    return [*effects[:i], *extra, *effects[i:]]


def chirp_excess(ax, fig, p: Prepared) -> None:
    """Each chirp's wideband power over its frame's median chirp, dB (what ``detect_interference`` flags)."""
    r = p.chirp_wideband
    db = 10 * torch.log10(r / r.median(dim=1, keepdim=True).values)
    im = ax.imshow(db.T.numpy(), aspect="auto", origin="lower", vmin=-1, vmax=15, cmap="viridis",
                   interpolation="nearest")
    ax.set(xlabel="frame", ylabel="chirp")
    fig.colorbar(im, ax=ax, label="dB over the frame's median chirp")


def burst_lengths(p: Prepared, cfg: RadarConfig) -> torch.Tensor:
    """Each flagged chirp's burst length as ``detect_interference`` measures it (envelope over 9x the median), s."""
    fi, mi = torch.nonzero(p.burst_mask, as_tuple=True)
    med = p.chirp_power.median(dim=1).values[fi]
    env = p.moving[fi, :, mi].square().mean(dim=1)
    return (env > 9 * med[:, None]).double().sum(dim=-1) / cfg.sample_rate_Hz


def interference_panels(axes, fig, cfg: RadarConfig) -> None:
    """Chirp-by-chirp excess of one and of several interferer slopes, and the burst lengths measured."""
    cases = {"one slope (5 us bursts, 5 % of chirps)": ([Interference(0.05, 100.0, 5e-6)], (5e-6,)),
             "three slopes (5, 20, 60 us, 2 % each)": ([Interference(0.02, 100.0, d) for d in (5e-6, 20e-6, 60e-6)],
                                                      (5e-6, 20e-6, 60e-6))}
    ax_len = axes[2]
    for n, (ax, (name, (effects, _))) in enumerate(zip(axes[:2], cases.items())):
        p = Prepared(capture(cfg, after_if_gain(cfg, *effects)), cfg)
        s = detect_interference(p, cfg)
        chirp_excess(ax, fig, p)
        pr = s.params
        ax.set_title(f"interference, {name}; flagged over {max(3.0, 8 * pr['spread_dB']):.1f} dB\n"
                     f"{verdict(s)}: {100 * pr['probability']:.1f} % of chirps, "
                     f"{pr['excess_dB']:.1f} dB over their frame, {100 * pr['wideband']:.0f} % of bins raised, "
                     f"burst {1e6 * pr['duration_s']:.0f} us", fontsize=FS_TITLE)
        ax_len.hist((1e6 * burst_lengths(p, cfg)).numpy(), bins=torch.arange(0, 82, 2.0).numpy(), histtype="step",
                    color=f"C{n}", label=f"{name}: median {1e6 * pr['duration_s']:.0f} us")
    for d in (5, 20, 60):
        ax_len.axvline(d, color="k", lw=0.5, ls=":")
    ax_len.set_title("interference: burst lengths of the flagged chirps (envelope over 9x the median)\n"
                     "one slope or several: the same signature, one median length (dotted: put in)",
                     fontsize=FS_TITLE)
    ax_len.set(xlabel="measured burst length (us)", ylabel="flagged chirps")
    ax_len.legend(fontsize=6, loc="upper right")


# --------------------------------------------------------------------------- phase noise, drift
def phase_noise_panel(ax, cfg: RadarConfig) -> None:
    """Moving-part power over range around a strong return: the declared LO noise and 0.5 MHz RMS."""
    carrier = ((4.6, 3e-4),)
    lines = []
    for n, (name, pn) in enumerate({"declared LO noise": None,
                                    "0.5 MHz RMS": PhaseNoise(freq_noise_rms_Hz=0.5e6, corner_Hz=100e3)}.items()):
        p = Prepared(capture(cfg, chain(cfg) if pn is None else chain(cfg, pn), carrier), cfg)
        s = detect_phase_noise(p, cfg)
        pw = p.moving_bh4.abs().square().mean(dim=(0, 2))  # (R, K)
        r = torch.arange(pw.shape[1]) * cfg.range_resolution_m
        ref = pw.median()
        ax.plot(r, 10 * torch.log10(pw.mean(dim=0) / ref), color=f"C{n}", lw=0.8, label=f"{name}: {verdict(s)}")
        pr = s.params
        lines.append(f"{name} {verdict(s)} ({pr['skirt_dBc']:.1f} dBc, {pr['excess_dB']:+.1f} dB)")
    ax.axvline(carrier[0][0], color="k", lw=0.5, ls=":")
    ax.set_title(f"phase_noise on a strong carrier ({pr['carrier_snr_dB']:.0f} dB over the floor, dotted)\n"
                 + "; ".join(lines), fontsize=FS_TITLE)
    ax.set(xlabel="range (m)", ylabel="moving part, dB over its median (RX mean)")
    ax.legend(fontsize=6, loc="upper right")


def drift_panels(ax_dc, ax_gain, cfg: RadarConfig) -> None:
    """Frame series of the chirp DC per RX (DC drift) and of the static returns' levels (gain drift)."""
    p = Prepared(capture(cfg, chain(cfg, FrameDrift(gain_rms_dB=0.0, dc_rms_counts=3.0)), ROOM), cfg)
    s = detect_frame_drift(p, cfg)
    dc = ((p.counts * p.bh4).sum(dim=-1) / p.bh4.sum()).mean(dim=-1)  # (F, R) frame means
    for i in range(cfg.num_rx):
        ax_dc.plot(dc[:, i] - dc[:, i].mean(), color=f"C{i}", marker=".", ms=3, lw=0.7, label=f"RX{i + 1}")
    pr = s.params
    ax_dc.set_title(f"frame_drift of the DC, 3 counts RMS put in\n{verdict(s)}: {pr['dc_rms_counts']:.2f} counts "
                    f"RMS (largest RX), variance ratio {pr['dc_f']:.0f}", fontsize=FS_TITLE)
    ax_dc.set(xlabel="frame", ylabel="chirp DC re its mean (counts)")
    ax_dc.legend(fontsize=6, loc="upper right", ncol=3)

    p = Prepared(capture(cfg, chain(cfg, FrameDrift(gain_rms_dB=0.5, dc_rms_counts=0.0)), ROOM), cfg)
    s = detect_frame_drift(p, cfg)
    pcf = p.static_hann.abs().square().mean(dim=1)  # (F, K)
    for n, (rng_m, _) in enumerate(ROOM):
        k0 = round(rng_m / cfg.range_resolution_m)
        k = k0 - 1 + int(pcf[:, k0 - 1: k0 + 2].mean(dim=0).argmax())
        lv = 10 * torch.log10(pcf[:, k])
        ax_gain.plot(lv - lv.mean(), color=f"C{n}", marker=".", ms=3, lw=0.7, label=f"return at {rng_m} m")
    pr = s.params
    ax_gain.set_title(f"frame_drift of the gain, 0.5 dB RMS put in\n{verdict(s)}: {pr['gain_rms_dB']:.2f} dB RMS "
                      f"over {pr['num_returns']:.0f} returns, variance ratio {pr['gain_f']:.0f}", fontsize=FS_TITLE)
    ax_gain.set(xlabel="frame", ylabel="static return's power re its mean (dB)")
    ax_gain.legend(fontsize=6, loc="upper right", ncol=3)


def main() -> None:
    """Draw the 5 x 3 figure."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    args = ap.parse_args()
    cfg = RadarConfig.bgt60tr13c()
    hot = cfg.replace(if_gain_dB=HIGH_IF_GAIN_DB)
    plt = pyplot()
    fig, axes = plt.subplots(5, 3, figsize=(16, 20))
    mismatch_panel(axes[0, 0], cfg, ROOM, "static returns, IF 33 dB")
    mismatch_panel(axes[0, 1], hot, ROOM, "static returns, IF 48 dB")
    mismatch_panel(axes[0, 2], hot, (), "no static return, IF 48 dB")
    highpass_panel(axes[1, 0], hot)
    highpass_panel(axes[1, 1], cfg)
    leakage_levels_panel(axes[1, 2], cfg)
    startup = leakage_startup_panel(axes[2, 0], cfg)
    clipping_panels(axes[2, 1], axes[2, 2], cfg, startup)
    interference_panels(axes[3], fig, cfg)
    phase_noise_panel(axes[4, 0], cfg)
    drift_panels(axes[4, 1], axes[4, 2], cfg)
    fig.tight_layout()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    atomic_savefig(fig, args.out, dpi=80)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
