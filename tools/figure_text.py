"""How the figure modules (``docs_figures_*.py``) write numbers and tables, and how they mark a figure that is not
fast; importing it puts the repository, ``studies/`` and ``examples/agents/`` on the path (their scripts are
imported, never copied)."""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
for _folder in (ROOT / "examples" / "agents", ROOT / "studies", ROOT):
    if str(_folder) not in sys.path:
        sys.path.insert(0, str(_folder))


def figure(fast: bool = True, study: str | None = None, rtol: float = 0.0):
    """Mark a figure function with the settings of ``regenerate_docs_figures.Figure`` other than the defaults."""
    def mark(compute):
        compute.figure = {"fast": fast, "study": study, "rtol": rtol}
        return compute
    return mark


def num(x: float, fmt: str) -> str:
    """``format(x, fmt)`` with a typographic minus (as the docs write negative numbers)."""
    return format(x, fmt).replace("-", "−")


def exponent(x: float, fmt: str = ".0e") -> str:
    """``x`` as the docs write a small number: ``1e-12``, ``2.5e-6`` (no leading zero in the exponent)."""
    return format(x, fmt).replace("e-0", "e-")


def span(values, fmt: str, sep: str = "-") -> str:
    """``lo-hi`` of ``values`` in ``fmt``, one number where both print alike."""
    lo, hi = num(min(values), fmt), num(max(values), fmt)
    return lo if lo == hi else f"{lo}{sep}{hi}"


def table(header: str, rows: Iterable[Iterable[str]]) -> str:
    """A markdown table between a blank line and a line end: ``header`` (``"| a | b |"``), ``|---|---|`` and a row of
    cells per item of ``rows``."""
    return "\n".join(["", header, "|---" * (header.count("|") - 1) + "|",
                      *("| " + " | ".join(cells) + " |" for cells in rows)]) + "\n"
