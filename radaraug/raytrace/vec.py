"""Small 3-vector helpers, written per component: faster than ``.sum(-1)`` or 3x3 GEMMs on ``(..., 3)`` rows."""

from __future__ import annotations

import torch


def dot(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """``(a * b).sum(-1)`` of broadcastable ``(..., 3)`` tensors."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def matvec(m: torch.Tensor, v: torch.Tensor) -> torch.Tensor:
    """``(m @ v[..., None])[..., 0]`` of broadcastable ``(..., 3, 3)`` and ``(..., 3)`` tensors."""
    return torch.stack([dot(m[..., 0, :], v), dot(m[..., 1, :], v), dot(m[..., 2, :], v)], dim=-1)
