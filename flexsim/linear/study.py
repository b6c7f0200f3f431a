"""Flutter studies over steady manoeuvres: turn radius and climb angle at several altitudes.

Source: Tuzcu & Nguyen (2014), Figs. 7-16: flutter Mach number and frequency versus turn radius R
(5-12 km) and climb angle gamma (-15 to 15 deg) at 0, 3048, 6096 and 9144 m, quasi-steady (QS) and
unsteady (US, Theodorsen) aerodynamics, with the trim quantities at 9144 m; the glide is the point of the
climb curve where the thrust vanishes.

Each condition is an independent flutter search (:class:`~flexsim.linear.flutter.FlutterAnalysis`),
run in parallel: local processes by default, or a Dask distributed cluster when a scheduler address is
given. Results are plain dicts (one per condition), written as CSV and JSON and plotted as PNG figures
laid out like the paper's.
"""

from __future__ import annotations

import csv
import hashlib
import json
import math
import os
import signal
import sys
import time
from collections import OrderedDict
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Callable, Iterable, Sequence

import numpy as np

from flexsim.atmosphere import isa_density
from flexsim.model.terms import Terms

__all__ = ["StudyCase", "StudyRecord", "case_key", "turn_cases", "climb_cases", "run_case", "run_chain", "run_point", "run_points", "run_study", "write_results", "plot_study", "plot_trim", "glide_from_climb"]

MODELS = {"QS": "quasi-steady", "US": "theodorsen", "FS": "unsteady"}
PAPER_ALTITUDES_M = (0.0, 3048.0, 6096.0, 9144.0)
#: Seconds to wait for a Dask scheduler before reporting that it cannot be reached.
DASK_CONNECT_TIMEOUT_S = 10.0


@dataclass(frozen=True)
class StudyCase:
    """One flutter search of a study.

    Attributes
    ----------
    aircraft : str
        Bundled name or TOML path (resolved in the worker).
    model : {"QS", "US", "FS"}
    altitude_m : float
    turn_radius_m : float
        ``inf`` for straight flight.
    climb_angle_deg : float or None
        None for a glide.
    mach_min, mach_max : float
        Search range.
    structural_damping : float or None
        Modal damping ratio of the elastic modes; None uses the aircraft file's value.
    formulation : {"physical", "paper"} or None
        Resolution of the strip airloads; None uses the aircraft file's (docs/design.md).
    linear_density_altitude_m : float or None
        Paper-replication setting: the linearised aerodynamics of the flutter search use the ISA density
        at this altitude [m] (the trims keep the true one); None: the flight's true density.
    coordinated : bool
        Turns: coordinated (zero sideslip, heading free) instead of the paper's turn.
    terms : Terms or None
        The physical terms of the case's model (:class:`flexsim.model.terms.Terms`, with aerodynamics); the analysis
        is that of ``AircraftModel(aircraft, terms=terms)`` with ``model``'s aerodynamic model
        (:meth:`FlutterAnalysis.from_model`). None (default): the aircraft's, with ``structural_damping`` and
        ``formulation`` (which must then be None when ``terms`` is given).
    mach_step : float or None
        Scan step of the search in Mach [-], in (0, mach_max - mach_min]; None:
        :func:`flexsim.linear.flutter.scan_step` of the range.
    """

    aircraft: str
    model: str
    altitude_m: float
    turn_radius_m: float = math.inf
    climb_angle_deg: float | None = 0.0
    mach_min: float = 0.5
    mach_max: float = 0.95
    structural_damping: float | None = None
    formulation: str | None = None
    linear_density_altitude_m: float | None = None
    coordinated: bool = False
    terms: Terms | None = None
    mach_step: float | None = None

    def __post_init__(self) -> None:
        if self.mach_step is not None and not (isinstance(self.mach_step, (int, float)) and not isinstance(self.mach_step, bool)
                                               and 0.0 < self.mach_step <= self.mach_max - self.mach_min):
            raise ValueError(f"mach_step = {self.mach_step!r}: must be in (0, {self.mach_max - self.mach_min:g}] "
                             "(the width of the Mach range)")
        if self.model not in MODELS:
            raise ValueError(f"model = {self.model!r}: must be one of {', '.join(MODELS)}")
        if self.terms is not None:
            if not isinstance(self.terms, Terms) or self.terms.aero is None:
                raise ValueError(f"terms = {self.terms!r}: must be a flexsim.model.terms.Terms with aerodynamics (or None)")
            given = [k for k in ("structural_damping", "formulation") if getattr(self, k) is not None]
            if given:
                raise ValueError(f"terms and {', '.join(given)}: give {', '.join(given)} inside terms "
                                 "(Terms.structural_damping, AeroOptions.formulation), not both")
        if self.coordinated and self.turn_radius_m == math.inf:
            raise ValueError("coordinated = True: applies to turns only (give turn_radius_m)")
        if self.formulation is not None and self.formulation not in ("physical", "paper"):
            raise ValueError(f"formulation = {self.formulation!r}: must be \"physical\" or \"paper\" (or None: the aircraft file's)")
        if self.linear_density_altitude_m is not None:
            isa_density(self.linear_density_altitude_m)  # validates the ISA range with a clear message

    def analysis(self):
        """The :class:`~flexsim.linear.flutter.FlutterAnalysis` of this case (aircraft loaded here)."""
        from flexsim.aircraft.toml_loader import load_aircraft
        from flexsim.linear.flutter import FlutterAnalysis

        from flexsim.model.aircraft_model import AircraftModel

        rho = None if self.linear_density_altitude_m is None else float(isa_density(self.linear_density_altitude_m))
        if self.terms is not None:
            return FlutterAnalysis.from_model(AircraftModel(load_aircraft(self.aircraft), terms=self.terms), MODELS[self.model],
                                              linear_aero_density_kg_m3=rho)
        return FlutterAnalysis(load_aircraft(self.aircraft), MODELS[self.model], structural_damping=self.structural_damping,
                               formulation=self.formulation, linear_aero_density_kg_m3=rho)

    @property
    def chain_key(self) -> tuple:
        """Cases with equal keys share one analysis and are run in order (:func:`run_chain`)."""
        return (self.aircraft, self.model, self.altitude_m, self.structural_damping, self.formulation, self.linear_density_altitude_m,
                self.terms)


