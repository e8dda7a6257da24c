"""What a per-item draw changes in the twin's signal: the pure pieces of ``DigitalTwin.simulate(..., draw=...)``.

Each person's paths scaled by its RCS draw, static point scatterers, the item's receiver (offsets,
phase noise, catalog effects) and the algebra that turns the room's cached signal by a drawn RX
mismatch. Functions of data only: the twin calls them (``DigitalTwin.simulate_items``), never the
other way round.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import TypeVar

import torch

from radaraug.config import RadarConfig
from radaraug.sensor.effects import (
    ADCNoise,
    Effect,
    PhaseNoise,
    RxGainPhaseMismatch,
    SystemGain,
    ThermalNoise,
)
from radaraug.sensor.effects.base import hardware_position
from radaraug.sensor.paths import Paths
from radaraug.sensor.receiver import FMCWReceiver

_E = TypeVar("_E", bound=Effect)

SCATTERER_ANTENNA_GAIN_DBI = 6.0
"""Antenna gain (TX and RX) applied to the static scatterers: the patch antenna's peak (their
azimuth is drawn within +-45 deg, where the pattern loses a few dB, small next to the RCS range)."""


def scale_people_paths(paths: Paths, segments: Sequence[int], rcs_scale_dB: Sequence[float]) -> Paths:
    """Scale each person's paths by ``10**(dB/20)`` (amplitude ~ sqrt(RCS)).

    ``paths`` are the target paths of people traced together (so that they still shadow each other),
    ``segments`` each person's number of body segments in that order. The ellipsoid tracer lays out
    ``S`` direct paths, then three multipath blocks of ``S K`` (``K`` mirror planes), segment-major; a
    multipath path belongs to its segment's person.

    Raises:
        ValueError: the number of scales is not the number of people.
        RuntimeError: the paths do not have that layout (the tracer changed: fix this helper).
    """
    s = int(sum(segments))
    p = paths.num_paths
    if s == 0 or not rcs_scale_dB:
        return paths
    if len(segments) != len(rcs_scale_dB):
        raise ValueError(f"{len(segments)} people but {len(rcs_scale_dB)} RCS scales")
    blocks = 3  # multipath blocks of S K slots (see ellipsoid_paths)
    if p < s or (p - s) % (blocks * s):
        raise RuntimeError(f"unexpected target path layout: {p} paths for {s} segments")
    k = (p - s) // (blocks * s)
    if paths.kind is not None and not (bool((paths.kind[..., :s] == 0).all())
                                       and bool((paths.kind[..., s:] == 1).all())):
        raise RuntimeError("unexpected target path layout: direct paths do not come first")
    dev = paths.amplitude.device
    per_person = torch.tensor([10 ** (db / 20) for db in rcs_scale_dB], dtype=torch.float64)
    per_segment = per_person.repeat_interleave(torch.tensor(list(segments)))
    mp = per_segment.repeat_interleave(k)
    per_path = torch.cat([per_segment, *([mp] * blocks)]).to(device=dev, dtype=paths.amplitude.real.dtype)
    return dataclasses.replace(paths, amplitude=paths.amplitude * per_path[:, None])


def item_receiver(receiver: FMCWReceiver, system_gain_offset_dB: float, noise_figure_offset_dB: float,
                  phase_noise: tuple[float, int] | None = None, *, adc_noise_offset_dB: float = 0.0,
                  extra_effects: Sequence[Effect] = ()) -> FMCWReceiver:
    """A receiver like ``receiver`` with its first ``system_gain`` and ``thermal_noise`` stages offset.

    Its ``phase_noise`` stage is set to ``phase_noise`` ``(rms_Hz, num_paths)`` when given, its
    ``adc_noise`` RMS scaled by ``adc_noise_offset_dB``, and ``extra_effects`` are inserted at their
    hardware position (:func:`~radaraug.sensor.effects.base.hardware_position`). ``receiver`` is not
    changed, so nothing leaks from one item to the next, even across threads.
    """
    effects = list(receiver.effects)

    def replace_first(kind: type[_E], make: Callable[[_E], Effect]) -> None:
        """The first stage of type ``kind``, ``e``, becomes ``make(e)``."""
        for i, e in enumerate(effects):
            if isinstance(e, kind):
                effects[i] = make(e)
                return

    if phase_noise is not None:
        replace_first(PhaseNoise, lambda e: PhaseNoise(freq_noise_rms_Hz=phase_noise[0], corner_Hz=e.corner_Hz,
                                                       num_paths=phase_noise[1]))
    replace_first(SystemGain, lambda e: SystemGain(gain_dB=e.gain_dB + system_gain_offset_dB))
    replace_first(ThermalNoise, lambda e: ThermalNoise(noise_figure_dB=e.noise_figure_dB + noise_figure_offset_dB,
                                                       temperature_K=e.temperature_K))
    if adc_noise_offset_dB != 0.0:
        replace_first(ADCNoise, lambda e: ADCNoise(rms_counts=e.rms_counts * 10 ** (adc_noise_offset_dB / 20)))
    for new in extra_effects:
        effects.insert(hardware_position([e.name for e in effects], new.name), new)
    return FMCWReceiver(receiver.config, effects=effects, tx_power_dBm=receiver.tx_power_dBm,
                        synthesis=receiver.synthesis, front_end_gain_dB=receiver.front_end_gain_dB,
                        taylor_tol=receiver.taylor_tol, noise_tol=receiver.noise_tol)


def quadrature(receiver: FMCWReceiver, paths: Paths) -> torch.Tensor:
    """The signal of ``paths`` through the linear stages with every beat tone turned by -90 deg.

    A path's amplitude times ``j`` (the receiver conjugates it); a per-RX complex gain ``a exp(j phi)``
    on the in-phase signal ``S`` is then exactly ``a (cos(phi) S - sin(phi) Q)``.
    """
    return receiver.static_signal(dataclasses.replace(paths, amplitude=paths.amplitude * 1j))


def rx_gain(mismatch: RxGainPhaseMismatch, like: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """``(amplitude, phase)`` of a mismatch stage, ``(RX, 1, 1)`` on ``like``'s device and dtype."""
    amp = torch.pow(10.0, mismatch.gain_dB / 20).to(like)
    return amp[:, None, None], mismatch.phase_rad.to(like)[:, None, None]


