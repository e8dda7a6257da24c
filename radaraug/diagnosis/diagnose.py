"""`radaraug diagnose`: twin vs capture, the effect search, the report and the fitted twin profile.

:func:`diagnose` simulates the capture's scene (or estimates its static scene), runs the search and
locates what is left unexplained; :func:`write_report` writes ``report.json``, ``summary.md``, the
figures and ``profile.json``. See ``docs/diagnosis.md``.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.diagnosis.base_bounds import check_base
from radaraug.diagnosis.catalog import (
    BASE_STAGES,
    CATALOG_NAMES,
    Chain,
    _as_list,
    find,
    require,
    with_effect,
)
from radaraug.diagnosis.declip import declipped_mean_chirp
from radaraug.diagnosis.room import ROOM_PRIORS
from radaraug.diagnosis.search import Search, SearchResult, SearchSettings
from radaraug.diagnosis.twin_source import STATIC_STAGES, TwinSource
from radaraug.diagnosis.views import VIEW_UNITS, Views, _db
from radaraug.errors import CalibrationError
from radaraug.files import atomic_write_json, atomic_write_text
from radaraug.sensor.profile import TwinProfile, as_profile
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.units import DB_CONVENTION, FLOAT_CONVENTION

MIN_FRAMES = 4
UNEXPLAINED_DB = 6.0
"""A frame-averaged RD cell is unexplained when capture and twin differ by more than this (and by
more than 4 robust standard deviations of the residual map)."""


@dataclass
class Diagnosis:
    """Everything :func:`diagnose` found (see :func:`write_report` for the files)."""

    capture: str
    scene: str | None
    mode: str
    config: RadarConfig
    result: SearchResult
    unexplained: list[dict[str, Any]]
    profile: TwinProfile
    frames: dict[str, int]
    runtime_s: float
    capture_views: Views
    evidence: dict[str, Any] = field(default_factory=dict)
    """Per effect with a detector, its :class:`~radaraug.diagnosis.evidence.Evidence` (empty when
    the signatures were not read)."""
    refitted_declared: list[dict[str, Any]] = field(default_factory=list)
    """Declared stages the capture shows at other parameters, refitted in the profile: ``effect``,
    ``params_before``, ``params_after``, ``measured``."""

    @property
    def named_effects(self) -> list[str]:
        """Every effect the diagnosis names: the search's steps, then declared stages refitted at other parameters."""
        return [s["effect"] for s in self.result.steps] + [r["effect"] for r in self.refitted_declared]

    @property
    def base_check(self) -> list[dict[str, Any]]:
        """The base refit against its physical bounds (:func:`~radaraug.diagnosis.base_bounds.check_base`)."""
        return check_base(self.result.chain_before, self.result.chain_after, self.unexplained)

    def report(self) -> dict[str, Any]:
        """The ``report.json`` content."""
        r = self.result
        units = {"overall": VIEW_UNITS["overall"], "views": "dB (see docs/diagnosis.md for each view's error)"}
        return {
            "capture": self.capture,
            "scene": self.scene,
            "mode": self.mode,
            "mode_explanation": _MODE_TEXT[self.mode],
            "config": self.config.to_dict(),
            "frames": self.frames,
            "error_before": {**r.before.as_dict(), "units": units},
            "error_base_refit": {**r.base.as_dict(), "units": units},
            "error_after": {**r.after.as_dict(), "units": units},
            "base_refit": {"params": _base_params(r.chain_base), "params_before": _base_params(r.chain_before),
                           "params_final": _base_params(r.chain_after)},
            "room": {"fitted": sorted(r.room_after), "params_before": r.room_before, "params": r.room_base,
                     "params_final": r.room_after, "note": _room_note(self.mode, r.room_after)},
            "steps": [{k: v for k, v in s.items() if k not in ("views_before", "views_after")} | {
                "views_before": s["views_before"], "views_after": s["views_after"]} for s in r.steps],
            "candidates_tried": r.tried,
            "signatures": [e.as_dict() for e in self.evidence.values()],
            "verdict": verdicts(self),
            "unexplained": self.unexplained,
            "base_check": self.base_check,
            "refitted_declared": self.refitted_declared,
            "catalog": list(CATALOG_NAMES),
            "evaluations": r.evaluations,
            "runtime_s": round(self.runtime_s, 2),
            "db_convention": DB_CONVENTION,
            "units": FLOAT_CONVENTION,
        }


