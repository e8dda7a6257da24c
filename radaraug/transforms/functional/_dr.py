"""The noise-floor clamp of RandomDR and CalibratedDR, and the floors they draw."""

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
    """A floor map ``N ~ Normal(mean_db, std_db**2)`` in dB, i.i.d. per element (CalibratedDR's draw).

    Args:
        shape: the floor's shape.
        mean_db: the mean ``m_t``.
        std_db: the standard deviation ``s_t``, >= 0.
        like: a tensor whose dtype and device the floor takes.
        generator: draw from it (else torch's global RNG).

    Examples:
        >>> calibrated_floor((2, 3, 8, 4), -100.0, 3.0, like=torch.zeros(1)).shape
        torch.Size([2, 3, 8, 4])
    """
    return draw("normal", tuple(shape), like, generator, float(mean_db), float(std_db))


def empirical_floor(
    shape: tuple[int, ...],
    quantiles_db: torch.Tensor,
    *,
    like: torch.Tensor,
    generator: torch.Generator | None = None,
) -> torch.Tensor:
    """A floor map drawn i.i.d. per element from a distribution given by its quantiles (in dB).

    Inverse-transform sampling: ``N = Q(u)``, ``u ~ Uniform[0, 1)``, ``Q`` interpolating ``quantiles_db``
    linearly at probabilities ``0, 1/(K-1), ..., 1`` (CalibratedDR's ``floor="empirical"``).

    Args:
        shape: the floor's shape.
        quantiles_db: ``(K,)`` non-decreasing quantiles, ``K >= 2``.
        like: a tensor whose dtype and device the floor takes.
        generator: draw from it (else torch's global RNG).

    Examples:
        >>> floor = empirical_floor((100_000,), torch.tensor([-110.0, -100.0, -80.0]), like=torch.zeros(1))
        >>> round(float(floor.min())), round(float(floor.median())), round(float(floor.max()))
        (-110, -100, -80)
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
    """RandomDR's floor ``m + s * noise``: sample ``k`` gets ``Normal(m_k, s_k**2)`` per cell.

    Args:
        shape: the leading (per-sample) dims of ``mean_db`` and ``std_db``.
        mean_db: per-sample means ``m`` (dB).
        std_db: per-sample standard deviations ``s`` (dB).
        noise: standard normal draws ``(*shape, *event)``, the shape of the result.

    Examples:
        >>> random_floor((2,), torch.tensor([-110.0, -95.0]), torch.tensor([1.0, 4.0]), torch.zeros(2, 3)).tolist()
        [[-110.0, -110.0, -110.0], [-95.0, -95.0, -95.0]]
    """
    event = (1,) * (noise.ndim - len(shape))
    return torch.addcmul(mean_db.reshape(tuple(shape) + event), noise, std_db.reshape(tuple(shape) + event))


def dr_clamp(x: torch.Tensor, noise_db: torch.Tensor) -> torch.Tensor:
    """The paper's clamp ``max(S, N)`` in dB: cells below the floor become it, the others are unchanged.

    Args:
        x: dB RD maps ``(..., rx, range, doppler)``.
        noise_db: the floor ``N``, broadcastable to ``x`` (cast to its dtype).

    Examples:
        >>> dr_clamp(torch.tensor([[[-130.0, -60.0]]]), torch.tensor(-100.0)).tolist()
        [[[-100.0, -60.0]]]
    """
    x = check_tensor(x, "dr_clamp expects a dB RD map (..., rx, range, doppler)", finite=False)
    if not isinstance(noise_db, torch.Tensor):
        raise InputTensorError(f"dr_clamp: noise_db must be a torch.Tensor, got {type(noise_db).__name__}")
    return torch.maximum(x, noise_db.to(dtype=x.dtype))

