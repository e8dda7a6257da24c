"""Fixtures of the ray-tracer tests: never compile (warm-up is slow); shared closed-form scenes."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

HELPERS = "raytrace_scenes"


def _load_helpers() -> None:
    # Tests run with --import-mode=importlib: register the helper module under its (unique) name
    # so the test files can `from raytrace_scenes import ...`.
    if HELPERS not in sys.modules:
        spec = importlib.util.spec_from_file_location(HELPERS, Path(__file__).with_name(f"{HELPERS}.py"))
        module = importlib.util.module_from_spec(spec)
        sys.modules[HELPERS] = module
        spec.loader.exec_module(module)


_load_helpers()


@pytest.fixture(autouse=True)
def _eager_kernels(monkeypatch: pytest.MonkeyPatch) -> None:
    """Tests must not depend on torch.compile: force the eager kernels."""
    monkeypatch.setenv("RADARAUG_COMPILE", "0")
