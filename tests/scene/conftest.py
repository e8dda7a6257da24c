"""Fixtures of the scene tests, and the shared stand-ins of ``scene_stubs.py``."""

from __future__ import annotations

import importlib.util
import sys
import types
from pathlib import Path

import pytest

import radaraug.scene.scene_file as scene_file

HELPERS = "scene_stubs"


def _load_helpers() -> types.ModuleType:
    # Tests run with --import-mode=importlib: register the helper module under its (unique) name
    # so the test files can `from scene_stubs import ...`.
    if HELPERS not in sys.modules:
        spec = importlib.util.spec_from_file_location(HELPERS, Path(__file__).with_name(f"{HELPERS}.py"))
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[HELPERS] = module
        spec.loader.exec_module(module)
    return sys.modules[HELPERS]


_STUB_TYPES = _load_helpers().STUB_TYPES


@pytest.fixture
def stub_people(monkeypatch: pytest.MonkeyPatch) -> types.SimpleNamespace:
    """The stand-in person types, registered under their scene-file ``type`` for the loader."""
    monkeypatch.setattr(scene_file, "PERSON_TYPES", {cls.type_name: cls for cls in _STUB_TYPES})
    return types.SimpleNamespace(**{cls.__name__: cls for cls in _STUB_TYPES})
