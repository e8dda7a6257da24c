"""The noise-floor clamp of RandomDR and CalibratedDR, with the floor given explicitly."""

from __future__ import annotations

import torch

from radaraug.errors import InputTensorError
from radaraug.transforms._checks import check_tensor
from radaraug.transforms._rng import draw


def calibrated_floor(
    shape: tuple[int, ...],
    mean_db: float,
    std_db: float,
    *,
    like: torch.Tensor,
    generator: torch.Generator | None = None,
) -> torch.Tensor:
    """A floor map ``N ~ Normal(mean_db, std_db**2)``, i.i.d. per element (CalibratedDR's draw).

    Args:
        shape: the floor's shape (usually the maps' shape).
        mean_db: the mean ``m_t`` in dB.
        std_db: the standard deviation ``s_t`` in dB, >= 0.
        like: a tensor whose dtype and device the floor takes.
        generator: draw from it (else torch's global RNG). A generator on another device than
            ``like`` draws on its own device and the result is moved.

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> maps = torch.full((2, 3, 8, 4), -130.0)
        >>> floor = F.calibrated_floor(maps.shape, -100.0, 3.0, like=maps,
        ...                            generator=torch.Generator().manual_seed(0))
        >>> floor.shape, bool((F.dr_clamp(maps, floor) == floor).all())
        (torch.Size([2, 3, 8, 4]), True)
    """
    return draw("normal", tuple(shape), like, generator, float(mean_db), float(std_db))


def empirical_floor(
    shape: tuple[int, ...],
    quantiles_db: torch.Tensor,
    *,
    like: torch.Tensor,
    generator: torch.Generator | None = None,
) -> torch.Tensor:
    """A floor map drawn i.i.d. per element from a measured distribution given by its quantiles.

    Inverse-transform sampling: ``u ~ Uniform[0, 1)`` and ``N = Q(u)``, with ``Q`` the piecewise
    linear interpolation of ``quantiles_db`` at equally spaced probabilities ``0, 1/(K-1), ..., 1``.
    The draws follow the measured floor's distribution (its upper tail included) to within the
    table's resolution, unlike a normal distribution with the same mean and std (CalibratedDR's
    ``floor="empirical"``).

    Args:
        shape: the floor's shape (usually the maps' shape).
        quantiles_db: ``(K,)`` non-decreasing quantiles in dB, ``K >= 2``.
        like: a tensor whose dtype and device the floor takes.
        generator: draw from it (else torch's global RNG).

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> q = torch.tensor([-110.0, -100.0, -80.0])  # median -100 dB, upper half up to -80 dB
        >>> floor = F.empirical_floor((100_000,), q, like=torch.zeros(1),
        ...                           generator=torch.Generator().manual_seed(0))
        >>> bool(floor.min() >= -110) and bool(floor.max() <= -80), round(float(floor.median()))
        (True, -100)
    """
    if quantiles_db.ndim != 1 or quantiles_db.numel() < 2:
        raise InputTensorError(f"empirical_floor: quantiles_db must be 1-D with >= 2 values, got {tuple(quantiles_db.shape)}")
    u = draw("rand", tuple(shape), like, generator)
    table = quantiles_db.to(device=u.device, dtype=u.dtype)
    pos = u * (table.numel() - 1)
    lo = pos.floor().long().clamp_(max=table.numel() - 2)
    return torch.lerp(table[lo], table[lo + 1], pos - lo)


def random_floor(
    shape: tuple[int, ...],
    mean_db: torch.Tensor,
    std_db: torch.Tensor,
    noise: torch.Tensor,
) -> torch.Tensor:
    """RandomDR's floor from per-sample ``(m, s)`` and standard normal draws: ``m + s * noise``.

    Args:
        shape: the leading (per-sample) dims of ``mean_db`` and ``std_db``.
        mean_db: per-sample floor means ``m`` (dB), shape ``shape``.
        std_db: per-sample floor standard deviations ``s`` (dB), shape ``shape``.
        noise: standard normal draws ``(*shape, *event)``.

    Returns:
        ``(*shape, *event)``: sample ``k``'s floor is ``Normal(m_k, s_k**2)`` per cell.

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> z = torch.zeros(2, 1, 2, 2)
        >>> F.random_floor((2,), torch.tensor([-110.0, -95.0]), torch.tensor([1.0, 4.0]), z)[:, 0, 0, 0]
        tensor([-110.,  -95.])
    """
    event = (1,) * (noise.ndim - len(shape))
    return torch.addcmul(mean_db.reshape(tuple(shape) + event), noise, std_db.reshape(tuple(shape) + event))


def dr_clamp(x: torch.Tensor, noise_db: torch.Tensor) -> torch.Tensor:
    """The paper's clamp ``max(S, N)`` in dB: cells below the floor become it, the rest stay bit for bit.

    Args:
        x: dB RD maps ``(..., rx, range, doppler)``.
        noise_db: the floor ``N``, broadcastable to ``x`` (cast to ``x``'s dtype).

    Returns:
        A new tensor of ``x``'s shape.

    Examples:
        >>> import torch
        >>> from radaraug.transforms import functional as F
        >>> F.dr_clamp(torch.tensor([[[-130.0, -60.0]]]), torch.tensor(-100.0)).tolist()
        [[[-100.0, -60.0]]]
    """
    x = check_tensor(x, "dr_clamp expects a dB RD map (..., rx, range, doppler)", finite=False)
    if not isinstance(noise_db, torch.Tensor):
        raise InputTensorError(f"dr_clamp: noise_db must be a torch.Tensor, got {type(noise_db).__name__}")
    return torch.maximum(x, noise_db.to(dtype=x.dtype))

