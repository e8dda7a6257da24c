"""`Paths`: the interface between the ray tracer and the FMCW receiver.

The paths seen at one snapshot time, with each delay extrapolated linearly over the frame; the optional
per-chirp delay and gain carry what a line misses (a limb's acceleration, a slot occluded mid-frame), as
:class:`~radaraug.sim.twin.DigitalTwin` fills them from sub-frame snapshots.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import torch


@dataclass
class Paths:
    """Propagation paths of one (or a batch of) snapshot(s): ``P`` paths, ``RX`` channels, leading dims ``...``.

    Attributes:
        delay_s: ``(..., P, RX)`` round-trip delay TX -> scatterer(s) -> each RX at the snapshot time, s.
        delay_rate: ``(..., P, RX)`` d(delay)/dt, s/s (``2 v / c`` for a point target receding at ``v``).
        amplitude: ``(..., P, RX)`` complex, sqrt(W) at the RX port per sqrt(W) at the TX port: antenna gains,
            path loss and scattering (with its phase) included; the propagation phase ``exp(-j 2 pi f tau)``
            is not (the receiver applies it from ``delay_s``).
        kind: optional ``(..., P)`` int8: 0 single bounce, 1 multipath.
        mask: optional ``(..., P)`` bool, False for padding slots; None means all valid.
        chirp_delay_s: optional ``(..., P, M)`` extra delay at chirp ``m``, shared by the RX: the delay at
            sample ``t_n`` is ``delay_s + delay_rate * (m T + t_d + t_n) + chirp_delay_s[m]``. None means zero.
        chirp_gain: optional ``(..., P, M)`` real amplitude factor per chirp, shared by the RX. None means one.
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
        """No paths: empty ``(*lead, 0, RX)`` tensors of ``dtype`` (complex amplitude); ``mask`` if ``mask=True``."""
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
