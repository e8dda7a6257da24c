"""The training recipes: one base recipe and small per-task, per-method and ablation overrides (YAML).

A recipe name ``TASK_METHOD`` is ``base.yaml`` + ``task/TASK.yaml`` + ``method/METHOD.yaml``, merged as
LightningCLI merges several ``--config`` files; ``radaraug reproduce`` composes its runs from the same
files (docs/training.md, "Recipes"). This module reads only YAML: no torch, no Lightning.
"""

from __future__ import annotations

import copy
import importlib.util
from pathlib import Path, PurePosixPath
from typing import Any

from radaraug.errors import ConfigError


def _recipes_dir() -> Path:
    """The recipe files' folder: the checkout's top-level ``recipes/``, installed as ``radaraug.recipe_files``."""
    spec = importlib.util.find_spec("radaraug.recipe_files")
    if spec is None or spec.origin is None:
        raise ConfigError("radaraug's recipe files are not installed (package radaraug.recipe_files); reinstall "
                          "radaraug (pip install radaraug, or pip install -e . in a checkout)")
    return Path(spec.origin).resolve().parent


RECIPES_DIR = _recipes_dir()
"""The folder of the installed recipe files (the checkout's top-level ``recipes/``)."""


def _stems(kind: str) -> list[str]:
    return sorted(p.stem for p in (RECIPES_DIR / kind).glob("*.yaml"))


def tasks() -> list[str]:
    """The tasks with an override file (``task/*.yaml``)."""
    return _stems("task")


def methods() -> list[str]:
    """The methods with an override file (``method/*.yaml``)."""
    return _stems("method")


def ablations() -> list[str]:
    """The ablation overrides (``ablation/*.yaml``)."""
    return _stems("ablation")


def recipe_names() -> list[str]:
    """The recipe names, one per task x method (``occupancy_rt`` ... ``counting_cdr_profile``)."""
    return sorted(f"{t}_{m}" for t in tasks() for m in methods())


def _parts(text: str) -> list[Path] | None:
    """The files that ``text`` names, or None.

    ``TASK_METHOD`` (also with ``.yaml`` or a ``recipes/`` prefix) names three files; ``base``, ``task/T``,
    ``method/M`` and ``ablation/A`` name one.
    """
    p = PurePosixPath(text.replace("\\", "/"))
    if p.suffix not in ("", ".yaml", ".yml"):
        return None
    parts = list(p.with_suffix("").parts)
    if parts[:1] == ["recipes"]:
        parts = parts[1:]
    if len(parts) == 1:
        (stem,) = parts
        if stem == "base":
            return [RECIPES_DIR / "base.yaml"]
        for task in tasks():
            method = stem[len(task) + 1:]
            if stem.startswith(task + "_") and method in methods():
                return [RECIPES_DIR / "base.yaml", RECIPES_DIR / "task" / f"{task}.yaml",
                        RECIPES_DIR / "method" / f"{method}.yaml"]
        return None
    if len(parts) == 2 and parts[0] in ("task", "method", "ablation") and parts[1] in _stems(parts[0]):
        return [RECIPES_DIR / parts[0] / f"{parts[1]}.yaml"]
    return None


def recipe_files(name: str) -> list[Path]:
    """The installed files a recipe name stands for, in merge order.

    Raises:
        ConfigError: ``name`` is no installed recipe (the message lists them).
    """
    files = _parts(name)
    if files is None:
        raise ConfigError(f"no recipe named {name!r}; the installed recipes are {', '.join(recipe_names())} "
                          f"(and the overrides base, task/*, method/*, ablation/*)")
    return files


def is_recipe_name(text: str) -> bool:
    """True when ``text`` names installed recipe files (a name, not a path of the working folder)."""
    return _parts(text) is not None


def merge(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    """``override`` merged into a copy of ``base``: mappings key by key, anything else replaced.

    A mapping that names another ``class_path`` replaces the old one whole (its ``init_args`` belong to the
    old class).
    """
    out = copy.deepcopy(base)
    for key, value in override.items():
        old = out.get(key)
        if (isinstance(value, dict) and isinstance(old, dict)
                and value.get("class_path", old.get("class_path")) == old.get("class_path")):
            out[key] = merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def load(path: str | Path) -> dict[str, Any]:
    """One recipe file as a mapping (ConfigError naming the file when it is not one)."""
    import yaml

    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except (OSError, yaml.YAMLError) as e:
        raise ConfigError(f"recipe {path}: cannot be read as YAML ({e})") from e
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise ConfigError(f"recipe {path}: must be a mapping (trainer / model / data keys), got {type(data).__name__}")
    return data


def compose(*names: str) -> dict[str, Any]:
    """The merged recipe of ``names`` (recipe names or YAML files), in order.

    Example: ``compose("counting_cdr", "ablation/cdr_normal_floor")["data"]["method"]["init_args"]["floor"] == "normal"``.
    """
    out: dict[str, Any] = {}
    for name in names:
        for path in _parts(name) or [Path(name)]:
            out = merge(out, load(path))
    return out


def method_of(entry: Any) -> str | None:
    """The method name (``method/NAME.yaml``) whose ``data.method`` has the ``class_path`` of ``entry``."""
    path = entry.get("class_path") if isinstance(entry, dict) else None
    for name in methods():
        own = compose(f"method/{name}").get("data", {}).get("method", {})
        if path is not None and own.get("class_path") == path:
            return name
    return None


def ablation(name: str) -> tuple[str, dict[str, Any]]:
    """``(method, changes)`` of an ablation override: the method its ``data.method`` names, and its data keys."""
    data = dict(compose(f"ablation/{name}").get("data", {}))
    method = method_of(data.get("method"))
    if method is None:
        raise ConfigError(f"recipe ablation/{name}.yaml must name its method (data.method.class_path: that of one "
                          f"of {methods()})")
    init_args = data.pop("method").get("init_args")
    return method, data | ({"method": init_args} if init_args else {})


def ablation_method(name: str) -> str:
    """The method an ablation override changes (the one its ``data.method`` names)."""
    return ablation(name)[0]


def recipe_text(*names: str) -> str:
    """The merged recipe of ``names`` as YAML, headed by the files it came from."""
    import yaml

    files = [str(p.relative_to(RECIPES_DIR)) for n in names for p in recipe_files(n)]
    head = (f"# radaraug recipe {' + '.join(names)}: merged from {' + '.join(files)} (installed with radaraug;\n"
            "# docs/training.md explains every key). Edit a copy and run it with --config my.yaml.\n")
    return head + yaml.safe_dump(compose(*names), sort_keys=False)
