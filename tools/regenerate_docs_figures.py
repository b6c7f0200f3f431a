"""Regenerate the figures quoted in README.md and docs/*.md that this script owns (or check them).

Each figure lives in a marked region of a document::

    <!-- figures:NAME -->...<!-- /figures:NAME -->

(HTML comments: invisible on rendered pages; regions may be inline, e.g. inside a table cell, or span lines).
This script recomputes the text of every region from the code and rewrites it; ``--check`` only compares and
exits 1 naming every region that differs. ``tests/test_docs_figures.py`` checks that every region in the docs
names a known figure (fast) and runs ``--check`` under ``pytest -m slow``.

Figures (name: document, what, time on a quiet 2-core machine):

* ``readme-calibration``: README.md, US (Theodorsen p-k) flutter Mach of the bundled gtm against the paper's
  Table 3 at 0, 3048, 6096, 9144 m, as ``flexsim flutter --models US`` prints it (about 15 s);
* ``env-baselines``: docs/environments.md, the baseline and random returns of every environment over seeds 0-9
  (``examples/agents/evaluate_baselines.py --episodes 10``; about 4 minutes).

Other quoted figures come from their own scripts, named beside them: ``studies/calibrate_gtm.py``
(docs/calibration.md), ``flexsim flutter`` / ``flexsim sweep`` (docs/flutter.md, docs/figures/), ``benchmarks/``
(docs/performance.md and the speed tables, dated).

Run from the repository root::

    python tools/regenerate_docs_figures.py                 # rewrite every region
    python tools/regenerate_docs_figures.py --check         # exit 1 if a region is stale
    python tools/regenerate_docs_figures.py --only readme-calibration
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from collections.abc import Callable
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
REGION = re.compile(r"<!-- figures:(?P<name>[\w-]+) -->(?P<body>.*?)<!-- /figures:(?P=name) -->", re.DOTALL)
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def readme_calibration() -> str:
    """US M_F of the bundled gtm against paper Table 3, e.g. ``+0.1 %, +1.2 %, +11.6 % and +17.1 % at 0, ...``."""
    from flexsim.linear.paper_data import TABLE_US
    from flexsim.linear.study import StudyCase, run_study

    altitudes = [row[0] for row in TABLE_US]
    rows = run_study([StudyCase("gtm", "US", h) for h in altitudes], workers=2, progress=False)
    diffs = []
    for h, ref in zip(altitudes, TABLE_US):
        (row,) = [r for r in rows if r["altitude_m"] == h]
        if "error" in row:
            raise RuntimeError(f"readme-calibration: no US flutter point at {h:g} m: {row['error']}")
        diffs.append(f"{100 * (row['mach'] / ref[1] - 1):+.1f} %")
    return (f"US M_F {', '.join(diffs[:-1])} and {diffs[-1]} against the paper at "
            f"{', '.join(f'{h:g}' for h in altitudes[:-1])} and {altitudes[-1]:g} m")


def env_baselines() -> str:
    """The markdown table of baseline and random returns (seeds 0-9, full episodes, default settings)."""
    sys.path.insert(0, str(ROOT / "examples" / "agents"))
    from evaluate_baselines import evaluate

    from baselines import BASELINES

    lines = ["", "| id | baseline return | random return | random episodes end by |", "|---|---|---|---|"]
    for env_id in BASELINES:
        import gymnasium as gym

        limit = gym.spec(env_id).max_episode_steps
        result = evaluate(env_id, 10)
        base, rand = result["baseline"], result["random"]
        reasons = [r for r in rand["reasons"] if r]
        if not reasons:
            ending = "time limit"
        else:
            common = max(set(reasons), key=reasons.count)
            ending = f"{common.replace('_', ' ')} ({reasons.count(common)}/10), {rand['lengths'].mean():.0f} steps on average"
        label = env_id.removeprefix("FlexSim/GTM-").removesuffix("-v0")
        lines.append(f"| {label} (max {limit}) | {base['returns'].mean():.1f} +- {base['returns'].std():.1f} | "
                     f"{rand['returns'].mean():.1f} +- {rand['returns'].std():.1f} | {ending} |")
    return "\n".join(lines) + "\n"


FIGURES: dict[str, Callable[[], str]] = {"readme-calibration": readme_calibration, "env-baselines": env_baselines}


def regions(text: str) -> list[re.Match]:
    """The marked regions of a document."""
    return list(REGION.finditer(text))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     epilog="Figures: " + ", ".join(FIGURES))
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 if a region is stale")
    parser.add_argument("--only", action="append", choices=list(FIGURES), metavar="NAME",
                        help=f"regenerate this figure only (repeatable; one of {', '.join(FIGURES)})")
    args = parser.parse_args(argv)
    wanted = args.only or list(FIGURES)
    values: dict[str, str] = {}
    stale = []
    for doc in DOCUMENTS:
        text = doc.read_text(encoding="utf-8")
        found = [m for m in regions(text) if m.group("name") in wanted]
        for m in found:
            if m.group("name") not in values:
                print(f"computing {m.group('name')} ...", flush=True)
                values[m.group("name")] = FIGURES[m.group("name")]()
        new = REGION.sub(lambda m: m.group(0) if m.group("name") not in values else
                         f"<!-- figures:{m.group('name')} -->{values[m.group('name')]}<!-- /figures:{m.group('name')} -->", text)
        if new != text:
            stale += [f"{doc.relative_to(ROOT)}: {m.group('name')}" for m in found
                      if m.group("body") != values[m.group("name")]]
            if not args.check:
                doc.write_text(new, encoding="utf-8")
    missing = [name for name in wanted if name not in values]
    if missing:
        print(f"no region in the docs for: {', '.join(missing)}", file=sys.stderr)
        return 1
    if stale:
        print(("stale: " if args.check else "rewritten: ") + "; ".join(stale))
        return 1 if args.check else 0
    print("all regions up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
