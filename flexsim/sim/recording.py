"""Flight logs written while a simulation runs: log paths and the sink that feeds the MCAP writer.

The log format is that of :mod:`flexsim.io.flight_log` (``docs/logs.md``): per sample the body pose,
the state (named by :attr:`OutputMaps.state_names`), the controls, the flight signals
(:attr:`OutputMaps.signal_names`, computed by :meth:`OutputMaps.signals` in the run's wind) and the deformed
beams of every component (11 nodes each), plus events; the header records the model's physical terms
(:meth:`flexsim.model.terms.Terms.record`) and aerodynamic formulation; every name is from :mod:`flexsim.io.vocabulary`. The writer flushes at least every ``flush_interval_s`` of simulated time (and every second of
wall time), so a killed simulation leaves a log readable up to about that long before the kill.
"""

from __future__ import annotations

import math
import os
import time
import warnings
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from flexsim.io.flight_log import FlightLogWriter
from flexsim.io.output_paths import check_not_link, reserve_new
from flexsim.model.aircraft_model import Wind
from flexsim.sim.outputs import OutputMaps

__all__ = ["DEFAULT_LOG_DIR", "default_log_path", "resolve_log_path", "LogSink"]

#: Default directory of flight logs, relative to the working directory (created when needed).
DEFAULT_LOG_DIR = Path("logs")


def default_log_path(name: str) -> Path:
    """``logs/<name>-<YYYYmmdd-HHMMSS>.mcap`` (local time) for a run called ``name``, reserved as a new empty file;
    a name taken already (another run in the same second, in this or another process) gets ``-2``, ``-3``, ...
    (:func:`flexsim.io.output_paths.reserve_new`), so no log replaces another."""
    safe = "".join(ch if ch.isalnum() or ch in "-_" else "_" for ch in str(name)) or "simulation"
    return reserve_new(DEFAULT_LOG_DIR, f"{safe}-{time.strftime('%Y%m%d-%H%M%S')}", ".mcap")


def resolve_log_path(log_path: str | os.PathLike | bool | None, name: str = "simulation") -> Path | None:
    """Validate a log path (None: no log; True: :func:`default_log_path`).

    The file must end in ``.mcap`` and must not be a directory; its directory must exist, except the
    default directory ``logs/``, which is created.

    Raises
    ------
    ValueError
        Wrong suffix, a directory given, or a directory that is not writable.
    FileNotFoundError
        The directory does not exist (and is not the default ``logs/``).
    """
    if log_path is None or log_path is False:
        return None
    if not isinstance(log_path, (bool, str, os.PathLike)) or log_path == "":
        raise ValueError(f"log_path = {log_path!r}: must be a path ending in .mcap, True (default logs/ file) or None")
    path = default_log_path(name) if log_path is True else check_not_link("log_path", log_path)
    if path.is_dir():
        raise ValueError(f"log_path = {str(path)!r}: is a directory; give a file name ending in .mcap")
    if path.suffix != ".mcap":
        raise ValueError(f"log_path = {str(path)!r}: must end in .mcap (flight logs are MCAP files)")
    parent = path.parent
    if not parent.exists():
        if parent == DEFAULT_LOG_DIR:
            parent.mkdir(parents=True, exist_ok=True)
        else:
            raise FileNotFoundError(f"log_path = {str(path)!r}: directory {str(parent)!r} does not exist "
                                    f"(only the default {str(DEFAULT_LOG_DIR)!r} directory is created)")
    if not parent.is_dir():
        raise ValueError(f"log_path = {str(path)!r}: {str(parent)!r} is not a directory")
    if not os.access(parent, os.W_OK):
        raise ValueError(f"log_path = {str(path)!r}: directory {str(parent)!r} is not writable")
    if log_path is not True and path.is_file() and path.stat().st_size > 0:
        with open(path, "rb") as f:
            head = f.read(8)
        if head != b"\x89MCAP0\r\n":
            raise FileExistsError(f"log_path = {str(path)!r}: an existing file that is not a flight log; it is not "
                                  "overwritten: remove it or choose another name")
        warnings.warn(f"log_path = {str(path)!r}: replacing the existing flight log (log_path=True writes a new file "
                      "in logs/ instead)", UserWarning, stacklevel=3)
    return path


