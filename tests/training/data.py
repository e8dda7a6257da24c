"""Small labelled captures from an independent point-scatterer generator (not the twin).

Used as the test side of the training tests: it shares no code with radaraug's twin (no ray
tracer, no receiver chain), only the capture writer. A person is a handful of point scatterers
(torso plus swinging limbs) moving along the boresight; the IF signal is a sum of real beat
tones, plus per-RX DC offsets and white noise, quantized to 12 bits.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from radaraug.config import RadarConfig
from radaraug.io import write_capture

C0 = 299_792_458.0


def small_config() -> RadarConfig:
    """The paper's chirp with 64 samples and 16 chirps: 32 x 16 RD maps, cheap to simulate."""
    return RadarConfig.bgt60tr13c(num_samples_per_chirp=64, num_chirps_per_frame=16)


def point_scatterer_frames(config: RadarConfig, people: int, frames: int, seed: int) -> np.ndarray:
    """ADC counts ``(frames, rx, chirps, samples)`` of ``people`` walkers (0 = empty room)."""
    rng = np.random.default_rng(seed)
    n, m, nrx = config.num_samples_per_chirp, config.num_chirps_per_frame, config.num_rx
    t = np.arange(n) / config.sample_rate_Hz
    tc = np.arange(m) * config.chirp_repetition_time_s
    slope, fc = config.slope_Hz_per_s, config.center_frequency_Hz
    walkers = [(rng.uniform(1.0, 6.0), rng.choice([-1, 1]) * rng.uniform(0.6, 1.5)) for _ in range(people)]
    out = np.empty((frames, nrx, m, n))
    for f in range(frames):
        x = np.zeros((nrx, m, n))
        t0 = f * config.frame_repetition_time_s
        # static clutter: a wall at 7.3 m and the TX->RX leakage near 0 m
        scat = [(7.3, 0.0, 3e-3), (0.05, 0.0, 2e-2)]
        for r0, v in walkers:
            r = r0 + v * t0
            scat.append((r, v, 8e-3 / max(r, 0.5)))
            for k in range(4):  # limbs: sinusoidal velocity around the torso's
                amp = 1.5 * v * math.sin(2 * math.pi * 1.8 * t0 + k * math.pi / 2)
                scat.append((r + 0.1 * k, v + amp, 3e-3 / max(r, 0.5)))
        for r, v, a in scat:
            rr = r + v * tc[:, None]  # (m, 1)
            phase = 2 * math.pi * (slope * 2 * rr / C0 * t[None, :] + fc * 2 * rr / C0)
            x += a * np.cos(phase)[None]
        x += rng.normal(0, 1.4 / 2047.5, size=x.shape)
        x += np.array([1620, 1945, 2067.5])[:nrx, None, None] / 2047.5 - 1
        out[f] = x
    return np.clip(np.round((out + 1) * 4095 / 2), 0, 4095).astype(np.uint16)


def write_test_captures(folder: Path, frames: int = 6, seed: int = 0) -> tuple[Path, list[tuple[Path, int]]]:
    """An empty-room calibration capture and one capture per count 0/1/2 (file label + per-frame)."""
    folder.mkdir(parents=True, exist_ok=True)
    cfg = small_config()
    cal = write_capture(folder / "empty_room.h5", point_scatterer_frames(cfg, 0, 12, seed), cfg)
    tests = []
    for count in (0, 1, 2):
        counts = point_scatterer_frames(cfg, count, frames, seed + 1 + count)
        path = write_capture(folder / f"walk_{count}.h5", counts, cfg,
                             labels={"count": np.full(frames, count, dtype=np.int64)})
        tests.append((path, count))
    return cal, tests
