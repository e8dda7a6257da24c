"""No import cycles among radaraug's modules, counting imports inside functions too.

A cycle hidden behind a function-level import still ties two modules together (neither can be
understood, tested or moved without the other), so both kinds are edges here. Imports under
``if TYPE_CHECKING:`` never run and are left out, as is the implicit import of a parent package.
"""

from __future__ import annotations

import ast
from pathlib import Path

from tests.conftest import REPO_ROOT

PACKAGE = REPO_ROOT / "radaraug"


def _modules() -> dict[str, Path]:
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = list(path.relative_to(REPO_ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _is_type_checking(node: ast.If) -> bool:
    t = node.test
    return (isinstance(t, ast.Name) and t.id == "TYPE_CHECKING") or (
        isinstance(t, ast.Attribute) and t.attr == "TYPE_CHECKING"
    )


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """radaraug modules that ``name`` imports anywhere in its body."""
    is_package = path.name == "__init__.py"
    package = name if is_package else name.rpartition(".")[0]
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and _is_type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join([*anchor, base] if base else anchor)
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                found.add(sub if sub in modules else base)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(path.read_text(), str(path)))
    return {m for m in found if m in modules and m != name}


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []

    def strong(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    return out


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    return {name: _imports(name, path, modules) for name, path in modules.items()}


def test_no_import_cycles() -> None:
    graph = _graph()
    cycles = _cycles(graph)
    detail = [" <-> ".join(c) + "\n    " + "\n    ".join(f"{m} -> {sorted(graph[m] & set(c))}" for m in c)
              for c in cycles]
    assert not cycles, "import cycles:\n" + "\n".join(detail)


def test_the_checker_sees_function_level_and_relative_imports() -> None:
    graph = _graph()
    assert "radaraug.transforms.dsp_spec" in graph["radaraug.transforms.dr"]  # module level
    assert "radaraug.io" in graph["radaraug.transforms._fit_sources"]  # inside a function
    assert "radaraug.scene.people._rotations" in graph["radaraug.scene.people.walker"]  # from pkg import mod
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def _absolute(node: ast.ImportFrom, name: str, path: Path) -> str:
    """The absolute module a ``from ... import`` names (relative imports resolved against ``name``)."""
    if not node.level:
        return node.module or ""
    anchor = (name if path.name == "__init__.py" else name.rpartition(".")[0]).split(".")
    anchor = anchor[: len(anchor) - (node.level - 1)]
    return ".".join([*anchor, node.module] if node.module else anchor)


def _imported_names(name: str, path: Path) -> set[str]:
    """Every module ``name`` imports, at module level, inside functions, or under ``TYPE_CHECKING``.

    ``from X import y`` counts as ``X.y`` too (``y`` may be a submodule), and a literal
    ``importlib.import_module("...")`` / ``__import__("...")`` as the module it names.
    """
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = _absolute(node, name, path)
            found.add(base)
            found.update(f"{base}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant):
            func = node.func
            called = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            if called in ("import_module", "__import__") and isinstance(node.args[0].value, str):
                found.add(node.args[0].value)
    return found


def _io_imports_of_transforms() -> dict[str, list[str]]:
    out = {}
    for name, path in sorted(_modules().items()):
        if name == "radaraug.io" or name.startswith("radaraug.io."):
            bad = sorted(m for m in _imported_names(name, path)
                         if m == "radaraug.transforms" or m.startswith("radaraug.transforms."))
            if bad:
                out[name] = bad
    return out


def test_io_imports_nothing_of_transforms() -> None:
    """radaraug.io knows nothing of transforms (its docstring): no import of radaraug.transforms, anywhere in it."""
    bad = _io_imports_of_transforms()
    assert not bad, "radaraug.io must not import radaraug.transforms (move the code above io):\n" + "\n".join(
        f"    {m} -> {', '.join(v)}" for m, v in bad.items())


def test_the_io_check_sees_every_kind_of_import(tmp_path: Path) -> None:
    pkg = tmp_path / "radaraug" / "io"
    pkg.mkdir(parents=True)
    cases = {
        "a.py": "def f():\n    from radaraug.transforms.per_item import transform_item\n",
        "b.py": "import radaraug.transforms\n",
        "c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from radaraug import transforms\n",
        "d.py": "import importlib\ndef f():\n    return importlib.import_module('radaraug.transforms.dr')\n",
        "e.py": "from ..transforms import RangeDoppler\n",
        "f.py": "from radaraug.io.base import CaptureReader\nimport radaraug.units\n",
    }
    for file, text in cases.items():
        (pkg / file).write_text(text)
    seen = {f: any(m == "radaraug.transforms" or m.startswith("radaraug.transforms.")
                   for m in _imported_names(f"radaraug.io.{f[:-3]}", pkg / f)) for f in cases}
    assert seen == {"a.py": True, "b.py": True, "c.py": True, "d.py": True, "e.py": True, "f.py": False}
