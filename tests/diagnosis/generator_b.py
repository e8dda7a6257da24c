"""Generator B: an office seen by a 60 GHz FMCW radar, written from scratch in NumPy.

A second independent capture generator for the calibration tests. It shares no code (and no
modelling shortcut) with ``radaraug.sim``, ``radaraug.raytrace``, ``radaraug.sensor``,
``radaraug.scene``, ``radaraug.testsets.independent`` or ``tests/diagnosis/numpy_capture.py``; it reads only the
numbers of a :class:`~radaraug.config.RadarConfig`. Its conventions are its own:

* **Room**: an empty office (back wall 4.6 m away, two side walls, a metal cabinet, a desk, a
  ceiling lamp, a door frame), as point scatterers with a radar cross-section (m^2), at real
  3-D positions. The radar sits at the origin looking along +z (x right, y up). Every scatterer
  is seen by every RX over its own bistatic path ``|p - tx| + |p - rx_i|`` (TX and RX phase
  centres from the config), so returns carry their true angle of arrival, and two returns in one
  range bin beat differently in each RX.
* **Radar equation** (not a level relative to the TX): ``P_r = P_t G^2 lambda^2 sigma /
  ((4 pi)^3 R_t^2 R_r^2)``, ``P_t = 4 dBm`` at TX power level 31 (``20 log10(level / 31)`` below),
  antenna gain 6 dBi.
* **IF synthesis** on a time grid ``OVERSAMPLE`` x the ADC rate, per chirp, from the ramp start
  (``t = 0``, RF = ``start_frequency_Hz``, slope from the config) to the last ADC sample; the
  beat of a path of delay ``tau`` is ``cos(2 pi (f_start tau + S tau t - S tau^2 / 2))`` for
  ``t >= tau``, zero before (the echo has not arrived).
* **Voltages**: RX port voltage ``sqrt(2 P R)`` (peak, ``R = 50`` ohm) times the RF/mixer voltage
  gain (22 dB) and any per-RX mismatch; thermal noise at the port, ``k T0 NF (fs_sim / 2) R`` volts^2
  (NF 12 dB), white over the simulated band (so noise above the ADC's Nyquist folds back through
  the anti-alias filter, as in hardware).
* **Filters**: Butterworth IIR filters designed here (analog prototype, pre-warped bilinear
  transform, second-order sections) and run sample by sample from a zero state at the ramp
  start: the IF high-pass (nominal: order 1 at ``config.effective_hp_cutoff_Hz``), then the IF
  gain (``config.if_gain_dB``, volts), then a 2nd-order anti-alias low-pass at
  ``config.effective_aaf_cutoff_Hz``. A strong near-DC input (the TX->RX leakage) therefore shows
  the high-pass's start-up transient.
* **ADC**: every ``OVERSAMPLE``-th sample from ``adc_delay_s`` on; ``counts = v / V_pp * full + dc +
  n_adc`` (``V_pp = 1`` V input range, DC level per RX in counts, white ADC noise 1 count RMS),
  rounded, clipped to ``0 .. full`` (the rails). Output in the library's unit, Infineon SDK floats
  ``2 * counts / full - 1``, layout ``(frames, rx, chirps, samples)``.

Effects (``effects={name: params}``; catalog names, generator B's own parameters):

==========================  ============================================================================
``adc_clipping``            ``adc_range_Vpp``: a smaller ADC input range (nominal 1 V): everything is
                            larger in counts and the strong part hits the rails
``phase_noise``             ``lo_fm_rms_Hz``, ``lo_fm_corner_Hz``: LO frequency noise, an AR(1)
                            (Lorentzian) process along fast time, restarted every ramp (the PLL
                            relocks), common to all RX; a path of delay ``tau`` gets the phase
                            ``2 pi tau nu(t)`` (to first order: ``-A sin(theta) 2 pi tau nu``)
``spur_tone``               ``freq_Hz``, ``amplitude_mV``, ``phase_rad``: a tone at the ADC input at
                            absolute time (``t_abs = frame * T_frame + chirp * PRT + t``), all RX;
                            optional ``unlocked: True``: a source that restarts at a uniformly random
                            phase every chirp (not locked to the chirp timing), the same on all RX
``if_highpass``             ``cutoff_Hz``, ``order``: the high-pass as a Butterworth of that order
``rx_gain_phase_mismatch``  ``gain_dB``, ``phase_deg`` (one per RX): complex gain of each RX's RF
                            front end (signal and thermal noise)
``tx_rx_leakage``           ``coupling_dB`` (power at RX1's port re the TX power), ``length_mm``: direct
                            coupling in the package, an electrical path ``length_mm`` plus the TX-RX
                            antenna spacing ``d_i`` (a few mm; delay ``(length + d_i) / c``),
                            power ``1/d_i^2`` relative to RX1
``interference``            ``probability``, ``power_dBm``, ``duration_us``: another radar's ramp
                            crossing ours in a chirp (probability per chirp): an RF burst whose beat
                            sweeps linearly from ``-1.8 fs`` to ``+1.8 fs`` in ``duration_us``, from
                            broadside (same on all RX), random start and phase; a list of durations
                            is several radars of other chirp slopes (each burst draws one)
``vibrating_clutter``       ``position_m`` (x, y, z), ``rcs_m2``, ``displacement_mm``, ``vibration_Hz``:
                            a scatterer oscillating along its line of sight (a fan), exact phase
``frame_drift``             ``gain_rms_dB``, ``dc_rms_counts``: the IF gain and each RX's DC level
                            redrawn every frame
==========================  ============================================================================

Randomness: ``np.random.default_rng([seed, stream])`` per random stage (thermal, ADC noise,
phase noise, interference, drift, room phases), so adding an effect does not change another
stage's draws.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from radaraug.config import RadarConfig

C0 = 299_792_458.0
KB = 1.380649e-23
T0 = 290.0
OVERSAMPLE = 4
R_PORT = 50.0
RF_GAIN_DB = 22.0
NOISE_FIGURE_DB = 12.0
ANT_GAIN_DBI = 6.0
TX_DBM_MAX = 4.0
V_ADC_PP = 1.0
ADC_NOISE_COUNTS = 1.0
AAF_ORDER = 2
DC_COUNTS = (2010.0, 2080.0, 1985.0, 2040.0)

# name -> required parameters
EFFECTS: dict[str, tuple[str, ...]] = {
    "adc_clipping": ("adc_range_Vpp",),
    "phase_noise": ("lo_fm_rms_Hz", "lo_fm_corner_Hz"),
    "spur_tone": ("freq_Hz", "amplitude_mV", "phase_rad"),
    "if_highpass": ("cutoff_Hz", "order"),
    "rx_gain_phase_mismatch": ("gain_dB", "phase_deg"),
    "tx_rx_leakage": ("coupling_dB", "length_mm"),
    "interference": ("probability", "power_dBm", "duration_us"),
    "vibrating_clutter": ("position_m", "rcs_m2", "displacement_mm", "vibration_Hz"),
    "frame_drift": ("gain_rms_dB", "dc_rms_counts"),
}

OPTIONAL: dict[str, tuple[str, ...]] = {"spur_tone": ("unlocked",)}
"""Parameters an effect may also take (a variant of its physics)."""

_STREAMS = {"room": 1, "thermal": 2, "adc": 3, "phase_noise": 4, "interference": 5, "drift": 6, "spur": 7}

OFFICE: tuple[tuple[tuple[float, float, float], float], ...] = (
    # back wall (plasterboard), a few bright spots
    ((0.0, 0.0, 4.6), 6.0), ((-1.1, 0.3, 4.6), 2.5), ((1.2, -0.4, 4.6), 2.5),
    # side walls
    ((-1.7, 0.0, 2.6), 1.5), ((1.7, 0.2, 3.4), 1.5),
    # metal filing cabinet, desk edge, ceiling lamp, door frame
    ((0.7, -0.3, 2.4), 12.0), ((-0.5, -0.6, 1.9), 0.8), ((0.1, 1.3, 3.2), 0.4), ((-1.6, 0.1, 3.9), 1.0),
)
"""Generator B's office: (position x, y, z in m; RCS in m^2). Nearest return ~2 m."""