_MODE_TEXT = {
    "scene": "the capture's scene was simulated (room traced with the capture's radar config)",
    "estimated": "no scene given: the static scene was estimated from the capture (its mean chirp over the fitting "
                 "frames), so static stages (TX->RX leakage, room clutter, multipath) are taken as measured and "
                 "only what varies was diagnosed",
}


def _room_note(mode: str, room: dict[str, float]) -> str:
    if room:
        return "room parameters fitted with the base (RayTracer options; the profile's room section)"
    if mode == "scene":
        return "the scene's room has no diffuse scattering paths: no room parameter to fit"
    return "no scene: the room is part of the estimated static scene, no room parameter is fitted"


def _base_params(chain: Chain) -> dict[str, Any]:
    return {name: e["params"] for name in BASE_STAGES if (e := find(chain, name)) is not None}


def _read_capture(capture: Any, max_frames: int) -> tuple[str, RadarConfig, torch.Tensor]:
    from radaraug.io import open_capture

    if isinstance(capture, (str, os.PathLike)):
        with open_capture(capture) as reader:
            return _read_capture(reader, max_frames)
    n = min(capture.num_frames, int(max_frames))
    if n < MIN_FRAMES:
        raise CalibrationError(f"{capture.path}: {capture.num_frames} frames; diagnosing needs at least {MIN_FRAMES}")
    return str(capture.path), capture.config, capture.read(0, n).to(torch.float64)


def _source(config: RadarConfig, scene: Any, fit: torch.Tensor, sim_frames: int,
            rx: FMCWReceiver, tracer_options: dict[str, Any] | None) -> tuple[TwinSource, Chain, str | None]:
    chain = rx.to_dict()["effects"]
    if scene is None:
        chain = [e for e in chain if e["name"] not in STATIC_STAGES]
        return TwinSource(config, mean_chirp=declipped_mean_chirp(fit), tx_power_dBm=rx.tx_power_dBm,
                          front_end_gain_dB=rx.front_end_gain_dB), chain, None
    from radaraug.scene.scene import Scene
    from radaraug.sim.twin import DigitalTwin

    sc = Scene.load(scene)
    twin = DigitalTwin(sc, config=config, tracer_options=tracer_options, dtype=torch.float64)
    tracer = twin.tracer
    # Specular and diffuse parts apart: the search scales the diffuse one (the room's diffuse gain).
    specular, diffuse = tracer.static_paths("specular"), tracer.static_paths("diffuse")
    moving = None
    if sc.people:
        moving = twin.frame_paths(sc.people, twin.frame_times(range(sim_frames * 2)))
    name = scene if isinstance(scene, str) else str(getattr(sc, "name", "scene"))
    return TwinSource(config, static_paths=specular, diffuse_paths=diffuse, diffuse_gain_dB=tracer.diffuse_gain_dB,
                      moving=moving, tx_power_dBm=rx.tx_power_dBm,
                      front_end_gain_dB=rx.front_end_gain_dB), chain, str(name)