def turn_cases(aircraft: str, radii_m: Sequence[float] = tuple(range(5000, 12001, 1000)),
               altitudes_m: Sequence[float] = PAPER_ALTITUDES_M, models: Sequence[str] = ("QS", "US"),
               structural_damping: float | None = None, **settings) -> list[StudyCase]:
    """Level turns of the paper's Figs. 7-10 (R = 5-12 km); ``settings``: further :class:`StudyCase` fields."""
    return [StudyCase(aircraft, m, h, turn_radius_m=float(r), structural_damping=structural_damping, **settings)
            for m in models for h in altitudes_m for r in radii_m]


def climb_cases(aircraft: str, angles_deg: Sequence[float] = tuple(range(-15, 16, 5)),
                altitudes_m: Sequence[float] = PAPER_ALTITUDES_M, models: Sequence[str] = ("QS", "US"),
                structural_damping: float | None = None, **settings) -> list[StudyCase]:
    """Steady climbs and descents of the paper's Figs. 12-15 (gamma = -15 to 15 deg); ``settings`` as :func:`turn_cases`."""
    return [StudyCase(aircraft, m, h, climb_angle_deg=float(g), structural_damping=structural_damping, **settings)
            for m in models for h in altitudes_m for g in angles_deg]


def run_case(case: StudyCase, mach_guess: float | None = None, analysis=None, shared=None) -> dict:
    """Flutter search of one case; a plain dict with the flutter point and its trim, or an ``error``.

    ``analysis`` (default: built here) may be one built for another model that has this case's models too (a
    "US" analysis has the quasi-steady one); ``shared``: a :class:`~flexsim.linear.flutter.SharedEvaluations` of
    that analysis, holding the trims and linearisations of the other searches of the same manoeuvre.
    """
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    from flexsim.linear.flutter import FlutterNotFound, scan_step
    from flexsim.trimming import SteadyManoeuvre, TrimError

    row = asdict(case)
    gamma = None if case.climb_angle_deg is None else math.radians(case.climb_angle_deg)
    try:
        analysis = analysis or case.analysis()
        start = SteadyManoeuvre.level(case.altitude_m, mach=case.mach_max)  # its speed is replaced by the searched one
        man = SteadyManoeuvre(start.speed_m_s, case.altitude_m, case.turn_radius_m, gamma, case.coordinated)
        fp = analysis.search(man, mach_range=(case.mach_min, case.mach_max), mach_step=(scan_step((case.mach_min, case.mach_max))
                                                                                    if case.mach_step is None else case.mach_step),
                             mach_guess=mach_guess, aero_model=MODELS[case.model], shared=shared)
    except (FlutterNotFound, TrimError, ValueError) as exc:
        row["error"] = str(exc)
        return row
    s = fp.trim.summary()
    row.update(
        mach=fp.mach, omega_rad_s=fp.frequency_rad_s, mode=fp.mode.name, mode_coordinate=fp.mode.dominant_dof,
        theta_deg=s["theta_deg"], phi_deg=s["phi_deg"], sideslip_deg=s["sideslip_deg"], gamma_deg=s["gamma_deg"], thrust_kN=s["thrust_kN"],
        aileron_deg=s["aileron_deg"], elevator_deg=s["elevator_deg"], rudder_deg=s["rudder_deg"],
        tip_deflection_m=s["tip_deflection_m"], tip_twist_deg=s["tip_twist_deg"], evaluations=fp.evaluations,
        rigid_instabilities=len(fp.rigid_instabilities),
        trim_stability=fp.trim.stability.verdict if fp.trim.stability is not None else None,
        mode_symmetry=fp.mode_symmetry, symmetric_fraction=fp.symmetric_fraction, normalised_by=fp.normalised_by,
        participation=[p.as_dict() for p in fp.participation],
        formulation=fp.formulation, aero_density_kg_m3=fp.aero_density_kg_m3, aero_density_fixed=fp.aero_density_fixed,
        model_terms=fp.terms,
        linear_range=fp.trim.linear_range,
        warnings=list(fp.warnings),
    )
    return row


