"""Evidence: the capture's signatures read against the declared chain's."""

from __future__ import annotations

from radaraug.diagnosis.evidence import INTRINSIC, RELATIVE, assess
from radaraug.diagnosis.signatures import SIGNATURE_EFFECTS, Signature


def _sigs(**over: Signature) -> list[Signature]:
    return [over.get(n, Signature(n, 0.0, False, {}, "nothing")) for n in SIGNATURE_EFFECTS]


def test_every_detector_is_read_one_way() -> None:
    assert sorted(INTRINSIC + RELATIVE) == sorted(SIGNATURE_EFFECTS)


def test_intrinsic_signatures_are_the_evidence() -> None:
    cap = _sigs(spur_tone=Signature("spur_tone", 25.0, True, {"freq_Hz": 156e3}, "line"))
    ev = assess(cap, _sigs(), num_rx=3)
    assert ev["spur_tone"].present and ev["spur_tone"].kind == "intrinsic"
    assert not any(e.present for n, e in ev.items() if n != "spur_tone")
    d = ev["spur_tone"].as_dict()
    assert d["capture"]["params"]["freq_Hz"] == 156e3 and "declared" not in d


def test_high_pass_departs_only_beyond_the_margin() -> None:
    def hp(fc: float, order: float, present: bool = True) -> Signature:
        return Signature("if_highpass", 1.0, present, {"cutoff_Hz": fc, "order": order}, "fit")

    declared = _sigs(if_highpass=hp(80e3, 1, present=False))
    assert assess(_sigs(if_highpass=hp(150e3, 1)), declared, 3)["if_highpass"].present  # 1.9x the cutoff
    assert assess(_sigs(if_highpass=hp(85e3, 3)), declared, 3)["if_highpass"].present  # another order
    assert not assess(_sigs(if_highpass=hp(95e3, 1)), declared, 3)["if_highpass"].present  # within 1.3x
    # The detector itself must see a high-pass shape: a cutoff estimate alone is not evidence.
    assert not assess(_sigs(if_highpass=hp(150e3, 2, present=False)), declared, 3)["if_highpass"].present


def test_mismatch_is_the_detectors_own_reading() -> None:
    # The declared chain has no channel mismatch, and an estimated static scene copies the capture's
    # static gains: the detector (static returns and noise agreeing) is the evidence.
    on = Signature("rx_gain_phase_mismatch", 1.0, True, {"gain_dB_rx2": 1.2}, "static and noise agree")
    off = Signature("rx_gain_phase_mismatch", 0.0, False, {"gain_dB_rx2": 1.2}, "noise disagrees")
    assert assess(_sigs(rx_gain_phase_mismatch=on), _sigs(), 3)["rx_gain_phase_mismatch"].present
    assert not assess(_sigs(rx_gain_phase_mismatch=off), _sigs(), 3)["rx_gain_phase_mismatch"].present
