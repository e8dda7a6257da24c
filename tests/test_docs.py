"""Every Python block of README.md and docs/*.md runs as written.

A page's blocks run in order in one fresh interpreter (a block may continue the ones above it, as
a reader would type them), in an empty temporary folder, on data the project ships or makes.
Blocks fenced as ``text``/``bash`` are not run.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK = re.compile(r"```python\n(.*?)```", re.S)


def _pages_with_code() -> list[Path]:
    return [p for p in PAGES if p.is_file() and BLOCK.search(p.read_text(encoding="utf-8"))]


@pytest.mark.parametrize("page", _pages_with_code(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_python_blocks_run(page: Path, tmp_path: Path) -> None:
    code = "\n\n".join(BLOCK.findall(page.read_text(encoding="utf-8")))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
           "RADARAUG_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, f"{page.name}: its Python blocks fail as written:\n{r.stderr[-3000:]}"