def run_chain(cases: Sequence[StudyCase]) -> list[dict]:
    """Run cases that differ in one manoeuvre parameter in order, each seeded with the previous flutter Mach.

    The models are built once per chain; neighbouring conditions have neighbouring flutter points, so
    bracketing near the previous one saves most of the grid scan.
    """
    analysis = cases[0].analysis() if cases else None
    rows, guess = [], None
    for case in cases:
        row = run_case(case, mach_guess=guess, analysis=analysis)
        guess = row.get("mach", guess)
        rows.append(row)
    return rows


#: Flutter analyses built in this process, keyed by content (aircraft file bytes, model, damping, formulation,
#: linearisation density), so the points of one chain, and of the other altitudes, reuse the models.
_ANALYSES: "OrderedDict[tuple, object]" = OrderedDict()
_ANALYSES_MAX = 8


def _analysis(case: StudyCase):
    from flexsim.aircraft.toml_loader import resolve_aircraft_path

    path = resolve_aircraft_path(case.aircraft)
    # what the analysis depends on: not the altitude, so that a worker reuses it over the points of all altitudes
    key = (hashlib.sha256(path.read_bytes()).hexdigest(), case.model, case.structural_damping, case.formulation,
           case.linear_density_altitude_m, case.terms)
    if key in _ANALYSES:
        _ANALYSES.move_to_end(key)
        return _ANALYSES[key]
    analysis = case.analysis()
    _ANALYSES[key] = analysis
    while len(_ANALYSES) > _ANALYSES_MAX:
        _ANALYSES.popitem(last=False)
    return analysis


def run_point(case: StudyCase, mach_guess: float | None = None) -> tuple[dict, float]:
    """One point of a study in a worker: ``(row, wall seconds)``; any failure becomes the row's ``error``."""
    t0 = time.perf_counter()
    try:
        row = run_case(case, mach_guess=mach_guess, analysis=_analysis(case))
    except Exception as exc:  # noqa: BLE001 - one point's failure must not abort the study
        row = asdict(case)
        row["error"] = f"{type(exc).__name__}: {exc}"
    return row, time.perf_counter() - t0


def run_points(cases: Sequence[StudyCase]) -> list[tuple[dict, float]]:
    """Unseeded points of one manoeuvre with different aerodynamic models, in a worker: ``[(row, wall seconds)]``.

    The searches run on one analysis (that of the costliest model: "US" and "FS" analyses have the quasi-steady
    models too) and share their trims and linearisations (:class:`~flexsim.linear.flutter.SharedEvaluations`):
    the quasi-steady and p-k scans trim and linearise at the same Mach numbers, so the QS search costs little
    more than its eigen-analyses there. Each row equals that of :func:`run_point` alone, bit for bit.
    """
    from flexsim.linear.flutter import SharedEvaluations

    order = sorted(range(len(cases)), key=lambda k: _COST_RANK[cases[k].model])
    out: list = [None] * len(cases)
    t0 = time.perf_counter()
    try:
        analysis = _analysis(cases[order[0]])
        shared = SharedEvaluations(analysis)
    except Exception as exc:  # noqa: BLE001 - one point's failure must not abort the study
        return [({**asdict(c), "error": f"{type(exc).__name__}: {exc}"}, time.perf_counter() - t0) for c in cases]
    for k in order:
        try:
            row = run_case(cases[k], analysis=analysis, shared=shared)
        except Exception as exc:  # noqa: BLE001
            row = asdict(cases[k])
            row["error"] = f"{type(exc).__name__}: {exc}"
        t1 = time.perf_counter()
        out[k] = (row, t1 - t0)
        t0 = t1
    return out


#: Order of the models in :func:`run_points`: the first one's analysis is used for all (it has the models of the rest).
_COST_RANK = {"US": 0, "FS": 1, "QS": 2}


def case_key(case_or_row: StudyCase | dict) -> str:
    """Identity of a study point: the JSON of its :class:`StudyCase` fields (used to resume)."""
    fields = StudyCase.__dataclass_fields__
    d = asdict(case_or_row) if isinstance(case_or_row, StudyCase) else case_or_row
    return json.dumps({k: d.get(k) for k in fields}, sort_keys=True)


