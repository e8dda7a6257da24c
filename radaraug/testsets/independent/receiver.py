"""An independent FMCW receiver in NumPy: raw ADC frames of point scatterers, from the physics.

It shares no code with :mod:`radaraug.sensor` (it reads only a
:class:`~radaraug.config.RadarConfig`'s numbers), so captures made with it can test the twin and the
diagnosis loop with known, undeclared effects. The signal model, the receiver chain, the IF
filters (``filter_method``), the ``effects``, the ``scene``/``tracks`` formats and the seeding are
specified in docs/heldout_worlds.md ("Receiver").
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from radaraug.config import RadarConfig

C_LIGHT = 299_792_458.0
K_BOLTZMANN = 1.380649e-23
T0_K = 290.0

FILTER_METHODS = ("analog", "steady", "circular", "iir")
"""``"iir"`` is an alias of ``"analog"``."""
ROLL = 16
"""Samples generated before the first and after the last ADC sample (``"analog"``, ``"steady"``)."""
_FRAME_BLOCK = 16

# name -> (required parameters, optional parameters with defaults)
EFFECT_PARAMS: dict[str, tuple[tuple[str, ...], dict[str, Any]]] = {
    "spur_tone": (("freq_Hz", "amplitude_counts", "phase_rad"), {}),
    "adc_noise": (("rms_counts",), {}),
    "rx_gain_phase_mismatch": (("gain_dB", "phase_rad"), {}),
    "static_clutter": (("range_m", "level_dB", "phase_rad"), {}),
    "vibrating_clutter": (
        ("range_m", "level_dB", "displacement_m", "vibration_Hz", "phase_rad"),
        {"path_phase_rad": 0.0},
    ),
    "multipath": (("extra_range_m", "level_dB", "phase_rad"), {}),
    "interference": (("probability", "amplitude_counts", "duration_s"), {}),
    "frame_drift": (("gain_rms_dB", "dc_rms_counts"), {}),
    "phase_noise": (("freq_noise_rms_Hz", "corner_Hz"), {}),
    "chirp_nonlinearity": (("deviation_Hz", "ripple_Hz", "phase_rad"), {}),
    "moving_target": (("range_m", "speed_m_s", "level_dB"), {"phase_rad": 0.0}),
}
EFFECT_NAMES = tuple(EFFECT_PARAMS)

# Random stream keys (spawn_key[0]) of the random stages.
_STREAM = {"thermal": 0, "adc_noise": 1, "interference": 2, "frame_drift": 3, "phase_noise": 4}


@dataclass
class _Path:
    coef: np.ndarray  # (RX,) complex, float units at 0 dB IF gain, before system gain / mismatch
    range_m: float
    speed_m_s: float = 0.0
    displacement_m: float = 0.0
    vibration_Hz: float = 0.0
    vibration_phase_rad: float = 0.0
    # Tracks: range and rate at each chirp's first ADC sample, (F, 1, M, 1), and a complex gain
    # per chirp and RX, (F, RX, M, 1) or broadcastable, on top of ``coef``.
    track_range_m: np.ndarray | None = None
    track_rate_m_s: np.ndarray | None = None
    gain: np.ndarray | None = None

    @property
    def static(self) -> bool:
        return self.speed_m_s == 0.0 and self.displacement_m == 0.0 and self.track_range_m is None


def _rng(seed: int, stream: str, occurrence: int = 0) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(_STREAM[stream], occurrence)))


def _per_rx(value: Any, n_rx: int, what: str) -> np.ndarray:
    arr = np.asarray(value, dtype=np.float64).reshape(-1)
    if arr.size == 1:
        return np.full(n_rx, float(arr[0]))
    if arr.size != n_rx:
        raise ValueError(f"{what}: expected a scalar or {n_rx} values (one per RX), got {arr.size}")
    return arr


def _check_keys(what: str, given: Iterable[str], required: Iterable[str], optional: Iterable[str]) -> None:
    """Raise ValueError naming the ``required`` keys missing from ``given`` and the unknown ones."""
    given, required = list(given), list(required)
    missing = [k for k in required if k not in given]
    unknown = [k for k in given if k not in required and k not in optional]
    if missing or unknown:
        raise ValueError(f"{what}: missing {missing}, unknown {unknown}")


def _check_effects(effects: Iterable[Mapping[str, Any]]) -> list[dict[str, Any]]:
    out = []
    for e in effects:
        e = dict(e)
        name = e.pop("name", None)
        if name not in EFFECT_PARAMS:
            raise ValueError(f"unknown effect {name!r}; known: {', '.join(EFFECT_NAMES)}")
        required, optional = EFFECT_PARAMS[name]
        _check_keys(f"effect {name!r}", e, required, optional)
        out.append({"name": name, **optional, **e})
    return out


def _amplitude(level_dB: Any, tx_power_W: float, g_fe: float) -> Any:
    """Peak amplitude (float units, 0 dB IF gain) of paths received at ``level_dB`` (array) re TX power."""
    return np.sqrt(2.0 * tx_power_W * 10.0 ** (np.asarray(level_dB, dtype=np.float64) / 10.0)) * g_fe


def _lo_frequency_noise(
    rng: np.random.Generator, shape: tuple[int, int], length: int, fs: float, rms_Hz: float, corner_Hz: float
) -> np.ndarray:
    """LO frequency noise ``(F, M, length)`` in Hz, Lorentzian-shaped along the last axis.

    Generated on twice the length and cropped, so the FFT filter's circular wrap does not
    correlate the end of a chirp with its start. Scaled to the *expected* RMS ``rms_Hz``.
    """
    n_pad = 2 * length
    white = rng.standard_normal((*shape, n_pad))
    mag = 1.0 / np.sqrt(1.0 + (np.fft.rfftfreq(n_pad, 1.0 / fs) / corner_Hz) ** 2)
    nu = np.fft.irfft(np.fft.rfft(white, axis=-1) * mag, n=n_pad, axis=-1)[..., :length]
    # Variance of a circularly filtered white N(0, 1) sequence: mean of |H|^2 over all FFT bins.
    var = np.mean(1.0 / (1.0 + (np.fft.fftfreq(n_pad, 1.0 / fs) / corner_Hz) ** 2))
    return nu * (rms_Hz / math.sqrt(var))


def _nonlinearity_cycles(
    tau: Any, t: np.ndarray, deviation_Hz: float, ripple_Hz: float, phase_rad: float
) -> Any:
    """Extra beat phase (cycles) ``integral_{t - tau}^{t} dF`` of ``dF = dev sin(2 pi r t + phase)``."""
    if ripple_Hz == 0.0:
        return deviation_Hz * math.sin(phase_rad) * tau
    w = 2.0 * math.pi * ripple_Hz
    return deviation_Hz / w * (np.cos(w * (t - tau) + phase_rad) - np.cos(w * t + phase_rad))


def _track_path(p: Mapping[str, Any], F: int, n_rx: int, M: int, p_tx: float, g_fe: float) -> _Path:
    """The :class:`_Path` of a track ``p`` (see :func:`generate`) over ``F`` frames of ``M`` chirps."""
    _check_keys("track", p, ("range_m", "rate_m_s", "level_dB"), ("phase_rad", "rx_phase_rad"))
    rng_m = np.asarray(p["range_m"], dtype=np.float64)
    rate = np.asarray(p["rate_m_s"], dtype=np.float64)
    if rng_m.shape != (F, M) or rate.shape != (F, M):
        raise ValueError(f"track: range_m and rate_m_s must be (frames, chirps) = {(F, M)}, got "
                         f"{rng_m.shape} and {rate.shape}")

    def broadcast(key: str, allowed: str, shape: tuple[int, ...], from_1d: Any) -> np.ndarray:
        """The track's ``key`` broadcast to ``shape``; a 1-D value is first expanded by ``from_1d``."""
        a = np.asarray(p.get(key, 0.0), dtype=np.float64)
        if a.ndim == 1:
            a = from_1d(a)
        try:
            return np.broadcast_to(a, shape)
        except ValueError:
            raise ValueError(f"track: {key} must be {allowed}, got {a.shape}") from None

    # (F,) -> (F, 1): one level per frame; (RX,) -> (1, RX, 1): one phase per RX
    level = broadcast("level_dB", "a scalar, (F,) or (F, M)", (F, M), lambda a: a[:, None])
    rx_phase = broadcast("rx_phase_rad", "a scalar, (RX,) or (F, RX, M)", (F, n_rx, M),
                         lambda a: _per_rx(a, n_rx, "rx_phase_rad")[None, :, None])
    # Amplitude relative to the 0 dB reference of ``_Path.coef``: sqrt(2 P_tx 10^(L/10)) g_fe.
    phase = rx_phase + float(p.get("phase_rad", 0.0))
    gain = _amplitude(level, p_tx, g_fe)[:, None, :] * np.exp(1j * phase)
    return _Path(
        np.ones(n_rx, dtype=np.complex128),
        float(rng_m[0, 0]),
        track_range_m=rng_m[:, None, :, None],
        track_rate_m_s=rate[:, None, :, None],
        gain=gain[..., None],
    )