def _rng(seed: int, stream: str) -> np.random.Generator:
    return np.random.default_rng([int(seed), _STREAMS[stream]])


def _tx_power_W(cfg: RadarConfig) -> float:
    if cfg.tx_power_level <= 0:
        return 0.0
    return 1e-3 * 10 ** ((TX_DBM_MAX + 20 * math.log10(cfg.tx_power_level / 31)) / 10)


# --------------------------------------------------------------------------- filters
def butterworth_sos(order: int, cutoff_Hz: float, fs: float, kind: str) -> list[tuple[np.ndarray, np.ndarray]]:
    """Digital Butterworth sections ``[(b, a), ...]`` (pre-warped bilinear transform).

    Analog prototype poles ``exp(j pi (2k + n + 1) / (2n))``; a low-pass scales them by the
    pre-warped cutoff ``wa = 2 fs tan(pi fc / fs)``, a high-pass inverts them (``wa / p``) and puts
    its zeros at DC. Each conjugate pair is one biquad, an odd order adds a first-order section;
    each section has unit gain at DC (low-pass) or Nyquist (high-pass).
    """
    if order < 1 or cutoff_Hz <= 0 or cutoff_Hz >= fs / 2:
        raise ValueError(f"bad Butterworth: order {order}, cutoff {cutoff_Hz} Hz at fs {fs} Hz")
    wa = 2 * fs * math.tan(math.pi * cutoff_Hz / fs)
    poles = [complex(math.cos(math.pi * (2 * k + order + 1) / (2 * order)),
                     math.sin(math.pi * (2 * k + order + 1) / (2 * order))) for k in range(order)]
    sp = [wa * p if kind == "low" else wa / p for p in poles]
    zp = [(1 + s / (2 * fs)) / (1 - s / (2 * fs)) for s in sp]
    z0 = -1.0 if kind == "low" else 1.0
    ref = 1.0 if kind == "low" else -1.0  # where each section has unit gain
    sections = []
    used = [False] * order
    for i, z in enumerate(zp):
        if used[i]:
            continue
        used[i] = True
        if abs(z.imag) < 1e-12:
            b = np.array([1.0, -z0, 0.0])
            a = np.array([1.0, -z.real, 0.0])
        else:
            j = min((k for k in range(order) if not used[k]), key=lambda k: abs(zp[k] - z.conjugate()))
            used[j] = True
            b = np.array([1.0, -2 * z0, 1.0])
            a = np.array([1.0, -2 * z.real, abs(z) ** 2])
        g = abs(np.polyval(a[::-1], 1 / ref) / np.polyval(b[::-1], 1 / ref))
        sections.append((b * g, a))
    return sections


