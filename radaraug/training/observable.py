"""Counting labels that say how many people a simulated frame shows (docs/training.md, "Issue 34, seventh round").

A drawn person can be weaker than what an empty room shows somewhere, or share one blob of the map with the
other person; a two-person label on such a frame teaches that one blob may be two people. Here a person counts
when a detector at the empty items' 5 % false-alarm level finds them apart from the other person.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import torch
import torch.nn.functional as nnf

from radaraug.errors import ConfigError
from radaraug.training.pipeline import level_chain
from radaraug.transforms.functional._floor import kept_cells

#: Range bins either side of a person's slant range searched for their own peak.
PERSON_RANGE_WINDOW = 2
#: The first range bins (the TX-RX leakage and the IF high-pass) hold no person.
SKIP_RANGE_BINS = 3


def person_range_bins(dataset: Any, index: int) -> list[int]:
    """The range bin of each person of simulated item ``index`` at its first frame (``t = 0``).

    The slant range from the item's radar (its room variant's) to the mean centre of the person's body
    ellipsoids, over the config's range resolution.
    """
    scenario = dataset.scenario(index)
    variant = dataset.room_variant(index)
    twin = dataset.twin if variant is None else dataset.variant_twin(variant)
    radar = twin.scene.radar.position.detach().to(torch.float64).cpu()
    step = float(dataset.config.range_resolution_m)
    t0 = torch.zeros(1, dtype=torch.float64)
    bins = []
    for person in scenario.people:
        centre = person.ellipsoids(t0).centers.reshape(-1, 3).to(torch.float64).mean(0)
        bins.append(int(round(float((centre - radar).norm()) / step)))
    return bins


def _regions(over: torch.Tensor) -> torch.Tensor:
    """Connected regions (8-neighbour) of bool maps ``(N, R, D)``: a label per cell, 0 outside."""
    n, r, d = over.shape
    ids = torch.arange(1, r * d + 1, dtype=torch.float32).reshape(1, r, d).expand(n, r, d)
    lab = torch.where(over, ids, torch.zeros_like(ids))
    while True:  # every cell takes the largest label around it until none changes
        grown = nnf.max_pool2d(lab[:, None], 3, stride=1, padding=1)[:, 0] * over
        if torch.equal(grown, lab):
            return lab.long()
        lab = grown


@torch.no_grad()
def observable_counts(db_maps: torch.Tensor, counts: torch.Tensor, range_bins: Sequence[Sequence[int]], *,
                      excise: torch.Tensor | None = None, blank_zero_doppler: int = 1,
                      false_alarm: float = 0.05) -> tuple[torch.Tensor, float]:
    """Counts lowered to the people each map shows apart, never below one for an occupied item.

    Args:
        db_maps: per-RX dB RD maps ``(N, rx, range, doppler)`` of the items (what training sees).
        counts: drawn people counts ``(N,)``.
        range_bins: each item's people's range bins (:func:`person_range_bins`).
        excise: cells excised from every map (the calibration's persistent lines).
        blank_zero_doppler: bins blanked on each side of zero Doppler.
        false_alarm: the share of empty items whose largest cell beats the threshold.

    Returns:
        ``(counts, threshold_db)``: ``min(count, max(1, regions))`` per item, where ``regions`` is the number
        of distinct connected regions over the threshold holding a person's peak (within
        ``PERSON_RANGE_WINDOW`` bins of their range), and the threshold over each row's floor.

    Raises:
        ConfigError: no empty item to set the threshold, or a count that does not match its range bins.
    """
    if len(range_bins) != len(counts) or any(len(b) != int(c) for b, c in zip(range_bins, counts)):
        raise ConfigError("observable_counts: each item needs one range bin per person")
    if not bool((counts == 0).any()):
        raise ConfigError("observable_counts: no empty item to set the detection threshold on")
    level = level_chain("floor_relative", excise, blank_zero_doppler)(db_maps.float()).squeeze(-3)
    n, r, d = level.shape
    valid = kept_cells(r, d, blank_zero_doppler, excise, device=level.device)
    valid[:SKIP_RANGE_BINS] = False
    level = level.masked_fill(~valid, -math.inf)
    peaks = level.flatten(1).amax(1)
    empty = peaks[counts == 0].sort().values
    threshold = float(empty[int(round((1 - false_alarm) * (len(empty) - 1)))])
    out = counts.clone()
    several = (counts > 1).nonzero().flatten().tolist()  # only they can be lowered
    if not several:
        return out, threshold
    regions = _regions(level[several] > threshold)
    for k, i in enumerate(several):
        seen = set()
        for b in range_bins[i]:
            lo, hi = max(SKIP_RANGE_BINS, b - PERSON_RANGE_WINDOW), min(r, b + PERSON_RANGE_WINDOW + 1)
            if lo >= hi:
                continue
            window = level[i, lo:hi]
            if bool((window > threshold).any()):
                row, col = divmod(int(window.argmax()), d)
                seen.add(int(regions[k, lo + row, col]))
        out[i] = min(int(counts[i]), max(1, len(seen)))
    return out, threshold