def _chirp_times(cfg: RadarConfig, frame_starts: np.ndarray) -> np.ndarray:
    """Times ``(F, M)`` of each chirp's first ADC sample for frame start times ``frame_starts`` ``(F,)``."""
    m = np.arange(cfg.num_chirps_per_frame, dtype=np.float64)
    return frame_starts[:, None] + m[None, :] * cfg.chirp_repetition_time_s + cfg.adc_delay_s


def _even_extension(x: np.ndarray) -> np.ndarray:
    """``x`` followed by itself reversed along the last axis: a periodic signal with no jump."""
    return np.concatenate([x, x[..., ::-1]], axis=-1)


def _path_cycles(
    p: _Path,
    t: np.ndarray,
    t_chirp: np.ndarray,
    f0: float,
    S: float,
    nonlin: list[dict[str, Any]],
    nu: np.ndarray | None,
) -> tuple[Any, Any, Any]:
    """Beat phase (cycles, float64, not reduced), delay and delay rate of ``p`` at fast times ``t``.

    Shapes: ``t`` is ``(T,)``; a static path without phase noise gives ``(T,)``, otherwise
    ``(F, 1, M, T)``. ``nu`` is ``(F, 1, M, T)`` or None.
    """
    if p.static:
        tau: Any = 2.0 * p.range_m / C_LIGHT
        tau_rate: Any = 0.0
    elif p.track_range_m is not None and p.track_rate_m_s is not None:
        r = p.track_range_m + p.track_rate_m_s * t  # (F, 1, M, T): linear within the chirp
        if np.min(r) <= 0.0:
            raise ValueError(f"a track reaches range {np.min(r):.3g} m <= 0 during the capture")
        tau = 2.0 * r / C_LIGHT
        tau_rate = np.broadcast_to(2.0 * p.track_rate_m_s / C_LIGHT, r.shape)
    else:
        t_abs = t_chirp + t  # (F, 1, M, T)
        r = p.range_m + p.speed_m_s * t_abs
        rate = np.full_like(t_abs, p.speed_m_s)
        if p.displacement_m:
            arg = 2.0 * math.pi * p.vibration_Hz * t_abs + p.vibration_phase_rad
            r = r + p.displacement_m * np.sin(arg)
            rate = rate + p.displacement_m * 2.0 * math.pi * p.vibration_Hz * np.cos(arg)
        if np.min(r) <= 0.0:
            raise ValueError(f"a moving path reaches range {np.min(r):.3g} m <= 0 during the capture")
        tau = 2.0 * r / C_LIGHT
        tau_rate = 2.0 * rate / C_LIGHT
    cyc = f0 * tau + S * tau * t - 0.5 * S * tau * tau
    for e in nonlin:
        cyc = cyc + _nonlinearity_cycles(tau, t, e["deviation_Hz"], e["ripple_Hz"], e["phase_rad"])
    if nu is not None:
        cyc = cyc + tau * nu
    return cyc, tau, tau_rate


