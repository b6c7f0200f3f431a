"""Figures quoted in README.md and docs/*.md that ``tools/regenerate_docs_figures.py`` owns are current.

Fast: every ``<!-- figures:NAME -->`` region of the docs names a figure the script knows, is closed, and each
known figure has a region (so a region cannot be orphaned or mistyped). Slow (``pytest -m slow``, several
minutes): ``regenerate_docs_figures.py --check`` recomputes every figure (the flutter search of README's
calibration line, 10 seeded episodes per environment for the baselines table) and must find no stale region.
"""

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOOL = ROOT / "tools" / "regenerate_docs_figures.py"


def _tool():
    spec = importlib.util.spec_from_file_location("regenerate_docs_figures", TOOL)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_region_names_a_known_figure_and_every_figure_has_a_region():
    tool = _tool()
    seen = set()
    for doc in tool.DOCUMENTS:
        text = doc.read_text(encoding="utf-8")
        opened = re.findall(r"<!-- figures:([\w-]+) -->", text)
        closed = re.findall(r"<!-- /figures:([\w-]+) -->", text)
        names = [m.group("name") for m in tool.regions(text)]
        assert opened == closed == names, f"{doc.relative_to(ROOT)}: unbalanced figure regions {opened} / {closed}"
        unknown = set(names) - set(tool.FIGURES)
        assert not unknown, f"{doc.relative_to(ROOT)}: regions of unknown figures {sorted(unknown)}"
        assert all(m.group("body").strip() for m in tool.regions(text)), f"{doc.relative_to(ROOT)}: an empty region"
        seen |= set(names)
    assert seen == set(tool.FIGURES)


@pytest.mark.slow
def test_regenerating_the_figures_changes_nothing():
    run = subprocess.run([sys.executable, str(TOOL), "--check"], cwd=ROOT, capture_output=True, text=True, timeout=3600)
    assert run.returncode == 0, run.stdout + run.stderr
