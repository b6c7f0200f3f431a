"""Shared pytest configuration for flexsim's tests.

Tiers (markers registered in pyproject.toml): the default run, ``python3 -m pytest``, leaves out ``slow`` (long
studies: ``pytest -m slow``); ``docs`` marks the tests that run the documentation in child interpreters (every
Python block of README.md and docs/*.md, the fast docs figures, the examples' ``--help``), so
``pytest -m "not slow and not docs"`` is the quick development tier.
"""

import os
import signal
import sys
from pathlib import Path

import pytest

# Test the installed flexsim (README: python3 -m pip install ".[test]" && python3 -m pytest; tests/installed.py):
# ``python3 -m pytest`` from the checkout puts its root first on sys.path (the working directory, and pytest's rootdir
# for the package ``tests``), where ``flexsim/`` is the source tree, without ``flexsim.envs``. Take the root off before
# flexsim is first imported and import it now, so that every later ``import flexsim...`` finds the installed copy (an
# editable install finds the checkout itself, through its own finder).
_ROOT = Path(__file__).resolve().parents[1]
sys.path[:] = [p for p in sys.path if Path(p or os.curdir).resolve() != _ROOT]
try:
    import flexsim  # noqa: E402,F401
except ModuleNotFoundError:
    raise pytest.UsageError('flexsim is not installed in this interpreter: python3 -m pip install ".[test]" '
                            '(or -e ".[test]" for an editable install), then python3 -m pytest') from None

# Small dense linear algebra does not benefit from BLAS threads and suffers from oversubscription
# (see docs/performance.md, "BLAS threads"); pin before numpy is imported by the tests.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")

# A run started with SIGINT ignored (in the background of a non-interactive shell, under GNU time) passes that on to
# every child: the Rerun servers of tests/io/test_viewer.py then ignore the SIGINT that stops them and are killed
# after 10 s each. With Python's own handler, as in a terminal, the children start with the default disposition.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

#: Test files (relative to tests/) whose tests run the documentation, and single tests of other files.
DOCS_FILES = {"test_docs.py", "test_examples_help.py", "test_readme_commands.py"}
DOCS_TESTS = {"test_docs_figures.py::test_the_fast_figures_are_current"}


def pytest_collection_modifyitems(config, items):
    for item in items:
        rel = item.nodeid.split("tests/", 1)[-1]
        if rel.split("::")[0] in DOCS_FILES or rel.split("[")[0] in DOCS_TESTS:
            item.add_marker(pytest.mark.docs)
