"""Dependencies: every module imports with only the declared runtime dependencies installed, and
a feature whose package is missing raises one clear DependencyNotFoundError.

The check runs in a fresh interpreter with a meta-path finder that refuses (ModuleNotFoundError)
every installed distribution that ``pip install radaraug`` would not bring (test tools, and
whatever else this environment holds), as well as the packages radaraug imports lazily, so a
module that imports one of those at import time fails here rather than in a user's environment.
"""

from __future__ import annotations

import importlib.metadata as md
import json
import subprocess
import sys
import textwrap

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from radaraug._optional import PACKAGES, install_hint, lazy_import, missing_dependency
from radaraug.errors import DependencyNotFoundError, RadarAugError
from tests.conftest import REPO_ROOT

tomllib = pytest.importorskip("tomllib")


def _runtime_distributions() -> set[str]:
    """radaraug's runtime dependencies (pyproject.toml) and, recursively, theirs (installed ones)."""
    declared = tomllib.loads((REPO_ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    todo = [(Requirement(r), None) for r in declared]
    seen: set[str] = set()
    while todo:
        req, extra = todo.pop()
        env = {"extra": extra or ""}
        if req.marker is not None and not req.marker.evaluate(env):
            continue
        name = canonicalize_name(req.name)
        try:
            dist = md.distribution(req.name)
        except md.PackageNotFoundError:
            continue  # an optional platform dependency that is not installed here
        key = (name, tuple(sorted(req.extras)))
        if key in seen:
            continue
        seen.add(key)
        for sub in dist.requires or []:
            sub_req = Requirement(sub)
            for e in [None, *req.extras]:
                todo.append((sub_req, e))
    return {n for n, _ in seen}


# Packages radaraug imports lazily that no other runtime dependency needs (tqdm comes with
# lightning, so it cannot be missing on its own).
LAZY = ["matplotlib", "pymeshlab", "scipy", "trimesh"]


def _blocked() -> dict[str, list[str]]:
    """Installed distributions outside the runtime set, plus the lazy ones, and their top-level modules."""
    allowed = _runtime_distributions() - {canonicalize_name(p) for p in LAZY}
    modules, dists = set(LAZY), {canonicalize_name(p) for p in LAZY}
    for module, names in md.packages_distributions().items():
        if module in sys.stdlib_module_names or module == "radaraug":
            continue
        if not any(canonicalize_name(d) in allowed for d in names):
            modules.add(module)
            dists.update(canonicalize_name(d) for d in names)
    dists.discard("radaraug")
    return {"modules": sorted(modules), "distributions": sorted(dists)}


_CHILD = textwrap.dedent(
    """
    import importlib, json, pkgutil, sys, traceback
    from importlib.machinery import PathFinder

    blocked = json.loads(sys.argv[1])
    BLOCKED, BLOCKED_DISTS = set(blocked["modules"]), set(blocked["distributions"])

    def canonical(name):
        return name.lower().replace("_", "-").replace(".", "-")

    class WithoutBlocked(PathFinder):
        # Blocked packages look not installed: `import x` raises ModuleNotFoundError,
        # importlib.util.find_spec("x") is None and importlib.metadata finds no distribution
        # (what libraries that probe for optional packages look at).
        @classmethod
        def find_spec(cls, name, path=None, target=None):
            if name.split(".")[0] in BLOCKED:
                return None
            return PathFinder.find_spec(name, path, target)

        @classmethod
        def find_distributions(cls, *args, **kwargs):
            for d in PathFinder.find_distributions(*args, **kwargs):
                if canonical(d.metadata["Name"] or "") not in BLOCKED_DISTS:
                    yield d

    sys.meta_path[sys.meta_path.index(PathFinder)] = WithoutBlocked
    import radaraug

    out = {"file": radaraug.__file__, "modules": 0, "failed": {}, "errors": {}}
    for m in pkgutil.walk_packages(radaraug.__path__, "radaraug."):
        if m.name == "radaraug.__main__":
            continue  # runs the CLI
        try:
            importlib.import_module(m.name)
            out["modules"] += 1
        except BaseException:
            out["failed"][m.name] = traceback.format_exc(limit=-3)

    def error_of(key, fn):
        try:
            fn()
            out["errors"][key] = None
        except Exception as e:
            out["errors"][key] = [type(e).__name__, getattr(e, "name", None), str(e)]

    import torch
    from radaraug._optional import pyplot
    from radaraug.scene.people import simplify_mesh
    from radaraug.scene.room import box
    from radaraug.cli import main

    error_of("matplotlib", pyplot)
    error_of("trimesh", lambda: box((0, 0, 0), (1, 1, 1), "concrete"))
    v = torch.rand(8, 3, dtype=torch.float64)
    f = torch.tensor([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5], [0, 5, 6]])
    error_of("pymeshlab", lambda: simplify_mesh(v, f, 4))
    BLOCKED.discard("trimesh")
    BLOCKED_DISTS.discard("trimesh")  # with trimesh there, the convex-room check needs scipy
    from radaraug.raytrace.targets import _is_closed_convex
    error_of("scipy", lambda: _is_closed_convex(torch.rand(4, 3, 3), torch.ones(4)))
    out["cli_demo_status"] = main(["demo", "-o", sys.argv[2]])
    print(json.dumps(out))
    """
)


@pytest.fixture(scope="module")
def child(tmp_path_factory: pytest.TempPathFactory) -> dict:
    blocked = _blocked()
    assert {"pytest", "matplotlib"} <= set(blocked["modules"]) and "torch" not in blocked["modules"]
    proc = subprocess.run(
        [sys.executable, "-c", _CHILD, json.dumps(blocked), str(tmp_path_factory.mktemp("demo"))],
        cwd=REPO_ROOT, capture_output=True, text=True, timeout=300,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    out["stderr"] = proc.stderr
    return out


def test_every_module_imports_with_only_runtime_dependencies(child: dict) -> None:
    assert child["file"].startswith(str(REPO_ROOT))  # the checkout under test, not an installed copy
    assert child["failed"] == {}, "\n".join(f"{k}:\n{v}" for k, v in child["failed"].items())
    assert child["modules"] > 100


def test_lazy_packages_are_known() -> None:
    assert set(LAZY) <= set(PACKAGES)


@pytest.mark.parametrize("package", LAZY)
def test_missing_lazy_dependency_raises_one_clear_error(child: dict, package: str) -> None:
    kind, name, message = child["errors"][package]
    assert (kind, name) == ("DependencyNotFoundError", package)
    assert f"the package {package!r} is needed for" in message and "pip install" in message


def test_cli_reports_missing_dependency_with_status_4(child: dict) -> None:
    assert child["cli_demo_status"] == 4
    assert "error: the package 'matplotlib' is needed for figures" in child["stderr"]
    assert "Traceback" not in child["stderr"]


def test_dependency_error_is_an_import_error_not_a_bad_input_error() -> None:
    assert issubclass(DependencyNotFoundError, ModuleNotFoundError)
    assert not issubclass(DependencyNotFoundError, RadarAugError)
    with pytest.raises(ImportError, match=r"needed for a test .* pip install"):
        lazy_import("radaraug_no_such_package", feature="a test")


def test_a_package_missing_its_own_dependency_is_not_blamed_on_the_package() -> None:
    # lazy_import("json") cannot fail; a ModuleNotFoundError for another name passes through unchanged.
    err = missing_dependency(ModuleNotFoundError("x", name="lxml.etree"), "reading a.dae")
    assert err.name == "lxml" and "reading a.dae" in str(err)
    assert "radaraug[" not in install_hint("matplotlib")  # a runtime dependency, not an extra