def generate(
    cfg: RadarConfig,
    frames: int,
    *,
    seed: int,
    effects: Sequence[Mapping[str, Any]] = (),
    scene: Sequence[Mapping[str, Any]] = (),
    tracks: Sequence[Mapping[str, Any]] = (),
    start_time_s: float = 0.0,
    noise_figure_dB: float = 12.0,
    system_gain_dB: float = 0.0,
    front_end_gain_dB: float = 49.0,
    tx_power_dBm: float = 5.0,
    leakage_coupling_dB: Any = (-56.3, -64.3, -64.3),
    leak_range_m: float = 0.04,
    leak_phase_rad: Any = (0.0, 0.0, 0.0),
    dc_counts: Any = (1620.0, 1945.0, 2067.5),
    filter_method: str = "analog",
    phase_noise_min_level_dB: float = -math.inf,
) -> np.ndarray:
    """Raw ADC counts ``(frames, RX, chirps, samples)`` (uint16) of a scene through the receiver.

    The model and the formats of ``effects``, ``scene`` and ``tracks``: docs/heldout_worlds.md ("Receiver").

    Args:
        cfg: radar configuration (only its numbers are read).
        frames: number of frames F; frame ``f`` starts at ``f * cfg.frame_repetition_time_s``.
        seed: seed of every random draw (one stream per stage).
        effects: undeclared effects ``{"name": ..., **params}`` (:data:`EFFECT_PARAMS`).
        scene: static points ``{"range_m", "level_dB", "phase_rad" (0), "rx_phase_rad" (0)}``,
            level = received power relative to the TX power, dB.
        tracks: points on trajectories sampled per chirp ``{"range_m", "rate_m_s", "level_dB",
            "phase_rad" (0), "rx_phase_rad" (0)}``, ranges and rates ``(F, M)``.
        start_time_s: absolute time of the first frame's start (moves every time-dependent
            stage: moving target, vibrating clutter, spur phase).
        noise_figure_dB: receiver noise figure (``-inf`` turns the thermal noise off).
        system_gain_dB: flat gain on paths and thermal noise.
        front_end_gain_dB: ADC float units per sqrt(W) at the RX port at 0 dB IF gain, in dB.
        tx_power_dBm: transmit power.
        leakage_coupling_dB: TX->RX leakage power re TX power, scalar or per RX (``-inf``: none).
        leak_range_m: equivalent one-way range of the leakage path.
        leak_phase_rad: phase of the leakage tone, scalar or per RX.
        dc_counts: DC level of each RX in ADC counts (scalar or per RX).
        filter_method: ``"analog"`` (alias ``"iir"``), ``"steady"`` or ``"circular"``.
        phase_noise_min_level_dB: paths received below this level (dB re TX; a track's
            strongest chirp) get no LO phase noise, which saves time where their skirt is far
            under the noise. Default: every path.

    Raises:
        ValueError: an unknown filter method or effect, a bad parameter, or a path reaching range <= 0.
    """
    if filter_method not in FILTER_METHODS:
        raise ValueError(f"filter_method must be one of {FILTER_METHODS}, got {filter_method!r}")
    method = "analog" if filter_method == "iir" else filter_method
    if frames < 1:
        raise ValueError(f"frames must be >= 1, got {frames}")
    effs = _check_effects(effects)
    n_rx = cfg.num_rx
    M, N = cfg.num_chirps_per_frame, cfg.num_samples_per_chirp
    F = int(frames)
    fs = cfg.sample_rate_Hz
    S = cfg.slope_Hz_per_s
    f0 = cfg.sampled_start_frequency_Hz
    t_d = cfg.adc_delay_s
    fh = cfg.effective_hp_cutoff_Hz
    fl = cfg.effective_aaf_cutoff_Hz
    full = float(cfg.adc_full_scale_counts)
    to_float = 2.0 / full  # counts -> float units
    g_fe = 10.0 ** (front_end_gain_dB / 20.0)
    g_if = 10.0 ** (cfg.if_gain_dB / 20.0)
    p_tx = 1e-3 * 10.0 ** (tx_power_dBm / 10.0)

    roll = 0 if method == "circular" else ROLL
    L = roll + N + roll
    t = (np.arange(L, dtype=np.float64) - roll) / fs  # fast time, 0 at the first ADC sample
    # Time of each chirp's first ADC sample, (F, 1, M, 1).
    frame_starts = float(start_time_s) + np.arange(F, dtype=np.float64) * cfg.frame_repetition_time_s
    t_chirp = _chirp_times(cfg, frame_starts)[:, None, :, None]
    by_name = {name: [e for e in effs if e["name"] == name] for name in EFFECT_NAMES}

    # ---------------------------------------------------------------- 1. paths
    def point(level_dB: float, phase_rad: float, range_m: float, rx_phase: Any = 0.0, **motion: Any) -> _Path:
        """A point path received at ``level_dB`` re TX, with a per-RX phase and optional motion."""
        a = _amplitude(float(level_dB), p_tx, g_fe) * np.exp(1j * float(phase_rad))
        return _Path(a * np.exp(1j * _per_rx(rx_phase, n_rx, "rx_phase_rad")), float(range_m), **motion)

    paths: list[_Path] = []
    leak_amp = _amplitude(_per_rx(leakage_coupling_dB, n_rx, "leakage_coupling_dB"), p_tx, g_fe)
    leak_phase = _per_rx(leak_phase_rad, n_rx, "leak_phase_rad")
    if np.any(leak_amp > 0):
        paths.append(_Path(leak_amp * np.exp(1j * leak_phase), float(leak_range_m)))
    scene_paths: list[_Path] = []
    for pt in scene:
        _check_keys("scene point", pt, (), ("range_m", "level_dB", "phase_rad", "rx_phase_rad"))
        phase, rx_phase = pt.get("phase_rad", 0.0), pt.get("rx_phase_rad", 0.0)
        scene_paths.append(point(pt["level_dB"], phase, pt["range_m"], rx_phase))
    scene_paths += [_track_path(tr, F, n_rx, M, p_tx, g_fe) for tr in tracks]
    scene_paths += [point(e["level_dB"], e["phase_rad"], e["range_m"], speed_m_s=float(e["speed_m_s"]))
                    for e in by_name["moving_target"]]
    clutter_paths = [point(e["level_dB"], e["phase_rad"], e["range_m"]) for e in by_name["static_clutter"]]
    clutter_paths += [
        point(e["level_dB"], e["path_phase_rad"], e["range_m"], displacement_m=float(e["displacement_m"]),
              vibration_Hz=float(e["vibration_Hz"]), vibration_phase_rad=float(e["phase_rad"]))
        for e in by_name["vibrating_clutter"]
    ]
    ghosts: list[_Path] = []
    for e in by_name["multipath"]:
        ratio = 10.0 ** (e["level_dB"] / 20.0) * np.exp(1j * e["phase_rad"])
        extra = float(e["extra_range_m"])
        for p in scene_paths:
            ghost_track = None if p.track_range_m is None else p.track_range_m + extra
            ghosts.append(replace(p, coef=p.coef * ratio, range_m=p.range_m + extra, track_range_m=ghost_track))
    paths += scene_paths + ghosts + clutter_paths

    # Complex gain per RX after the system gain: system gain x mismatch.
    rx_gain = np.full(n_rx, 10.0 ** (system_gain_dB / 20.0), dtype=np.complex128)
    for e in by_name["rx_gain_phase_mismatch"]:
        rx_gain *= 10.0 ** (_per_rx(e["gain_dB"], n_rx, "gain_dB") / 20.0) * np.exp(
            1j * _per_rx(e["phase_rad"], n_rx, "phase_rad")
        )

    # Phase modulations of every path: LO frequency noise (F, 1, M, L) and ramp non-linearity.
    lo_noise = [_lo_frequency_noise(_rng(seed, "phase_noise", i), (F, M), L, fs, e["freq_noise_rms_Hz"],
                                    e["corner_Hz"]) for i, e in enumerate(by_name["phase_noise"])]
    nu = sum(lo_noise[1:], lo_noise[0])[:, None] if lo_noise else None
    nonlin = by_name["chirp_nonlinearity"]

    x = np.zeros((F, n_rx, M, L))
    static_wave = np.zeros((n_rx, L))
    # High-pass capacitor voltage at the ramp start that the steady state would have, (F, RX, M, 1).
    cap_v = np.zeros((F, n_rx, M, 1))
    t_ramp = np.array([-t_d])
    # LO noise at the ramp start: the nearest grid sample (or the first one)
    nu_ramp = None if nu is None else nu[..., max(roll - int(round(t_d * fs)), 0)][..., None]
    # Peak amplitude at or below which a path carries no LO noise (0 by default: a zero path has no
    # wave to modulate, so every path effectively carries it).
    pn_floor = math.sqrt(2.0 * p_tx) * g_fe * 10.0 ** (phase_noise_min_level_dB / 20.0)
    for p in paths:
        path_amp = float(np.max(np.abs(p.coef))) * (1.0 if p.gain is None else float(np.max(np.abs(p.gain))))
        pn = nu if path_amp > pn_floor else None
        coef: np.ndarray = p.coef * rx_gain
        c4 = coef[None, :, None, None] * (1.0 if p.gain is None else p.gain)  # (1 or F, RX, 1 or M, 1)
        cyc, _, _ = _path_cycles(p, t, t_chirp, f0, S, nonlin, pn)
        phi = 2.0 * math.pi * np.mod(cyc, 1.0)
        if np.ndim(phi) == 1:
            static_wave += coef.real[:, None] * np.cos(phi) - coef.imag[:, None] * np.sin(phi)
        else:
            x += c4.real * np.cos(phi) - c4.imag * np.sin(phi)
        if method == "analog":
            cyc_r, tau_r, rate_r = _path_cycles(
                p, t_ramp, t_chirp, f0, S, nonlin, None if pn is None else nu_ramp
            )
            f_beat = S * tau_r + (f0 - S * t_d - S * tau_r) * rate_r  # instantaneous, at the ramp start
            ph_r = np.exp(2j * math.pi * np.mod(cyc_r, 1.0)) / (1.0 + 1j * f_beat / fh)
            cap_v += np.real(c4 * ph_r)  # ph_r: (1,) or (F, 1, M, 1)
    x += static_wave[None, :, None, :]

    # ---------------------------------------------------------------- 2-3. thermal noise, gains
    noise_W = K_BOLTZMANN * T0_K * 10.0 ** (noise_figure_dB / 10.0) * fs / 2.0
    if noise_W > 0:
        sigma = math.sqrt(noise_W) * g_fe * np.abs(rx_gain)  # (RX,)
        x += _rng(seed, "thermal").standard_normal(x.shape) * sigma[None, :, None, None]

    # ---------------------------------------------------------------- 5. signals after the IF gain
    after = np.zeros_like(x) if by_name["adc_noise"] or by_name["interference"] else None
    for i, e in enumerate(by_name["adc_noise"]):
        after += _rng(seed, "adc_noise", i).standard_normal(x.shape) * (e["rms_counts"] * to_float)
    for i, e in enumerate(by_name["interference"]):
        rng = _rng(seed, "interference", i)
        hit = rng.random((F, M)) < e["probability"]
        start = rng.uniform(0.0, max(N / fs - e["duration_s"], 0.0), size=(F, M))
        phase = rng.uniform(0.0, 2.0 * math.pi, size=(F, M))
        fi, mi = np.nonzero(hit)  # the chirps with a burst (none: every array below is empty)
        dur = float(e["duration_s"])
        u = t[None, :] - start[fi, mi][:, None]  # (bursts, L)
        inside = (u >= 0.0) & (u <= dur)
        window = np.sin(math.pi * u / dur) ** 2
        # instantaneous beat frequency (fs/2)(2u/dur - 1): zero where the ramps cross
        sweep = 2.0 * math.pi * (fs / 2.0) * (u * u / dur - u) + phase[fi, mi][:, None]
        burst = np.where(inside, window * np.cos(sweep), 0.0) * (e["amplitude_counts"] * to_float)
        assert after is not None  # allocated above whenever there is interference
        after[fi, :, mi, :] += burst[:, None, :]

    # ---------------------------------------------------------------- 4-6. high-pass, IF gain, AAF
    n_fft = L if method == "circular" else 2 * L
    f = np.fft.rfftfreq(n_fft, 1.0 / fs)
    h_aaf = 1.0 / (1.0 + 1j * f / fl)
    h_chain = (1j * f / fh) / (1.0 + 1j * f / fh) * g_if * h_aaf
    ext = (lambda a: a) if method == "circular" else _even_extension
    out = np.empty((F, n_rx, M, N))
    for f_lo in range(0, F, _FRAME_BLOCK):  # bounded memory
        blk = slice(f_lo, min(f_lo + _FRAME_BLOCK, F))
        spec = np.fft.rfft(ext(x[blk]), axis=-1) * h_chain
        if after is not None:
            spec += np.fft.rfft(ext(after[blk]), axis=-1) * h_aaf
        out[blk] = np.fft.irfft(spec, n=n_fft, axis=-1)[..., roll : roll + N]
    del x, after
    t = t[roll : roll + N]
    if method == "analog":
        s = t + t_d  # time since the ramp start
        wh, wl = 2.0 * math.pi * fh, 2.0 * math.pi * fl
        if abs(wl - wh) > 1e-9 * wl:
            decay = wl / (wl - wh) * (np.exp(-wh * s) - np.exp(-wl * s))
        else:
            decay = wh * s * np.exp(-wh * s)
        out += g_if * cap_v * decay

    # ---------------------------------------------------------------- 7. drift, spur, DC offset
    dc = np.broadcast_to(_per_rx(dc_counts, n_rx, "dc_counts")[None, :, None, None], (F, n_rx, 1, 1)).copy()
    for i, e in enumerate(by_name["frame_drift"]):
        rng = _rng(seed, "frame_drift", i)
        gain_dB = rng.normal(0.0, e["gain_rms_dB"], size=F)
        out *= (10.0 ** (gain_dB / 20.0))[:, None, None, None]
        dc += rng.normal(0.0, e["dc_rms_counts"], size=(F, n_rx))[:, :, None, None]
    counts = out * (full / 2.0) + dc
    for e in by_name["spur_tone"]:
        amp = _per_rx(e["amplitude_counts"], n_rx, "amplitude_counts")
        spur = np.cos(2.0 * math.pi * e["freq_Hz"] * (t_chirp + t) + e["phase_rad"])  # (F, 1, M, N)
        counts += amp[None, :, None, None] * spur

    # ---------------------------------------------------------------- 8. quantization, clipping
    return np.clip(np.round(counts), 0.0, full).astype(np.uint16)


