"""flexsim._numba_cache.depends_on: a cached caller recompiles when the file of a compiled callee changes.

Two throw-away modules under tmp_path: ``callee.py`` (``f() -> 1``) and ``caller.py`` (``g() -> callee.f()``, numba
``cache=True``). Each run is a fresh interpreter (so numba reads its on-disk cache); after ``f`` is changed to return 2,
``g`` must return 2. Without ``depends_on`` numba returns the stale 1 (checked too, so the test can fail: it shows
the hazard the decorator exists for).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.installed import child_env


CALLER = """
from numba import njit
import callee
from flexsim._numba_cache import depends_on

{decorator}
@njit(cache=True)
def g():
    return callee.f()

print(g())
"""


def _run(tmp_path: Path) -> int:
    env = child_env(tmp_path)
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run([sys.executable, str(tmp_path / "caller.py")], env=env, capture_output=True, text=True,
                         check=True, cwd=tmp_path)
    return int(out.stdout.split()[-1])


@pytest.mark.parametrize("decorated", [True, False])
def test_cached_caller_sees_changed_callee(tmp_path, decorated):
    (tmp_path / "caller.py").write_text(CALLER.format(decorator="@depends_on(callee)" if decorated else ""))
    (tmp_path / "callee.py").write_text("from numba import njit\n\n@njit(cache=True)\ndef f():\n    return 1\n")
    assert _run(tmp_path) == 1
    assert _run(tmp_path) == 1  # from the cache
    (tmp_path / "callee.py").write_text("from numba import njit\n\n@njit(cache=True)\ndef f():\n    return 2  # changed\n")
    assert _run(tmp_path) == (2 if decorated else 1)  # numba alone keeps the stale machine code of f inside g


def test_step_kernels_are_keyed_on_the_rhs_source():
    """The ETD2RK kernels' cache stamp includes the digest of the package flexsim._kernels and of the measurements
    they embed (flexsim.sim.measurements)."""
    from flexsim import _kernels
    from flexsim._numba_cache import source_digest
    from flexsim.sim import _step_kernels, measurements

    cache = getattr(_step_kernels.etd2rk_rows, "_cache", None)
    if cache is None:
        pytest.skip("NUMBA_DISABLE_JIT=1: no cache")
    for kernel in (_step_kernels.etd2rk_rows, _step_kernels.period_rows):
        assert kernel._cache._cache_file._source_stamp[1] == source_digest(_kernels, measurements)


PACKAGE_CALLER = """
import sys
from numba import njit
from flexsim._numba_cache import depends_on
from pkg import callee

@depends_on(sys.modules[__package__])
@njit(cache=True)
def g():
    return callee.f()
"""


def test_package_digest_covers_its_files(tmp_path):
    """A kernel keyed on its package (as flexsim._kernels' kernels are) recompiles when a sibling file changes."""
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "caller.py").write_text(PACKAGE_CALLER)
    (pkg / "callee.py").write_text("from numba import njit\n\n@njit(cache=True)\ndef f():\n    return 1\n")
    (tmp_path / "main.py").write_text("from pkg.caller import g\nprint(g())\n")
    run = tmp_path / "caller.py"  # _run runs tmp_path/caller.py
    run.write_text("import runpy\nrunpy.run_path('main.py')\n")
    assert _run(tmp_path) == 1
    assert _run(tmp_path) == 1
    (pkg / "callee.py").write_text("from numba import njit\n\n@njit(cache=True)\ndef f():\n    return 2  # changed\n")
    assert _run(tmp_path) == 2


def test_every_kernel_is_keyed_on_the_whole_kernel_package():
    """Each compiled kernel of flexsim._kernels carries the package's digest in its cache stamp (its callees are in
    sibling files of the package)."""
    import flexsim._kernels as package
    from flexsim._numba_cache import source_digest

    if getattr(package.rhs, "_cache", None) is None:
        pytest.skip("NUMBA_DISABLE_JIT=1: no cache")
    digest = source_digest(package)
    kernels = [obj for name in ("layout", "isa", "structure", "strips", "drag", "wind", "solve", "equations")
               for obj in vars(getattr(package, name)).values() if hasattr(obj, "_cache") and hasattr(obj, "py_func")
               and obj.targetoptions.get("inline") != "always"]  # inlined accessors compile inside their callers
    assert len(kernels) > 30
    for kernel in kernels:
        if kernel.py_func.__module__.startswith("flexsim._kernels"):
            assert kernel._cache._cache_file._source_stamp[1] == digest, kernel


