"""The package list in pyproject.toml is complete, and the top-level recipes install with the package."""

from __future__ import annotations

import pytest

from tests.conftest import REPO_ROOT

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11 (the project supports 3.10, where this skips)


def _setuptools() -> dict:
    return tomllib.loads((REPO_ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]


def test_every_package_is_listed() -> None:
    found = {".".join(p.parent.relative_to(REPO_ROOT).parts) for p in (REPO_ROOT / "radaraug").rglob("__init__.py")}
    listed = set(_setuptools()["packages"])
    assert listed - {"radaraug.recipe_files"} == found, "add new packages to pyproject.toml's [tool.setuptools] packages"


def test_the_recipes_are_the_checkouts_top_level_folder() -> None:
    from radaraug import recipes

    assert _setuptools()["package-dir"] == {"radaraug.recipe_files": "recipes"}
    assert recipes.RECIPES_DIR == (REPO_ROOT / "recipes").resolve()  # an editable install reads them in place
    assert {"base.yaml", "task", "method", "ablation"} <= {p.name for p in recipes.RECIPES_DIR.iterdir()}
    assert not list((REPO_ROOT / "radaraug" / "recipes").glob("**/*.yaml"))  # one home for the files
