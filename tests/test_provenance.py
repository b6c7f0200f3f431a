"""The repository explains itself: nothing cites material outside it.

Every Python, Markdown and TOML file (except the reference notes kept verbatim under ``docs/reference/`` and
``flexsim/aircraft/data/sources/``, whose provenance ``docs/reference/README.md`` gives) is scanned for paths
out of the repository (``shared/reference``, ``../shared``, ``/work/``) and for the old "DESIGN n" citations;
every ``docs/reference/<file>`` or ``data/sources/<file>`` named anywhere must exist. The scanner is tested
on synthetic text, so the test can fail.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VERBATIM = (ROOT / "docs" / "reference", ROOT / "flexsim" / "aircraft" / "data" / "sources")
OUTSIDE = re.compile(r"(?<!docs/reference/)\bshared/(?:reference|findings)|\.\./shared|/work/|\bDESIGN \d")
CITED = re.compile(r"(docs/reference/[\w.-]+\.\w+|aircraft/data/sources/[\w.-]+\.\w+)")


def problems(text: str, where: str) -> list[str]:
    """Citations in ``text`` that leave the repository or name a reference file that does not exist."""
    out = [f"{where}: cites {m.group(0)!r} outside the repository" for m in OUTSIDE.finditer(text)]
    for m in CITED.finditer(text):
        path = m.group(1) if m.group(1).startswith("docs/") else "flexsim/" + m.group(1)
        if not (ROOT / path).is_file():
            out.append(f"{where}: cites {m.group(1)!r}, which is not in the repository")
    return out


def _files():
    for pattern in ("*.py", "*.md", "*.toml"):
        for path in ROOT.rglob(pattern):
            rel = path.relative_to(ROOT)
            if rel.parts[0].startswith(".") or any(path.is_relative_to(v) for v in VERBATIM) or "egg-info" in str(rel):
                continue
            if path == Path(__file__).resolve():
                continue
            yield rel, path.read_text(encoding="utf-8", errors="replace")


def test_nothing_cites_material_outside_the_repository():
    found = [p for rel, text in _files() for p in problems(text, str(rel))]
    assert found == []


def test_scanner_reports_outside_and_missing_citations():
    assert len(problems("see ``shared/reference/aero-kinematics.md`` §1", "x")) == 1
    assert len(problems("Three models (DESIGN 5)", "x")) == 1
    assert len(problems("(shared/findings/paper-mechanism-probe.md, section A)", "x")) == 1
    assert len(problems("python tools/make_gtm_toml.py ../shared/reference", "x")) == 1
    assert problems("see docs/reference/no-such-note.md", "x") == ["x: cites 'docs/reference/no-such-note.md', which is not in the repository"]
    assert problems("see docs/reference/aero-kinematics.md §2.1 and flexsim/aircraft/data/sources/gtm-notional.md", "x") == []
