"""`DigitalTwin`: a scene's people at frame times -> ray-traced paths -> raw ADC frames.

One object per process: it traces and synthesizes the static room once, then simulates any batch of
frame times with tensor work only (the people's paths over each frame, their shadow on the room,
the receiver). See docs/simulation.md.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, overload

import torch

from radaraug.config import RadarConfig
from radaraug.errors import ConfigError, InputTensorError
from radaraug.raytrace.shadow import SHADOW_TOL, correction_paths, shadow_transmission
from radaraug.raytrace.targets import slot_segments
from radaraug.raytrace.tracer import RayTracer
from radaraug.scene.geometry import Ellipsoids
from radaraug.scene.scene import Scene
from radaraug.sensor.effects import PhaseNoise, RxGainPhaseMismatch
from radaraug.sensor.paths import Paths
from radaraug.sensor.profile import as_profile
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sensor.synthesis import ChirpTiming
from radaraug.sim.intra_frame import DEFAULT_TOL_CYCLES, check_intra_frame, chirp_times, intra_frame_paths
from radaraug.sim.item_signal import (
    item_receiver,
    like_batch,
    quadrature,
    rx_gain,
    scale_people_paths,
    static_mismatch,
    static_scatterer_paths,
)

#: Version of the twin's physics, part of the cache key of every simulated map set
#: (:func:`radaraug.training.cache.cache_spec`): bumped when a change makes the same inputs simulate
#: other frames, so that no cache made before is reused (history: docs/simulation.md, "Model versions").
TWIN_MODEL_VERSION = 4

if TYPE_CHECKING:
    from radaraug.sim.randomization import ItemDraw

_People: TypeAlias = "Sequence[Any] | _PeopleRows"
"""One set of people for every frame, or each frame's own (:meth:`DigitalTwin.simulate_items`)."""

WEAK_PATH_DB = 100.0
"""A person's path more than this below its frame's strongest person's path is left out of the
synthesis (:func:`negligible_paths_off`)."""


def negligible_paths_off(paths: Paths, below_dB: float = WEAK_PATH_DB) -> Paths:
    """``paths`` ``(T, P, RX)`` with the slots more than ``below_dB`` under their frame's strongest off.

    Masked per frame (a frame's result does not depend on its batch). The default leaves out only
    paths under the RD noise floor, even when the strongest echo fills the ADC (docs/simulation.md).
    """
    if paths.num_paths == 0:
        return paths
    mag = paths.amplitude.abs().amax(dim=-1)  # (T, P)
    if paths.chirp_gain is not None:
        mag = mag * paths.chirp_gain.abs().amax(dim=-1)
    if paths.mask is not None:
        mag = mag * paths.mask
    strongest = mag.amax(dim=-1, keepdim=True)
    keep = mag >= strongest * 10 ** (-below_dB / 20)
    mask = keep if paths.mask is None else paths.mask & keep
    return dataclasses.replace(paths, mask=mask)


