"""List the lines of README.md and docs/*.md that quote numbers outside generated regions and code fences.

A crude scanner for the rule ("every figure quoted is produced by a script or checked by a test"): it prints every
line that holds a decimal number or a number with a unit (``%``, ``×``, ``s``, ``ms``, ``rad/s``, ``m``, ``Hz``,
``steps``) outside ``<!-- figures:NAME -->...<!-- /figures:NAME -->`` regions (written by
``tools/regenerate_docs_figures.py``) and outside fenced code blocks. Each hit is to be classified by a person:
an input, default, tolerance or unit (keep); a value quoted from a cited source (keep, with the citation); a dated
benchmark record with its command (keep); or a result of flexsim's code (put it in a generated region, or reword).

Run from the repository root::

    python tools/audit_docs_numbers.py                     # every page: file:line: text, then counts
    python tools/audit_docs_numbers.py docs/flutter.md     # one page
    python tools/audit_docs_numbers.py --count             # the counts only
    python tools/audit_docs_numbers.py --integers          # also bare integers of 2+ digits (counts such as
                                                           # "704 evaluations"; years left out)
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
REGION = re.compile(r"<!-- figures:([\w-]+) -->.*?<!-- /figures:\1 -->", re.DOTALL)
FENCE = re.compile(r"^```.*?^```", re.DOTALL | re.MULTILINE)
NUMBER = re.compile(r"(?<![\w./-])[−+-]?\d[\d,]*\.\d+"
                    r"|(?<![\w./])\d+(?:\.\d+)?\s?(?:%|×|x\b|µs|us\b|ms\b|s\b|rad/s|m\b|Hz|steps)")
#: Bare integers of two or more digits (``--integers``), not inside words, paths or section numbers.
INTEGER = re.compile(r"(?<![\w./§-])\d{2,}(?![\w.])")


def _counts_integer(line: str) -> bool:
    """Whether ``line`` holds a bare integer of 2+ digits that is not a year (1900-2099)."""
    return any(not 1900 <= int(m.group(0)) <= 2099 for m in INTEGER.finditer(line))


def _blank(match: re.Match) -> str:
    """The matched text with everything but its line breaks removed (keeps line numbers)."""
    return "\n" * match.group(0).count("\n")


def hits(path: Path, integers: bool = False) -> list[tuple[int, str]]:
    """``(line number, line)`` of every line of ``path`` quoting a number outside regions and code fences
    (with ``integers``, bare integers of 2+ digits count too)."""
    text = FENCE.sub(_blank, REGION.sub(_blank, path.read_text(encoding="utf-8")))
    return [(i, line) for i, line in enumerate(text.splitlines(), 1)
            if NUMBER.search(line) or (integers and _counts_integer(line))]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pages", nargs="*", type=Path, help="pages to scan (default: README.md and docs/*.md)")
    parser.add_argument("--count", action="store_true", help="print only the number of lines per page")
    parser.add_argument("--integers", action="store_true", help="also list lines with bare integers of 2+ digits")
    args = parser.parse_args(argv)
    pages = args.pages or [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    total = 0
    counts = []
    for page in pages:
        found = hits(page, args.integers)
        total += len(found)
        counts.append(f"{page.name}: {len(found)} lines with numbers outside regions")
        if not args.count:
            for lineno, line in found:
                print(f"{page.name}:{lineno}: {line.strip()}")
    print("\n".join(counts))
    print(f"total {total}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
