"""Small 3-vector helpers that are fast on ``(..., 3)`` tensors.

Reducing a ``(..., 3)`` product with ``.sum(-1)`` (or multiplying ``(..., 3, 3) @ (..., 3, 1)``
as batched 3x3 matrices) runs a generic reduction or a tiny GEMM per row; writing the three
components out is one fused pass per component and measured 3-4x faster on half a million
rows on a CPU (the shadow test and the people's occlusion test do this per frame).
"""

from __future__ import annotations

import torch


def dot(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """``(a * b).sum(-1)`` of broadcastable ``(..., 3)`` tensors."""
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def matvec(m: torch.Tensor, v: torch.Tensor) -> torch.Tensor:
    """``(m @ v[..., None])[..., 0]`` of broadcastable ``(..., 3, 3)`` and ``(..., 3)`` tensors."""
    return torch.stack([dot(m[..., 0, :], v), dot(m[..., 1, :], v), dot(m[..., 2, :], v)], dim=-1)
