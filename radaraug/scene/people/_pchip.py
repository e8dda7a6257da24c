"""Periodic PCHIP (monotone piecewise-cubic Hermite) curves, evaluated in torch.

Boulic's joint-angle trajectories are given as control points over one normalized gait cycle
and interpolated with PCHIP (MATLAB ``pchip``) over three copies of the cycle; repeating the
control points with period 1 and using the interior PCHIP slopes is the same curve. Several
curves are evaluated in one batched call, with the exact derivative of the interpolant.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import torch


def _pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Fritsch-Carlson slopes as in MATLAB ``pchip`` / SciPy ``PchipInterpolator``."""
    h = np.diff(x)
    delta = np.diff(y) / h
    d = np.zeros_like(y)
    for k in range(1, len(x) - 1):
        if delta[k - 1] * delta[k] <= 0.0:
            continue  # local extremum (or flat): zero slope keeps the curve monotone
        w1 = 2.0 * h[k] + h[k - 1]
        w2 = h[k] + 2.0 * h[k - 1]
        d[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])
    return d


class PeriodicPchip:
    """A bank of ``C`` periodic PCHIP curves of period 1.

    Args:
        curves: one ``(x, y)`` control-point list per curve; ``x`` strictly increasing and
            spanning less than one period.
    """

    def __init__(self, curves: Sequence[tuple[Sequence[float], Sequence[float]]]) -> None:
        tables = []
        for x, y in curves:
            xa, ya = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
            xs = np.concatenate([xa - 1.0, xa, xa + 1.0])
            ys = np.concatenate([ya, ya, ya])
            tables.append((xs, ys, _pchip_slopes(xs, ys)))
        k = max(len(t[0]) for t in tables)
        pad = lambda a, fill: np.concatenate([a, fill[: k - len(a)]])  # noqa: E731
        self._x = np.stack([pad(xs, 10.0 + np.arange(k)) for xs, _, _ in tables])
        self._y = np.stack([pad(ys, np.full(k, ys[-1])) for _, ys, _ in tables])
        self._d = np.stack([pad(ds, np.zeros(k)) for _, _, ds in tables])
        self._cache: dict[tuple[torch.device, torch.dtype], tuple[torch.Tensor, ...]] = {}

    def _tables(self, device: torch.device, dtype: torch.dtype) -> tuple[torch.Tensor, ...]:
        key = (device, dtype)
        if key not in self._cache:
            x, y, d = (torch.as_tensor(a, dtype=dtype, device=device) for a in (self._x, self._y, self._d))
            lo = torch.stack([x, y, d], dim=-1)  # (C, K, 3): knot k
            hi = torch.roll(lo, -1, dims=1)  # knot k + 1 (the wrapped last row is never used)
            self._cache[key] = (x, lo, hi)
        return self._cache[key]

    def __call__(self, u: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Evaluate every curve.

        Args:
            u: ``(C, N)`` normalized cycle times in ``[0, 1)``.

        Returns:
            ``(value, d value / du)``, both ``(C, N)``.
        """
        x, lo, hi = self._tables(u.device, u.dtype)
        k = x.shape[1]
        # Interval index by counting knots <= u, and the interval's end data by a one-hot
        # masked sum: plain elementwise ops (cheaper on small tensors than searchsorted +
        # gathers, and exact, unlike a matmul that may run in TF32).
        idx = ((u.unsqueeze(-1) >= x.unsqueeze(1)).sum(-1) - 1).clamp(0, k - 2)
        onehot = (idx.unsqueeze(-1) == torch.arange(k, device=u.device)).to(u.dtype)  # (C, N, K)
        ends = (onehot.unsqueeze(-1) * torch.cat([lo, hi], dim=-1).unsqueeze(1)).sum(-2)  # (C, N, 6)
        x0, y0, d0, x1, y1, d1 = ends.unbind(-1)
        h = x1 - x0
        s = (u - x0) / h
        s2, s3 = s * s, s * s * s
        h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2
        val = h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1
        g00, g10, g01, g11 = 6 * s2 - 6 * s, 3 * s2 - 4 * s + 1, -6 * s2 + 6 * s, 3 * s2 - 2 * s
        der = (g00 * y0 + g01 * y1) / h + g10 * d0 + g11 * d1
        return val, der