def _run_sos(x: np.ndarray, sections: Sequence[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """Filter along the last axis, sample by sample, from a zero state (transposed direct form II)."""
    y = np.array(x, dtype=np.float64, copy=True)
    for b, a in sections:
        z1 = np.zeros(y.shape[:-1])
        z2 = np.zeros(y.shape[:-1])
        for n in range(y.shape[-1]):
            xn = y[..., n]
            yn = b[0] * xn + z1
            z1 = b[1] * xn - a[1] * yn + z2
            z2 = b[2] * xn - a[2] * yn
            y[..., n] = yn
    return y


def sos_power_response(sections: Sequence[tuple[np.ndarray, np.ndarray]], f: np.ndarray, fs: float) -> np.ndarray:
    """``|H(exp(j 2 pi f / fs))|^2`` of the sections."""
    z = np.exp(-2j * np.pi * np.asarray(f, dtype=np.float64) / fs)
    h = np.ones_like(z)
    for b, a in sections:
        h = h * (b[0] + b[1] * z + b[2] * z * z) / (a[0] + a[1] * z + a[2] * z * z)
    return np.abs(h) ** 2


# --------------------------------------------------------------------------- the capture
def _check(effects: Mapping[str, Mapping[str, Any]]) -> None:
    for name, params in effects.items():
        if name not in EFFECTS:
            raise ValueError(f"generator B has no effect {name!r}; known: {', '.join(EFFECTS)}")
        missing = set(EFFECTS[name]) - set(params)
        unknown = set(params) - set(EFFECTS[name]) - set(OPTIONAL.get(name, ()))
        if missing or unknown:
            raise ValueError(f"effect {name!r}: missing {sorted(missing)}, unknown {sorted(unknown)}")


def _per_rx(v: Any, n: int) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64).reshape(-1)
    return np.full(n, float(a[0])) if a.size == 1 else a[:n]


def make_capture(
    config: RadarConfig,
    effects: Mapping[str, Mapping[str, Any]] | None = None,
    seed: int = 0,
    frames: int = 40,
    *,
    scatterers: Sequence[tuple[tuple[float, float, float], float]] | None = None,
    thermal_noise: bool = True,
    adc_noise_counts: float = ADC_NOISE_COUNTS,
) -> np.ndarray:
    """Raw frames ``(frames, rx, chirps, samples)`` in SDK floats of generator B's office.

    Args:
        config: radar configuration (only its numbers are read).
        effects: ``{effect name: {parameter: value}}`` (module docstring); none by default.
        seed: seed of every random stage.
        frames: number of frames.
        scatterers: ``[((x, y, z), rcs_m2), ...]`` instead of the office (``[]``: no room).
        thermal_noise: add the receiver's thermal noise.
        adc_noise_counts: RMS of the white ADC noise (counts).
    """
    effects = dict(effects or {})
    _check(effects)
    cfg = config
    F, R, M, N = int(frames), cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp
    fs = cfg.sample_rate_Hz
    fsim = OVERSAMPLE * fs
    lam = cfg.wavelength_m
    S = cfg.slope_Hz_per_s
    f_start = cfg.start_frequency_Hz
    full = float(cfg.adc_full_scale_counts)
    # Simulation grid: ADC sample n is grid point j0 + OVERSAMPLE n; the grid starts at (or just
    # before) the ramp start.
    j0 = int(math.ceil(cfg.adc_delay_s * fsim))
    L = j0 + OVERSAMPLE * N
    t = cfg.adc_delay_s + (np.arange(L) - j0) / fsim  # time since the ramp start
    t_chirp = (np.arange(F)[:, None] * cfg.frame_repetition_time_s
               + np.arange(M)[None, :] * cfg.chirp_repetition_time_s)  # (F, M) ramp starts

    tx = np.asarray(cfg.tx_position_m, dtype=np.float64)
    rx = np.asarray(cfg.rx_positions, dtype=np.float64)  # (R, 3)
    p_t = _tx_power_W(cfg)
    g_ant = 10 ** (ANT_GAIN_DBI / 10)
    g_rf = 10 ** (RF_GAIN_DB / 20)
    rx_gain = np.full(R, g_rf, dtype=np.complex128)
    if "rx_gain_phase_mismatch" in effects:
        e = effects["rx_gain_phase_mismatch"]
        rx_gain = rx_gain * 10 ** (_per_rx(e["gain_dB"], R) / 20) * np.exp(1j * np.deg2rad(_per_rx(e["phase_deg"], R)))

    def port_amplitude(p_r: float | np.ndarray) -> Any:
        return np.sqrt(2 * np.asarray(p_r) * R_PORT)

    def beat(tau: np.ndarray, tt: np.ndarray) -> np.ndarray:
        """Beat phase (rad) of delay ``tau`` at ramp time ``tt`` (broadcast), reduced mod 2 pi."""
        cyc = f_start * tau + S * tau * tt - 0.5 * S * tau * tau
        return 2 * np.pi * np.mod(cyc, 1.0)

    # ------------------------------------------------------------ static paths (same every chirp)
    room = list(OFFICE if scatterers is None else scatterers)
    static = np.zeros((R, L))
    pn_weight = np.zeros((R, L))  # sum_p A_p tau_p sin(theta_p): what LO frequency noise multiplies
    room_phase = _rng(seed, "room").uniform(0, 2 * np.pi, len(room))  # each surface's own phase
    for (pos, rcs), ph0 in zip(room, room_phase):
        pos = np.asarray(pos, dtype=np.float64)
        r_t = float(np.linalg.norm(pos - tx))
        r_r = np.linalg.norm(pos[None] - rx, axis=1)  # (R,)
        p_r = p_t * g_ant * g_ant * lam**2 * rcs / ((4 * np.pi) ** 3 * r_t**2 * r_r**2)
        tau = (r_t + r_r) / C0  # (R,)
        theta = beat(tau[:, None], t[None, :]) + ph0
        amp = port_amplitude(p_r)[:, None] * np.abs(rx_gain)[:, None]
        theta = theta + np.angle(rx_gain)[:, None]
        live = t[None, :] >= tau[:, None]
        static += np.where(live, amp * np.cos(theta), 0.0)
        pn_weight += np.where(live, amp * tau[:, None] * np.sin(theta), 0.0)
    if "tx_rx_leakage" in effects:
        d = np.linalg.norm(rx - tx[None], axis=1)  # (R,) TX-RX spacing, a few mm
        p_l = p_t * 10 ** (effects["tx_rx_leakage"]["coupling_dB"] / 10) * (d[0] / d) ** 2
        tau = (d + effects["tx_rx_leakage"]["length_mm"] * 1e-3) / C0
        theta = beat(tau[:, None], t[None, :]) + np.angle(rx_gain)[:, None]
        amp = port_amplitude(p_l)[:, None] * np.abs(rx_gain)[:, None]
        static += np.where(t[None, :] >= tau[:, None], amp * np.cos(theta), 0.0)
        pn_weight += amp * tau[:, None] * np.sin(theta)

    x = np.broadcast_to(static[None, :, None, :], (F, R, M, L)).copy()

    # ------------------------------------------------------------ phase noise (per chirp, all RX)
    if "phase_noise" in effects:
        e = effects["phase_noise"]
        rho = math.exp(-2 * math.pi * e["lo_fm_corner_Hz"] / fsim)
        rng = _rng(seed, "phase_noise")
        w = rng.standard_normal((F, M, L))
        nu = np.empty((F, M, L))
        nu[..., 0] = w[..., 0]  # stationary start
        k = math.sqrt(1 - rho * rho)
        for n in range(1, L):
            nu[..., n] = rho * nu[..., n - 1] + k * w[..., n]
        nu *= e["lo_fm_rms_Hz"]
        # cos(theta + 2 pi tau nu) ~ cos(theta) - 2 pi tau nu sin(theta): nu is tiny next to 1/tau.
        x -= 2 * np.pi * nu[:, None] * pn_weight[None, :, None, :]

    # ------------------------------------------------------------ vibrating scatterer (exact)
    if "vibrating_clutter" in effects:
        e = effects["vibrating_clutter"]
        pos = np.asarray(e["position_m"], dtype=np.float64)
        r_t = float(np.linalg.norm(pos - tx))
        r_r = np.linalg.norm(pos[None] - rx, axis=1)
        p_r = p_t * g_ant * g_ant * lam**2 * e["rcs_m2"] / ((4 * np.pi) ** 3 * r_t**2 * r_r**2)
        t_abs = t_chirp[:, :, None] + t[None, None, :]  # (F, M, L)
        dr = e["displacement_mm"] * 1e-3 * np.sin(2 * np.pi * e["vibration_Hz"] * t_abs)
        for i in range(R):
            tau = (r_t + r_r[i] + 2 * dr) / C0
            theta = beat(tau, t[None, None, :]) + np.angle(rx_gain[i])
            amp = port_amplitude(p_r[i]) * abs(rx_gain[i])
            x[:, i] += np.where(t[None, None, :] >= tau, amp * np.cos(theta), 0.0)

    # ------------------------------------------------------------ interference (RF bursts)
    if "interference" in effects:
        e = effects["interference"]
        rng = _rng(seed, "interference")
        hit = rng.random((F, M)) < e["probability"]
        durs = np.atleast_1d(np.asarray(e["duration_us"], dtype=float)) * 1e-6  # several: several chirp slopes
        f_max = 1.8 * fs
        amp = port_amplitude(1e-3 * 10 ** (e["power_dBm"] / 10)) * g_rf
        for f_i, m_i in zip(*np.nonzero(hit)):
            dur = durs[rng.integers(len(durs))] if len(durs) > 1 else durs[0]
            t0 = rng.uniform(t[0], t[-1] - 0.25 * dur)
            u = t - t0
            inside = (u >= 0) & (u <= dur)
            ph = 2 * np.pi * (-f_max * u + f_max / dur * u * u) + rng.uniform(0, 2 * np.pi)
            x[f_i, :, m_i] += np.where(inside, amp * np.cos(ph), 0.0)[None, :]

    # ------------------------------------------------------------ thermal noise at the RX port
    if thermal_noise:
        sigma = math.sqrt(KB * T0 * 10 ** (NOISE_FIGURE_DB / 10) * (fsim / 2) * R_PORT)
        x += _rng(seed, "thermal").standard_normal(x.shape) * (sigma * np.abs(rx_gain))[None, :, None, None]

    # ------------------------------------------------------------ IF chain: HP, IF gain, AAF
    hp = effects.get("if_highpass", {"cutoff_Hz": cfg.effective_hp_cutoff_Hz, "order": 1})
    chain = butterworth_sos(int(hp["order"]), float(hp["cutoff_Hz"]), fsim, "high")
    chain += butterworth_sos(AAF_ORDER, cfg.effective_aaf_cutoff_Hz, fsim, "low")
    g_if = 10 ** (cfg.if_gain_dB / 20)
    v = _run_sos(x, chain)[..., j0::OVERSAMPLE][..., :N] * g_if  # (F, R, M, N) volts at the ADC
    del x
    t_adc = t[j0::OVERSAMPLE][:N]

    # ------------------------------------------------------------ drift, spur, ADC
    v_pp = effects.get("adc_clipping", {}).get("adc_range_Vpp", V_ADC_PP)
    dc = np.broadcast_to(np.resize(np.asarray(DC_COUNTS), R)[None, :, None, None], (F, R, 1, 1)).copy()
    if "frame_drift" in effects:
        e = effects["frame_drift"]
        rng = _rng(seed, "drift")
        v = v * 10 ** (rng.normal(0, e["gain_rms_dB"], (F, 1, 1, 1)) / 20)
        dc = dc + rng.normal(0, e["dc_rms_counts"], (F, R, 1, 1))
    if "spur_tone" in effects:
        e = effects["spur_tone"]
        t_abs = t_chirp[:, None, :, None] + t_adc[None, None, None, :]
        phase = 2 * np.pi * np.mod(e["freq_Hz"] * t_abs, 1.0) + e["phase_rad"]
        if e.get("unlocked", False):
            phase = phase + _rng(seed, "spur").uniform(0, 2 * np.pi, (F, 1, M, 1))
        v = v + e["amplitude_mV"] * 1e-3 * np.cos(phase)
    counts = v / v_pp * full + dc
    if adc_noise_counts > 0:
        counts = counts + _rng(seed, "adc").normal(0, adc_noise_counts, counts.shape)
    counts = np.clip(np.round(counts), 0, full)
    return 2 * counts / full - 1


# --------------------------------------------------------------------------- closed forms
def thermal_psd_float(config: RadarConfig, f: np.ndarray, hp: tuple[float, int] | None = None,
                      aliases: int = 2) -> np.ndarray:
    """One-sided PSD (SDK float^2 / Hz) of the thermal noise at the ADC, from the analog responses.

    ``k T0 NF R`` (V^2/Hz at the port) times ``(g_rf g_if 2 / V_pp)^2`` times the analog Butterworth
    high-pass and anti-alias power responses, summed over the aliases the ADC folds in (``f``,
    ``fs - f``, ``fs + f``, ...) up to the simulation's Nyquist (``OVERSAMPLE fs / 2``).
    """
    fs = config.sample_rate_Hz
    fc, n = hp if hp is not None else (config.effective_hp_cutoff_Hz, 1)
    fl = config.effective_aaf_cutoff_Hz
    f = np.asarray(f, dtype=np.float64)
    total = np.zeros_like(f)
    for k in range(0, aliases + 1):
        for g in ((k * fs + f), (k * fs - f)) if k else (f,):
            g = np.abs(g)
            ok = g < OVERSAMPLE * fs / 2
            x = (g / fc) ** (2 * n)
            total += np.where(ok, x / (1 + x) / (1 + (g / fl) ** (2 * AAF_ORDER)), 0.0)
    scale = (10 ** (RF_GAIN_DB / 20) * 10 ** (config.if_gain_dB / 20) * 2 / V_ADC_PP) ** 2
    return KB * T0 * 10 ** (NOISE_FIGURE_DB / 10) * R_PORT * scale * total


# --------------------------------------------------------------------------- the test cases
CFG_A = RadarConfig.bgt60tr13c()
"""The paper's BGT60TR13C setting (256 samples, 64 chirps, IF gain 33 dB)."""
CFG_A_HIGH = RadarConfig.bgt60tr13c(if_gain_dB=43)
"""The same at a 10 dB higher IF gain."""
CFG_B = RadarConfig.bgt60tr13c(num_samples_per_chirp=128, num_chirps_per_frame=32,
                               chirp_repetition_time_s=300e-6, if_gain_dB=40)
"""Another setting: 128 samples, 32 chirps at 300 us, IF gain 40 dB."""

_PARAMS: dict[str, dict[str, Any]] = {
    "adc_clipping": {"adc_range_Vpp": 0.12},
    "phase_noise": {"lo_fm_rms_Hz": 400e3, "lo_fm_corner_Hz": 100e3},
    "spur_tone": {"freq_Hz": 187_300.0, "amplitude_mV": 1.5, "phase_rad": 0.4},
    "if_highpass": {"cutoff_Hz": 150e3, "order": 2},
    "rx_gain_phase_mismatch": {"gain_dB": [0.0, 1.8, -2.2], "phase_deg": [0.0, 35.0, -60.0]},
    "tx_rx_leakage": {"coupling_dB": -60.0, "length_mm": 30.0},
    "interference": {"probability": 0.08, "power_dBm": -65.0, "duration_us": 20.0},
    "vibrating_clutter": {"position_m": (0.4, 0.2, 2.9), "rcs_m2": 2.0, "displacement_mm": 0.3,
                          "vibration_Hz": 420.0},
    "frame_drift": {"gain_rms_dB": 0.6, "dc_rms_counts": 4.0},
}

_CFGS = {"A": CFG_A, "Ahi": CFG_A_HIGH, "B": CFG_B}


WEAK_ROOM: tuple[tuple[tuple[float, float, float], float], ...] = (
    ((0.0, 0.0, 4.6), 0.05), ((1.2, -0.4, 5.5), 0.05),
)
"""A bare room: two faint returns 4.6-5.5 m away, ~15-18 dB over the per-chirp floor."""

_VARIANTS: dict[str, tuple[str, dict[str, Any]]] = {
    "spur_unlocked": ("spur_tone", _PARAMS["spur_tone"] | {"unlocked": True}),
    "interference_slopes": ("interference", _PARAMS["interference"] | {"duration_us": [5.0, 20.0, 60.0]}),
    "vibration_band": ("vibrating_clutter", _PARAMS["vibrating_clutter"] | {"displacement_mm": 6.0,
                                                                            "vibration_Hz": 25.0}),
    "phase_noise_weak_carrier": ("phase_noise", {"lo_fm_rms_Hz": 1.5e6, "lo_fm_corner_Hz": 100e3}),
    # 18 dB over the usual case: its high-pass start-up transient clips the first samples of every chirp
    "leakage_clipping": ("tx_rx_leakage", _PARAMS["tx_rx_leakage"] | {"coupling_dB": -42.0}),
}
"""Physical variants of an effect (issue: each effect's signature wide enough for the forms it takes):
case name -> (the effect's catalog name, its parameters)."""

_VARIANT_ROOMS = {"phase_noise_weak_carrier": WEAK_ROOM}
"""Variants that need another room than :data:`OFFICE` (a skirt under the floor of every cell)."""


class Case(NamedTuple):
    """One row of the table: what :func:`make_capture` is called with and what must be named."""

    name: str
    config: RadarConfig
    effects: dict[str, dict[str, Any]]
    expected: tuple[str, ...]
    scatterers: tuple[tuple[tuple[float, float, float], float], ...] | None = None

    def capture(self, seed: int, frames: int = 40) -> np.ndarray:
        """The case's raw frames at ``seed``."""
        return make_capture(self.config, self.effects, seed=seed, frames=frames, scatterers=self.scatterers)


def _case(name: str, cfg_key: str, names: Sequence[str]) -> Case:
    effects = dict(_VARIANTS[n] if n in _VARIANTS else (n, _PARAMS[n]) for n in names)
    room = next((_VARIANT_ROOMS[n] for n in names if n in _VARIANT_ROOMS), None)
    return Case(f"{name}@{cfg_key}", _CFGS[cfg_key], {n: dict(p) for n, p in effects.items()}, tuple(effects), room)


CASES: list[Case] = [
    _case("control", "A", ()),
    _case("control", "Ahi", ()),
    _case("control", "B", ()),
    *[_case(n, k, (n,)) for n in _PARAMS for k in ("A", "Ahi", "B")],
    _case("spur+vibration", "A", ("spur_tone", "vibrating_clutter")),
    _case("phase_noise+interference", "A", ("phase_noise", "interference")),
    _case("mismatch+leakage", "B", ("rx_gain_phase_mismatch", "tx_rx_leakage")),
    _case("highpass+drift", "Ahi", ("if_highpass", "frame_drift")),
    _case("interference+vibration", "B", ("interference", "vibrating_clutter")),
    _case("clipping+spur", "A", ("adc_clipping", "spur_tone")),
    *[_case(v, k, (v,)) for v in _VARIANTS for k in ("A", "Ahi", "B")],
]
"""A :class:`Case` per row: a control per config, every effect alone at three settings (the
paper's config at IF gain 33 and 43 dB, and 128 samples x 32 chirps at 40 dB), six pairs, and each
physical variant (:data:`_VARIANTS`) at the three settings."""


__all__ = ["CASES", "CFG_A", "Case", "CFG_A_HIGH", "CFG_B", "EFFECTS", "OFFICE", "butterworth_sos", "make_capture",
           "sos_power_response", "thermal_psd_float", "WEAK_ROOM"]