class LogSink:
    """Writes simulation samples and events to a flight log as the integration proceeds.

    Parameters
    ----------
    path : Path
        A validated ``.mcap`` path (:func:`resolve_log_path`).
    outputs : OutputMaps
        Names and output maps of the simulated model.
    metadata : mapping of str to str
        Run metadata (record ``run`` of the log).
    wind : callable, optional
        The run's disturbance (air data and loads of the logged signals); None: still air. A sink logs one run.
    flush_interval_s : float
        Simulated time between flushes to disk [s].
    """

    def __init__(self, path: Path, outputs: OutputMaps, metadata: Mapping[str, str], wind: Wind | None = None,
                 flush_interval_s: float = 0.5) -> None:
        self.path = path
        self.outputs = outputs
        self.wind = wind
        self._writer = FlightLogWriter(
            path, state_names=outputs.state_names, control_names=outputs.control_names,
            signal_names=outputs.signal_names,
            structure_topology={name: outputs.n_nodes for name in outputs.model.aircraft.component_names},
            metadata=dict(metadata), terms=outputs.model.terms.record(), formulation=outputs.model.formulation,
            flush_interval_s=flush_interval_s)
        self._last_ns = -1
        self._pending: list[tuple[float, str, str]] = []

    def schedule(self, t: float, text: str, level: str = "info") -> None:
        """Log an event when the samples reach time t [s] (events ahead of the samples would hold up the
        writer's sim-time flushes, whose clock follows the times written)."""
        self._pending.append((float(t), str(text), level))
        self._pending.sort(key=lambda e: e[0])

    def _release(self, t: float) -> None:
        while self._pending and self._pending[0][0] <= t:
            t_e, text, level = self._pending.pop(0)
            self._writer.event(max(t_e, 0.0), text, level)

    def write(self, t: np.ndarray, x: np.ndarray, u: np.ndarray) -> None:
        """Append samples at times t (k,) [s] with states x (k, n) and controls u (k, 4).

        Samples whose time does not advance by at least 1 ns on the previous one are skipped.
        """
        out = self.outputs
        t, x, u = np.atleast_1d(np.asarray(t, float)), np.atleast_2d(np.asarray(x, float)), np.atleast_2d(np.asarray(u, float))
        keep, last = [], self._last_ns
        for k, tk in enumerate(t):
            ns = round(float(tk) * 1e9)
            if ns > last:
                keep.append(k)
                last = ns
        if not keep:
            return
        t, x, u = t[keep], x[keep], u[keep]
        cols = out.series(out.signal_names, t, x, u, self.wind)  # all samples at once
        signals = np.column_stack([cols[n] for n in out.signal_names])
        lay = out.model.layout
        if lay.rigid:
            pos, eul = x[:, lay.position], x[:, lay.euler]
        else:
            pose = [out.position_euler(xk) for xk in x]
            pos, eul = np.array([p for p, _ in pose]), np.array([e for _, e in pose])
        nodes = out.structure_series(x)
        start = 0
        while start < len(t):  # the events due up to a sample go before it (as sample by sample)
            self._release(float(t[start]))
            end = len(t)
            if self._pending:
                end = max(start + 1, int(np.searchsorted(t, self._pending[0][0], side="left")))
            rows = slice(start, end)
            self._writer.write_samples(t[rows], position_m=pos[rows], euler_rad=eul[rows], state=x[rows], controls=u[rows],
                                       signals=signals[rows], structure={name: v[rows] for name, v in nodes.items()})
            self._last_ns = round(float(t[end - 1]) * 1e9)
            start = end

    def event(self, t: float, text: str, level: str = "info") -> None:
        """Log an event at sim time t [s] (``level``: info, warning or error; errors are flushed at once)."""
        self._writer.event(max(float(t), 0.0), text, level)

    def close(self) -> None:
        """Log the events still scheduled and finish the MCAP file (summary and footer)."""
        try:
            self._release(math.inf)
        finally:
            self._writer.close()
