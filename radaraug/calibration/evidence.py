"""Evidence for undeclared effects: the capture's signatures against the declared chain's.

:mod:`radaraug.calibration.signatures` says whether a capture *shows* an effect's signature. Some
effects are part of every sensor and of the declared receiver chain (TX->RX leakage, LO phase
noise, the IF high-pass, the board's channel balance); what the loop must find is where the
capture departs from the declaration. So each signature is read one of two ways:

* **intrinsic** (``adc_clipping``, ``spur_tone``, ``interference``, ``vibrating_clutter``,
  ``frame_drift``): the declared chain makes none of these, so the capture's signature is the
  evidence. ``tx_rx_leakage`` and ``phase_noise`` are read the same way because their detectors
  already compare with the declared chain in closed form (a visible near-DC return more than 15 dB
  from the declared leakage's level, a skirt 3 dB over the declared LO noise's:
  :mod:`radaraug.calibration.signatures`); an estimated static scene copies the capture's leakage,
  so a twin run could not serve as the reference there. ``rx_gain_phase_mismatch`` too: the declared
  chain has none, and its detector already asks for the same per-RX gain in the static returns *and*
  in the noise (an estimated static scene copies the capture's static gains, so again no twin run).
* **relative** (``if_highpass``): the same detector runs on frames the declared chain makes (the
  twin with the base chain), and the effect is undeclared only when the capture departs from them
  by more than a physical margin: a cutoff off by a factor of 1.3, or another order.

:func:`assess` returns one :class:`Evidence` per effect with a detector. The search uses it to
decide which catalog candidates may be added (:mod:`radaraug.calibration.search`) and the report
states it per effect.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from typing import Any

from radaraug.calibration.signatures import SIGNATURE_EFFECTS, Signature, detect_all

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
    """Is the capture's high-pass beyond the declared chain's (the one :data:`RELATIVE` effect)? ``(undeclared, reason)``."""
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
        capture: :func:`~radaraug.calibration.signatures.detect_all` of the capture.
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
        source: the search's :class:`~radaraug.calibration.twin_source.TwinSource`.
        chain: the declared chain the source simulates.
        num_frames: frames to simulate (as many as the capture's, so both statistics match).
        seed: noise seed.
    """
    return detect_all(source.frames(list(chain), num_frames, seed=seed), source.config)


__all__ = ["Evidence", "INTRINSIC", "RELATIVE", "assess", "declared_signatures"]
