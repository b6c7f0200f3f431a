"""Numba's on-disk cache made stale by the source of the kernel modules a compiled function calls into.

Numba keys the cache of a ``cache=True`` function on the source of its own file only (a SHA-256 of the file in
numba 0.68; ``numba/core/caching.py``, ``_SourceFileBackedLocatorMixin.get_source_stamp``). A function that
calls a compiled function of another file embeds that callee's machine code, so a change of the callee's file
alone leaves the caller's cached code stale: the caller would go on running the old callee (numba's
documentation, "Cache invalidation"). :func:`depends_on` adds the SHA-256 of the named files to the stamp a
dispatcher's index is saved and checked with, so such a change recompiles the caller on its next call. A
package counts as the source of all its ``.py`` files (``flexsim._kernels``: the kernels are split into modules
that call each other; each of its kernels and every compiled caller outside it depend on the whole package).

Under ``NUMBA_DISABLE_JIT=1`` the decorated object is the plain Python function and is returned unchanged.

:func:`is_cached` tells whether a dispatcher has machine code in the cache that its current source can load, and
:func:`announce_compilation` prints one line when flexsim's kernels start compiling (the first run after an
install or a change of the kernels' source: tens of seconds; a run after it loads them in about a second).
"""

from __future__ import annotations

import contextlib
import hashlib
import sys
from pathlib import Path
from types import ModuleType
from typing import Callable, Iterator, TextIO, TypeVar

__all__ = ["depends_on", "source_digest", "is_cached", "announce_compilation"]

F = TypeVar("F", bound=Callable)


def source_digest(*modules: ModuleType) -> tuple[str, ...]:
    """SHA-256 (hex) of the source files of ``modules``, in order; of a package: of the names and contents of all
    its ``.py`` files (recursively, sorted by relative path). A package may be passed while its ``__init__`` runs
    (its ``__path__`` is set by then)."""
    return tuple(_digest(m) for m in modules)


def _digest(module: ModuleType) -> str:
    paths = getattr(module, "__path__", None)
    if paths is None:
        return hashlib.sha256(Path(module.__file__).read_bytes()).hexdigest()
    h = hashlib.sha256()
    for root in map(Path, paths):
        for f in sorted(root.rglob("*.py")):
            h.update(f.relative_to(root).as_posix().encode() + b"\0")
            h.update(hashlib.sha256(f.read_bytes()).digest())
    return h.hexdigest()


def depends_on(*modules: ModuleType) -> Callable[[F], F]:
    """Decorator for a ``numba.njit(cache=True)`` dispatcher: its cache is also stale when the source of any of
    ``modules`` changes (see the module docstring). Apply it outside the ``njit`` decorator."""
    extra = source_digest(*modules)

    def wrap(dispatcher: F) -> F:
        cache_file = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
        if cache_file is None:  # NUMBA_DISABLE_JIT=1 (a Python function) or caching off
            return dispatcher
        if not hasattr(cache_file, "_source_stamp"):
            raise RuntimeError(f"numba's cache index of {dispatcher!r} has no _source_stamp: the numba version changed "
                               "the cache internals flexsim._numba_cache relies on")
        cache_file._source_stamp = (cache_file._source_stamp, extra)
        return dispatcher

    return wrap


def is_cached(*dispatchers) -> bool:
    """Whether every one of ``dispatchers`` (``numba.njit(cache=True)`` functions) has a cache index that its
    current source stamp (with :func:`depends_on`'s digests) can load, i.e. a later call loads machine code instead
    of compiling it (a new signature still compiles). True under ``NUMBA_DISABLE_JIT=1`` (nothing compiles)."""
    for dispatcher in dispatchers:
        cache_file = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
        if cache_file is None:
            if hasattr(dispatcher, "py_func"):  # a dispatcher without a cache: compiles in every process
                return False
            continue
        if not cache_file._load_index():  # numba's index loader: {} when absent or of another source stamp
            return False
    return True


@contextlib.contextmanager
def announce_compilation(stream: TextIO | None = None) -> Iterator[None]:
    """Within the block, print one line on ``stream`` (default ``sys.stderr``) when numba first starts compiling
    a function of flexsim in this process (numba's ``numba:compile`` event, which fires on compilation only, not
    on a load from the cache)."""
    from numba.core import event

    class _Announcer(event.Listener):
        said = False

        def on_start(self, ev) -> None:
            dispatcher = ev.data.get("dispatcher")
            module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
            if not self.said and module.startswith("flexsim"):
                self.said = True
                print("flexsim: compiling the numerical kernels for this machine (once after an install, cached "
                      "for later runs; about 40 s of CPU) ...", file=stream or sys.stderr, flush=True)

        def on_end(self, ev) -> None:
            pass

    listener = _Announcer()
    event.register("numba:compile", listener)
    try:
        yield
    finally:
        event.unregister("numba:compile", listener)
