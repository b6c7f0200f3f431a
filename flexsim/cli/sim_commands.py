"""Command-line commands for simulation and log viewing (thin adapters over :mod:`flexsim.sim`).

    flexsim simulate MANOEUVRE|SCRIPT.py [--duration S] [--log PATH | --no-log] [--aero unsteady|quasi-steady]
                     [--method auto|Radau|DOP853|...] [--rtol R]
    flexsim view LOG.mcap [--save FILE.rrd] [--connect URL] [--port N]

MANOEUVRE is a registered manoeuvre (:func:`flexsim.sim.manoeuvres.manoeuvre_names`); a SCRIPT.py is run
as ``__main__`` with ``--duration``, ``--log`` and ``--aero`` passed on (scripts read them with
:func:`script_arguments`). ``view`` opens the log in a Rerun viewer, or with ``--save`` writes a Rerun
recording (``.rrd``) without a viewer.
"""

from __future__ import annotations

import argparse
import runpy
import shutil
import sys
import warnings
from pathlib import Path
from typing import Sequence

from flexsim.aircraft.definition import FORMULATIONS

__all__ = ["add_sim_commands", "script_arguments"]

_AERO = ("unsteady", "quasi-steady")


def script_arguments(description: str | None = None, argv: Sequence[str] | None = None) -> argparse.Namespace:
    """Options shared by manoeuvre scripts and ``flexsim simulate``: ``--duration``, ``--log``, ``--aero``.

    Returns
    -------
    argparse.Namespace
        ``duration`` (float [s] or None: the manoeuvre's default), ``log`` (path or None: the default
        ``logs/<manoeuvre>-<time>.mcap``), ``aero`` ("unsteady" or "quasi-steady").
    """
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--duration", type=float, metavar="S", help="simulated time [s] (default: the manoeuvre's)")
    parser.add_argument("--log", metavar="PATH", help="flight log to write (.mcap) [logs/<manoeuvre>-<time>.mcap]")
    parser.add_argument("--aero", choices=_AERO, default="unsteady", help="aerodynamic model [unsteady]")
    return parser.parse_args(argv)


def _simulate(args: argparse.Namespace) -> int:
    from flexsim.sim.manoeuvres import build_manoeuvre
    from flexsim.sim.recording import default_log_path
    from flexsim.sim.run_settings import OutputSettings
    from flexsim.sim.simulate import IntegratorSettings

    target = args.manoeuvre
    if target.endswith(".py"):
        return _run_script(Path(target), args)
    if args.log is not None and args.no_log:
        raise ValueError("--log and --no-log: give at most one")
    if args.log is not None:
        from flexsim.cli.validation import check_log_path

        check_log_path("simulate", args.log)
    setup = build_manoeuvre(target, aero=args.aero, duration_s=args.duration, formulation=args.formulation)
    log_path = None if args.no_log else (args.log or default_log_path(setup.name))
    integrator = IntegratorSettings(args.method, args.rtol)
    print(f"{setup.name}: {setup.description}; {setup.duration_s:g} s, aero {args.aero}")
    result = setup.simulate(integrator=integrator, output=OutputSettings(log_path=log_path))
    print(result.summary())
    return 1 if result.status in ("non_finite", "solver_failure") else 0


def _run_script(path: Path, args: argparse.Namespace) -> int:
    if not path.is_file():
        raise FileNotFoundError(f"script {str(path)!r} not found")
    if args.no_log or args.method != "auto" or args.rtol is not None or args.formulation is not None:
        raise ValueError("--no-log, --method, --rtol and --formulation apply to named manoeuvres; a script takes --duration, --log, --aero")
    argv = [str(path), "--aero", args.aero]
    if args.duration is not None:
        argv += ["--duration", repr(args.duration)]
    if args.log is not None:
        argv += ["--log", args.log]
    saved = sys.argv
    sys.argv = argv
    try:
        runpy.run_path(str(path), run_name="__main__")
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        sys.argv = saved
    return 0


def _port(text: str) -> int:
    """argparse type: a TCP port number in [1, 65535]."""
    try:
        port = int(text)
    except ValueError:
        port = 0
    if not 1 <= port <= 65535:
        raise argparse.ArgumentTypeError(f"--port = {text!r}: must be an integer in [1, 65535]")
    return port


def _executable(text: str) -> str:
    """argparse type: the path of an executable file (``--viewer``), or a command name found on PATH."""
    found = shutil.which(text)
    if found is None:
        raise argparse.ArgumentTypeError(f"--viewer = {text!r}: not an executable file nor a command on PATH")
    return found


def _view(args: argparse.Namespace) -> int:
    if args.log.endswith(".rrd"):  # a Rerun recording (e.g. of a flutter mode): shown as it is
        from flexsim.io.mode_recording import open_recording

        if args.save:
            raise ValueError(f"--save = {args.save!r}: {args.log!r} is already a Rerun recording (open it with `rerun {args.log}`)")
        print(f"sent {args.log} to {open_recording(args.log, connect=args.connect, viewer_port=args.port, viewer_executable=args.viewer)}")
        return 0
    from flexsim.io.flight_log import FlightLogRecoveryWarning, read_flight_log
    from flexsim.io.viewer import HEADLESS_HINT, ViewerUnavailableError, viewer_unavailable_reason

    no_viewer = viewer_unavailable_reason() if not args.save and args.connect is None else None
    if no_viewer is not None:  # fail before importing rerun and reading the log
        raise ViewerUnavailableError(f"cannot open a Rerun viewer: {no_viewer}; {HEADLESS_HINT}")
    from flexsim.io.rerun_view import log_to_recording

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", FlightLogRecoveryWarning)
        log = read_flight_log(args.log)
    for w in caught:
        if issubclass(w.category, FlightLogRecoveryWarning):
            print(f"flexsim view: warning: {w.message}", file=sys.stderr)
    span = f"t = {log.t[0]:g} .. {log.t[-1]:g} s" if len(log.t) else "no samples"
    print(f"{args.log}: {len(log.t)} samples ({span}), {len(log.events)} events, "
          f"{'complete' if log.complete else 'incomplete (recovered)'}")
    for event in log.events:
        print(f"  [{event.level}] t = {event.t_s:.3f} s: {event.text}")
    if args.save and args.connect is None:
        log_to_recording(log, rrd_path=args.save)
        print(f"Rerun recording saved to {args.save} (open it with: rerun {args.save})")
        return 0
    where = args.connect or f"a new Rerun viewer on port {args.port}"
    print(f"sending the log to {where} ...", flush=True)
    log_to_recording(log, rrd_path=args.save, spawn=args.connect is None, connect=args.connect, viewer_port=args.port,
                     viewer_executable=args.viewer)
    if args.save:
        print(f"Rerun recording saved to {args.save} (open it with: rerun {args.save})")
    return 0


def add_sim_commands(subparsers: argparse._SubParsersAction) -> None:
    """Add the ``simulate`` and ``view`` commands to the ``flexsim`` parser's subparsers."""
    from flexsim.sim.manoeuvres import manoeuvre_names
    from flexsim.sim.simulate import METHODS

    names = ", ".join(manoeuvre_names())
    p_sim = subparsers.add_parser("simulate", help="simulate a named manoeuvre or run a manoeuvre script, writing a flight log",
                                  description=f"Simulate a named manoeuvre ({names}) or run a manoeuvre script (.py). "
                                              "A script is Python code and is executed with your rights, like "
                                              "'python SCRIPT.py': run only scripts you trust.")
    p_sim.add_argument("manoeuvre", metavar="MANOEUVRE|SCRIPT.py", help=f"one of: {names}; or a Python script (executed as code)")
    p_sim.add_argument("--duration", type=float, metavar="S", help="simulated time [s] (default: the manoeuvre's)")
    p_sim.add_argument("--log", metavar="PATH", help="flight log (.mcap) [logs/<manoeuvre>-<time>.mcap]")
    p_sim.add_argument("--no-log", action="store_true", help="do not write a flight log")
    p_sim.add_argument("--aero", choices=_AERO, default="unsteady", help="aerodynamic model [unsteady]")
    p_sim.add_argument("--formulation", choices=FORMULATIONS, default=None,
                       help="force resolution of the strip airloads (physical or paper, docs/design.md) [the aircraft file's]")
    p_sim.add_argument("--method", choices=["auto", *METHODS], default="auto", help="integration method [auto: ETD2RK (20 ms steps) with aerodynamics, DOP853 without]")
    p_sim.add_argument("--rtol", type=float, help="relative tolerance [method's default]")
    p_sim.set_defaults(func=_simulate)

    p_view = subparsers.add_parser("view", help="show a flight log in Rerun, or save it as a Rerun recording")
    p_view.add_argument("log", metavar="LOG.mcap", help="flight log written by flexsim simulate, or a Rerun recording (.rrd)")
    p_view.add_argument("--save", metavar="FILE.rrd", help="write a Rerun recording instead of opening a viewer")
    p_view.add_argument("--connect", metavar="URL",
                        help="stream to a Rerun viewer or server already running at URL (rerun+http://HOST:9876/proxy) "
                             "instead of starting one (with --save: both)")
    p_view.add_argument("--port", type=_port, default=9876, metavar="N",
                        help="port of the viewer to start (a viewer already listening there is reused) [9876]")
    p_view.add_argument("--viewer", type=_executable, metavar="PATH",
                        help="the rerun executable to start [the one installed with rerun-sdk]")
    p_view.set_defaults(func=_view)