def test_announce_compilation_says_it_once_on_a_compile_and_is_cached_sees_the_index(tmp_path, monkeypatch):
    """One line when a flexsim function compiles (numba's compile event), none for a function of another package;
    is_cached is False before the first call of a cache=True function and True after it (its index is saved)."""
    import io

    import numba

    from flexsim._numba_cache import announce_compilation, is_cached

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    src = tmp_path / "probe_kernels.py"
    src.write_text("def twice(x):\n    return 2.0 * x\n")
    namespace = {"__name__": "flexsim.probe_kernels", "__file__": str(src)}
    exec(compile(src.read_text(), str(src), "exec"), namespace)
    flexsim_fn = numba.njit(cache=True)(namespace["twice"])
    other = numba.njit(lambda x: 3.0 * x)
    stream = io.StringIO()
    with announce_compilation(stream):
        other(1.0)
        assert stream.getvalue() == ""
        assert not is_cached(flexsim_fn)
        assert flexsim_fn(2.0) == 4.0
        flexsim_fn(2)  # a second compile: no second line
    assert stream.getvalue().count("\n") == 1 and "compiling" in stream.getvalue()
    assert is_cached(flexsim_fn)


def _wait_idle(progress, timeout_s: float = 10.0) -> None:
    import time

    deadline = time.monotonic() + timeout_s
    while progress._timer is not None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert progress._timer is None, "the progress timer did not end after the compiles"


def test_compile_progress_moves_while_one_function_compiles(monkeypatch):
    """A log gets the announcement once per process, then a line every LOG_INTERVAL_S while a compile runs (so that a
    first run is never silent for long, even inside one large function), and the totals; a terminal gets one status
    line, redrawn in place (at most 78 characters, so it never wraps), erased when the compiles end."""
    import io
    import time

    from flexsim import _numba_cache as nc

    monkeypatch.setattr(nc, "LOG_INTERVAL_S", 0.2)
    monkeypatch.setattr(nc, "TTY_INTERVAL_S", 0.05)
    log = io.StringIO()
    progress = nc.CompileProgress(log, tty=False)
    progress.start("flexsim._kernels.equations.rhs")
    progress.start("flexsim._kernels.strips.strip_wind")
    time.sleep(0.9)
    progress.end()
    progress.end()
    _wait_idle(progress)
    lines = log.getvalue().splitlines()
    assert lines[0].startswith("flexsim: compiling the numerical kernels") and "cached for later runs" in lines[0]
    status = [ln for ln in lines if ln.startswith("flexsim: compiling kernels:")]
    assert len(status) >= 2 and "(now strip_wind)" in status[0]
    assert lines[-1].startswith("flexsim: compiled 2 functions in")
    progress.start("flexsim.sim._step_kernels.etd2rk_rows")  # another burst: no second announcement
    progress.end()
    _wait_idle(progress)
    assert log.getvalue().count("compiling the numerical kernels") == 1

    tty = io.StringIO()
    progress = nc.CompileProgress(tty, tty=True)
    progress.start("flexsim.linear._pk_kernels." + "a_very_long_kernel_name" * 4)
    time.sleep(0.3)
    progress.end()
    _wait_idle(progress)
    text = tty.getvalue()
    assert "\n" not in text and text.count("\r\033[K") >= 3 and text.endswith("\r\033[K")
    drawn = [part for part in text.split("\r\033[K") if part]
    assert drawn and all(len(part) <= 78 for part in drawn) and "compiling kernels" in drawn[-1]


def test_compile_progress_is_on_for_the_process():
    """Importing flexsim's kernels turns the progress display on for the whole process (the CLI and the Python API),
    unless FLEXSIM_COMPILE_PROGRESS=0."""
    import os

    import flexsim._kernels  # noqa: F401
    from flexsim import _numba_cache as nc

    if os.environ.get(nc.PROGRESS_ENV, "1") == "0":
        assert nc._PROCESS_PROGRESS is None
    else:
        assert isinstance(nc._PROCESS_PROGRESS, nc.CompileProgress)
