"""The written-out 3-vector helpers against torch's own reductions and matrix products."""

from __future__ import annotations

import torch

from radaraug.raytrace.vec import dot, matvec


def test_dot_and_matvec_match_torch_with_broadcasting():
    g = torch.Generator().manual_seed(0)
    a = torch.randn(4, 1, 5, 3, generator=g, dtype=torch.float64)
    b = torch.randn(1, 6, 5, 3, generator=g, dtype=torch.float64)
    m = torch.randn(4, 1, 1, 3, 3, generator=g, dtype=torch.float64)
    torch.testing.assert_close(dot(a, b), (a * b).sum(-1))
    torch.testing.assert_close(matvec(m, b), (m @ b[..., None])[..., 0])
    assert matvec(m, b).shape == (4, 6, 5, 3)
