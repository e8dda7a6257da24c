"""Evidence for undeclared effects: the capture's signatures against the declared chain's.

Leakage, LO phase noise and the IF high-pass are in every sensor and in the declared chain, so what
counts is where the capture departs from the declaration. A signature is **intrinsic** (the capture's
signature is the evidence: the declared chain makes none, or the detector compares with it in closed
form) or **relative** (``if_highpass``: undeclared when the cutoff is off by 1.3x from the declared
chain's, or the order differs). See ``docs/diagnosis.md``, "The effect catalog and the search".
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

from radaraug.diagnosis.signatures import SIGNATURE_EFFECTS, Signature, detect_all

INTRINSIC = ("adc_clipping", "spur_tone", "interference", "vibrating_clutter", "frame_drift", "tx_rx_leakage",
             "phase_noise", "rx_gain_phase_mismatch")
RELATIVE = ("if_highpass",)

CUTOFF_FACTOR = 1.3
"""High-pass cutoff ratio (either way) that makes the IF high-pass undeclared."""


@dataclass(frozen=True)
class Evidence:
    """Whether the capture carries an effect the declared chain does not make.

    Attributes:
        effect: catalog name.
        present: the effect is undeclared (the capture's signature, beyond the declared chain's).
        kind: ``"intrinsic"`` or ``"relative"`` (module docstring).
        score: the capture's signature score (its unit in ``capture.detail``).
        reason: one line a radar engineer can check.
        capture: the capture's signature.
        declared: the declared chain's signature (relative effects), else None.
    """

    effect: str
    present: bool
    kind: str
    score: float
    reason: str
    capture: Signature
    declared: Signature | None = None

    def as_dict(self) -> dict[str, Any]:
        """JSON-able form for report.json."""
        d = {"effect": self.effect, "present": self.present, "kind": self.kind, "score": round(self.score, 4),
             "reason": self.reason, "capture": _sig_dict(self.capture)}
        if self.declared is not None:
            d["declared"] = _sig_dict(self.declared)
        return d


def _sig_dict(s: Signature) -> dict[str, Any]:
    d = asdict(s)
    d["params"] = {k: round(float(v), 6) for k, v in s.params.items()}
    d["score"] = round(float(s.score), 4)
    return d


def _highpass_relative(cap: Signature, twin: Signature) -> tuple[bool, str]:
    """``(undeclared, reason)``: is the capture's high-pass beyond the declared chain's?"""
    if "cutoff_Hz" not in cap.params or "cutoff_Hz" not in twin.params:
        return False, "noise floor too flat to fit a high-pass"
    ratio = float(cap.params["cutoff_Hz"]) / max(float(twin.params["cutoff_Hz"]), 1.0)
    other_order = round(float(cap.params["order"])) != round(float(twin.params["order"]))
    off = ratio > CUTOFF_FACTOR or ratio < 1 / CUTOFF_FACTOR or other_order
    return off and cap.present, (
        f"capture's floor: order {cap.params['order']:g} at {cap.params['cutoff_Hz'] / 1e3:.1f} kHz; "
        f"declared chain's: order {twin.params['order']:g} at {twin.params['cutoff_Hz'] / 1e3:.1f} kHz")


def assess(capture: Sequence[Signature], declared: Sequence[Signature] | None, num_rx: int) -> dict[str, Evidence]:
    """One :class:`Evidence` per effect with a detector.

    Args:
        capture: :func:`~radaraug.diagnosis.signatures.detect_all` of the capture.
        declared: the same on frames of the declared chain (the twin with the base chain); None
            reads every relative effect as absent.
        num_rx: RX channels.
    """
    cap = {s.effect: s for s in capture}
    dec = {s.effect: s for s in declared or ()}
    out: dict[str, Evidence] = {}
    for name in SIGNATURE_EFFECTS:
        s, ref = cap[name], None if name in INTRINSIC else dec.get(name)
        if name in INTRINSIC:
            present, reason = bool(s.present), s.detail
        elif ref is None:
            present, reason = False, "no declared-chain frames to compare with"
        else:
            present, reason = _highpass_relative(s, ref)
        kind = "intrinsic" if name in INTRINSIC else "relative"
        out[name] = Evidence(name, present, kind, float(s.score), reason, s, ref)
    return out


def declared_signatures(source: Any, chain: Sequence[Mapping[str, Any]], num_frames: int,
                        seed: int) -> list[Signature]:
    """Signatures of frames the declared chain makes (the search's source with the base chain).

    Args:
        source: the search's :class:`~radaraug.diagnosis.twin_source.TwinSource`.
        chain: the declared chain the source simulates.
        num_frames: frames to simulate (as many as the capture's, so both statistics match).
        seed: noise seed.
    """
    return detect_all(source.frames(list(chain), num_frames, seed=seed), source.config)


__all__ = ["Evidence", "INTRINSIC", "RELATIVE", "assess", "declared_signatures"]
