"""Metrics on hand-made confusion matrices (values worked out by hand, not by the code)."""

import json

import pytest
import torch

from radaraug.errors import ConfigError
from radaraug.training.metrics import (
    accuracy,
    balanced_accuracy,
    causal_context,
    classification_report,
    confusion_matrix,
    save_metrics,
)


def test_confusion_matrix_counts_true_rows_predicted_columns():
    y = torch.tensor([0, 0, 1, 1, 1, 2])
    p = torch.tensor([0, 1, 1, 1, 2, 2])
    cm = confusion_matrix(p, y, 3)
    assert cm.tolist() == [[1, 1, 0], [0, 2, 1], [0, 0, 1]]


def test_balanced_accuracy_is_mean_recall():
    cm = torch.tensor([[8, 2], [1, 9]])  # recalls 0.8 and 0.9
    assert balanced_accuracy(cm) == pytest.approx(0.85)
    assert accuracy(cm) == pytest.approx(17 / 20)


def test_balanced_accuracy_ignores_an_absent_class():
    # a 3-class counting model on a test split with no 2-person frames
    cm = torch.tensor([[3, 1, 0], [1, 1, 2], [0, 0, 0]])  # recalls 0.75, 0.25, absent
    assert balanced_accuracy(cm) == pytest.approx(0.5)
    # macro accuracy over all three classes would give (0.75 + 0.25 + 0) / 3 = 0.333
    rep = classification_report(cm, ["0", "1", "2"])
    assert rep["recall"]["2"] is None and rep["support"]["2"] == 0


def test_imbalanced_classes_chance_level():
    # always "occupied" on 10 empty and 90 occupied frames: accuracy 0.9, balanced 0.5
    cm = torch.tensor([[0, 10], [0, 90]])
    assert accuracy(cm) == pytest.approx(0.9)
    assert balanced_accuracy(cm) == pytest.approx(0.5)


def test_empty_matrix_is_nan_and_bad_labels_raise():
    assert torch.isnan(torch.tensor(balanced_accuracy(torch.zeros(2, 2, dtype=torch.long))))
    with pytest.raises(ConfigError, match="outside"):
        confusion_matrix(torch.tensor([0, 3]), torch.tensor([0, 1]), 3)
    with pytest.raises(ConfigError, match="predictions"):
        confusion_matrix(torch.tensor([0]), torch.tensor([0, 1]), 3)


def test_save_metrics_writes_json_and_png(tmp_path):
    cm = torch.tensor([[5, 0, 0], [1, 3, 1], [0, 2, 3]])
    rep = save_metrics(cm, ["0", "1", "2"], tmp_path, "test", extra={"method": "cdr"})
    data = json.loads((tmp_path / "test_metrics.json").read_text())
    assert data["balanced_accuracy"] == pytest.approx((1 + 0.6 + 0.6) / 3)
    assert data["method"] == "cdr" and data["confusion_matrix"] == cm.tolist()
    assert (tmp_path / "test_confusion.png").read_bytes()[:4] == b"\x89PNG"
    assert rep["accuracy"] == pytest.approx(11 / 15)



def test_causal_context_averages_the_frames_before_within_a_recording():
    probs = torch.tensor([[1.0, 0.0], [0.0, 1.0], [0.0, 1.0], [1.0, 0.0], [0.0, 1.0]])
    starts = torch.tensor([True, False, False, True, False])
    out = causal_context(probs, starts, 2)
    expected = torch.tensor([[1.0, 0.0], [0.5, 0.5], [0.0, 1.0], [1.0, 0.0], [0.5, 0.5]])
    assert torch.allclose(out, expected)  # frame 3 starts a recording: it does not see frame 2
    out3 = causal_context(probs, starts, 3)
    assert torch.allclose(out3[2], torch.tensor([1 / 3, 2 / 3]))
    assert torch.equal(causal_context(probs, starts, 1), probs)
    # causal: changing a later frame never changes an earlier one
    later = probs.clone()
    later[4] = torch.tensor([1.0, 0.0])
    assert torch.equal(causal_context(later, starts, 3)[:4], out3[:4])
    # a long window equals the running mean from the recording's start
    run = causal_context(probs, starts, 100)
    assert torch.allclose(run[2], probs[:3].mean(dim=0)) and torch.allclose(run[4], probs[3:].mean(dim=0))


