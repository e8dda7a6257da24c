"""The RD noise floor of dB maps: the statistic `radaraug info` prints.

:func:`noise_floor_db` is a plain tensor statistic. The capture summary around it
(``summarize_capture``, which runs the RD chain) lives in :mod:`radaraug.transforms.summary`:
this package knows nothing of transforms.

Units: ``radaraug.units.DB_CONVENTION`` (dBFS: both FFTs divided by their window sums).
"""

from __future__ import annotations

import torch


def noise_floor_db(db: torch.Tensor) -> float | None:
    """The RD noise floor of dB maps ``(..., rx, range, doppler)``.

    The median cell of the far half of range, leaving out zero Doppler +-1 bin (static returns) -- None
    (JSON null, not the invalid NaN) when there are too few chirps (<= 4) to leave zero Doppler out.
    """
    m = db.shape[-1]
    if m <= 4:
        return None
    zero = m // 2
    off_zero = torch.cat([db[..., :zero - 1], db[..., zero + 2:]], dim=-1)
    return float(off_zero[..., db.shape[-2] // 2:, :].median())
