"""The synthesis' error contract: its error against the exact sum, in every range-Doppler cell, under the noise.

The twin's fast synthesis truncates series (the coupling's Chebyshev orders, chosen against
``taylor_tol``). What that may cost is set by the receiver's noise, not by the frame's strongest path:
an error far under the noise cannot change a capture-like frame, a map or a label. For a scene and a
config, :func:`contract_margin` simulates the same frames with the fast and the exact synthesis (same
random draws, the ADC's rounding and clipping left out so that only the synthesis differs), and the
receiver's noise alone (the same frames with and without its noise stages), and returns by how many dB
the worst cell's error stays under the mean noise cell (docs/simulation.md, "The synthesis' error contract").
``radaraug bench contract`` records it per tolerance and config, with the twin's speed at each.
"""

from __future__ import annotations

import math
import os
import platform
import statistics
import time
from dataclasses import dataclass
from typing import Any

import torch

from radaraug.bench import torch_threads, write_figures
from radaraug.config import RadarConfig
from radaraug.scene.scene import Scene
from radaraug.sensor.defaults import default_effects
from radaraug.sensor.effects import ADCNoise, Effect, ThermalNoise
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sensor.synthesis import DEFAULT_TAYLOR_TOL

CONTRACT_DB = 30.0
"""The synthesis error stays at least this far under the frame's mean noise cell, in every cell."""

#: The configs the contract is checked at: the paper's, a short frame, an odd sample count, both IF-gain ends.
CONTRACT_CONFIGS: dict[str, dict[str, Any]] = {
    "paper": {},
    "128x32": {"num_samples_per_chirp": 128, "num_chirps_per_frame": 32},
    "200 samples": {"num_samples_per_chirp": 200},
    "IF 18 dB": {"if_gain_dB": 18.0},
    "IF 60 dB": {"if_gain_dB": 60.0},
}


@dataclass(frozen=True)
class ContractResult:
    """One config's worst cell: ``margin_dB`` = mean noise cell (dB) - worst error cell (dB), over RX and frames."""

    config: str
    margin_dB: float
    worst_error_dB: float
    mean_noise_dB: float

    def to_dict(self) -> dict[str, Any]:
        """JSON types, rounded to 0.1 dB."""
        return {"config": self.config, "margin_dB": round(self.margin_dB, 1),
                "worst_error_dB": round(self.worst_error_dB, 1), "mean_noise_dB": round(self.mean_noise_dB, 1)}


def _chain(config: RadarConfig, *, noise: bool) -> list[Effect]:
    """The default chain without the ADC's rounding and clipping; its noise stages silent unless ``noise``."""
    out = []
    for e in default_effects(config):
        if e.name in ("adc_quantization", "adc_clipping"):
            continue
        if not noise and isinstance(e, ThermalNoise):
            e = ThermalNoise(noise_figure_dB=float(e.noise_figure_dB), temperature_K=0.0)
        if not noise and isinstance(e, ADCNoise):
            e = ADCNoise(rms_counts=0.0)
        out.append(e)
    return out


def _rd_power(x: torch.Tensor) -> torch.Tensor:
    """``(frames, RX, chirps, samples)`` -> Hann-windowed complex 2-D spectrum power, per cell (range FFT one-sided)."""
    m, n = x.shape[-2:]
    w = torch.hann_window(m, periodic=False, dtype=torch.float64)[:, None] * torch.hann_window(
        n, periodic=False, dtype=torch.float64)[None, :]
    spec = torch.fft.fft(torch.fft.rfft(x.double() * w, dim=-1), dim=-2)
    return spec.abs().square()


def contract_margin(config: RadarConfig, *, name: str = "", scene: str = "corridor_two_walkers",
                    frames: int = 2, taylor_tol: float = DEFAULT_TAYLOR_TOL, seed: int = 0,
                    start_frame: int = 10, noise_tol: float | None = None) -> ContractResult:
    """The worst range-Doppler cell of the fast synthesis' error, in dB under the mean noise cell.

    The twin as it runs (diffuse clutter, shadowing, motion inside the frame on) on ``scene`` with
    ``config``; the frames ``start_frame .. start_frame + frames`` with the scene's people.

    Args:
        config: the radar config.
        name: a label for the result.
        scene: a built-in scene with people.
        frames: frames compared.
        taylor_tol: the fast synthesis' tolerance under test.
        seed: seed of the receiver's random draws (the same for every run).
        start_frame: the first frame's index.
        noise_tol: the fast synthesis' bound relative to the noise instead (``FMCWReceiver(noise_tol=...)``).

    Returns:
        The margin (positive: the error is under the noise by that many dB).
    """
    from radaraug.sim.twin import DigitalTwin

    base = Scene.builtin(scene)
    out: dict[tuple[str, bool], torch.Tensor] = {}
    # The room's signal goes through the linear stages only, so the quiet run reuses the noisy one's.
    static: dict[str, torch.Tensor] = {}
    for synthesis, noise in (("exact", True), ("fast", True), ("fast", False)):
        rx = FMCWReceiver(config, effects=_chain(config, noise=noise), synthesis=synthesis, taylor_tol=taylor_tol,
                          noise_tol=noise_tol)
        twin = DigitalTwin(base, config=config, receiver=rx, static_signal=static.get(synthesis))
        static[synthesis] = twin.static_signal()
        times = twin.frame_times(range(start_frame, start_frame + frames))
        g = torch.Generator().manual_seed(seed)
        out[synthesis, noise] = twin.simulate(base.people, times, generators=g).double()
    worst_db = 10 * math.log10(max(float(_rd_power(out["fast", True] - out["exact", True]).amax()), 1e-300))
    noise_db = 10 * math.log10(float(_rd_power(out["fast", True] - out["fast", False]).mean()))
    return ContractResult(name, noise_db - worst_db, worst_db, noise_db)


