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
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from types import ModuleType
from typing import Callable, TypeVar

__all__ = ["depends_on", "source_digest"]

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
