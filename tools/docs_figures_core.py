"""The figure registry entry and the long-study checkpoints of ``tools/regenerate_docs_figures.py``.

A module of figures (``tools/docs_figures_*.py``) registers each figure as a :class:`Figure`: the function that
computes the region's text and its tier,

* ``fast``: run by the default test suite (``--check --fast``), well under a minute;
* neither: a slow figure (minutes), run by ``--check`` under ``pytest -m slow``;
* ``long``: a long study (10 minutes to an hour: the recorded configurations of docs/calibration.md and
  docs/flutter.md), run by the plain command, left out by ``--skip-long`` and by every test.

A long figure computes its study points through :func:`checkpoint`, one call per finished piece of work (a
configuration, or one altitude of it): the JSON result is stored under :data:`CACHE_DIR` keyed by content (the
figure's name for the piece, its arguments and :func:`source_digest`, the SHA-256 of every source and data file
under ``flexsim/`` and ``studies/``), so an interrupted regeneration resumes at the first unfinished piece, and a
change to the code or to the arguments recomputes everything it can affect — never a stale result by name or date.

Use (docsb, docsa)::

    from docs_figures_core import Figure, checkpoint

    def c1_rows(h):
        return checkpoint("paper-residuals", {"config": "C1", "model": "US", "altitude_m": h, ...},
                          lambda: density_finding.run(...))   # JSON data: dicts, lists, str, float, int, None

    MY_FIGURES = {"calibration-c1": Figure(c1_table, long=True)}

and add ``**MY_FIGURES`` to ``FIGURES`` in ``tools/regenerate_docs_figures.py``. The value :func:`checkpoint`
returns is always the JSON round trip of the computed one (tuples become lists, keys strings), also on the first
call, so a figure reads the same data whether it was computed now or resumed.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any, NamedTuple

ROOT = Path(__file__).resolve().parents[1]
#: Where long studies' finished pieces are stored (outside the repository; ``FLEXSIM_DOCS_FIGURES_CACHE``
#: overrides it, the tests point it at ``tmp_path``).
CACHE_DIR = Path(os.environ.get("FLEXSIM_DOCS_FIGURES_CACHE",
                                Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "flexsim" / "docs-figures"))
#: The folders whose content keys a checkpoint.
SOURCE_DIRS = ("flexsim", "studies")
#: Files that are not source (byte code, numba's cache): left out of the digest.
_NOT_SOURCE = (".pyc", ".pyo", ".nbi", ".nbc")


class Figure(NamedTuple):
    """A figure of the docs: the function computing its text, and its tier (``fast``: default test suite;
    ``long``: a long study, left out by ``--skip-long`` and by the tests; neither: slow, ``pytest -m slow``)."""

    compute: Callable[[], str]
    fast: bool = False
    study: str | None = None  # "turn" / "climb": the study it reads, whose docs/figures/flutter_<study>*.png are redrawn
    long: bool = False


@functools.cache
def source_digest(root: Path = ROOT) -> str:
    """SHA-256 over the relative path and bytes of every file under ``flexsim/`` and ``studies/`` of ``root``
    (``__pycache__`` and numba's cache left out)."""
    h = hashlib.sha256()
    for folder in SOURCE_DIRS:
        for path in sorted((root / folder).rglob("*")):
            if not path.is_file() or "__pycache__" in path.parts or path.suffix in _NOT_SOURCE:
                continue
            h.update(str(path.relative_to(root)).encode() + b"\0")
            h.update(path.read_bytes() + b"\0")
    return h.hexdigest()


def checkpoint_path(name: str, args: dict, cache_dir: Path | None = None, source: str | None = None) -> Path:
    """The file of one piece of a long study: ``<cache>/<name>/<sha256 of name, args and the source>.json``
    (``source``: the :func:`source_digest` of this tree unless given)."""
    if not name or not name.replace("-", "").replace("_", "").isalnum():
        raise ValueError(f"checkpoint name {name!r}: letters, digits, '-' and '_' only")
    key = json.dumps({"name": name, "args": args, "source": source or source_digest()}, sort_keys=True, allow_nan=True)
    return (cache_dir or CACHE_DIR) / name / f"{hashlib.sha256(key.encode()).hexdigest()}.json"


def checkpoint(name: str, args: dict, compute: Callable[[], Any], cache_dir: Path | None = None,
               source: str | None = None) -> Any:
    """The result of ``compute()`` (JSON data) for this piece of a long study, from its checkpoint if one was
    stored for the same name, arguments and source digest, else computed now and stored (written to a temporary
    file and renamed, so an interrupted write leaves no partial checkpoint).

    ``args`` must determine the result together with the code (every input of ``compute``: aircraft, factors,
    options, altitudes, starting values); it is stored beside the result for reading. ``source`` replaces the
    tree's source digest in the key when the result comes from other code."""
    path = checkpoint_path(name, args, cache_dir, source)
    if path.is_file():
        stored = json.loads(path.read_text(encoding="utf-8"))
        print(f"  {name}: resumed from {path}", flush=True)
        return stored["result"]
    result = json.loads(json.dumps(compute(), allow_nan=True))
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, suffix=".tmp", delete=False, encoding="utf-8") as f:
        json.dump({"name": name, "args": args, "source": source or source_digest(), "result": result}, f, indent=1)
    os.replace(f.name, path)
    return result


