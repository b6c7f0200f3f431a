"""Figures quoted in README.md and docs/*.md that ``tools/regenerate_docs_figures.py`` owns are current.

Default suite: every ``<!-- figures:NAME -->`` region of the docs names a figure the script knows, is closed, and
each known figure has a region (so a region cannot be orphaned or mistyped); ``regenerate_docs_figures.py --check
--fast`` recomputes the fast figures (README's calibration line, the level-flight and glide points of
docs/flutter.md: five US flutter searches, well under a minute on a quiet 2-core machine) and must find no stale
region. Slow (``pytest -m slow``, about 15 minutes): ``--check`` recomputes every figure (also the turn and climb
studies of docs/flutter.md, the m = n table, the tight climb search and 10 seeded episodes per environment for
the baselines table).
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


def test_the_fast_figures_are_current():
    tool = _tool()
    assert any(f.fast for f in tool.FIGURES.values()) and not all(f.fast for f in tool.FIGURES.values())
    run = subprocess.run([sys.executable, str(TOOL), "--check", "--fast"], cwd=ROOT, capture_output=True, text=True,
                         timeout=900)
    assert run.returncode == 0, run.stdout + run.stderr


def test_a_stale_region_is_reported(tmp_path, monkeypatch):
    """``--check`` names a region whose text differs from the computed one and leaves the document alone."""
    tool = _tool()
    doc = tmp_path / "doc.md"
    text = "a <!-- figures:one -->old<!-- /figures:one --> b <!-- figures:two -->2<!-- /figures:two -->\n"
    doc.write_text(text, encoding="utf-8")
    monkeypatch.setattr(tool, "ROOT", tmp_path)
    monkeypatch.setattr(tool, "DOCUMENTS", [doc])
    monkeypatch.setattr(tool, "FIGURES", {"one": tool.Figure(lambda: "new", fast=True),
                                          "two": tool.Figure(lambda: "2", fast=True)})
    assert tool.main(["--check"]) == 1
    assert doc.read_text(encoding="utf-8") == text
    assert tool.main([]) == 0
    assert doc.read_text(encoding="utf-8") == text.replace("old", "new")
    assert tool.main(["--check"]) == 0


@pytest.mark.slow
def test_regenerating_the_figures_changes_nothing():
    run = subprocess.run([sys.executable, str(TOOL), "--check"], cwd=ROOT, capture_output=True, text=True, timeout=3600)
    assert run.returncode == 0, run.stdout + run.stderr
