"""Figures quoted in README.md and docs/*.md that ``tools/regenerate_docs_figures.py`` owns are current, compared at
the precision the docs print them.

Default suite: every ``<!-- figures:NAME -->`` region names a registered figure, is closed, and each figure has a
region; the comparison at printed precision (``difference``) behaves as documented; no region prints a round-off
residual; ``regenerate_docs_figures.py --check --fast`` recomputes the fast figures and must find no stale region.
Slow (``pytest -m slow``, about 3 minutes): ``--check`` recomputes every figure.
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
    """``--check`` names a region whose text differs from the computed one and leaves the document alone; the plain
    command rewrites only the stale region (a region equal at the printed precision keeps its digits)."""
    tool = _tool()
    doc = tmp_path / "doc.md"
    text = "a <!-- figures:one -->old<!-- /figures:one --> b <!-- figures:two -->2.01<!-- /figures:two -->\n"
    doc.write_text(text, encoding="utf-8")
    monkeypatch.setattr(tool, "ROOT", tmp_path)
    monkeypatch.setattr(tool, "DOCUMENTS", [doc])
    monkeypatch.setattr(tool, "FIGURES", {"one": tool.Figure(lambda: "new", fast=True),
                                          "two": tool.Figure(lambda: "2.02", fast=True)})
    assert tool.main(["--check"]) == 1
    assert doc.read_text(encoding="utf-8") == text
    assert tool.main([]) == 0
    assert doc.read_text(encoding="utf-8") == text.replace("old", "new")
    assert tool.main(["--check"]) == 0


@pytest.mark.parametrize("old, new, rtol, agrees", [
    ("0.6858 / 36.744 (0 m)", "0.6858 / 36.744 (0 m)", 0.0, True),
    ("0.6858 / 36.744 (0 m)", "0.6859 / 36.743 (0 m)", 0.0, True),  # one unit of the last digit: a rounding boundary
    ("0.6858 / 36.744 (0 m)", "0.6860 / 36.744 (0 m)", 0.0, False),  # two units: the value moved
    ("US M_F +1.7 %", "US M_F +1.8 %", 0.0, True),
    ("US M_F +1.7 %", "US M_F +1.9 %", 0.0, False),
    ("M_F +0.00000 at 9144 m", "M_F −0.00000 at 9144 m", 0.0, True),  # a sign of zero
    ("−2.2e-5 at 0 m", "-2.3e-5 at 0 m", 0.0, True),  # typographic or ASCII minus; exponent: unit 1e-6
    ("−2.2e-5 at 0 m", "−2.4e-5 at 0 m", 0.0, False),
    ("−2.2e-5 at 0 m", "−2.4e-5 at 0 m", 0.1, True),  # a stated relative tolerance
    ("1,726,464 steps", "1,726,465 steps", 0.0, False),  # counts are exact
    ("120 points", "121 points", 0.0, False),
    ("120 points", "120 points, 8 chains", 0.0, False),
    ("M_F decreases as R increases", "M_F increases as R increases", 0.0, False),  # the words are exact
    ("DOP853 at rtol 1e-9", "DOP854 at rtol 1e-9", 0.0, False),  # digits inside a word are text
    ("| C1 | 0.714 |", "| C1 | 0.7140 |", 0.0, True),  # a figure printed with another number of digits
    ("to 1e-13", "to 2e-13", 0.0, True),  # a one-digit residual: one unit is all it resolves ...
    ("to 1e-13", "to 3e-13", 0.0, False),
    ("within 1e-12", "within 1e-11", 0.0, False),  # ... and a bound keeps its exponent
    ("9.1e-05 m", "1.0e-04 m", 0.5, True),
])
def test_figures_are_compared_at_the_printed_precision(old, new, rtol, agrees):
    assert (_tool().difference(old, new, rtol) is None) == agrees


#: Words that mark a tiny number as a bound or a setting rather than a computed residual.
_BOUND_WORDS = ("<", "below", "within", "rtol", "than", "+-")


def test_no_region_prints_a_round_off_residual():
    """A number below 1e-9 in a generated region is a bound (``< 1e-12``, ``below 1e-9°``) or a setting (``rtol
    1e-9``), never a computed value: its digits would differ between two correct machines."""
    tool = _tool()
    found = []
    for doc in tool.DOCUMENTS:
        for m in tool.regions(doc.read_text(encoding="utf-8")):
            body = m.group("body")
            for n in tool.NUMBER.finditer(body):
                value = tool._value(n.group())[0]
                before = body[:n.start()].split()[-1:] or [""]
                if 0.0 < abs(value) < 1e-9 and before[0].lower() not in _BOUND_WORDS:
                    found.append(f"{doc.relative_to(ROOT)}: {m.group('name')}: {body[max(0, n.start() - 40):n.end()]!r}")
    assert not found, "round-off residuals printed as values:\n" + "\n".join(found)


@pytest.mark.slow
def test_regenerating_the_figures_changes_nothing():
    run = subprocess.run([sys.executable, str(TOOL), "--check"], cwd=ROOT, capture_output=True, text=True,
                         timeout=3600)
    assert run.returncode == 0, run.stdout + run.stderr
