"""Imports of third-party packages that only some features need, with one clear error.

Packages imported inside a function (so that ``import radaraug`` stays light) go through :func:`lazy_import`:
a missing one raises :class:`~radaraug.errors.DependencyNotFoundError` naming the package, the feature
and the ``pip`` command. :data:`PACKAGES` are runtime dependencies (missing only in a partial environment, ``pip install
--no-deps``) except those of an extra (``radaraug[export]``: ONNX export).
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import NamedTuple

from radaraug.errors import DependencyNotFoundError


class Package(NamedTuple):
    """How a lazily imported package is installed."""

    distribution: str
    """The name ``pip`` installs it under."""
    extra: str | None = None
    """The radaraug extra that brings it (None: a runtime dependency)."""


PACKAGES: dict[str, Package] = {
    "matplotlib": Package("matplotlib"),
    "onnx": Package("onnx", "export"),
    "onnxruntime": Package("onnxruntime", "export"),
    "onnxscript": Package("onnxscript", "export"),
    "pymeshlab": Package("pymeshlab"),
    "scipy": Package("scipy"),
    "tqdm": Package("tqdm"),
    "trimesh": Package("trimesh"),
}
"""Top-level module name -> distribution, for every package imported through :func:`lazy_import`."""


def install_hint(module: str) -> str:
    """The ``pip`` command that brings ``module`` (its top-level package)."""
    top = module.split(".")[0]
    package = PACKAGES.get(top, Package(top))
    if package.extra is not None:
        return f"pip install 'radaraug[{package.extra}]'"
    return f"pip install {package.distribution} (a runtime dependency of radaraug: pip install radaraug installs it)"


def lazy_import(name: str, *, feature: str) -> ModuleType:
    """Import ``name`` (a module, dotted names allowed) for ``feature``.

    Args:
        name: the module, e.g. ``"matplotlib.pyplot"``.
        feature: what needs it, for the message (``"figures"``, ``"mesh files"``...).

    Returns:
        The module.

    Raises:
        DependencyNotFoundError: the module's top-level package is not installed; the message
            names it, the feature and the ``pip`` command.

    Example:
        >>> lazy_import("json", feature="an example").__name__
        'json'
    """
    try:
        return importlib.import_module(name)
    except ModuleNotFoundError as err:
        top = name.split(".")[0]
        if err.name is not None and err.name.split(".")[0] != top:
            raise  # the package is there but one of its own dependencies is missing: keep pip's truth
        raise missing_dependency(err, feature) from None


def missing_dependency(err: ModuleNotFoundError, feature: str) -> DependencyNotFoundError:
    """The clear error for a package that a third-party library (trimesh reading a format...) found missing.

    Example:
        >>> missing_dependency(ModuleNotFoundError("no", name="lxml"), "reading x.dae").name
        'lxml'
    """
    top = (err.name or "?").split(".")[0]
    return DependencyNotFoundError(
        f"the package {top!r} is needed for {feature} but is not installed: {install_hint(top)}", name=top
    )


def pyplot() -> ModuleType:
    """``matplotlib.pyplot`` with the non-interactive Agg backend (radaraug only writes files)."""
    matplotlib = lazy_import("matplotlib", feature="figures")
    matplotlib.use("Agg")
    return lazy_import("matplotlib.pyplot", feature="figures")