class DigitalTwin:
    """Simulate raw frames of a scene.

    Args:
        scene: room, radar pose and config (its ``people`` are the default people).
        config: radar config to simulate instead of the scene's (e.g. one read from a real
            recording); the pose stays the scene's.
        receiver: the FMCW receiver (default: :class:`FMCWReceiver` with the BGT60TR13C chain).
        tracer_options: keyword arguments of :class:`RayTracer` (``method``, ``max_bounces``,
            ``cache``...); the traced room is cached on disk per (scene, config, tracer version).
        multipath: first-order multipath of the people via the room's walls.
        device: where to simulate (default CPU).
        dtype: real dtype of the tracer (float32; the receiver follows the paths' dtype).
        static_signal: the room's signal from an earlier :meth:`static_signal` of the same
            scene, config and receiver (skips the room's trace and synthesis).
        profile: a fitted twin profile (:class:`~radaraug.sensor.profile.TwinProfile`, its JSON
            path or dict): the receiver is built from it, and its room section goes to the tracer
            unless ``tracer_options`` sets it. Give ``receiver`` or ``profile``, not both.
        shadowing: the people shadow the room's paths (knife-edge diffraction,
            :mod:`radaraug.raytrace.shadow`; the image method's rooms, not SBR's).
        intra_frame: motion inside a frame: ``"auto"`` (default, :mod:`radaraug.sim.intra_frame`), a
            fixed number of knot intervals per frame, or ``0`` (one snapshot, delays extrapolated linearly).
        intra_frame_tol_cycles: tolerance of the automatic choice, carrier cycles of delay.
        shadow_intervals: ``0`` (default) holds the people's shadow at the frame's start; ``K >= 1``
            moves it inside the frame (:meth:`shadow_knots`) at ``K + 1`` times its cost (docs/shadowing.md).

    Raises:
        ConfigError: a bad option, or both ``receiver`` and ``profile``.
    """

    def __init__(
        self,
        scene: Scene,
        *,
        config: RadarConfig | None = None,
        receiver: FMCWReceiver | None = None,
        tracer_options: dict[str, Any] | None = None,
        multipath: bool = True,
        device: torch.device | str = "cpu",
        dtype: torch.dtype = torch.float32,
        static_signal: torch.Tensor | None = None,
        profile: Any = None,
        shadowing: bool = True,
        intra_frame: int | str = "auto",
        intra_frame_tol_cycles: float = DEFAULT_TOL_CYCLES,
        shadow_intervals: int = 0,
    ) -> None:
        self.scene = scene
        self.config = config or scene.config
        self.device = torch.device(device)
        self.dtype = dtype
        self.multipath = multipath
        self.shadowing = shadowing
        profile = as_profile(profile)
        # A profile's room section (its fitted diffuse gain) is a tracer option; the caller's win.
        room = profile.tracer_options() if profile is not None else {}
        options = {"scattering": getattr(scene, "scattering", None), **room, **(tracer_options or {})}
        self.tracer = RayTracer(
            scene.room.to(self.device), scene.radar, self.config, device=self.device, dtype=dtype, **options,
        )
        if profile is not None:
            if receiver is not None:
                raise ConfigError("DigitalTwin: give a receiver or a profile, not both")
            receiver = profile.receiver(self.config)
        self.receiver = (receiver or FMCWReceiver(self.config)).to(self.device)
        self._static_signal = None if static_signal is None else static_signal.to(self.device)
        self._static_basis: torch.Tensor | None = None
        check_intra_frame(intra_frame, intra_frame_tol_cycles)
        self.intra_frame = intra_frame
        self.intra_frame_tol_cycles = float(intra_frame_tol_cycles)
        if isinstance(shadow_intervals, bool) or not isinstance(shadow_intervals, int) or shadow_intervals < 0:
            raise ConfigError(f"DigitalTwin: shadow_intervals must be an integer >= 0, got {shadow_intervals!r}")
        self.shadow_intervals = shadow_intervals
        # What the catalog needs of the room (its strongest paths and their signal, the quadrature of its
        # signal), computed on first use: dict.setdefault keeps one value when threads race.
        self._room_cache: dict[tuple[str, int], Any] = {}
        self.last_intervals: torch.Tensor | None = None
        """Knot intervals each frame of the last :meth:`paths` call used (``(T,)``; 0: one snapshot)."""

    @property
    def cached_static_signal(self) -> torch.Tensor | None:
        """The room's signal if computed (or given) yet, else None: for another twin of the same scene."""
        return self._static_signal

    def static_signal(self) -> torch.Tensor:
        """The room's contribution ``(rx, chirps, samples)`` through the linear stages, the same in every frame.

        Traced and synthesized once (superposition: :meth:`FMCWReceiver.static_signal`).
        """
        if self._static_signal is None:
            self._static_signal = self.receiver.static_signal(self.tracer.static_paths())
        return self._static_signal

    def frame_times(self, frame_indices: Sequence[int] | torch.Tensor) -> torch.Tensor:
        """Start time (s) of each frame: ``index * frame_repetition_time``."""
        idx = torch.as_tensor(frame_indices, dtype=torch.float64)
        return idx * self.config.frame_repetition_time_s

    def ellipsoids(self, people: Sequence[Any], times: torch.Tensor) -> Ellipsoids | None:
        """Every person's segments at ``times`` ``(T,)`` -> ``(T, S_total)`` (None without people)."""
        if not people:
            return None
        t = times.to(torch.float64)
        parts = [p.ellipsoids(t) for p in people]
        e = Ellipsoids.cat(parts) if len(parts) > 1 else parts[0]
        dev, dt = self.device, self.dtype
        omega = None if e.angular_velocities is None else e.angular_velocities.to(device=dev, dtype=dt)
        return Ellipsoids(e.centers.to(device=dev, dtype=dt), e.semi_axes.to(device=dev, dtype=dt),
                          e.rotations.to(device=dev, dtype=dt), e.velocities.to(device=dev, dtype=dt), e.material,
                          omega)

    def paths(self, people: Sequence[Any], times: torch.Tensor) -> Paths:
        """Paths ``(T, P, RX)`` of the people over the frames starting at ``times``, with per-chirp terms.

        The per-chirp delays and gains ``(T, P, chirps)`` are absent with ``intra_frame=0``.
        """
        if not people:
            return self._no_paths(times)
        return self._traced(lambda t, rows: self._ellipsoids_at(people, t, rows), times)

    def _no_paths(self, times: torch.Tensor) -> Paths:
        rx = self.config.num_rx
        z = torch.zeros(int(times.shape[0]), 0, rx, dtype=self.dtype, device=self.device)
        c = torch.complex64 if self.dtype == torch.float32 else torch.complex128
        self.last_intervals = torch.zeros(int(times.shape[0]), dtype=torch.long)
        return Paths(z, z.clone(), z.to(c))

    def _ellipsoids_at(self, people: _People, t: torch.Tensor, rows: torch.Tensor) -> Ellipsoids:
        """The segments at times ``t`` ``(n,)`` of frames ``rows``: one set of people, or each frame's own."""
        if isinstance(people, _PeopleRows):
            return people.ellipsoids(t, rows)
        e = self.ellipsoids(people, t)
        assert e is not None  # people is not empty
        return e

    def _traced(self, ellipsoids_at: Callable[[torch.Tensor, torch.Tensor], Ellipsoids], times: torch.Tensor,
                dead: Callable[[Paths, torch.Tensor], Paths] | None = None) -> Paths:
        """:meth:`paths` of the segments ``ellipsoids_at(t, rows)``; ``dead`` masks the slots a frame lacks."""

        def trace(t: torch.Tensor, rows: torch.Tensor) -> Paths:
            p = self.tracer.target_paths(ellipsoids=ellipsoids_at(t, rows), multipath=self.multipath)
            return p if dead is None else dead(p, rows)

        def trace_slots(t: torch.Tensor, slots: torch.Tensor, rows: torch.Tensor) -> Paths:
            """The slots ``slots`` ``(P,)`` of :func:`trace` (the others zero): their segments' paths only."""
            ell = ellipsoids_at(t, rows)
            s_count, n_slots = ell.centers.shape[-2], slots.shape[0]
            segment = slot_segments(s_count, n_slots, slots.device)
            targets = segment[slots].unique()
            part = self.tracer.target_paths(ellipsoids=ell, multipath=self.multipath, targets=targets)
            where = torch.isin(segment, targets).nonzero()[:, 0].to(part.delay_s.device)  # the targets' slots, in order

            def full(x: torch.Tensor, rx: bool) -> torch.Tensor:
                out = x.new_zeros(*x.shape[:-2], n_slots, x.shape[-1]) if rx else x.new_zeros(*x.shape[:-1], n_slots)
                return out.index_copy_(-2 if rx else -1, where, x)
            p = Paths(full(part.delay_s, True), full(part.delay_rate, True), full(part.amplitude, True),
                      None if part.kind is None else full(part.kind, False),
                      None if part.mask is None else full(part.mask, False))
            return p if dead is None else dead(p, rows)

        paths, self.last_intervals = intra_frame_paths(
            trace, times, ChirpTiming.from_config(self.config), intervals=self.intra_frame,
            tol_cycles=self.intra_frame_tol_cycles, trace_slots=trace_slots,
        )
        return paths

    def shadow_transmission(self, people: _People, times: torch.Tensor,
                            rows: torch.Tensor | None = None) -> torch.Tensor | None:
        """``(T, P)`` field transmission of the room's paths through the people at ``times``, or None.

        None: no people, ``shadowing=False``, or an SBR room (its merged paths have no vertices).
        ``rows``: the frame of each time when each frame has its own people (:meth:`simulate_items`).
        """
        if not people or not self.shadowing:
            return None
        vertices = self.tracer.static_vertices()
        if vertices is None or vertices.shape[0] == 0:
            return None
        every = torch.arange(int(times.shape[0])) if rows is None else rows
        return shadow_transmission(vertices, self._ellipsoids_at(people, times, every), self.config.wavelength_m)

    def shadow_knots(self, people: _People, times: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor | None] | None:
        """The shadow over each frame: transmissions ``(T, J, P)`` at its knots and the chirps' weights ``(M, J)``.

        With ``shadow_intervals=K >= 1`` the knots are ``K + 1`` instants from the first chirp's first
        ADC sample to the last's, with hat-function weights, so a limb sweeping through a wall's Fresnel
        zone modulates that wall across the chirps; with ``K = 0`` one knot at the frame's start, weights
        None. None as for :meth:`shadow_transmission`.
        """
        tc = chirp_times(ChirpTiming.from_config(self.config))
        k = self.shadow_intervals
        if k == 0 or tc.shape[0] < 2:
            offsets, weights = torch.zeros(1, dtype=torch.float64), None
        else:
            offsets = tc[0] + (tc[-1] - tc[0]) * torch.arange(k + 1, dtype=torch.float64) / k
            x = (tc - tc[0]) / (tc[-1] - tc[0]) * k  # each chirp's position, in knot intervals
            weights = (1 - (x[:, None] - torch.arange(k + 1, dtype=torch.float64)).abs()).clamp(min=0)
        t64 = times.to(torch.float64).reshape(-1)
        rows = torch.arange(t64.shape[0]).repeat_interleave(offsets.shape[0])
        t = self.shadow_transmission(people, (t64[:, None] + offsets[None, :]).reshape(-1), rows)
        return None if t is None else (t.reshape(t64.shape[0], offsets.shape[0], -1), weights)

    def shadow_paths(self, people: Sequence[Any], times: torch.Tensor) -> Paths | None:
        """Correction paths ``(T, P', RX)`` for the room's paths that the people shadow, or None.

        ``(T - 1) * a`` at the static paths' delays, one set per knot of :meth:`shadow_knots` with its
        weight as the per-chirp gain.
        """
        knots = self.shadow_knots(people, times)
        if knots is None:
            return None
        t, weights = knots
        # One selection of the shadowed paths for every knot (as shadow_signal's): (T * J, P', RX).
        paths = correction_paths(self.tracer.static_paths(), t.reshape(-1, t.shape[-1]))
        if weights is not None:
            n_frames, n_knots = t.shape[:2]

            def knot(x: torch.Tensor, j: int) -> torch.Tensor:
                return x.reshape(n_frames, n_knots, *x.shape[1:])[:, j]

            parts = []
            for j in range(n_knots):
                p = paths.map(functools.partial(knot, j=j))
                gain = weights[:, j].to(device=p.delay_s.device, dtype=p.delay_s.dtype)
                parts.append(dataclasses.replace(p, chirp_gain=gain.expand(*p.delay_s.shape[:-1], -1)))
            paths = Paths.cat(parts)
        return paths.map(lambda x: x.to(self.device))

    def static_basis(self) -> torch.Tensor:
        """``(P, 2, RX, N)`` one chirp of each static path's signal and of its quadrature twin.

        Both through the linear stages (the path, and with its amplitude times ``j``). A frame in which
        the people multiply path ``p``'s amplitude by ``T_p`` then differs from the cached room signal by
        ``sum_p Re(T_p - 1) b_p0 + Im(T_p - 1) b_p1`` on every chirp (:meth:`shadow_signal`). Computed
        once per twin.
        """
        if self._static_basis is None:
            static = self.tracer.static_paths()
            parts = []
            for s in range(0, static.num_paths, 256):
                one = static.select((slice(s, s + 256), None))  # (k, 1, RX): a batch of single paths
                quad = dataclasses.replace(one, amplitude=one.amplitude * 1j)
                parts.append(torch.stack([self.receiver.static_chirp(one), self.receiver.static_chirp(quad)], dim=1))
            n = self.config.num_samples_per_chirp
            self._static_basis = (torch.cat(parts) if parts else
                                  torch.zeros(0, 2, self.config.num_rx, n, device=self.device, dtype=self.dtype))
        return self._static_basis

    @overload
    def shadow_signal(self, people: _People, times: torch.Tensor, *,
                      quadrature: Literal[False] = False, groups: torch.Tensor | None = None) -> torch.Tensor | None: ...

    @overload
    def shadow_signal(self, people: _People, times: torch.Tensor, *,
                      quadrature: Literal[True], groups: torch.Tensor | None = None
                      ) -> tuple[torch.Tensor, torch.Tensor] | None: ...

    def shadow_signal(
        self, people: _People, times: torch.Tensor, *, quadrature: bool = False,
        groups: torch.Tensor | None = None,
    ) -> torch.Tensor | tuple[torch.Tensor, torch.Tensor] | None:
        """``(T, RX, chirps, N)`` what the people's shadow changes in the room's signal, or None.

        ``(T, RX, 1, N)`` where the shadow is held for the frame. One matrix product with the
        :meth:`static_basis` per knot. ``quadrature``: also the change of ``-j (T - 1)`` (to turn it by
        a per-RX complex gain). ``groups`` ``(T,)``: the item of each frame (:meth:`simulate_items`); a
        path is kept per item, where that item's people touch it. None as for :meth:`shadow_transmission`.
        """
        knots = self.shadow_knots(people, times)
        if knots is None:
            return None
        t, weights = knots
        d = (t - 1).to(self.device)  # (T, J, P)
        touched = d.abs() > SHADOW_TOL
        if groups is None:
            hit = touched.reshape(-1, d.shape[-1]).any(0)  # (P,) the paths some frame's people touch
            if not bool(hit.any()):
                return None
            d = d * hit
        else:
            if not bool(touched.any()):
                return None
            g = groups.to(self.device)
            hits = torch.zeros(int(g.max()) + 1, d.shape[-1], dtype=torch.int32, device=self.device)
            hits.index_add_(0, g, touched.any(1).to(torch.int32))  # (items, P): as each item alone
            d = d * (hits[g] > 0)[:, None, :]
        if quadrature:
            d = torch.stack([d, -1j * d])
        basis = self.static_basis()  # (P, 2, RX, N)
        # One GEMM over every static path (those the people do not touch have zero coefficients):
        # cheaper than gathering the touched paths' basis rows (a copy of tens of MB per batch).
        coef = torch.view_as_real(d).to(basis.dtype).reshape(-1, 2 * d.shape[-1])  # [Re, Im] per path
        out = (coef @ basis.reshape(coef.shape[1], -1)).reshape(*d.shape[:-1], *basis.shape[2:])  # (..., T, J, RX, N)
        if weights is None:
            out = out[..., 0, :, None, :]
        else:
            out = torch.einsum("mj,...tjrn->...trmn", weights.to(device=out.device, dtype=out.dtype), out)
        return (out[0], out[1]) if quadrature else out

    def frame_paths(self, people: Sequence[Any], times: torch.Tensor) -> Paths:
        """The people's paths (negligible ones masked) and their shadow corrections (:meth:`shadow_paths`).

        With the room's cached signal they give the frames of :meth:`simulate`, for code that needs the
        paths themselves (the calibration, the proxy).
        """
        people = list(people or [])
        paths = negligible_paths_off(self.paths(people, times))
        shadow = self.shadow_paths(people, times)
        return paths if shadow is None else Paths.cat([paths, shadow])

    # ------------------------------------------------------------------ a per-item draw
    def _room_cached(self, key: tuple[str, int], make: Any) -> Any:
        if key not in self._room_cache:
            value = make()  # a room synthesis takes a second; setdefault keeps the first of racing threads
            return self._room_cache.setdefault(key, value)
        return self._room_cache[key]

    def strongest_room_paths(self, k: int) -> tuple[Paths, torch.Tensor]:
        """The ``k`` room paths with the largest ``|amplitude| x delay`` and their cached-room signal.

        The ``phase_noise`` stage's ranking (largest skirt); their signal is what leaves the cached room
        signal when they are passed to the receiver as paths. Cached per ``k``.
        """
        def make() -> tuple[Paths, torch.Tensor]:
            room = self.tracer.static_paths()
            strength = (room.amplitude.abs() * room.delay_s).amax(-1)  # (P,)
            if room.mask is not None:
                strength = strength * room.mask
            idx = torch.topk(strength, min(k, room.num_paths)).indices.sort().values
            picked = Paths(room.delay_s[idx], room.delay_rate[idx], room.amplitude[idx])
            return picked, self.receiver.static_signal(picked)
        return self._room_cached(("strongest", k), make)

    def room_quadrature(self, k: int = 0) -> torch.Tensor:
        """:func:`~radaraug.sim.item_signal.quadrature` of the room, less that of its ``k`` strongest paths (cached)."""
        def make() -> torch.Tensor:
            if k:
                return self.room_quadrature() - quadrature(self.receiver, self.strongest_room_paths(k)[0])
            return quadrature(self.receiver, self.tracer.static_paths())
        return self._room_cached(("quadrature", k), make)

    def _drawn_parts(self, draw: ItemDraw, paths: Paths
                     ) -> tuple[FMCWReceiver, Paths, torch.Tensor, RxGainPhaseMismatch | None]:
        """The item's receiver, all its paths and the room's signal before the people's shadow and the gain offset.

        ``paths`` are the people's (RCS-scaled, negligible ones off). The room's cached signal is adjusted
        exactly: turned by a drawn RX mismatch as ``a (cos(phi) S - sin(phi) Q)`` (``Q``:
        :meth:`room_quadrature`; the mismatch is returned to turn the shadow alike), less the strongest
        returns passed as paths for their phase noise (docs/simulation.md, "Twin randomization").
        """
        if draw.scatterers:
            paths = Paths.cat([paths, static_scatterer_paths(self.config, draw.scatterers, paths)])
        pn = None if not draw.phase_noise_rms_Hz else (draw.phase_noise_rms_Hz, draw.phase_noise_paths)
        extra = draw.catalog_effects(self.config)
        receiver = item_receiver(self.receiver, draw.system_gain_offset_dB, draw.noise_figure_offset_dB, pn,
                                 adc_noise_offset_dB=draw.adc_noise_offset_dB, extra_effects=extra)
        static = self.static_signal()
        k = draw.static_phase_noise_paths if any(isinstance(e, PhaseNoise) for e in receiver.effects) else 0
        if k:
            strong, strong_signal = self.strongest_room_paths(k)
            paths = Paths.cat([paths, like_batch(strong, paths)])
            static = static - strong_signal
        # The people's shadow on the room is geometry only: the RCS scale does not change it. (Room paths
        # moved out of the cache for the phase noise keep their shadow here, in the cached part.)
        mismatch = static_mismatch(receiver, extra)
        if mismatch is not None:
            amp, phase = rx_gain(mismatch, static)
            static = amp * (torch.cos(phase) * static - torch.sin(phase) * self.room_quadrature(k))
        return receiver, paths, static, mismatch

    @torch.no_grad()
    def simulate(
        self,
        people: Sequence[Any] | None,
        times: torch.Tensor,
        *,
        generators: Sequence[torch.Generator] | torch.Generator | None = None,
        draw: ItemDraw | None = None,
        t0: float = 0.0,
    ) -> torch.Tensor:
        """Raw frames ``(T, rx, chirps, samples)`` in SDK floats at frame start ``times`` ``(T,)``.

        Args:
            people: the people (default: none); ``scene.people`` for the scene's own.
            times: frame start times in seconds.
            generators: one generator per frame (frame ``k`` then depends only on its seed), one
                for the batch, or None (global RNG).
            draw: a per-item draw (:meth:`~radaraug.sim.randomization.TwinRandomization.item`) to
                simulate under (docs/simulation.md, "Twin randomization"); its room variant is
                not applied here: simulate with that variant's twin. None (default): the twin as it is.
            t0: the recording's time at ``times == 0``, s: the receiver's time-locked effects (a spur
                tone) see ``t0 + times``, so that several scenes can be played into one recording.
        """
        return self.simulate_items([TwinItem(people, times, generators, draw, t0)])[0]

    @torch.no_grad()
    def simulate_items(self, items: Sequence[TwinItem]) -> list[torch.Tensor]:
        """:meth:`simulate` of several items at once, each with its own people and draw, in this twin's room.

        The people of every item are traced together (padded to one segment count) and their shadows
        computed together; each item then gets its own receiver. Equal to one :meth:`simulate` call per
        item within the synthesis' contract (docs/simulation.md, "Many items per call").

        Returns:
            each item's frames ``(T_i, rx, chirps, samples)``, in order.
        """
        if not items:
            return []
        times = [it.times.to(torch.float64).reshape(-1) for it in items]
        counts = [int(t.shape[0]) for t in times]
        all_times = torch.cat(times)
        who = _PeopleRows(self, [list(it.people or []) for it in items], times)
        traced = self._traced(who.ellipsoids, all_times, who.dead) if who else self._no_paths(all_times)
        starts = [sum(counts[:i]) for i in range(len(items) + 1)]
        parts = []
        for i, it in enumerate(items):
            paths = traced.select(slice(starts[i], starts[i + 1]))
            if it.draw is not None and who.people[i]:
                pad = who.s_max - sum(who.segments[i])
                paths = scale_people_paths(paths, who.segments[i] + ([pad] if pad else []),
                                           [*it.draw.rcs_scale_dB, *([0.0] if pad else [])])
            paths = negligible_paths_off(paths)
            parts.append((self.receiver, paths, self.static_signal(), None) if it.draw is None
                         else self._drawn_parts(it.draw, paths))
        turned = any(m is not None for *_, m in parts)
        shadow = self.shadow_signal(who, all_times, quadrature=True, groups=who.row_item) if turned else \
            self.shadow_signal(who, all_times, groups=who.row_item)
        out = []
        for i, (it, (receiver, paths, static, mismatch)) in enumerate(zip(items, parts)):
            rows = slice(starts[i], starts[i + 1])
            if shadow is not None and who.people[i]:
                if isinstance(shadow, tuple):  # some item's mismatch turns its shadow: the quadrature too
                    change = shadow[0][rows] if mismatch is None else _turned(mismatch, shadow[0][rows], shadow[1][rows])
                else:
                    change = shadow[rows]
                static = static + change
            if it.draw is not None:
                static = _gain_offset(static, it.draw)
            out.append(_receive(receiver, paths, static, times[i], it.generators, it.t0))
        return out