def locate_unexplained(capture: Views, twin: Views, config: RadarConfig, limit: int = 10) -> list[dict[str, Any]]:
    """Residual no effect explains, located by range (m) and Doppler (m/s).

    Clusters of frame-averaged RD cells where capture and twin differ by more than :data:`UNEXPLAINED_DB`
    (and 4 robust sigmas), plus runs of range bins where the noise floor is off by more than 3 dB.
    """
    ex = _db(capture.stats.power.mean(dim=0)) - _db(twin.stats.power.mean(dim=0))  # (range, doppler)
    med = ex.median()
    sigma = 1.4826 * (ex - med).abs().median()
    thr = max(UNEXPLAINED_DB, 4 * float(sigma))
    rng = config.range_axis_m()
    vel = config.velocity_axis_m_s()
    items: list[dict[str, Any]] = []
    for sign in (1, -1):
        mask = (sign * (ex - med)) > thr
        for cells in _clusters(mask):
            vals = torch.tensor([float(ex[r, d]) for r, d in cells])
            k = int((sign * vals).argmax())
            r, d = cells[k]
            items.append({
                "view": "rd_map",
                "kind": "excess" if sign > 0 else "deficit",
                "range_m": round(rng[r], 3),
                "velocity_m_s": round(vel[d], 3),
                "range_span_m": [round(rng[min(c[0] for c in cells)], 3), round(rng[max(c[0] for c in cells)], 3)],
                "velocity_span_m_s": [round(vel[min(c[1] for c in cells)], 3), round(vel[max(c[1] for c in cells)], 3)],
                "size_dB": round(float(vals[k]), 2),
                "cells": len(cells),
            })
    floor_res = capture["noise_floor"] - twin["noise_floor"]
    run: list[int] = []
    for k in range(floor_res.numel() + 1):
        off = k < floor_res.numel() and abs(float(floor_res[k])) > 3.0
        if off:
            run.append(k)
        elif run:
            worst = max(run, key=lambda i: abs(float(floor_res[i])))
            items.append({"view": "noise_floor", "kind": "excess" if floor_res[worst] > 0 else "deficit",
                          "range_m": round(rng[worst], 3), "velocity_m_s": None,
                          "range_span_m": [round(rng[run[0]], 3), round(rng[run[-1]], 3)],
                          "size_dB": round(float(floor_res[worst]), 2), "cells": len(run)})
            run = []
    items.sort(key=lambda i: -abs(i["size_dB"]))
    return items[:limit]


# Which catalog effects could make an unexplained item of each kind (view, where in Doppler).
_NEAREST: dict[str, tuple[str, ...]] = {
    "rd_map moving": ("spur_tone", "vibrating_clutter", "interference", "phase_noise", "frame_drift"),
    "rd_map static": ("tx_rx_leakage", "rx_gain_phase_mismatch", "adc_clipping"),
    "noise_floor": ("if_highpass", "phase_noise", "interference", "adc_clipping"),
}


def closest_effects(items: list[dict[str, Any]], evidence: dict[str, Any] | None) -> list[dict[str, Any]]:
    """``items`` with ``closest``: the catalog effects that could make each, and the measurement that ruled them out.

    Each candidate comes with its signature's verdict (``present`` and the detector's one-line
    measurement), so a user sees why nothing was named.
    """
    out = []
    for it in items:
        if it["view"] == "noise_floor":
            key = "noise_floor"
        else:
            key = "rd_map static" if abs(it.get("velocity_m_s") or 0.0) < 1e-9 else "rd_map moving"
        closest = []
        for name in _NEAREST[key]:
            ev = (evidence or {}).get(name)
            closest.append({"effect": name, "present": None if ev is None else bool(ev.present),
                            "measured": "no signature run" if ev is None else ev.reason})
        out.append({**it, "closest": closest})
    return out


def _clusters(mask: torch.Tensor) -> list[list[tuple[int, int]]]:
    """4-connected clusters of True cells (Doppler wraps around)."""
    todo = {tuple(x) for x in mask.nonzero().tolist()}
    M = mask.shape[1]
    out = []
    while todo:
        seed = todo.pop()
        stack, cells = [seed], [seed]
        while stack:
            r, d = stack.pop()
            for nb in ((r + 1, d), (r - 1, d), (r, (d + 1) % M), (r, (d - 1) % M)):
                if nb in todo:
                    todo.remove(nb)
                    stack.append(nb)
                    cells.append(nb)
        out.append(cells)
    out.sort(key=len, reverse=True)
    return out[:50]


def profile_chain(result_chain: Chain, default_chain: Chain, mode: str) -> Chain:
    """The fitted chain for training.

    In estimated mode the static stages the loop did not diagnose come back from the default chain.
    """
    if mode == "scene":
        return result_chain
    out = list(result_chain)
    for e in default_chain:
        if e["name"] in STATIC_STAGES and find(out, e["name"]) is None:
            out = with_effect(out, e["name"], e["params"])
    return out


