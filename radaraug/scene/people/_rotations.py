"""Elementary rotations with their time derivatives, and Euler-angle helpers.

Kinematic chains are propagated as pairs ``(R, dR/dt)``: composing ``(A, A') (B, B')`` gives
``(AB, A'B + AB')``, so every joint velocity is the exact derivative of its position (no finite
differences). All functions are vectorized over any leading dims.
"""

from __future__ import annotations

import math

import torch

_AXES = {"x": 0, "y": 1, "z": 2}


def axis_rotation(axis: str, angle: torch.Tensor | float) -> torch.Tensor:
    """Right-handed rotation matrices about a coordinate axis.

    Args:
        axis: ``"x"``, ``"y"`` or ``"z"``.
        angle: ``(...)`` radians, or one Python float (a pose from a config: evaluated on the
            host with ``math.cos``/``math.sin`` in float64, the values NumPy gives too).

    Returns:
        ``(..., 3, 3)`` rotation matrices (``(3, 3)`` float64 on the CPU for a float angle).
    """
    if isinstance(angle, (int, float)):
        kk, cc, ss = _basis(axis, torch.device("cpu"), torch.float64)
        return kk + math.cos(angle) * cc + math.sin(angle) * ss
    kk, cc, ss = _basis(axis, angle.device, angle.dtype)
    return kk + torch.cos(angle)[..., None, None] * cc + torch.sin(angle)[..., None, None] * ss


_BASIS_CACHE: dict[tuple[str, torch.device, torch.dtype], tuple[torch.Tensor, torch.Tensor, torch.Tensor]] = {}


def _basis(axis: str, device: torch.device, dtype: torch.dtype) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Constant matrices with ``R(a) = K + cos(a) C + sin(a) S`` for a rotation about ``axis``."""
    key = (axis, device, dtype)
    if key not in _BASIS_CACHE:
        k = _AXES[axis]
        i, j = (k + 1) % 3, (k + 2) % 3  # the cyclic pair following k: R = [[c, -s], [s, c]] on it
        kk, cc, ss = (torch.zeros(3, 3, dtype=dtype, device=device) for _ in range(3))
        kk[k, k] = 1.0
        cc[i, i] = cc[j, j] = 1.0
        ss[i, j], ss[j, i] = -1.0, 1.0
        _BASIS_CACHE[key] = (kk, cc, ss)
    return _BASIS_CACHE[key]


def rotation_from_cos_sin(
    axis: str, c: torch.Tensor, s: torch.Tensor, rate: torch.Tensor
) -> tuple[torch.Tensor, torch.Tensor]:
    """A rotation about a coordinate axis and its time derivative, ``(R, dR/dt)``.

    From precomputed ``cos``/``sin`` of the angle and its ``rate`` in rad/s (lets a caller evaluate all
    its trigonometric functions in one batched call).
    """
    kk, cc, ss = _basis(axis, c.device, c.dtype)
    c, s, rt = c[..., None, None], s[..., None, None], rate[..., None, None]
    return kk + c * cc + s * ss, (c * rt) * ss - (s * rt) * cc


def compose(
    a: tuple[torch.Tensor, torch.Tensor], b: tuple[torch.Tensor, torch.Tensor]
) -> tuple[torch.Tensor, torch.Tensor]:
    """Product of two rotations-with-derivative ``(A, A')(B, B') = (AB, A'B + AB')``."""
    return a[0] @ b[0], a[1] @ b[0] + a[0] @ b[1]


def apply(rd: tuple[torch.Tensor, torch.Tensor], v: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Rotate constant vectors ``v`` ``(..., 3)`` (broadcast): returns ``(R v, R' v)``, ``(..., 3)``."""
    vc = v.unsqueeze(-1)
    return (rd[0] @ vc).squeeze(-1), (rd[1] @ vc).squeeze(-1)


def euler_from_matrix(r: torch.Tensor, order: str) -> torch.Tensor:
    """Angles ``(a1, a2, a3)`` such that ``R = R_o1(a1) R_o2(a2) R_o3(a3)`` (intrinsic order).

    Only Tait-Bryan orders (three different axes) are supported; the middle angle is in
    ``[-pi/2, pi/2]``.

    Args:
        r: ``(..., 3, 3)`` rotation matrices.
        order: e.g. ``"zxy"``.

    Returns:
        ``(..., 3)`` radians.
    """
    i, j, k = (_AXES[a] for a in order)
    # Parity of the permutation (i, j, k) decides the signs of the closed form.
    sign = 1.0 if (j - i) % 3 == 1 else -1.0
    a2 = torch.asin(torch.clamp(sign * r[..., i, k], -1.0, 1.0))
    a1 = torch.atan2(-sign * r[..., j, k], r[..., k, k])
    a3 = torch.atan2(-sign * r[..., i, j], r[..., i, i])
    return torch.stack([a1, a2, a3], dim=-1)


def matrix_from_euler(angles: torch.Tensor, order: str) -> torch.Tensor:
    """``R = R_o1(a1) R_o2(a2) R_o3(a3)`` from ``(..., 3)`` radians."""
    r = axis_rotation(order[0], angles[..., 0])
    r = r @ axis_rotation(order[1], angles[..., 1])
    return r @ axis_rotation(order[2], angles[..., 2])