def save_capture(path: Any, cfg: RadarConfig, counts: np.ndarray) -> None:
    """Write ``counts`` ``(F, RX, M, N)`` as a radaraug HDF5 capture (the public writer)."""
    from radaraug.io import write_capture

    write_capture(path, np.asarray(counts), cfg)


# ---------------------------------------------------------------------------- random effects
RANDOM_RANGES = {
    "spur_tone": "freq_Hz U(0.05, 0.45) fs; amplitude_counts log-U(2, 15) x U(0.7, 1.3) per RX; phase U(0, 2pi)",
    "adc_noise": "rms_counts log-U(3, 10)",
    "rx_gain_phase_mismatch": "RX0: 0 dB, 0 rad (reference); others gain +-U(1, 3) dB, phase +-U(0.3, 1.5) rad",
    "static_clutter": "range_m U(1, min(8, 0.4 max_range)); level_dB U(-95, -75); phase U(0, 2pi)",
    "vibrating_clutter": (
        "range_m U(1, min(6, 0.3 max_range)); level_dB U(-90, -75); displacement_m U(0.1, 1) mm; "
        "vibration_Hz U(2, 0.25 M) x Doppler bin (1/(M T)); phase U(0, 2pi) (tone phase: 0)"
    ),
    "multipath": "extra_range_m U(0.3, 2); level_dB U(-12, -4); phase U(0, 2pi)",
    "interference": "probability U(0.05, 0.3); amplitude_counts log-U(50, 500); duration_s U(5, 30) us",
    "frame_drift": "gain_rms_dB U(0.2, 1.0); dc_rms_counts U(2, 10)",
    "phase_noise": "freq_noise_rms_Hz log-U(50, 500) kHz; corner_Hz log-U(20, 200) kHz",
    "chirp_nonlinearity": "deviation_Hz log-U(0.2, 2) MHz; ripple_Hz U(1.5, 10) x fs/N; phase U(0, 2pi)",
    "moving_target": (
        "speed_m_s +-U(0.3, min(1, 0.3 v_max, 0.4 max_range / (100 frame periods))); range_m U(1, min(6, "
        "0.3 max_range)), plus |speed| x 100 frame periods when approaching (stays > 1 m for 100 frames); "
        "level_dB U(-90, -75); phase 0"
    ),
}
"""Documented ranges of :func:`random_effect` (U = uniform, log-U = log-uniform)."""