def static_scatterer_paths(config: RadarConfig, scatterers: Sequence[tuple[float, float, float, float]],
                           like: Paths) -> Paths:
    """Paths of static point scatterers ``(range_m, azimuth_deg, elevation_deg, rcs_dBsm)``.

    In the radar's frame (x right, y up, z boresight), batched like ``like`` ``(..., P, RX)``.
    """
    from radaraug.sensor.point_target import point_target_paths

    sc = torch.tensor(scatterers, dtype=torch.float64)
    r, az, el = sc[:, 0], torch.deg2rad(sc[:, 1]), torch.deg2rad(sc[:, 2])
    pos = torch.stack([r * torch.sin(az) * torch.cos(el), r * torch.sin(el), r * torch.cos(az) * torch.cos(el)], -1)
    p = point_target_paths(config, pos, rcs_m2=10 ** (sc[:, 3] / 10), antenna_gain_dBi=SCATTERER_ANTENNA_GAIN_DBI)
    return like_batch(p, like)



def static_mismatch(receiver: FMCWReceiver, extra: Sequence[Effect]) -> RxGainPhaseMismatch | None:
    """The item's drawn mismatch stage (in ``extra``) when the room's cached signal must get it by hand.

    That is, when it comes before the receiver's first non-linear stage, where the cached signal is
    added (a mismatch of the twin's own receiver is in the cached signal already).
    """
    drawn = next((e for e in extra if isinstance(e, RxGainPhaseMismatch)), None)
    if drawn is None:
        return None
    effects = list(receiver.effects)
    first_nonlinear = next((i for i, e in enumerate(effects) if e.kind == "nonlinear"), len(effects))
    position = next(i for i, e in enumerate(effects) if e is drawn)
    return drawn if position < first_nonlinear else None


def like_batch(paths: Paths, like: Paths) -> Paths:
    """Static ``paths`` ``(P, RX)`` on ``like``'s device and dtypes, batched like it ``(..., P, RX)``."""
    dt, dev = like.delay_s.dtype, like.delay_s.device
    cdt = like.amplitude.dtype if like.amplitude.is_complex() else None
    p = Paths(paths.delay_s.to(dev, dt), paths.delay_rate.to(dev, dt),
              paths.amplitude.to(dev, cdt) if cdt is not None else paths.amplitude.to(dev, dt))
    batch = tuple(like.delay_s.shape[:-2])
    return p.map(lambda t: t.expand(*batch, *t.shape))


__all__ = [
    "SCATTERER_ANTENNA_GAIN_DBI", "item_receiver", "quadrature", "rx_gain", "scale_people_paths",
    "like_batch", "static_mismatch", "static_scatterer_paths",
]