def diagnose(
    capture: Any,
    *,
    scene: Any = None,
    max_frames: int = 100,
    settings: SearchSettings | None = None,
    start_profile: Any = None,
    tracer_options: dict[str, Any] | None = None,
    progress: bool = False,
) -> Diagnosis:
    """Compare a capture with the twin, search the effect catalog, fit a twin profile.

    Args:
        capture: a capture path (radaraug HDF5 or Infineon recording folder) or an open reader.
        scene: the capture's scene (a :class:`~radaraug.scene.Scene`, a scene file or a built-in
            name); ``None`` estimates the static scene from the capture.
        max_frames: frames read (the first half fits, the second half scores).
        settings: search knobs (:class:`SearchSettings`).
        start_profile: start from this twin profile instead of the default chain (and, in scene
            mode, from its room section's diffuse gain).
        tracer_options: the room trace's options in scene mode (``diffuse_gain_dB`` there is the
            start of the fitted diffuse gain unless ``start_profile`` has one).
        progress: print one line per decision.

    Returns:
        A :class:`Diagnosis`; :func:`write_report` writes it.

    Raises:
        CalibrationError: fewer than 4 frames, or a profile that does not fit the capture.
    """
    t0 = time.perf_counter()
    path, config, frames = _read_capture(capture, max_frames)
    settings = settings or SearchSettings()
    half = frames.shape[0] // 2
    fit, held = frames[:half], frames[half:]
    start = as_profile(start_profile)
    receiver = start.receiver(config) if start is not None else FMCWReceiver(config)
    default_chain = receiver.to_dict()["effects"]
    source, chain, scene_name = _source(config, scene, fit, settings.sim_frames, receiver, tracer_options)
    say = (lambda s: print(f"diagnose: {s}", flush=True)) if progress else None
    search = Search(source, fit, held, settings, progress=say)
    room: dict[str, float] = {}
    if start is not None:
        # The start profile's room values where this scene has them (clipped to the prior).
        room = {k: min(max(v, ROOM_PRIORS[k].lo), ROOM_PRIORS[k].hi) for k, v in start.room.items()
                if k in source.room_params}
    evidence: dict[str, Any] = {}
    if settings.use_signatures:
        from radaraug.diagnosis.evidence import assess, declared_signatures
        from radaraug.diagnosis.signatures import detect_all

        # Identifiability first: what the capture's raw frames show, against what the declared
        # chain makes, before anything is fitted.
        declared = declared_signatures(source, chain, int(frames.shape[0]), seed=settings.seed * 7919 + 3)
        evidence = assess(detect_all(frames, config), declared, config.num_rx)
    result = search.run(chain, room=room, evidence=evidence or None)
    unexplained = closest_effects(locate_unexplained(search.cap_held, result.after.twin, config), evidence)
    runtime = time.perf_counter() - t0
    full_chain = profile_chain(result.chain_after, default_chain, source.mode)
    refitted: list[dict[str, Any]] = []
    if source.mode == "estimated" and any(st["effect"] == "tx_rx_leakage" for st in result.steps):
        full_chain = _measured_leakage(full_chain, evidence["tx_rx_leakage"], config.num_rx)
    elif source.mode == "estimated" and _declared_elsewhere(evidence.get("tx_rx_leakage")):
        # Declared, but at other parameters: the profile takes the measured level, and the report says so.
        moved = _measured_leakage(full_chain, evidence["tx_rx_leakage"], config.num_rx)
        refitted.append({"effect": "tx_rx_leakage",
                         "params_before": {"coupling_dB": (find(full_chain, "tx_rx_leakage") or {}).get(
                             "params", {}).get("coupling_dB")},
                         "params_after": {"coupling_dB": require(moved, "tx_rx_leakage")["params"]["coupling_dB"]},
                         "measured": evidence["tx_rx_leakage"].reason})
        full_chain = moved
    rx_dict = {**receiver.to_dict(), "effects": full_chain}
    # The room parameters fitted (scene mode, a room with diffuse paths); what the loop could not
    # see (estimated mode, no diffuse paths) is kept from a start profile, like the static stages.
    fitted_room = {**(start.room if start is not None else {}), **result.room_after}
    profile = TwinProfile(rx_dict, {
        "capture": Path(path).name,
        "scene": scene_name,
        "mode": source.mode,
        "config": config.to_dict(),
        "error_before_dB": round(result.before.overall, 4),
        "error_after_dB": round(result.after.overall, 4),
        "effects_added": [s["effect"] for s in result.steps],
        "room_fitted": sorted(result.room_after),
    }, room=fitted_room)
    return Diagnosis(path, scene_name, source.mode, config, result, unexplained, profile,
                     {"read": int(frames.shape[0]), "fit": int(half), "held_out": int(frames.shape[0] - half),
                      "simulated_per_evaluation": search.n_fit}, runtime, search.cap_held, evidence=evidence,
                     refitted_declared=refitted)


