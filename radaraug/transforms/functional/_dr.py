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

