"""The paper's scenarios as a seeded sampler: empty corridor, one walker, two walkers (Sec. 2.1-2.2).

What the paper leaves open (speed, height, start, lateral offset, heading, gait phase) is drawn from
ranges, all from the generator passed in, so a scenario is a pure function of its seed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import torch

from radaraug.errors import ConfigError
from radaraug.scene.people import StandingPerson, Walker


@dataclass
class Scenario:
    """One sampled situation: the people and the labels."""

    people: list[Any]
    params: list[dict[str, float]] = field(default_factory=list)

    @property
    def count(self) -> int:
        """Number of people (the counting label)."""
        return len(self.people)

    @property
    def occupancy(self) -> int:
        """1 if anyone is there (the occupancy label)."""
        return int(self.count > 0)


def _uniform(lo_hi: tuple[float, float], g: torch.Generator) -> float:
    lo, hi = lo_hi
    return lo + (hi - lo) * float(torch.rand((), generator=g, dtype=torch.float64))


@dataclass
class ScenarioSampler:
    """Draw corridor scenarios with 0, 1 or 2 walkers.

    Args:
        counts: people counts to draw from.
        count_weights: relative probability of each count (default uniform: balanced classes).
        speed_m_s: walking speed range (slow to brisk adult walking).
        min_speed_difference_m_s: two walkers differ by at least this much (the paper's
            "different speeds").
        height_m: body height range.
        range_m: start distance of the pelvis from the radar along its boresight.
        lateral_m: lateral offset range from the corridor axis (keep people inside the walls).
        p_toward: probability that a walker heads toward the radar (else away).
        heading_jitter_deg: extra random heading around straight toward/away.
        crossing_probability: chance that a drawn walker crosses the corridor (across its axis,
            either side, plus the jitter) instead of walking toward/away; 0 (default) draws nothing extra.
        standing_probability: chance that a drawn person stands (a :class:`~radaraug.scene.people.StandingPerson`
            at the drawn start, facing the drawn heading); they count. 0 (default) draws nothing extra.
        breathing_m, breathing_Hz: a standing person's peak chest displacement (m) and breathing rate.
        sway_rad, sway_Hz: their peak postural sway about the ankles (rad) and its frequency.
    """

    counts: tuple[int, ...] = (0, 1, 2)
    count_weights: tuple[float, ...] | None = None
    speed_m_s: tuple[float, float] = (0.6, 1.8)
    min_speed_difference_m_s: float = 0.2
    height_m: tuple[float, float] = (1.55, 1.95)
    range_m: tuple[float, float] = (1.0, 12.0)
    lateral_m: tuple[float, float] = (-0.6, 0.6)
    p_toward: float = 0.5
    heading_jitter_deg: float = 5.0
    crossing_probability: float = 0.0
    standing_probability: float = 0.0
    breathing_m: tuple[float, float] = (0.003, 0.012)
    breathing_Hz: tuple[float, float] = (0.2, 0.4)
    sway_rad: tuple[float, float] = (0.002, 0.012)
    sway_Hz: tuple[float, float] = (0.1, 0.5)

    def __post_init__(self) -> None:
        for name in ("crossing_probability", "standing_probability"):
            p = getattr(self, name)
            if isinstance(p, bool) or not isinstance(p, (int, float)) or not 0.0 <= float(p) <= 1.0:
                raise ConfigError(f"scenario sampler: {name} must be in [0, 1], got {p!r}")
            setattr(self, name, float(p))

    def sample(
        self, generator: torch.Generator, *, radar_xy: tuple[float, float] = (0.1, 0.0),
        axis_deg: float = 0.0,
    ) -> Scenario:
        """Draw a scenario.

        Args:
            generator: the only source of randomness.
            radar_xy: radar position in the floor plane (start distances are measured from it).
            axis_deg: direction of the corridor axis the radar looks along (0 = +x).
        """
        g = generator
        weights = torch.tensor(self.count_weights or [1.0] * len(self.counts), dtype=torch.float64)
        count = self.counts[int(torch.multinomial(weights, 1, generator=g))]
        speeds = self._speeds(count, g)
        axis = math.radians(axis_deg)
        ux, uy = math.cos(axis), math.sin(axis)
        people: list[Walker | StandingPerson] = []
        params: list[dict[str, float]] = []
        for speed in speeds:
            rng = _uniform(self.range_m, g)
            lat = _uniform(self.lateral_m, g)
            toward = bool(torch.rand((), generator=g) < self.p_toward)
            jitter = math.radians(_uniform((-self.heading_jitter_deg, self.heading_jitter_deg), g))
            heading = axis + (math.pi if toward else 0.0) + jitter
            # Drawn only when crossing walkers are on, so that the other draws are unchanged.
            crossing = self.crossing_probability > 0 and \
                float(torch.rand((), generator=g, dtype=torch.float64)) < self.crossing_probability
            if crossing:
                side = 1.0 if float(torch.rand((), generator=g, dtype=torch.float64)) < 0.5 else -1.0
                heading = axis + side * math.pi / 2 + jitter
            height = _uniform(self.height_m, g)
            phase = _uniform((0.0, 1.0), g)
            start = (radar_xy[0] + rng * ux - lat * uy, radar_xy[1] + rng * uy + lat * ux)
            # Drawn only when standing people are on, so that the walkers-only draws are unchanged.
            if self.standing_probability > 0 and float(torch.rand((), generator=g, dtype=torch.float64)) \
                    < self.standing_probability:
                motion = {"breathing_m": _uniform(self.breathing_m, g), "breathing_Hz": _uniform(self.breathing_Hz, g),
                          "breathing_phase": _uniform((0.0, 1.0), g), "sway_rad": _uniform(self.sway_rad, g),
                          "sway_Hz": _uniform(self.sway_Hz, g), "sway_phase": _uniform((0.0, 1.0), g),
                          "sway_direction_rad": _uniform((0.0, 2 * math.pi), g)}
                people.append(StandingPerson(height_m=height, position=start, facing_rad=heading, **motion))
                params.append({"range_m": rng, "lateral_m": lat, "speed_m_s": 0.0, "height_m": height,
                               "toward": float(toward), "heading_rad": heading, "standing": 1.0, **motion})
                continue
            people.append(Walker(height_m=height, speed_m_s=speed, start=start, heading_rad=heading, phase=phase))
            params.append({"range_m": rng, "lateral_m": lat, "speed_m_s": speed, "height_m": height,
                           "toward": float(toward), "heading_rad": heading, "phase": phase,
                           **({"crossing": 1.0} if crossing else {})})
        return Scenario(people, params)

    def _speeds(self, count: int, g: torch.Generator) -> list[float]:
        if count == 0:
            return []
        lo, hi = self.speed_m_s
        first = _uniform(self.speed_m_s, g)
        speeds = [first]
        for _ in range(count - 1):
            # Draw from the range minus a +-min_difference band around every earlier speed.
            for _attempt in range(64):
                s = _uniform((lo, hi), g)
                if all(abs(s - o) >= self.min_speed_difference_m_s for o in speeds):
                    break
            speeds.append(s)
        return speeds
