"""Every Python block of README.md and docs/*.md runs on its own (docs that cannot drift).

Each fenced block opened with ```` ```python ```` is one test, named ``<file>:<line>``. It runs as a script in a fresh
interpreter with the current directory an empty ``tmp_path`` (so a block must import what it uses and create
what it reads: no block may rely on an earlier one or on files of the checkout), the flexsim the tests import (the
installed package, :func:`tests.installed.child_env`) and the matplotlib backend ``Agg``. A block fails the test if it exits non-zero or runs over
``BLOCK_TIMEOUT_S``.

Markers, an HTML comment on the line right above the fence (invisible on rendered pages):

* ``<!-- docs-test: slow -->`` — the block takes more than ~30 s; it runs under ``pytest -m slow`` only.

There is no marker to skip a block: a block that should not run is not a ```` ```python ```` block (use
```` ```text ```` for output or pseudo-code).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.installed import child_env

ROOT = Path(__file__).resolve().parents[1]
DOC_FILES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCK_TIMEOUT_S = 900.0
_FENCE = re.compile(r"^(?:<!--\s*docs-test:\s*(?P<mark>[\w-]+)\s*-->[ \t]*\n)?```python[^\n]*\n(?P<code>.*?)^```[ \t]*$",
                    re.DOTALL | re.MULTILINE)
_MARKS = {"slow": pytest.mark.slow}


def python_blocks(path: Path) -> list[tuple[int, str, str | None]]:
    """(line of the fence, code, marker or None) of every ```python block of ``path``."""
    text = path.read_text(encoding="utf-8")
    blocks = []
    for match in _FENCE.finditer(text):
        fence_line = text.count("\n", 0, match.start("code"))  # 1-based line of the ```python fence
        blocks.append((fence_line, match.group("code"), match.group("mark")))
    return blocks


def _params():
    params = []
    for path in DOC_FILES:
        for line, code, mark in python_blocks(path):
            if mark is not None and mark not in _MARKS:
                raise ValueError(f"{path.relative_to(ROOT)}:{line}: unknown docs-test marker {mark!r} "
                                 f"(known: {', '.join(_MARKS)})")
            marks = [_MARKS[mark]] if mark else []
            params.append(pytest.param(code, id=f"{path.relative_to(ROOT)}:{line}", marks=marks))
    return params


def test_the_docs_have_python_blocks():
    """The fence pattern finds the blocks (guards against a pattern that silently matches nothing)."""
    readme = python_blocks(ROOT / "README.md")
    assert len(readme) >= 3 and all(code.strip() for _, code, _ in readme)


@pytest.mark.parametrize("code", _params())
def test_python_block_runs_standalone(code, tmp_path):
    script = tmp_path / "block.py"
    script.write_text(code, encoding="utf-8")
    env = child_env(base={**os.environ, "MPLBACKEND": "Agg"})
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=BLOCK_TIMEOUT_S)
    assert run.returncode == 0, f"the block failed (exit {run.returncode}):\n{code}\n--- stderr ---\n{run.stderr[-3000:]}"
