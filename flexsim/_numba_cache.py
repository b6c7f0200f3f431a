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
:class:`CompileProgress` shows, on stderr, that flexsim's kernels are compiling and how far (the first use of a
kernel after an install or a change of the kernels' source: seconds to tens of seconds per command; a run after it
loads them in about a second); :func:`show_compile_progress` turns it on for the whole process.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import sys
import threading
import time
from pathlib import Path
from types import ModuleType
from typing import Callable, Iterator, TextIO, TypeVar

__all__ = ["depends_on", "source_digest", "is_cached", "CompileProgress", "show_compile_progress", "announce_compilation"]

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


#: Seconds between progress updates while kernels compile: on a terminal the status line is redrawn this often; in a
#: log (stderr not a terminal) a line is written every :data:`LOG_INTERVAL_S`.
TTY_INTERVAL_S = 0.5
LOG_INTERVAL_S = 5.0

#: Environment variable that silences the progress (``FLEXSIM_COMPILE_PROGRESS=0``).
PROGRESS_ENV = "FLEXSIM_COMPILE_PROGRESS"


class CompileProgress:
    """Progress of numba compiling flexsim's functions in this process, shown on ``stream`` while it lasts.

    Fed by numba's ``numba:compile`` events (they fire on compilation only, not on a load from the cache). While
    compiles run, the count of compiled functions, the elapsed time and the function being compiled are shown from
    a timer thread, so the display moves even while one large function compiles: on a terminal one status line of
    at most 78 characters, redrawn every :data:`TTY_INTERVAL_S` and erased when the compiles end (so that it never
    stays in the middle of a command's table); on a log (stderr not a terminal) one line announcing the compile,
    once per process, then a line every :data:`LOG_INTERVAL_S` and one with the totals at the end of a burst that
    lasted that long.

    Parameters
    ----------
    stream : text stream, optional
        Default ``sys.stderr`` (looked up when writing).
    tty : bool, optional
        Terminal display; default ``stream.isatty()``.
    """

    def __init__(self, stream: TextIO | None = None, tty: bool | None = None) -> None:
        self._stream = stream
        self._tty = tty
        self._lock = threading.Lock()
        self._depth = 0
        self._count = 0
        self._current = ""
        self._announced = False
        self._started = 0.0
        self._last = 0.0
        self._wake = threading.Event()
        self._timer: threading.Thread | None = None
        if hasattr(os, "register_at_fork"):  # a forked worker has no timer thread, and the lock may have been held
            os.register_at_fork(after_in_child=self._forked)

    def _forked(self) -> None:
        self._lock = threading.Lock()
        self._wake = threading.Event()
        self._timer, self._depth = None, 0

    @property
    def stream(self) -> TextIO:
        return self._stream or sys.stderr

    def _is_tty(self) -> bool:
        if self._tty is not None:
            return self._tty
        try:
            return bool(self.stream.isatty())
        except (AttributeError, ValueError):
            return False

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):  # stderr closed (a pipe that ended)
            pass

    def _status(self, now: float, width: int | None = None) -> str:
        """The progress in one line, cut to ``width`` characters (a terminal's status line must not wrap)."""
        name = self._current.rsplit(".", 1)[-1]
        if width is None:
            return (f"flexsim: compiling kernels: {self._count} functions compiled, {now - self._started:.0f} s"
                    + (f" (now {name})" if name else ""))
        text = f"flexsim: compiling kernels (first use; cached after): {self._count} done, {now - self._started:.0f} s"
        text += f", {name}" if name else ""
        return text if len(text) <= width else text[: width - 3] + "..."

    def start(self, qualname: str) -> None:
        """A flexsim function starts compiling (``qualname``: module and name)."""
        with self._lock:
            now = time.perf_counter()
            self._current = qualname
            self._depth += 1
            if self._depth > 1:
                return
            if not self._announced and not self._is_tty():  # on a terminal the status line says it
                self._announced = True
                self._write("flexsim: compiling the numerical kernels this command needs for this machine (first use "
                            "after an install or an update; cached for later runs) ...\n")
            if self._timer is None:  # a burst of compiles starts (the timer ends when the compiles end)
                self._started = self._last = now
                self._count = 0
                self._timer = threading.Thread(target=self._tick, name="flexsim-compile-progress", daemon=True)
                self._timer.start()

    def end(self) -> None:
        """A flexsim function finished compiling."""
        with self._lock:
            self._count += 1
            self._depth = max(0, self._depth - 1)
            if self._depth == 0:
                self._wake.set()

    def _tick(self) -> None:
        """Timer thread of one burst of compiles: redraws the status until the compiles have ended for a moment
        (a command compiles its kernels one after another: one burst, one summary)."""
        tty = self._is_tty()
        drawn = False
        idle_since = None
        while True:
            self._wake.wait(TTY_INTERVAL_S)
            self._wake.clear()
            with self._lock:
                now = time.perf_counter()
                if self._depth == 0:
                    idle_since = now if idle_since is None else idle_since
                    if now - idle_since >= TTY_INTERVAL_S:  # no new compile within the interval: the burst is over
                        if tty and drawn:
                            self._write("\r\033[K")
                        elif not tty and now - self._started >= LOG_INTERVAL_S:
                            self._write(f"flexsim: compiled {self._count} functions in {idle_since - self._started:.0f} s\n")
                        self._timer = None
                        return
                    continue
                idle_since = None
                if tty:
                    drawn = True
                    self._write("\r\033[K" + self._status(now, 76) + " " + "|/-\\"[int(now / TTY_INTERVAL_S) % 4])
                elif now - self._last >= LOG_INTERVAL_S:
                    self._last = now
                    self._write(self._status(now) + "\n")


