"""flexsim.linear._precompile: the two groups of the first compile name the signatures the search uses.

After a flutter point (US and FS, so every kernel of the search has run), each (kernel, argument types) of either
group is a signature the search compiled: among the kernel's signatures in this process, or, for a kernel only
called by another compiled kernel that this process loaded from numba's cache (so the callee itself was not
loaded), among the signatures in the callee's cache index for its current source. A kernel whose arguments
changed fails here, instead of leaving the split compile to build code nobody loads.
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
    for dispatcher, args in _precompile._signatures() + _precompile._signatures_here():
        compiled = [tuple(s) for s in dispatcher.signatures]
        if tuple(args) not in compiled:  # a callee of a kernel loaded from the cache: its index holds its signatures
            compiled = [tuple(key[0]) for key in dispatcher._cache._cache_file._load_index()]
        assert tuple(args) in compiled, (dispatcher.py_func.__name__, compiled)


def test_no_helper_when_the_group_is_cached(monkeypatch):
    monkeypatch.setattr("flexsim._numba_cache.is_cached", lambda *d: True)
    assert _precompile.start() is None


def test_no_helper_without_an_idle_core(monkeypatch):
    monkeypatch.setattr("flexsim._numba_cache.is_cached", lambda *d: False)
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    for load in (8.0, 1.6):  # 1.6 on 2 cores: this process and more than half a core of other work
        monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
        assert _precompile.start() is None
