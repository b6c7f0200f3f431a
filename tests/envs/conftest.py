"""Shared helpers of the environment tests (see each test module for what it checks)."""

import sys
from pathlib import Path

import pytest

from flexsim import envs  # noqa: F401  (registers the FlexSim/* ids)

AGENTS = Path(__file__).resolve().parents[2] / "examples" / "agents"


@pytest.fixture(scope="session")
def agents_path():
    """Puts examples/agents on sys.path (the baselines are scripts, not a package)."""
    sys.path.insert(0, str(AGENTS))
    yield AGENTS
    sys.path.remove(str(AGENTS))
