"""A straightforward NumPy implementation of the paper's RD chain: the benchmark baseline.

Same steps and conventions as the torch transforms, float64, vectorized over the batch like the torch
version, so that the ratio measures the library, not a Python loop.
"""

from __future__ import annotations

import numpy as np


def numpy_rd_db(cube: np.ndarray) -> np.ndarray:
    """Raw cube ``(B, rx, chirps, samples)`` -> per-RX RD dB maps ``(B, rx, range, doppler)``."""
    _, _, m, n = cube.shape
    x = cube - cube.mean(axis=-1, keepdims=True)
    w_r = np.hanning(n)
    w_d = np.hanning(m)
    rng_fft = np.fft.fft(x * w_r, axis=-1)[..., : n // 2] / w_r.sum()
    rng_fft = np.swapaxes(rng_fft, -1, -2)  # (B, rx, range, chirps)
    rd = np.fft.fftshift(np.fft.fft(rng_fft * w_d, axis=-1), axes=-1) / w_d.sum()
    return 20 * np.log10(np.abs(rd) + 1e-12)


def numpy_rd_chain(
    cube: np.ndarray,
    *,
    mean_db: float,
    std_db: float,
    vmin: float,
    vmax: float,
    lut: np.ndarray,
    rng: np.random.Generator,
) -> np.ndarray:
    """Raw cube ``(B, rx, chirps, samples)`` -> viridis images ``(B, 3, range, doppler)``.

    Args:
        cube: raw frames in SDK floats.
        mean_db: CDR noise-floor mean.
        std_db: CDR noise-floor standard deviation.
        vmin: clip lower bound in dB.
        vmax: clip upper bound in dB.
        lut: ``(256, 3)`` colormap table.
        rng: NumPy random generator for the CDR draw.
    """
    db = numpy_rd_db(cube)
    noise = rng.normal(mean_db, std_db, size=db.shape)
    db = np.maximum(db, noise)
    db = 10 * np.log10(np.mean(10 ** (db / 10), axis=1, keepdims=True))  # combine RX on power
    norm = (np.clip(db, vmin, vmax) - vmin) / (vmax - vmin)
    idx = np.clip((norm * 255).astype(np.int64), 0, 255)
    img = lut[idx[:, 0]]  # (B, range, doppler, 3)
    return np.moveaxis(img, -1, -3)