@dataclasses.dataclass(frozen=True)
class TwinItem:
    """One item of :meth:`DigitalTwin.simulate_items`: the arguments of one :meth:`DigitalTwin.simulate` call."""

    people: Sequence[Any] | None
    times: torch.Tensor
    generators: Sequence[torch.Generator] | torch.Generator | None = None
    draw: ItemDraw | None = None
    t0: float = 0.0


class _PeopleRows:
    """The people of several items, item ``i`` on its own frames, padded to one segment count for one trace.

    The padding segments sit 1 km behind the radar and are 1 mm across: traced with the rest, they touch
    nothing, and :meth:`dead` masks their paths.
    """

    def __init__(self, twin: DigitalTwin, people: list[list[Any]], times: list[torch.Tensor]) -> None:
        self.twin, self.people = twin, people
        self.row_item = torch.repeat_interleave(torch.arange(len(people)), torch.tensor([int(t.shape[0]) for t in times]))
        self.segments = [[int(p.ellipsoids(t[:1]).centers.shape[-2]) for p in ps] for ps, t in zip(people, times)]
        self.counts = torch.tensor([sum(s) for s in self.segments], dtype=torch.long)
        self.s_max = int(self.counts.max()) if len(people) else 0

    def __bool__(self) -> bool:
        return self.s_max > 0

    def ellipsoids(self, t: torch.Tensor, rows: torch.Tensor) -> Ellipsoids:
        """``(n, S_max)`` segments at times ``t`` of frames ``rows``: each frame's item's, then padding."""
        tw = self.twin
        dev, dt, n, s = tw.device, tw.dtype, int(t.shape[0]), self.s_max
        radar = tw.scene.radar
        far = (radar.position - 1000.0 * radar.rotation[:, 2]).to(device=dev, dtype=dt)
        centers = far.expand(n, s, 3).clone()
        semi = torch.full((n, s, 3), 1e-3, device=dev, dtype=dt)
        rot = torch.eye(3, device=dev, dtype=dt).expand(n, s, 3, 3).clone()
        vel = torch.zeros(n, s, 3, device=dev, dtype=dt)
        omega: torch.Tensor | None = None
        material = "skin"
        item_of = self.row_item[rows]
        for i in torch.unique(item_of).tolist():
            if not self.people[i]:
                continue
            sel = (item_of == i).nonzero()[:, 0].to(dev)
            e = tw.ellipsoids(self.people[i], t[sel.cpu()])
            assert e is not None
            k = e.centers.shape[-2]
            material = e.material
            centers[sel, :k], semi[sel, :k], rot[sel, :k], vel[sel, :k] = e.centers, e.semi_axes, e.rotations, e.velocities
            if e.angular_velocities is not None:
                omega = torch.zeros_like(vel) if omega is None else omega
                omega[sel, :k] = e.angular_velocities
        return Ellipsoids(centers, semi, rot, vel, material, omega)

    def dead(self, p: Paths, rows: torch.Tensor) -> Paths:
        """``p`` with the padding segments' slots masked and zeroed in frames ``rows``."""
        dev = p.delay_s.device
        segment = slot_segments(self.s_max, p.num_paths, dev)
        live = segment[None, :] < self.counts.to(dev)[self.row_item[rows].to(dev)][:, None]  # (n, P)
        mask = live if p.mask is None else p.mask & live
        return dataclasses.replace(p, amplitude=p.amplitude * live[..., None].to(p.amplitude.real.dtype), mask=mask)


