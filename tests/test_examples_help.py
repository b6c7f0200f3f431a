"""Every script under examples/ answers ``--help`` with a usage text and exit code 0.

Run as a user runs them: ``python examples/....py --help`` from the repository root, with the installed flexsim the
tests import (:func:`tests.installed.child_env`). A script without a command line would print nothing and exit 0, so
the test asks for the ``usage:`` line and a description.
"""

import subprocess
import sys
from pathlib import Path

import pytest

from tests.installed import child_env

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted(p for p in (ROOT / "examples").rglob("*.py") if p.name != "__init__.py")


def test_examples_exist():
    assert {"baselines.py", "lqr_design.py", "evaluate_baselines.py", "train_sb3.py"} <= {p.name for p in SCRIPTS}


@pytest.mark.parametrize("script", SCRIPTS, ids=[str(p.relative_to(ROOT)) for p in SCRIPTS])
def test_example_answers_help(script):
    run = subprocess.run([sys.executable, str(script), "--help"], cwd=ROOT, env=child_env(), capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    lines = run.stdout.strip().splitlines()
    assert lines and lines[0].startswith("usage:") and len(lines) >= 4, run.stdout