def random_effect(name: str, cfg: RadarConfig, rng: np.random.Generator) -> dict[str, Any]:
    """Random parameters for effect ``name`` that make it clearly visible yet realistic.

    See :data:`RANDOM_RANGES`. Path effects (clutter, moving target) are placed 1 m or more away
    so the IF high-pass passes them; multipath, phase noise and chirp non-linearity are visible
    only on a strong path (add a scene point or clutter at about -80 dB re TX).
    """
    n_rx = cfg.num_rx
    fs = cfg.sample_rate_Hz
    two_pi = 2.0 * math.pi

    def u(lo: float, hi: float) -> float:
        return float(rng.uniform(lo, hi))

    def logu(lo: float, hi: float) -> float:
        return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))

    def signed(lo: float, hi: float) -> float:
        return float(rng.choice([-1.0, 1.0]) * rng.uniform(lo, hi))

    far = min(8.0, 0.4 * cfg.max_range_m)
    near = min(6.0, 0.3 * cfg.max_range_m)
    if name == "spur_tone":
        base = logu(2.0, 15.0)
        params: dict[str, Any] = {
            "freq_Hz": u(0.05 * fs, 0.45 * fs),
            "amplitude_counts": [base * u(0.7, 1.3) for _ in range(n_rx)],
            "phase_rad": u(0.0, two_pi),
        }
    elif name == "adc_noise":
        params = {"rms_counts": logu(3.0, 10.0)}
    elif name == "rx_gain_phase_mismatch":
        params = {
            "gain_dB": [0.0] + [signed(1.0, 3.0) for _ in range(n_rx - 1)],
            "phase_rad": [0.0] + [signed(0.3, 1.5) for _ in range(n_rx - 1)],
        }
    elif name == "static_clutter":
        params = {"range_m": u(1.0, far), "level_dB": u(-95.0, -75.0), "phase_rad": u(0.0, two_pi)}
    elif name == "vibrating_clutter":
        doppler_bin = 1.0 / (cfg.num_chirps_per_frame * cfg.chirp_repetition_time_s)
        params = {
            "range_m": u(1.0, near),
            "level_dB": u(-90.0, -75.0),
            "displacement_m": u(0.1e-3, 1.0e-3),
            "vibration_Hz": u(2.0, 0.25 * cfg.num_chirps_per_frame) * doppler_bin,
            "phase_rad": u(0.0, two_pi),
        }
    elif name == "multipath":
        params = {"extra_range_m": u(0.3, 2.0), "level_dB": u(-12.0, -4.0), "phase_rad": u(0.0, two_pi)}
    elif name == "interference":
        params = {
            "probability": u(0.05, 0.3),
            "amplitude_counts": logu(50.0, 500.0),
            "duration_s": u(5e-6, 30e-6),
        }
    elif name == "frame_drift":
        params = {"gain_rms_dB": u(0.2, 1.0), "dc_rms_counts": u(2.0, 10.0)}
    elif name == "phase_noise":
        params = {"freq_noise_rms_Hz": logu(50e3, 500e3), "corner_Hz": logu(20e3, 200e3)}
    elif name == "chirp_nonlinearity":
        params = {
            "deviation_Hz": logu(0.2e6, 2e6),
            "ripple_Hz": u(1.5, 10.0) * fs / cfg.num_samples_per_chirp,
            "phase_rad": u(0.0, two_pi),
        }
    elif name == "moving_target":
        span = 100 * cfg.frame_repetition_time_s
        speed = signed(0.3, min(1.0, 0.3 * cfg.max_velocity_m_s, 0.4 * cfg.max_range_m / span))
        start = u(1.0, near) + (abs(speed) * span if speed < 0 else 0.0)
        params = {"range_m": start, "speed_m_s": speed, "level_dB": u(-90.0, -75.0)}
    else:
        raise ValueError(f"unknown effect {name!r}; known: {', '.join(EFFECT_NAMES)}")
    return {"name": name, **params}


__all__ = [
    "C_LIGHT",
    "EFFECT_NAMES",
    "EFFECT_PARAMS",
    "FILTER_METHODS",
    "K_BOLTZMANN",
    "RANDOM_RANGES",
    "ROLL",
    "T0_K",
    "generate",
    "random_effect",
    "save_capture",
]