REFIT_DECLARED_DB = 3.0
"""A declared stage the capture shows this far (dB) from its declaration, on some RX, is refitted."""


def _declared_elsewhere(ev: Any) -> bool:
    """The leakage detector called the leakage declared, but it stands :data:`REFIT_DECLARED_DB` or more from it."""
    if ev is None or ev.present or not ev.capture.params.get("within_declared"):
        return False
    return abs(float(ev.capture.params["excess_dB"])) >= REFIT_DECLARED_DB


def _measured_leakage(chain: Chain, ev: Any, num_rx: int) -> Chain:
    """``chain`` with its leakage moved by the level the capture shows over the declared one (per RX)."""
    leak = find(chain, "tx_rx_leakage")
    if leak is None:
        return chain
    cur = _as_list(leak["params"].get("coupling_dB", -60.0), num_rx)
    new = []
    for i in range(num_rx):
        a = ev.capture.params.get(f"level_dBFS_rx{i + 1}")
        b = ev.capture.params.get(f"declared_dBFS_rx{i + 1}")  # the detector's declared level
        shift = float(a) - float(b) if a is not None and b is not None else 0.0
        new.append(min(-20.0, max(-100.0, float(cur[i]) + shift)))
    return with_effect(chain, "tx_rx_leakage", {**leak["params"], "coupling_dB": new})


def write_report(diag: Diagnosis, out_dir: str | os.PathLike, figures: bool = True) -> Path:
    """Write ``report.json``, ``summary.md``, ``profile.json`` and the view figures under ``out_dir``."""
    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise CalibrationError(f"{out}: cannot create the report folder ({e.strerror or e})") from None
    report = diag.report()
    diag.profile.save(out / "profile.json")
    report["profile"] = "profile.json"
    if figures:
        from radaraug.diagnosis.figures import view_figures

        report["figures"] = view_figures(diag, out)
    atomic_write_json(out / "report.json", report, newline=False, indent=1, default=_json_default)
    atomic_write_text(out / "summary.md", summary_text(diag, report))
    return out


def _json_default(o: Any) -> Any:
    if isinstance(o, torch.Tensor):
        return o.tolist()
    if isinstance(o, float) and not math.isfinite(o):
        return None
    raise TypeError(type(o).__name__)


def _fmt_params(params: dict[str, Any]) -> str:
    def f(v: Any) -> str:
        if isinstance(v, list):
            return "[" + ", ".join(f(x) for x in v) + "]"
        if isinstance(v, float):
            return f"{v:.4g}"
        return str(v)

    return ", ".join(f"{k}={f(v)}" for k, v in params.items())


