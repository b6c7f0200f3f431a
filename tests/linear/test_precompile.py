"""flexsim.linear._precompile: the p-k group compiled on a second core names the signatures the search uses.

After a flutter point (US and FS, so every p-k kernel has run), each (kernel, argument types) of the group is among
the kernel's compiled signatures in this process: a kernel whose arguments changed fails here, instead of leaving
the background compile to build code nobody loads.
"""

import os

import pytest

from flexsim.linear import _precompile
from flexsim.linear.study import StudyCase, run_point


@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="nothing is compiled")
def test_group_signatures_are_those_the_search_compiles():
    for model in ("US", "FS"):
        row, _ = run_point(StudyCase("gtm", model, 9144.0, mach_min=0.85, mach_max=0.95))
        assert "mach" in row
    for dispatcher, args in _precompile._signatures():
        assert tuple(args) in [tuple(s) for s in dispatcher.signatures], (dispatcher.py_func.__name__, dispatcher.signatures)


def test_no_helper_when_the_group_is_cached(monkeypatch):
    monkeypatch.setattr("flexsim._numba_cache.is_cached", lambda *d: True)
    assert _precompile.start() is None


def test_no_helper_without_an_idle_core(monkeypatch):
    monkeypatch.setattr("flexsim._numba_cache.is_cached", lambda *d: False)
    monkeypatch.setattr(_precompile, "idle_cores", lambda window_s=0.2: 0.3)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    assert _precompile.start() is None


def test_idle_cores_is_between_zero_and_the_core_count():
    idle = _precompile.idle_cores(0.05)
    assert 0.0 <= idle <= (os.cpu_count() or 1) + 1e-9