def _turned(mismatch: RxGainPhaseMismatch, shadow: torch.Tensor, quad: torch.Tensor) -> torch.Tensor:
    """A shadow change turned by the per-RX complex gain of ``mismatch``, from it and its quadrature."""
    amp, phase = rx_gain(mismatch, shadow)
    return amp * (torch.cos(phase) * shadow + torch.sin(phase) * quad)


def _gain_offset(static: torch.Tensor, draw: ItemDraw) -> torch.Tensor:
    """The room's signal scaled by the draw's system-gain offset (by linearity)."""
    return static * 10 ** (draw.system_gain_offset_dB / 20) if draw.system_gain_offset_dB != 0.0 else static


def _receive(receiver: FMCWReceiver, paths: Paths, static: torch.Tensor, times: torch.Tensor,
             generators: Sequence[torch.Generator] | torch.Generator | None, t0: float) -> torch.Tensor:
    """The receiver's frames of ``paths`` and the room's ``static`` signal at frame starts ``times`` (+ ``t0``)."""
    start = times.to(torch.float64) + t0 if t0 else times.to(torch.float64)
    if isinstance(generators, Sequence):
        if len(generators) != times.shape[0]:
            raise InputTensorError(f"need one generator per frame: {len(generators)} for {times.shape[0]} frames")
        frames = [
            receiver(paths.select(k), generator=g, frame_start_s=float(start[k]),
                     static_signal=static[k] if static.dim() == 4 else static)
            for k, g in enumerate(generators)
        ]
        return torch.stack(frames)
    # Each frame of the batch starts at its own time (time-locked effects such as a spur tone).
    return receiver(paths, generator=generators, frame_start_s=start, static_signal=static)
