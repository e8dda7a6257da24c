"""Every Python block of README.md and docs/*.md runs as written; every shell command parses.

A page's blocks run in order in one fresh interpreter (a block may continue the ones above it, as
a reader would type them), in an empty temporary folder, on data the project ships or makes.
Blocks fenced as ``text``/``bash`` are not run, but every ``radaraug ...`` command in a ``bash``
block must be accepted by the CLI's parser (``train`` commands by LightningCLI, with
``--print_config``, run outside the checkout so that the recipes they name must be installed ones):
a renamed or misspelt option in the docs fails here.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK = re.compile(r"```python\n(.*?)```", re.S)
SHELL = re.compile(r"```(?:bash|sh|console)\n(.*?)```", re.S)
#: a synopsis' optional group, e.g. ``[--shard i/n]``
OPTIONAL = re.compile(r"\s\[--[^\]]*\]")


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


def _shell_commands() -> list[tuple[str, list[str]]]:
    """(page name, arguments after ``radaraug``) of every ``radaraug`` command in a shell block."""
    found = []
    for page in PAGES:
        if not page.is_file():
            continue
        for block in SHELL.findall(page.read_text(encoding="utf-8")):
            for line in block.replace("\\\n", " ").splitlines():
                line = line.strip().removeprefix("$ ")
                if not line.startswith(("radaraug ", "python -m radaraug ")):
                    continue
                words = shlex.split(OPTIONAL.sub("", line), comments=True)
                words = words[words.index("radaraug") + 1 if words[0] == "python" else 1:]
                for stop in ("|", ">", "&&", ";"):  # the command ends at a pipe, redirection or next command
                    words = words[:words.index(stop)] if stop in words else words
                found.append((page.name, words))
    return found


def test_docs_name_shell_commands() -> None:
    assert len(_shell_commands()) >= 30  # the extraction finds the pages' commands


@pytest.mark.parametrize(("page", "words"), _shell_commands(), ids=lambda v: v if isinstance(v, str) else " ".join(v[:3]))
def test_shell_commands_parse(page: str, words: list[str], capsys, monkeypatch, tmp_path) -> None:
    from radaraug.cli import build_parser

    if words[0] != "train":
        try:
            build_parser().parse_args(words)
        except SystemExit as e:  # argparse's usage error, or --help / --version
            assert e.code == 0, f"{page}: `radaraug {' '.join(words)}` is refused:\n{capsys.readouterr().err}"
        return
    from radaraug.cli import main

    # Outside the checkout: a recipe named in the docs must be one installed with the package.
    monkeypatch.chdir(tmp_path)
    try:
        code = main([*words, "--print_config"])
    except SystemExit as e:  # LightningCLI exits after printing the config (or on a bad argument)
        code = e.code
    assert code == 0, f"{page}: `radaraug {' '.join(words)}` is refused:\n{capsys.readouterr().err}"