class StudyRecord:
    """The points of a study written as JSON lines as they complete (``<out>/<stem>.jsonl``).

    Each finished point is one line, flushed and synced at once, so an interrupted or killed study
    keeps every point finished before; ``resume=True`` reads them back and the study skips them. A
    partial last line (the process killed while writing it) is ignored and counted.

    Raises
    ------
    FlexsimError
        When the file already holds points and ``resume`` is False (finished work is never overwritten), or another
        process is writing the same file (a lock ``<file>.lock`` beside it, held until :meth:`close`).
    """

    def __init__(self, path: str | Path, resume: bool = False) -> None:
        self.path = Path(path)
        self.done: dict[str, dict] = {}
        self.damaged_lines = 0
        self._lock = _lock_beside(self.path)  # one study at a time per file: a second one would mix or lose rows
        try:
            self._read(resume)
        except BaseException:
            self.close()
            raise

    def _read(self, resume: bool) -> None:
        from flexsim.errors import FlexsimError

        self._file = None
        if self.path.exists():
            for line in self.path.read_text(encoding="utf-8", errors="replace").splitlines():
                try:
                    row = json.loads(line)
                    key = row.pop("_case", None)  # the case as it was asked for (a row resolves e.g. formulation)
                    self.done[key if isinstance(key, str) else case_key(row)] = row
                except (ValueError, TypeError, AttributeError):
                    self.damaged_lines += 1
            if self.done and not resume:
                raise FlexsimError(f"{self.path}: already holds {len(self.done)} finished points of a study; give --resume "
                                   f"to continue it, or another --out")
            if not resume:
                self.path.unlink()
            elif self.damaged_lines:
                # rewrite without the partial line(s), so new points start on a clean line
                self.path.write_text("".join(json.dumps({**r, "_case": k}, default=str) + "\n" for k, r in self.done.items()))
        self._file = self.path.open("a", encoding="utf-8")

    def append(self, row: dict, case: StudyCase | None = None) -> None:
        """Write ``row`` as one line, flushed and synced; with ``case``, the case's key too (``_case``), by which a
        resumed study recognises the point (a row's own fields are resolved: ``formulation`` None becomes the
        file's, so the row alone would not match its case and every point would be computed again)."""
        self._file.write(json.dumps(row if case is None else {**row, "_case": case_key(case)}, default=str) + "\n")
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
        if self._lock is not None:
            self._lock.close()  # releases the lock
            self._lock = None


