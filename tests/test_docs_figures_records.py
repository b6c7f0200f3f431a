"""The historical rows of docs/flutter.md (``tools/docs_figures_records.py``) fail with a clear message, naming the
commit, where the repository's git history is missing (an sdist, a shallow clone)."""

import importlib
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _records():
    sys.path.insert(0, str(ROOT / "tools"))
    sys.path.insert(0, str(ROOT / "studies"))
    return importlib.import_module("docs_figures_records")


def test_without_git_history_the_historical_rows_name_the_commit(tmp_path, monkeypatch):
    records = _records()
    core = importlib.import_module("docs_figures_core")
    monkeypatch.setattr(core, "ROOT", tmp_path)  # not a git repository
    monkeypatch.setattr(core, "CACHE_DIR", tmp_path / "cache")
    with pytest.raises(RuntimeError, match="b32192e.*not in this checkout's git history"):
        records._historical.__wrapped__(records.GTM, ("none",), "decomposition-historical")


def test_the_recorded_command_is_the_scripts_own_spelling():
    """The command a historical figure runs parses with the study script's own options (today's parser; the
    options are the same at b32192e), so the docs quote a command that runs."""
    records = _records()
    args = records.C1.args(["none"])
    assert args[:2] == ["--scaling", records.C1.get("--scaling")]
    assert args[args.index("--incidence") + 1: args.index("--incidence") + 3] == ["1.81", "2.7"]
    run = subprocess.run([sys.executable, str(ROOT / "studies" / "manoeuvre_decomposition.py"), *args, "--help"],
                         capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert run.returncode == 0, run.stderr
