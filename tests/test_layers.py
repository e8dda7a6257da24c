"""Every import of the package goes down the layers written in docs/architecture.md (or sideways).

Function-level imports count (a cycle behind one still ties two folders together); imports under
``if TYPE_CHECKING:`` never run and are left out.
"""

from __future__ import annotations

import re

from tests.conftest import REPO_ROOT
from tests.test_import_cycles import _graph

DOC = REPO_ROOT / "docs" / "architecture.md"


def layers() -> dict[str, int]:
    """Folder (or core module) -> its layer, from the doc's list."""
    text = DOC.read_text()
    block = text[text.index("<!-- layers"):text.index("<!-- /layers -->")]
    out: dict[str, int] = {}
    for line in block.splitlines():
        m = re.match(r"(\d+)\. (.*)", line)
        if m:
            for name in re.findall(r"`([\w]+)`", m.group(2).split(":")[0]):
                out[name] = int(m.group(1))
    return out


def _folder(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def test_every_folder_has_a_layer() -> None:
    placed = layers()
    missing = sorted({_folder(m) for m in _graph()} - set(placed))
    assert not missing, f"add these to docs/architecture.md's layers: {missing}"


def _up(graph: dict[str, set[str]], placed: dict[str, int]) -> list[str]:
    return sorted(f"{a} -> {b}" for a, targets in graph.items() for b in targets
                  if placed[_folder(b)] > placed[_folder(a)])


def test_imports_go_down_the_layers() -> None:
    up = _up(_graph(), layers())
    assert not up, "imports up the layers (docs/architecture.md):\n" + "\n".join(up)


def test_the_check_sees_an_import_up() -> None:
    placed = layers()
    assert placed["io"] < placed["transforms"] < placed["diagnosis"] < placed["cli"]
    assert placed["errors"] == placed["files"] == 1
    graph = {"radaraug.transforms.dr": {"radaraug.diagnosis.record", "radaraug.io.base"},
             "radaraug.sim.twin": {"radaraug.sim.seeding", "radaraug.sensor"}}
    assert _up(graph, placed) == ["radaraug.transforms.dr -> radaraug.diagnosis.record"]