def _lock_beside(path: Path):
    """An exclusive lock on ``<path>.lock`` held by the returned open file (released when it is closed or the process
    ends, even by SIGKILL); FlexsimError when another process holds it (POSIX ``flock``; elsewhere no lock)."""
    from flexsim.errors import FlexsimError

    try:
        import fcntl
    except ImportError:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    lock = open(path.with_name(path.name + ".lock"), "a")
    try:
        fcntl.flock(lock.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        lock.close()
        raise FlexsimError(f"{path}: another study is writing it now (a second sweep into the same --out would mix "
                           "its rows with that one's and overwrite its results); wait for it to finish, or give "
                           "another --out") from None
    return lock


def _describe(case: StudyCase) -> str:
    turn = "" if case.turn_radius_m == math.inf else f" R={case.turn_radius_m:g} m"
    climb = " glide" if case.climb_angle_deg is None else (f" gamma={case.climb_angle_deg:g} deg" if case.climb_angle_deg else "")
    return f"{case.model} h={case.altitude_m:g} m{turn}{climb}"


class _Progress:
    """A tqdm bar on a terminal; otherwise one line per completed point on stderr (visible when piped).

    The bar starts at :meth:`begin`, after the first compile of the kernels (which shows its own progress,
    :class:`flexsim._numba_cache.CompileProgress`): started before, its rate and time left would count the compile
    as the first point's time (an estimate of 10:46 for a 45 s run)."""

    def __init__(self, total: int, done: int, enabled: bool) -> None:
        self.total, self.count, self.enabled = total, done, enabled
        self.bar = None

    def begin(self) -> None:
        if self.bar is None and self.enabled and sys.stderr.isatty():
            from tqdm.auto import tqdm

            self.bar = tqdm(total=self.total, initial=self.count, desc="flutter points")

    def point(self, case: StudyCase, row: dict, seconds: float) -> None:
        self.count += 1
        if self.bar is not None:
            self.bar.update(1)
        elif self.enabled and not sys.stderr.isatty():  # on a terminal the bar, once begun, counts this point
            what = f"M_F {row['mach']:.4f}, {row['omega_rad_s']:.2f} rad/s" if "mach" in row else f"no flutter point: {str(row.get('error'))[:80]}"
            print(f"[{self.count}/{self.total}] {_describe(case)}: {what} ({seconds:.1f} s)", file=sys.stderr, flush=True)

    def note(self, text: str) -> None:
        (self.bar.write if self.bar is not None else lambda t: print(t, file=sys.stderr, flush=True))(text)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _ignore_sigint(parent_pid: int | None = None) -> None:
    """Process-pool initializer: Ctrl-C is handled by the parent, which stops the workers; and the worker ends with
    its parent even when the parent cannot stop it (killed with SIGKILL): on Linux the kernel sends it SIGTERM then
    (``prctl(PR_SET_PDEATHSIG)``)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):  # a handler inherited from the parent (the CLI's) would be caught as a task's error
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), signal.SIG_DFL)
    end_with_parent(parent_pid)


def end_with_parent(parent_pid: int | None = None) -> None:
    """Ask the kernel to send this process SIGTERM when its parent ends (Linux ``prctl(PR_SET_PDEATHSIG)``; elsewhere
    nothing is done: the parent's handlers stop its workers). A parent that ended before the call (this process's
    parent is no longer ``parent_pid``, or is init) ends this process at once."""
    if not sys.platform.startswith("linux"):
        return
    import ctypes

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):
        return
    if os.getppid() == 1 or (parent_pid is not None and os.getppid() != parent_pid):  # re-parented: the parent is gone
        os.kill(os.getpid(), signal.SIGTERM)


def run_study(cases: Iterable[StudyCase], *, scheduler: str | None = None, workers: int | None = None,
              progress: bool = True, record: StudyRecord | None = None, max_attempts: int = 2,
              chain_length: int | None = None, on_point: Callable[[StudyCase, dict, float], None] | None = None) -> list[dict]:
    """Run the cases in parallel and return rows in the input order, keeping every finished point.

    Cases of one model and altitude form a chain run in order, each point seeded with the previous
    flutter Mach; chains run in parallel, one point at a time each, and every finished point is handed
    to ``record`` (written at once) and reported by the progress display. Points already in ``record``
    (``resume``) are skipped. ``chain_length`` cuts the chains into shorter ones, down to single points,
    so that more workers than chains are used (a paper study has 8 chains of 7-8 points).

    Parameters
    ----------
    cases : iterable of StudyCase
    scheduler : str, optional
        Address of a Dask distributed scheduler (``tcp://host:8786``); needs ``dask[distributed]``
        (``pip install ".[dask]"`` from the checkout). The client sends pickled tasks to that scheduler and unpickles
        what it returns: give only the address of a cluster you trust. Default: local processes.
    workers : int, optional
        Local processes (default: all cores).
    progress : bool
        Show progress: a tqdm bar on a terminal, one line per finished point on stderr otherwise.
    record : StudyRecord, optional
        Where finished points are written as they complete (and read from when resuming).
    max_attempts : int
        Times a point is started when the process computing it dies (a killed worker); after that the
        point becomes an error row saying so. Lost points are reported on stderr.
    chain_length : int, optional
        Points per chain (>= 1): each (model, altitude) chain is cut into runs of at most this many
        consecutive cases, each run starting unseeded (1: every point an independent task). None
        (default): whole chains. The cut depends only on the cases and this number, never on the
        workers or the scheduler, so a given ``chain_length`` gives the same rows serially, on local
        processes and on any Dask cluster. A point without a seed scans the whole Mach range: more work
        per point, spread over more workers (``docs/performance.md``, sweeps).
    on_point : callable, optional
        ``on_point(case, row, seconds)`` as each point finishes (seconds: the point's wall time in its
        worker), e.g. to collect task times.

    Raises
    ------
    KeyboardInterrupt
        On Ctrl-C, after stopping the workers (within about a second); finished points are in ``record``.
    """
    cases = list(cases)
    if chain_length is not None and (isinstance(chain_length, bool) or not isinstance(chain_length, int) or chain_length < 1):
        raise ValueError(f"chain_length = {chain_length!r}: must be an integer >= 1 (points per chain) or None (whole chains)")
    chains: dict[tuple, list[int]] = {}
    position: dict[tuple, int] = {}
    for i, c in enumerate(cases):
        k = position[c.chain_key] = position.get(c.chain_key, -1) + 1
        chains.setdefault((c.chain_key, 0 if chain_length is None else k // chain_length), []).append(i)
    done = dict(record.done) if record is not None else {}
    rows: list[dict | None] = [done.get(case_key(c)) for c in cases]
    todo = [[i for i in g if rows[i] is None] for g in chains.values()]
    todo = [g for g in todo if g]
    guess0 = {}
    for g in chains.values():  # resumed chains start from their last finished point
        last = [rows[i] for i in g if rows[i] is not None and "mach" in rows[i]]
        if last:
            guess0[g[0]] = last[-1]["mach"]
    bar = _Progress(len(cases), sum(r is not None for r in rows), progress)
    attempts: dict[int, int] = {}

    def finish(i: int, row: dict, seconds: float) -> None:
        rows[i] = row
        if record is not None:
            record.append(row, cases[i])
        bar.point(cases[i], row, seconds)
        if on_point is not None:
            on_point(cases[i], row, seconds)

    chains_all = list(chains.values())
    chain_of = {i: k for k, g in enumerate(chains_all) for i in g}

    def run_here(step: tuple[int, ...]) -> None:
        """One step in this process (:func:`run_point` or :func:`run_points`), its rows finished."""
        results = ([run_point(cases[step[0]], guess_for(step[0]))] if len(step) == 1
                   else run_points([cases[i] for i in step]))
        for i, (row, seconds) in zip(step, results):
            finish(i, row, seconds)

    def guess_for(i: int) -> float | None:
        g = chains_all[chain_of[i]]
        prev = [rows[j] for j in g[: g.index(i)] if rows[j] is not None and "mach" in rows[j]]
        return prev[-1]["mach"] if prev else guess0.get(g[0])

    try:
        if scheduler:
            bar.begin()
            _run_dask(scheduler, cases, todo, guess_for, finish, bar, max_attempts)
        else:
            queues = _local_steps(cases, todo, [len(chains_all[chain_of[g[0]]]) for g in todo])
            n = max(1, min(workers or os.cpu_count() or 1, len(queues)))
            if queues and not _kernels_cached():  # compiled once here, then loaded by the workers (not once in each)
                from flexsim.linear import _precompile

                helper = _precompile.start() if n > 1 else None  # the p-k kernels on the other core meanwhile
                try:
                    k = min(range(len(queues)), key=lambda k: _longest_first(cases, queues[k]))
                    run_here(queues[k].pop(0))
                    queues = [q for q in queues if q]
                finally:
                    if helper is not None and helper.poll() is None:
                        helper.terminate()
            bar.begin()  # after the compile: the bar's rate is that of the points
            if n == 1:
                for queue in queues:
                    for step in queue:
                        run_here(step)
            else:
                _run_pool(n, cases, queues, guess_for, finish, bar, attempts, max_attempts)
    finally:
        bar.close()
    return [r for r in rows if r is not None]


def _kernels_cached() -> bool:
    """Whether the kernels of a flutter point load from numba's cache. If not, :func:`run_study` computes one step
    in this process before it starts the pool: the workers then load the machine code this process compiled and
    saved, instead of each compiling the same kernels (about 40 s of CPU each on a first run)."""
    from flexsim import _kernels
    from flexsim._numba_cache import is_cached
    from flexsim.aero import pk

    return is_cached(_kernels.rhs_batch, _kernels.aerodynamic_force, pk._track_kernel)


def _local_steps(cases: Sequence[StudyCase], todo: list[list[int]], chain_sizes: list[int]) -> list[list[tuple[int, ...]]]:
    """What the local processes run: per chain, its points one step each, in order; except that chains of a single
    point (unseeded) whose cases differ only in the model form one step of one queue, run by :func:`run_points`
    on one analysis with shared trims (the QS and US points of ``flexsim flutter``: same rows, less work)."""
    queues: list[list[tuple[int, ...]]] = []
    groups: dict[tuple, list[int]] = {}
    for g, size in zip(todo, chain_sizes):
        if len(g) == 1 and size == 1:
            key = json.dumps({k: v for k, v in asdict(cases[g[0]]).items() if k != "model"}, sort_keys=True, default=str)
            groups.setdefault(key, []).append(g[0])
        else:
            queues.append([(i,) for i in g])
    return queues + [[tuple(group)] for group in groups.values()]


def _in_worker(name: str, *args):
    """A pool task: ``(worker process id, run_point(*args) or run_points(*args))``; the function is looked up here,
    in the worker, by ``name``. The process id lets the scheduler send a worker more points of the analysis it has
    built (:func:`_run_pool`)."""
    return os.getpid(), globals()[name](*args)


def _analysis_of(cases: Sequence[StudyCase], step: tuple[int, ...]) -> tuple:
    """Which analysis a worker builds for ``step`` (:func:`_analysis`, :func:`run_points`): scheduling only."""
    case = min((cases[i] for i in step), key=lambda c: _COST_RANK[c.model])
    return (case.aircraft, case.model, case.structural_damping, case.formulation, case.linear_density_altitude_m, case.terms)


def _run_pool(n, cases, queues, guess_for, finish, bar, attempts, max_attempts) -> None:
    """Queues of steps (:func:`_local_steps`) on a process pool, one step per queue in flight; a pool broken by a
    dead worker is replaced and its in-flight points retried (up to ``max_attempts``).

    The costliest queues start first (:func:`_longest_first`); a worker that finishes a step is sent the costliest
    waiting step of an analysis it has already built (its models are warm there; building the GTM's p-k analysis
    takes ~0.3 s), else the costliest waiting step. Only the schedule depends on this, never the rows."""
    from concurrent.futures import FIRST_COMPLETED, wait
    from concurrent.futures.process import BrokenProcessPool

    queues = [list(q) for q in queues]
    while any(queues):
        pool = ProcessPoolExecutor(max_workers=n, initializer=_ignore_sigint, initargs=(os.getpid(),))
        running: dict = {}
        idle = sorted((k for k in range(len(queues)) if queues[k]), key=lambda k: _longest_first(cases, queues[k]))
        warm: dict[int, set] = {}  # worker process id -> analyses it has built
        freed: list[int] = []  # workers that finished a step in the last wait (the next steps go to them)
        lost: list[tuple[int, tuple[int, ...]]] = []
        broken = False
        try:
            while (idle or running) and not (lost or broken):
                while idle and len(running) < n:
                    built = warm.get(freed[0], set()) if freed else set()
                    pick = next((j for j, k in enumerate(idle) if _analysis_of(cases, queues[k][0]) in built), 0)
                    k = idle[pick]
                    step = queues[k][0]
                    try:
                        if len(step) == 1:
                            fut = pool.submit(_in_worker, "run_point", cases[step[0]], guess_for(step[0]))
                        else:
                            fut = pool.submit(_in_worker, "run_points", [cases[i] for i in step])
                    except BrokenProcessPool:  # a worker died since the last wait
                        broken = True
                        break
                    idle.pop(pick)
                    if freed:
                        freed.pop(0)
                    attempts[step] = attempts.get(step, 0) + 1
                    running[fut] = (k, step)
                if not running:
                    break
                finished, _ = wait(running, return_when=FIRST_COMPLETED)
                freed = []
                for fut in finished:
                    k, step = running.pop(fut)
                    try:
                        pid, results = fut.result()
                    except BrokenProcessPool:
                        lost.append((k, step))
                        continue
                    warm.setdefault(pid, set()).add(_analysis_of(cases, step))
                    freed.append(pid)
                    queues[k].pop(0)
                    for i, (row, seconds) in zip(step, [results] if len(step) == 1 else results):
                        finish(i, row, seconds)
                    if queues[k]:
                        idle.insert(0, k)  # continue this chain next (its models are warm in a worker)
        finally:
            _stop_pool(pool)
        if lost or broken:
            lost += list(running.values())
            names = ", ".join(_describe(cases[i]) for _, step in lost for i in step)
            n_lost = sum(len(step) for _, step in lost)
            bar.note(f"warning: a worker process died; {n_lost} point(s) in flight lost: {names}; "
                     f"the points finished before are kept; retrying on a new process pool")
            for k, step in lost:
                if attempts.get(step, 0) >= max_attempts:
                    queues[k].pop(0)
                    for i in step:
                        row = asdict(cases[i])
                        row["error"] = (f"the worker process computing this point died {attempts[step]} times "
                                        "(killed or out of memory)")
                        finish(i, row, 0.0)


def _longest_first(cases: Sequence[StudyCase], queue: list[tuple[int, ...]]) -> tuple:
    """Order in which queues start on the pool: the costliest first (steps with p-k and finite-state searches
    before quasi-steady ones, higher altitudes, with more grid points below the flutter Mach, before lower, more
    points before fewer), so that no worker is left with one long search at the end. Only the schedule depends on it."""
    step = queue[0]
    return (all(cases[i].model == "QS" for i in step), -cases[step[0]].altitude_m, -sum(len(s) for s in queue))


def _stop_pool(pool: ProcessPoolExecutor) -> None:
    """Shut a pool down at once: cancel queued work and terminate the worker processes."""
    processes = list(getattr(pool, "_processes", {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in processes:
        if p.is_alive():
            p.terminate()
    for p in processes:
        p.join(timeout=2.0)


def _run_dask(scheduler, cases, todo, guess_for, finish, bar, max_attempts) -> None:
    """Chains on a Dask cluster: one task per point; Dask itself reruns the tasks of a lost worker."""
    try:
        from dask.distributed import Client, as_completed
    except ImportError as exc:  # optional dependency
        raise RuntimeError(f"--scheduler {scheduler!r} needs dask.distributed: pip install \".[dask]\" from the flexsim checkout ({exc})") from None
    from flexsim.errors import FlexsimError

    try:
        client = Client(scheduler, timeout=DASK_CONNECT_TIMEOUT_S, set_as_default=False)
    except (OSError, TimeoutError) as exc:
        raise FlexsimError(f"--scheduler {scheduler!r}: cannot connect to a Dask scheduler there ({exc})") from None
    queues = [list(g) for g in todo]
    futures: dict = {}
    try:
        for k, q in enumerate(queues):
            i = q[0]
            f = client.submit(run_point, cases[i], guess_for(i), pure=False, retries=max_attempts - 1)
            futures[f] = (k, i)
        ac = as_completed(list(futures), loop=client.loop)
        for f in ac:
            k, i = futures.pop(f)
            try:
                row, seconds = f.result()
            except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker after repeated worker deaths
                row, seconds = asdict(cases[i]), 0.0
                row["error"] = f"{type(exc).__name__}: {exc}"
                bar.note(f"warning: point {_describe(cases[i])} lost on the cluster: {type(exc).__name__}")
            queues[k].pop(0)
            finish(i, row, seconds)
            if queues[k]:
                j = queues[k][0]
                nf = client.submit(run_point, cases[j], guess_for(j), pure=False, retries=max_attempts - 1)
                futures[nf] = (k, j)
                ac.add(nf)
    finally:
        if futures:
            client.cancel(list(futures))
        client.close(timeout=2)


def write_results(rows: list[dict], out_dir: str | Path, stem: str) -> tuple[Path, Path]:
    """Write rows as ``<stem>.csv`` and ``<stem>.json`` in ``out_dir`` (created if needed)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    json_path = out / f"{stem}.json"
    json_path.write_text(json.dumps(rows, indent=2, default=str))
    keys = sorted({k for r in rows for k in r}, key=lambda k: (k not in StudyCase.__dataclass_fields__, k))
    csv_path = out / f"{stem}.csv"
    with csv_path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: r.get(k, "") for k in keys})
    return csv_path, json_path