def verdicts(diag: Diagnosis) -> list[dict[str, Any]]:
    """One verdict per effect that was added or has a detector: what the loop concludes, and why."""
    out: list[dict[str, Any]] = []
    steps = {s["effect"]: s for s in diag.result.steps}
    for name, s in steps.items():
        line = f"{name}: added" if not s.get("source") else f"{name}: named from its signature"
        if "params_before" in s:
            # Only what the declaration holds: the step's other parameters are the signature's readings.
            after = {k: s["params"][k] for k in s["params_before"] if k in s["params"]} or s["params"]
            line += (f"; declared, at other parameters: {_fmt_params(s['params_before'])} -> "
                     f"{_fmt_params(after)}")
        if s.get("verdict") == "ambiguous":
            alts = ", ".join(f"{a['effect']} {a['held_out_error']:.2f} dB" for a in s.get("alternatives", [])
                             if a["effect"] in s.get("ambiguous_with", []))
            line += f" (ambiguous: {name} {s['error_after']:.2f} dB vs {alts})"
        out.append({"effect": name, "verdict": s.get("verdict", "clear"), "added": True, "text": line,
                    "signature": s.get("signature")})
    for rd in diag.refitted_declared:
        out.append({"effect": rd["effect"], "verdict": "declared, refitted", "added": False,
                    "text": f"{rd['effect']}: declared, at other parameters: refitted {_fmt_params(rd['params_before'])} "
                            f"-> {_fmt_params(rd['params_after'])} ({rd['measured']})",
                    "signature": rd["measured"]})
    refit = {rd["effect"] for rd in diag.refitted_declared}
    for name, e in diag.evidence.items():
        if name in steps or name in refit:
            continue
        text = (f"{name}: signature present ({e.reason}) but adding it did not lower the held-out error"
                if e.present else f"{name}: not found ({e.reason})")
        out.append({"effect": name, "verdict": "present, not added" if e.present else "absent", "added": False,
                    "text": text, "signature": e.reason})
    return out


def summary_text(diag: Diagnosis, report: dict[str, Any]) -> str:
    """A short readable summary of the diagnosis (Markdown)."""
    r = diag.result
    lines = [
        f"# Diagnosis of `{Path(diag.capture).name}`",
        "",
        f"- Mode: **{diag.mode}** ({_MODE_TEXT[diag.mode]}).",
        f"- Config: {diag.config.describe()}",
        f"- Frames: {diag.frames['fit']} to fit, {diag.frames['held_out']} held out; "
        f"{r.evaluations} twin evaluations in {diag.runtime_s:.1f} s.",
        f"- Held-out error (mean of the view errors, dB): default twin **{r.before.overall:.2f}**, "
        f"base chain refitted **{r.base.overall:.2f}**, after the search **{r.after.overall:.2f}**.",
        "",
        "## Effects added (in order)",
        "",
    ]
    if not r.steps:
        lines.append("None: no catalog effect improved the held-out error by the margin.")
    for s in r.steps:
        lines.append(f"1. `{s['effect']}`{' (refit)' if s['refit'] else ''}: {s['error_before']:.3f} -> "
                     f"{s['error_after']:.3f} dB; {_fmt_params(s['params'])}")
    if diag.evidence:
        lines += ["", "## Verdict per effect", ""]
        lines += [f"- {v['text']}" for v in verdicts(diag)]
    lines += ["", "## Room", ""]
    if r.room_after:
        lines += [f"- `{k}`: {r.room_before[k]:.2f} -> base refit {r.room_base[k]:.2f} -> final "
                  f"**{r.room_after[k]:.2f}**" for k in sorted(r.room_after)]
    else:
        lines.append(_room_note(diag.mode, r.room_after) + ".")
    lines += ["", "## Error per view (dB, held-out)", "", "| view | default twin | base refit | final |",
              "|---|---|---|---|"]
    for k in r.before.views:
        lines.append(f"| {k} | {r.before.views[k]:.2f} | {r.base.views[k]:.2f} | {r.after.views[k]:.2f} |")
    lines += ["", "## Base stages against their physical bounds", ""]
    lines += [f"- {'ok' if b['ok'] else '**not physical**'}: {b['text']}" for b in diag.base_check]
    lines += ["", "## Unexplained residual", ""]
    if not diag.unexplained:
        lines.append("Nothing above the thresholds.")
    for u in diag.unexplained:
        where = f"{u['range_m']} m" + (f", {u['velocity_m_s']} m/s" if u.get("velocity_m_s") is not None else "")
        lines.append(f"- {u['view']}: {u['kind']} of {u['size_dB']:+.1f} dB at {where} ({u['cells']} cells)")
        lines += [f"  - closest: `{c['effect']}`, {c['measured']}" for c in u.get("closest", [])]
    lines += ["", f"Units: {DB_CONVENTION}; samples {FLOAT_CONVENTION}.", ""]
    return "\n".join(lines)