TOLERANCES = (1e-5, 1e-4, 1e-3, 3e-3, 1e-2)
"""The tolerances :func:`run_contract_benchmark` measures (relative to the strongest moving path)."""
NOISE_TOLERANCES = (1e-3, 3e-3, 1e-2)
"""The noise-relative bounds it measures (``FMCWReceiver(noise_tol=...)``)."""


def _frames_per_s(receivers: dict[str, dict[str, Any]], blocks: int = 4, rounds: int = 3) -> dict[str, list[float]]:
    """Frames/s of the default twin (two walkers, paper config, 16-frame blocks) per receiver option set, interleaved."""
    from radaraug.sim.seeding import item_generator
    from radaraug.sim.twin import DigitalTwin

    scene = Scene.builtin("corridor_two_walkers")
    static = DigitalTwin(scene).static_signal()
    twins = {k: DigitalTwin(scene, receiver=FMCWReceiver(scene.config, **o), static_signal=static)
             for k, o in receivers.items()}
    for tw in twins.values():  # warm-up block
        tw.simulate(scene.people, tw.frame_times(range(16)), generators=item_generator(0, 0))
    out: dict[str, list[float]] = {k: [] for k in twins}
    for _ in range(rounds):
        for t, tw in twins.items():
            t0 = time.perf_counter()
            for j in range(1, blocks + 1):
                tw.simulate(scene.people, tw.frame_times(range(16 * j, 16 * (j + 1))), generators=item_generator(0, j))
            out[t].append(16 * blocks / (time.perf_counter() - t0))
    return out


def _margins(**options: Any) -> dict[str, Any]:
    """Each config's margin and a near walker's (frames 75-76: ~1.5 m away, the strongest moving path)."""
    rows = {r.config: r.to_dict() for r in
            (contract_margin(RadarConfig.bgt60tr13c(**c), name=n, frames=2, **options) for n, c in CONTRACT_CONFIGS.items())}
    for name in ("paper", "IF 60 dB"):
        near = contract_margin(RadarConfig.bgt60tr13c(**CONTRACT_CONFIGS[name]), name=f"{name}, near walker",
                               frames=2, start_frame=75, **options)
        rows[near.config] = near.to_dict()
    return rows


def run_contract_benchmark(*, out: str | os.PathLike | None = None, tolerances: tuple[float, ...] = TOLERANCES,
                           noise_tolerances: tuple[float, ...] = NOISE_TOLERANCES) -> dict[str, Any]:
    """The contract's margin per tolerance and config (and a near walker), and the twin's speed per tolerance.

    Tolerances relative to the strongest path (``taylor_tol``) and to the noise (``noise_tol``). The speed
    is a ratio against :data:`DEFAULT_TAYLOR_TOL` measured in the same process, interleaved.
    """
    t0 = time.perf_counter()
    with torch_threads(1):
        margins = {f"{tol:g}": _margins(taylor_tol=tol) for tol in tolerances}
        noise_margins = {f"{tol:g}": _margins(noise_tol=tol) for tol in noise_tolerances}
        receivers = {f"{t:g}": {"taylor_tol": t} for t in sorted({*tolerances, DEFAULT_TAYLOR_TOL})}
        receivers |= {f"noise {t:g}": {"noise_tol": t} for t in noise_tolerances}
        speed = _frames_per_s(receivers)
    base = statistics.median(speed[f"{DEFAULT_TAYLOR_TOL:g}"])
    worst = {k: min(v["margin_dB"] for v in rows.values()) for k, rows in margins.items()}
    noise_worst = {k: min(v["margin_dB"] for v in rows.values()) for k, rows in noise_margins.items()}
    met = [float(k) for k, w in worst.items() if w >= CONTRACT_DB]
    figures = {
        "benchmark": "contract",
        "what": "fast synthesis error against the exact sum, worst range-Doppler cell vs the mean noise cell, "
                "two-walker corridor, frames 10-11 (near walker: frames 75-76, one walker ~1.5 m away), diffuse "
                "clutter, shadowing and motion inside the frame on; ADC rounding and clipping left out "
                "(docs/simulation.md)",
        "contract_dB": CONTRACT_DB,
        "default_taylor_tol": DEFAULT_TAYLOR_TOL,
        "configs": CONTRACT_CONFIGS,
        "margin_dB": margins,
        "worst_margin_dB": worst,
        "largest_tolerance_meeting_contract": max(met) if met else None,
        "noise_tol_margin_dB": noise_margins,
        "noise_tol_worst_margin_dB": noise_worst,
        "frames_per_s_1proc": {k: [round(v, 1) for v in s] for k, s in speed.items()},
        "speed_ratio_vs_default": {k: round(statistics.median(s) / base, 3) for k, s in speed.items()},
        "wall_s": round(time.perf_counter() - t0, 1),
        "torch_version": torch.__version__, "cpu": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(), "threads": 1,
    }
    write_figures(out, figures)
    return figures


__all__ = ["CONTRACT_CONFIGS", "CONTRACT_DB", "NOISE_TOLERANCES", "TOLERANCES", "ContractResult", "contract_margin",
           "run_contract_benchmark"]