class _Listener:
    """numba ``numba:compile`` listener feeding a :class:`CompileProgress` with flexsim's functions only."""

    def __init__(self, progress: CompileProgress) -> None:
        from numba.core import event

        class Listener(event.Listener):
            def on_start(self, ev) -> None:
                name = _flexsim_name(ev)
                if name:
                    self.stack.append(True)
                    progress.start(name)
                else:
                    self.stack.append(False)

            def on_end(self, ev) -> None:
                if self.stack and self.stack.pop():
                    progress.end()

        self.listener = Listener()
        self.listener.stack = []


def _flexsim_name(ev) -> str:
    dispatcher = ev.data.get("dispatcher")
    func = getattr(dispatcher, "py_func", None)
    module = getattr(func, "__module__", "") or ""
    if not (module.startswith("flexsim") or module.startswith("envs")):
        return ""
    return f"{module}.{getattr(func, '__qualname__', '?')}"


_PROCESS_PROGRESS: CompileProgress | None = None


def show_compile_progress() -> None:
    """Show :class:`CompileProgress` on stderr for every compile of flexsim's functions in this process, from now on
    (called once when flexsim's kernels are imported; idempotent). ``FLEXSIM_COMPILE_PROGRESS=0`` in the environment
    turns it off; under ``NUMBA_DISABLE_JIT=1`` nothing compiles and nothing is shown."""
    global _PROCESS_PROGRESS
    if _PROCESS_PROGRESS is not None or os.environ.get(PROGRESS_ENV, "1").strip().lower() in ("0", "false", "no", "off"):
        return
    from numba.core import event

    _PROCESS_PROGRESS = CompileProgress()
    event.register("numba:compile", _Listener(_PROCESS_PROGRESS).listener)


@contextlib.contextmanager
def announce_compilation(stream: TextIO | None = None, tty: bool | None = None) -> Iterator[CompileProgress]:
    """Within the block, show :class:`CompileProgress` on ``stream`` (default ``sys.stderr``) for the flexsim
    functions numba compiles (for a stream other than the process-wide display of :func:`show_compile_progress`)."""
    from numba.core import event

    progress = CompileProgress(stream, tty)
    listener = _Listener(progress).listener
    event.register("numba:compile", listener)
    try:
        yield progress
    finally:
        event.unregister("numba:compile", listener)


show_compile_progress()
