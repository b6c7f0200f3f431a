"""Regenerate the figures quoted in README.md and docs/*.md from the current code, or check them.

Each figure lives in a marked region of a document (HTML comments, invisible when rendered; inline or spanning
lines; one name may mark several regions): ``<!-- figures:NAME -->...<!-- /figures:NAME -->``. The script
recomputes each region's text (:data:`FIGURES`) and compares it with the document **at the precision printed**
(:func:`difference`): the text between the numbers must be equal, counts (integers) equal, and every other number
within one unit of its last printed digit (two correct roundings of values less than a unit apart differ by at most
one unit), or within the figure's ``rtol`` (adaptive integrators and searches, whose step or iteration sequence
round-off can move). A region that agrees is left alone; a stale one is rewritten (``--check``: named, exit 1).
Round-off residuals are never printed: a figure prints the bound it checks. The plain command also redraws
``docs/figures/flutter_turn*.png`` and ``flutter_climb*.png`` from the study run.

``fast`` figures (well under a minute together) are checked by the default test suite
(``tests/test_docs_figures.py``); the others (the turn and climb studies, the environments, the simulation
accuracy table: about 3 minutes on a 2-core machine with the numba kernels cached) under ``pytest -m slow``. From
the repository root::

    python tools/regenerate_docs_figures.py                 # rewrite every stale region, redraw docs/figures
    python tools/regenerate_docs_figures.py --check         # exit 1 if a region is stale
    python tools/regenerate_docs_figures.py --check --fast  # the fast figures only
    python tools/regenerate_docs_figures.py --only readme-calibration
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import os
import re
import sys
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_flutter import _draw_study_figures  # noqa: E402

#: The figure modules: each public function defined in one computes the text of the regions of its name (``_`` read
#: as ``-``), with the settings of its ``figure_text.figure`` mark.
MODULES = [importlib.import_module(f"docs_figures_{name}") for name in ("flutter", "static", "studies", "usage", "envs")]
REGION = re.compile(r"<!-- figures:(?P<name>[\w-]+) -->(?P<body>.*?)<!-- /figures:(?P=name) -->", re.DOTALL)
#: A number as the docs print it: a sign (ASCII or typographic minus), digits (thousands separated by commas),
#: decimals, an exponent. Not inside a word: the digits of ``DOP853``, ``C1``, ``v0`` are text.
NUMBER = re.compile(r"(?<![\w.])[+\-−]?(?:\d{1,3}(?:,\d{3})+(?!\d)|\d+)(?:\.\d+)?(?:[eE][+\-−]?\d+)?")
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


class Figure(NamedTuple):
    """A figure: the function computing its text; ``fast``: checked by the default test suite; ``study``: the study
    it reads ("turn", "climb": its plots are redrawn); ``rtol``: a tolerance beyond the printed precision."""

    compute: Callable[[], str]
    fast: bool = True
    study: str | None = None
    rtol: float = 0.0


def _value(number: str) -> tuple[float, float, str]:
    """A printed number's value, the unit of its last digit and its kind: "count", "fixed" or "e<exponent>"."""
    text = number.replace("−", "-").replace(",", "")
    mantissa, e, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    kind = f"e{int(exponent)}" if e else "fixed" if "." in mantissa else "count"
    return float(text), 10.0 ** (int(exponent or 0) - decimals), kind


def difference(old: str, new: str, rtol: float = 0.0) -> str | None:
    """How ``old`` differs from ``new`` at the printed precision (None: they agree): equal text and counts, other
    numbers within one unit of the coarser last digit (same exponent: ``1e-12`` is not ``1e-11``) or ``rtol``."""
    old_text, new_text = NUMBER.split(old), NUMBER.split(new)
    if old_text != new_text:
        a, b = next(((a, b) for a, b in zip(old_text, new_text) if a != b), (old_text[-1], new_text[-1]))
        return f"text {a.strip()[:60]!r} against {b.strip()[:60]!r}" if a != b else "a different count of numbers"
    for a, b in zip(NUMBER.findall(old), NUMBER.findall(new)):
        (x, unit_a, kind_a), (y, unit_b, kind_b) = _value(a), _value(b)
        scientific = kind_a.startswith("e") or kind_b.startswith("e")
        digits = kind_a == kind_b if scientific else "fixed" in (kind_a, kind_b)
        if abs(x - y) > max(max(unit_a, unit_b) * (1 + 1e-9) if digits else 0.0, rtol * max(abs(x), abs(y))):
            return f"{a} against {b}"
    return None


FIGURES: dict[str, Figure] = {name.replace("_", "-"): Figure(f, **getattr(f, "figure", {}))
                               for module in MODULES for name, f in vars(module).items()
                               if inspect.isfunction(f) and f.__module__ == module.__name__ and not name.startswith("_")}


def regions(text: str) -> list[re.Match]:
    """The marked regions of a document."""
    return list(REGION.finditer(text))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0], epilog="Figures: " + ", ".join(FIGURES))
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 if a region is stale")
    parser.add_argument("--only", action="append", choices=list(FIGURES), metavar="NAME",
                        help="regenerate this figure only (repeatable)")
    parser.add_argument("--fast", action="store_true",
                        help=f"only the fast figures ({', '.join(n for n, f in FIGURES.items() if f.fast)})")
    args = parser.parse_args(argv)
    wanted = [name for name in args.only or FIGURES if FIGURES[name].fast or not args.fast]
    values: dict[str, str] = {}
    stale = []
    for doc in DOCUMENTS:
        text = doc.read_text(encoding="utf-8")
        changed = {}
        for m in regions(text):
            name = m.group("name")
            if name not in wanted:
                continue
            if name not in values:
                print(f"computing {name} ...", flush=True)
                values[name] = FIGURES[name].compute()
            why = difference(m.group("body"), values[name], FIGURES[name].rtol)
            if why is not None:
                stale.append(f"{doc.relative_to(ROOT)}: {name} ({why})")
                changed[m.start()] = values[name]
        if changed and not args.check:
            doc.write_text(REGION.sub(lambda m: m.group(0) if m.start() not in changed else
                                      f"<!-- figures:{m.group('name')} -->{changed[m.start()]}<!-- /figures:{m.group('name')} -->",
                                      text), encoding="utf-8")
    missing = [name for name in wanted if name not in values]
    if missing:
        print(f"no region in the docs for: {', '.join(missing)}", file=sys.stderr)
        return 1
    studies = sorted({FIGURES[name].study for name in values} - {None})
    if not args.check and studies:
        for path in _draw_study_figures(studies):
            print(f"drew {path.relative_to(ROOT)}")
    if stale:
        print(("stale: " if args.check else "rewritten: ") + "; ".join(stale))
        return 1 if args.check else 0
    print("all regions up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