def test_causal_context_refuses_bad_input():
    with pytest.raises(ValueError):
        causal_context(torch.ones(3, 2), torch.ones(3, dtype=torch.bool), 0)
    with pytest.raises(ValueError):
        causal_context(torch.ones(3, 2), torch.ones(2, dtype=torch.bool), 2)


def test_gated_predictions_raise_nobody_to_one_where_the_gate_fires_in_context() -> None:
    from radaraug.training.metrics import gated_predictions

    preds = torch.tensor([0, 0, 2, 0, 0, 0])
    gate = torch.tensor([True, True, False, False, True, False])
    starts = torch.tensor([True, False, False, True, False, False])
    # single frames: wherever the gate fires, "nobody" becomes 1; a count of 2 stays
    assert gated_predictions(preds, gate, None, 1).tolist() == [1, 1, 2, 0, 1, 0]
    # 2 frames of context: the gate fires where more than half of (this, previous) fired, not across a start
    assert gated_predictions(preds, gate, starts, 2).tolist() == [1, 1, 2, 0, 0, 0]
    with pytest.raises(ValueError, match="gate decisions"):
        gated_predictions(preds, gate[:3], starts, 2)


def test_empty_room_threshold_is_the_largest_context_score_and_sets_the_false_alarm_rate() -> None:
    from radaraug.training.metrics import empty_room_threshold, operating_point_predictions

    cal = torch.tensor([[0.9, 0.1], [0.5, 0.5], [0.8, 0.2]])
    # single frames: the largest 1 - P(empty); two frames of context: means over (this, previous)
    assert empty_room_threshold(cal, 1) == pytest.approx(0.5)
    assert empty_room_threshold(cal, 2) == pytest.approx(max(0.1, 0.3, 0.35))
    with pytest.raises(ValueError, match="no empty-room frames"):
        empty_room_threshold(cal[:0], 1)
    # closed form: an exchangeable new empty frame exceeds the largest of n calibration scores w.p. 1/(n+1)
    g = torch.Generator().manual_seed(0)
    n, trials = 19, 20000
    s = torch.rand(trials, n + 1, generator=g)
    exceed = (s[:, -1] > s[:, :-1].max(dim=1).values).double().mean().item()
    assert exceed == pytest.approx(1 / (n + 1), abs=0.006)
    probs = torch.stack([1 - s[:200, -1], s[:200, -1]], dim=1)
    thr = [empty_room_threshold(torch.stack([1 - row, row], dim=1), 1) for row in s[:200, :-1]]
    fired = [operating_point_predictions(p[None], None, 1, t).item() for p, t in zip(probs, thr)]
    assert fired == [int(a > b) for a, b in zip(s[:200, -1].tolist(), thr)]


def test_operating_point_predictions_match_argmax_at_one_half_and_count_among_people() -> None:
    from radaraug.training.metrics import context_predictions, operating_point_predictions

    g = torch.Generator().manual_seed(1)
    two = torch.softmax(torch.randn(50, 2, generator=g), dim=1)
    starts = torch.zeros(50, dtype=torch.bool)
    starts[[0, 20]] = True
    assert torch.equal(operating_point_predictions(two, starts, 4, 0.5), context_predictions(two, starts, 4))
    three = torch.tensor([[0.40, 0.35, 0.25], [0.70, 0.10, 0.20], [0.2, 0.3, 0.5]])
    # somebody = 0.60 / 0.30 / 0.80: at 0.5 the first is a person (the argmax of 1 vs 2 says one)
    assert operating_point_predictions(three, None, 1, 0.5).tolist() == [1, 0, 2]
    assert operating_point_predictions(three, None, 1, 0.25).tolist() == [1, 2, 2]
    assert operating_point_predictions(three, None, 1, 0.9).tolist() == [0, 0, 0]
