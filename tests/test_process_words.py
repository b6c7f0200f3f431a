"""No words of the development process in the product: code, docs, tests and tool output speak to users.

A user does not know the project's issue numbers, the names of the work that produced a change or its commits; the
history lives in git and ``CHANGELOG.md``. The checker scans every tracked text file (``git ls-files``) line by line
for

* an issue number: ``issue 15``, ``issues 4``, ``issue-11``, ``Issue #12``, or a bare ``#13``;
* a name of the work process: ``work stream``, ``work session``, ``session 8``, ``helper flutter``, ``the lead's``;
* a commit hash: a word of 7-40 hexadecimal digits with at least one digit and one letter (``d3d625b``).

A commit or an issue may be named where a user needs it (a data file pinned to the commit that wrote it, a citation
of another project's issue or commit): those are listed, with the reason, in ``ALLOWED``. Each hit is reported as ``path:line: kind 'match'``.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

PATTERNS: tuple[tuple[str, re.Pattern[str]], ...] = (
    ("issue number", re.compile(r"\bissues?[ -]?#?\d+\b", re.IGNORECASE)),
    ("issue reference", re.compile(r"(?<![\w&/#])#\d{1,4}\b")),
    ("work-process name", re.compile(
        r"\bwork[- ]?(?:streams?|sessions?)\b|\bsessions? \d+\b|\bthe lead'?s?\b|\bother helpers\b"
        r"|\bhelpers? (?:flutter|aot|batch|sim|rhs|envs|ci|docs|kernels|model|trim)\b", re.IGNORECASE)),
    # not the digits of a number in scientific notation (8.591490e-4): no '.' or digit before it
    ("commit hash", re.compile(r"(?<![.\d])\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")),
)

#: Matches a user needs, by file: the commit that wrote a stored data file (so that the data can be reproduced), and
#: citations of another project's issues and commits.
ALLOWED: dict[str, frozenset[str]] = {
    "tests/io/data/README.md": frozenset({"d8600f6"}),  # the format-1 flight logs were written by this commit
    "tests/model/data/README.md": frozenset({"9d7f24c"}),  # the dense kernel that wrote rhs_reference.npz
    # the mAEWing1 FEM is pinned to the commit of the public repository it was converted from:
    "flexsim/aircraft/data/maewing1.md": frozenset({"7683349c7711a14607347f8fc0b40095774cf549"}),
    "tools/make_maewing1_toml.py": frozenset({"7683349c7711a14607347f8fc0b40095774cf549"}),
    "tests/aircraft/test_maewing1.py": frozenset({"7683349c7711a14607347f8fc0b40095774cf549"}),
    # the PHC and Pazy data are pinned to the commits of the public repositories they were read from:
    "flexsim/aircraft/data/phc_wing.md": frozenset({"31776c20", "e7d3dfed", "399b9d6c"}),
    "flexsim/aircraft/data/pazy_wing.md": frozenset({"396710a"}),
    "flexsim/aircraft/data/pazy_wing.toml": frozenset({"396710a"}),
    # the derivation notes cite Aeroelasticity.jl's issue tracker and commits as sources:
    "docs/reference/aero-kinematics.md": frozenset({"issue #43", "#43", "d88b597", "1501a89", "6ca95da", "48483cf"}),
}

#: Third-party data copied verbatim (NASTRAN Bulk Data and the like): not our words.
VENDORED: tuple[str, ...] = ("flexsim/aircraft/data/sources/",)

#: This file names the words it looks for.
SELF = "tests/test_process_words.py"


def process_words(text: str, path: str) -> list[str]:
    """Every process word of ``text`` (the content of the file ``path``, relative to the repository root), as
    ``path:line: kind 'match'``; the first hit of a line only."""
    allowed = ALLOWED.get(path, frozenset())
    hits = []
    for number, line in enumerate(text.splitlines(), start=1):
        for kind, pattern in PATTERNS:
            match = next((m for m in pattern.finditer(line) if m.group(0) not in allowed), None)
            if match is not None:
                hits.append(f"{path}:{number}: {kind} {match.group(0)!r}")
                break
    return hits


def scan(root: Path, paths: list[str]) -> list[str]:
    """The process words of the text files ``paths`` under ``root`` (binary and non-UTF-8 files are skipped)."""
    hits = []
    for path in paths:
        data = (root / path).read_bytes() if (root / path).is_file() else b""
        if b"\0" in data:
            continue
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            continue
        hits += process_words(text, path)
    return hits


def tracked_files(root: Path = ROOT) -> list[str]:
    run = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True, check=True)
    return [p for p in run.stdout.decode("utf-8").split("\0") if p and p != SELF and not p.startswith(VENDORED)]


def test_the_tracked_files_hold_no_process_words():
    files = tracked_files()
    assert len(files) > 100  # the scan sees the repository (guards against an empty file list)
    hits = scan(ROOT, files)
    assert not hits, f"{len(hits)} lines name the development process:\n" + "\n".join(hits)


def test_a_planted_line_is_reported(tmp_path):
    """The checker fails on each kind of process word, names file and line, and passes the clean lines around them."""
    clean = "The flutter Mach number of the level flight [-].\nSee docs/flutter.md, Table 3 and eq. (32).\n"
    planted = {
        "issue number": "Level flight flutter (issue 15, fact 2).",
        "issue reference": "the CLI never changes the question (#12)",
        "work-process name": "measured by helper flutter in session 8",
        "commit hash": "results unchanged since d3d625b",
    }
    for kind, line in planted.items():
        doc = tmp_path / "docs" / "page.md"
        doc.parent.mkdir(exist_ok=True)
        doc.write_text(clean + line + "\n" + clean, encoding="utf-8")
        hits = scan(tmp_path, ["docs/page.md"])
        assert len(hits) == 1 and hits[0].startswith(f"docs/page.md:3: {kind} "), (kind, hits)
    assert scan(tmp_path, ["docs/absent.md"]) == []
    (tmp_path / "data.bin").write_bytes(b"\0issue 15")
    assert scan(tmp_path, ["data.bin"]) == []


def test_a_commit_a_user_needs_is_allowed_where_listed():
    line = "written by main at commit d8600f6\n"
    assert process_words(line, "tests/io/data/README.md") == []
    assert process_words(line, "docs/logs.md") == ["docs/logs.md:1: commit hash 'd8600f6'"]
    digest = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"  # a SHA-256, not a commit
    assert process_words(f"#: colour #1f77b4, sha256 {digest}, section #\n", "x.py") == []
    assert process_words("CG x = 8.20 + 8.591490e-4 in\n", "x.py") == []  # a number, not a commit