def glide_from_climb(rows: list[dict], model: str = "US", altitude_m: float = 9144.0) -> dict | None:
    """Interpolate the climb curve where T_e = 0 (the paper's glide: gamma, M_F, omega_F)."""
    pts = sorted((r["climb_angle_deg"], r["thrust_kN"], r["mach"], r["omega_rad_s"]) for r in rows
                 if r.get("model") == model and r.get("altitude_m") == altitude_m and "mach" in r and r.get("climb_angle_deg") is not None)
    for (g0, t0, m0, w0), (g1, t1, m1, w1) in zip(pts[:-1], pts[1:]):
        if t0 <= 0.0 <= t1 or t1 <= 0.0 <= t0:
            f = t0 / (t0 - t1) if t0 != t1 else 0.0
            return {"gamma_deg": g0 + f * (g1 - g0), "mach": m0 + f * (m1 - m0), "omega_rad_s": w0 + f * (w1 - w0)}
    return None


def plot_study(rows: list[dict], kind: str, path: str | Path) -> Path:
    """Flutter Mach and frequency versus R (``kind="turn"``) or gamma (``"climb"``), one row per altitude.

    Layout as the paper's Figs. 7-9 / 12-14: left M_F, right omega_F, QS and US curves.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    xkey, xlabel, scale = ("turn_radius_m", "R [km]", 1e-3) if kind == "turn" else ("climb_angle_deg", "γ [deg]", 1.0)
    altitudes = sorted({r["altitude_m"] for r in rows})
    fig = Figure(figsize=(9.0, 2.6 * max(1, len(altitudes))), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(max(1, len(altitudes)), 2, squeeze=False)
    for i, h in enumerate(altitudes):
        for model, style in (("QS", "o--"), ("US", "s-"), ("FS", "^-.")):
            sel = sorted((r[xkey] * scale, r["mach"], r["omega_rad_s"]) for r in rows
                         if r["altitude_m"] == h and r["model"] == model and "mach" in r)
            if sel:
                x, m, w = np.array(sel).T
                axes[i, 0].plot(x, m, style, label=model)
                axes[i, 1].plot(x, w, style, label=model)
        axes[i, 0].set_ylabel(f"M_F (h = {h:.0f} m)")
        axes[i, 1].set_ylabel("ω_F [rad/s]")
        for ax in axes[i]:
            ax.grid(alpha=0.3)
            ax.set_xlabel(xlabel)
    axes[0, 0].legend()
    fig.suptitle(f"Flutter versus {'turn radius' if kind == 'turn' else 'climb angle'} (flexsim, notional GTM)")
    out = Path(path)
    fig.savefig(out, dpi=110)
    return out


#: Trim quantities drawn by :func:`plot_trim` (paper Figs. 10 and 15): row key, axis label.
TRIM_PANELS = (("theta_deg", "θ [deg]"), ("thrust_kN", "T_e [kN]"), ("elevator_deg", "δ_e [deg]"),
               ("tip_deflection_m", "w_w(L_w) [m]"), ("tip_twist_deg", "ψ_w(L_w) [deg]"))


def plot_trim(rows: list[dict], kind: str, path: str | Path, altitude_m: float = 9144.0) -> Path:
    """Trim at the flutter point versus R or gamma at one altitude (the paper's Figs. 10 and 15, lower panels).

    One panel per quantity of :data:`TRIM_PANELS` (pitch, thrust, elevator, wing-tip deflection and
    twist), QS and US curves. Raises ``ValueError`` when no row has that altitude.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    xkey, xlabel, scale = ("turn_radius_m", "R [km]", 1e-3) if kind == "turn" else ("climb_angle_deg", "γ [deg]", 1.0)
    at_h = [r for r in rows if r["altitude_m"] == altitude_m and "mach" in r]
    if not at_h:
        raise ValueError(f"altitude_m = {altitude_m!r}: no flutter point at this altitude in the rows "
                         f"(altitudes present: {sorted({r['altitude_m'] for r in rows})})")
    fig = Figure(figsize=(12.0, 2.8), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, len(TRIM_PANELS))
    for model, style in (("QS", "o--"), ("US", "s-"), ("FS", "^-.")):
        sel = sorted((r[xkey] * scale, *(r[k] for k, _ in TRIM_PANELS)) for r in at_h if r["model"] == model)
        if sel:
            cols = np.array(sel).T
            for ax, y in zip(axes, cols[1:]):
                ax.plot(cols[0], y, style, label=model)
    for ax, (_, label) in zip(axes, TRIM_PANELS):
        ax.set_ylabel(label)
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3)
    axes[0].legend()
    fig.suptitle(f"Trim at the flutter point, h = {altitude_m:.0f} m (flexsim, notional GTM)")
    out = Path(path)
    fig.savefig(out, dpi=110)
    return out
