"""`Paths`: the interface between the ray tracer and the FMCW receiver.

A set of propagation paths seen by the radar at one instant (a frame's snapshot time),
with enough information to evaluate them at every chirp of the frame: the receiver
extrapolates each path's delay linearly over the frame (``tau(t) = delay_s + delay_rate * t``,
``t`` measured from the frame's first chirp start). That is accurate while a scatterer's
acceleration over one frame (~25 ms) moves it by much less than a wavelength's fraction that
matters for Doppler. A walker's limbs accelerate more than that (a foot's velocity changes by up
to ~10 Doppler bins in a frame): the optional ``chirp_delay_s`` carries each path's delay
beyond the linear reference at every chirp, and ``chirp_gain`` a per-chirp amplitude factor
(a slot that appears or is occluded mid-frame), as :class:`~radaraug.sim.twin.DigitalTwin`
fills them from sub-frame snapshots.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import torch


@dataclass
class Paths:
    """Propagation paths of one (or a batch of) snapshot(s).

    Shapes use ``P`` paths and ``RX`` receive channels, with any leading batch dims ``...``.

    Attributes:
        delay_s: ``(..., P, RX)`` round-trip delay TX -> scatterer(s) -> each RX, seconds,
            at the snapshot time.
        delay_rate: ``(..., P, RX)`` time derivative of the delay (s/s); a monostatic point
            target moving away at radial speed ``v`` has ``2 v / c``.
        amplitude: ``(..., P, RX)`` complex amplitude in sqrt(W) per watt of transmit power:
            ``|a|**2`` is the power at the RX port for 1 W at the TX port, including TX and RX
            antenna gains (pattern), path loss, scattering (RCS / Fresnel / PO) and any
            scattering phase. The propagation phase ``exp(-j 2 pi f tau)`` is *not* included:
            the receiver applies it from ``delay_s``.
        kind: ``(..., P)`` int8 path kind: 0 line-of-sight scattering (single bounce),
            1 multipath (more than one bounce). Optional.
        mask: ``(..., P)`` bool, False for padding entries (batched snapshots with different
            path counts). Optional; None means all valid.
        chirp_delay_s: ``(..., P, M)`` extra delay of each path at chirp ``m`` (``M`` chirps of
            the frame), shared by the RX channels: the delay at chirp ``m``, sample time ``t_n``
            is ``delay_s + delay_rate * (m T + t_d + t_n) + chirp_delay_s[m]`` (intra-frame
            acceleration). Optional; None means zero.
        chirp_gain: ``(..., P, M)`` real amplitude factor of each path at chirp ``m``, shared
            by the RX channels (``amplitude`` is the reference). Optional; None means one.
    """

    delay_s: torch.Tensor
    delay_rate: torch.Tensor
    amplitude: torch.Tensor
    kind: torch.Tensor | None = None
    mask: torch.Tensor | None = None
    chirp_delay_s: torch.Tensor | None = None
    chirp_gain: torch.Tensor | None = None

    @classmethod
    def empty(
        cls, num_rx: int, *, dtype: torch.dtype, device: torch.device | str | None = None,
        lead: tuple[int, ...] = (), mask: bool = False,
    ) -> Paths:
        """No paths: ``(*lead, 0, RX)`` tensors of ``dtype`` (the amplitude of its complex match).

        ``kind`` is an empty int8 tensor; ``mask`` an empty bool one with ``mask=True``, else None.
        """
        z = torch.zeros(*lead, 0, num_rx, dtype=dtype, device=device)
        cdt = torch.complex128 if dtype == torch.float64 else torch.complex64
        kind = torch.zeros(*lead, 0, dtype=torch.int8, device=device)
        valid = torch.zeros(*lead, 0, dtype=torch.bool, device=device) if mask else None
        return cls(z, z.clone(), z.to(cdt), kind, valid)

    @property
    def num_paths(self) -> int:
        """Number of path slots ``P``."""
        return int(self.delay_s.shape[-2])

    def map(self, fn: Callable[[torch.Tensor], torch.Tensor]) -> Paths:
        """Apply ``fn`` to every tensor (``None`` fields stay ``None``), e.g. to index or expand the batch."""
        def opt(t: torch.Tensor | None) -> torch.Tensor | None:
            return None if t is None else fn(t)

        return Paths(fn(self.delay_s), fn(self.delay_rate), fn(self.amplitude), opt(self.kind), opt(self.mask),
                     opt(self.chirp_delay_s), opt(self.chirp_gain))

    def select(self, index: Any) -> Paths:
        """Index the leading (batch) dims of every tensor: ``paths.select(k)`` is snapshot ``k``.

        Args:
            index: any tensor index (an int, a slice, a tuple of them, ``None`` for a new dim).
        """
        return self.map(lambda t: t[index])

    def to(self, device: torch.device | str) -> Paths:
        """Move every tensor to ``device``."""
        return self.map(lambda t: t.to(device))

    @staticmethod
    def cat(items: list[Paths]) -> Paths:
        """Concatenate path sets along the path axis (same batch shape)."""
        d = [p.delay_s for p in items]

        def cat_optional(ts: list[torch.Tensor | None], fill: float, per_chirp: bool) -> torch.Tensor | None:
            """Absent tensors filled with ``fill`` (``(..., P)``; ``(..., P, M)`` per chirp), concatenated."""
            present = [t for t in ts if t is not None]
            if not present:
                return None
            tail, dtype = ((present[0].shape[-1],), present[0].dtype) if per_chirp else ((), None)
            full = [
                t if t is not None else torch.full((*r.shape[:-1], *tail), fill, dtype=dtype, device=r.device)
                for t, r in zip(ts, d)
            ]
            return torch.cat(full, dim=-2 if per_chirp else -1)

        return Paths(
            delay_s=torch.cat(d, dim=-2),
            delay_rate=torch.cat([p.delay_rate for p in items], dim=-2),
            amplitude=torch.cat([p.amplitude for p in items], dim=-2),
            kind=cat_optional([p.kind for p in items], 0, per_chirp=False),
            mask=cat_optional([p.mask for p in items], True, per_chirp=False),
            chirp_delay_s=cat_optional([p.chirp_delay_s for p in items], 0.0, per_chirp=True),
            chirp_gain=cat_optional([p.chirp_gain for p in items], 1.0, per_chirp=True),
        )
