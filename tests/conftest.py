"""Shared pytest configuration for flexsim's tests.

Tiers (markers registered in pyproject.toml): the default run, ``python3 -m pytest``, leaves out ``slow`` (long
studies: ``pytest -m slow``); ``docs`` marks the tests that run the documentation in child interpreters (every
Python block of README.md and docs/*.md, the fast docs figures, the examples' ``--help``), so
``pytest -m "not slow and not docs"`` is the quick development tier.
"""

import os

import pytest

# Small dense linear algebra does not benefit from BLAS threads and suffers from oversubscription
# (see docs/design.md, "Performance"); pin before numpy is imported by the tests.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")

#: Test files (relative to tests/) whose tests run the documentation, and single tests of other files.
DOCS_FILES = {"test_docs.py", "test_examples_help.py"}
DOCS_TESTS = {"test_docs_figures.py::test_the_fast_figures_are_current"}


def pytest_collection_modifyitems(config, items):
    for item in items:
        rel = item.nodeid.split("tests/", 1)[-1]
        if rel.split("::")[0] in DOCS_FILES or rel.split("[")[0] in DOCS_TESTS:
            item.add_marker(pytest.mark.docs)
