"""Fuzz test: malformed captures, configs and calibrations end in a RadarAugError (or a documented
warning), never another exception type, a hang or unbounded memory (see ``fuzz_data.py``)."""

from __future__ import annotations

import collections
from pathlib import Path

import pytest


def _run(tmp_path: Path, seed: int, scale: int) -> None:
    import radaraug_tests_io_fuzz_data as fz  # registered by conftest.py
    bases = fz.make_bases(tmp_path / "bases")
    cases = fz.generate_cases(bases, seed=seed, scale=scale)
    outcomes = fz.run_cases(cases, tmp_path / "cases")
    failures = [(c.name, o) for c, o in zip(cases, outcomes) if fz.is_failure(o)]
    kinds = collections.Counter(o.split(":")[0] if ":" in o else o for o in outcomes)
    by_type = collections.Counter(o.split(":")[1].strip() if o.startswith("bad:") else o.split(":")[0]
                                  for _, o in failures)
    report = "\n".join(f"  {name}: {o}" for name, o in failures)
    print(f"{len(cases)} cases: {dict(kinds)}; failures by type: {dict(by_type)}")
    assert not failures, f"{len(failures)} of {len(cases)} cases failed ({dict(by_type)}):\n{report}"


def test_fuzz_malformed_inputs(tmp_path):
    _run(tmp_path, seed=9, scale=1)


@pytest.mark.slow
def test_fuzz_malformed_inputs_large(tmp_path):
    _run(tmp_path, seed=99, scale=4)
