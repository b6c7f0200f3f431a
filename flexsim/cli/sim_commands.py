"""Command-line commands for simulation and log viewing (thin adapters over :mod:`flexsim.sim`).

    flexsim simulate MANOEUVRE|SCRIPT.py|AIRCRAFT [--aircraft AIRCRAFT] [--altitude-m H] [--mach M | --speed-m-s V]
                     [--duration S] [--log PATH | --no-log] [--aero unsteady|quasi-steady]
                     [--method auto|Radau|DOP853|...] [--rtol R] [--nonlinear-beams [N]]
    flexsim view LOG.mcap [--save FILE.rrd] [--connect URL] [--port N]

MANOEUVRE is a registered manoeuvre (:func:`flexsim.sim.manoeuvres.manoeuvre_names`); a SCRIPT.py is run
as ``__main__`` with ``--duration``, ``--log`` and ``--aero`` passed on (scripts read them with
:func:`script_arguments`). ``view`` opens the log in a Rerun viewer, or with ``--save`` writes a Rerun
recording (``.rrd``) without a viewer.
"""

from __future__ import annotations

import argparse
import re
import runpy
import shutil
import sys
import warnings
from pathlib import Path
from typing import Sequence

import numpy as np

from flexsim.aircraft.definition import FORMULATIONS

__all__ = ["add_sim_commands", "script_arguments"]

_AERO = ("unsteady", "quasi-steady")
#: Port of the Rerun viewer that ``flexsim view`` starts without ``--port``.
VIEWER_PORT = 9876
#: What ``flexsim simulate AIRCRAFT`` flies.
DEFAULT_MANOEUVRE = "elevator-doublet"


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

    from flexsim.sim.manoeuvres import manoeuvre_names

    target = args.manoeuvre
    if target.endswith(".py"):
        if args.nonlinear_beams is not None:
            raise ValueError("--nonlinear-beams: applies to named manoeuvres and aircraft; a script builds its own model "
                             "(fs.simulate_flexible, docs/nonlinear-beams.md)")
        args.aero = args.aero or "unsteady"
        return _run_script(Path(target), args)
    if target not in manoeuvre_names():  # an aircraft: its elevator doublet from level flight at its cruise point
        from flexsim.aircraft.toml_loader import bundled_aircraft_names

        if not (target in bundled_aircraft_names() or target.endswith(".toml")):
            raise ValueError(f"{target!r}: unknown; valid manoeuvres: {', '.join(manoeuvre_names())}; or a script (.py), or "
                             f"an aircraft ({', '.join(bundled_aircraft_names())} or a .toml file)")
        if args.aircraft is not None:
            raise ValueError(f"{target!r} and --aircraft {args.aircraft!r}: give the aircraft once")
        target, args.aircraft = DEFAULT_MANOEUVRE, target
    if args.mach is not None and args.speed_m_s is not None:
        raise ValueError(f"--mach {args.mach:g} and --speed-m-s {args.speed_m_s:g}: give the speed once")
    if args.log is not None and args.no_log:
        raise ValueError("--log and --no-log: give at most one")
    if args.log is not None:
        from flexsim.cli.validation import check_log_path

        check_log_path("simulate", args.log)
    if args.nonlinear_beams is not None:
        return _simulate_nonlinear(target, args)
    args.aero = args.aero or "unsteady"
    setup = build_manoeuvre(target, aero=args.aero, duration_s=args.duration, formulation=args.formulation,
                            aircraft=args.aircraft, altitude_m=args.altitude_m, mach=args.mach, speed_m_s=args.speed_m_s)
    log_path = None if args.no_log else (args.log or default_log_path(setup.name))
    if args.rtol is not None and args.method in ("auto", "ETD2RK"):  # every named manoeuvre flies with aerodynamics
        raise ValueError(f"--rtol {args.rtol:g}: applies to the adaptive methods (--method DOP853, Radau, ...); ETD2RK, "
                         "the method with aerodynamics by default, takes fixed steps and has no tolerance")
    integrator = IntegratorSettings(args.method, args.rtol)
    print(f"{setup.name}: {setup.description}; {setup.duration_s:g} s, aero {args.aero}")
    result = setup.simulate(integrator=integrator, output=OutputSettings(log_path=log_path))
    print(result.summary())
    return 1 if result.status in ("non_finite", "solver_failure") else 0


def _simulate_nonlinear(name: str, args: argparse.Namespace) -> int:
    """``flexsim simulate MANOEUVRE --nonlinear-beams [N]``: the manoeuvre of the nonlinear aircraft
    (:func:`flexsim.sim.flexible_manoeuvres.build_flexible_manoeuvre`), its flight log with the deformed beams."""
    from flexsim.cli.nonlinear_commands import beams_option
    from flexsim.sim.flexible_manoeuvres import FLEXIBLE_MANOEUVRES, build_flexible_manoeuvre
    from flexsim.sim.flexible_run import write_flexible_log
    from flexsim.sim.recording import default_log_path

    if name not in FLEXIBLE_MANOEUVRES:
        raise ValueError(f"{name}: not flown with --nonlinear-beams; available: {', '.join(FLEXIBLE_MANOEUVRES)}")
    if args.aircraft is None:
        raise ValueError("--nonlinear-beams: give --aircraft (the aircraft file's flexible components need "
                         "ei_chord_nm2; e.g. phc_hale)")
    if args.formulation is not None:
        raise ValueError(f"--formulation {args.formulation}: applies to the linear structure's strips; with "
                         "--nonlinear-beams the strips resolve the full force on their deformed sections")
    if args.aero == "unsteady":
        raise ValueError("--aero unsteady: with --nonlinear-beams the strips are quasi-steady (give --aero quasi-steady "
                         "or leave it out)")
    if args.method not in ("auto", "BDF"):
        raise ValueError(f"--method {args.method}: with --nonlinear-beams the method is auto (ROS2, 10 ms fixed steps, "
                         "Jacobian frozen at the trim) or BDF (error-controlled, with --rtol)")
    if args.rtol is not None and args.method != "BDF":
        raise ValueError(f"--rtol {args.rtol:g}: applies to --method BDF; the ROS2 steps are fixed")
    if args.rtol is not None and not 0.0 < args.rtol <= 0.1:
        raise ValueError(f"--rtol = {args.rtol!r}: must be in (0, 0.1]")
    beams = beams_option(args.nonlinear_beams)
    setup = build_flexible_manoeuvre(name, args.aircraft, beams=beams, altitude_m=args.altitude_m, mach=args.mach,
                                     speed_m_s=args.speed_m_s, duration_s=args.duration)
    log_path = None if args.no_log else (args.log or default_log_path(setup.name))
    step = None if args.method == "BDF" else 0.01
    print(f"{setup.name}: {setup.description}; {setup.duration_s:g} s, geometrically nonlinear beams "
          f"({beams.elements_per_beam} elements per flexible component), quasi-steady strips")
    run = setup.fly(step_s=step, rtol=args.rtol or 1e-6)
    flex = run.point.aircraft
    peak = run.tip_deflection_fraction.max(axis=0)
    low = run.tip_deflection_fraction.min(axis=0)
    airspeed = np.linalg.norm(run.velocity_m_s - run.wind_body_m_s, axis=1)
    print(f"  integrator : {run.method}; {run.n_rhs} right-hand sides, {run.wall_s:.1f} s wall")
    for i, comp in enumerate(flex.beam_components):
        length = flex.structure.beams[i].length_m
        print(f"  tip {comp:<11}: {100 * run.point.tip_deflection_fraction[i]:+.1f} % of its {length:g} m at trim, "
              f"{100 * low[i]:+.1f} to {100 * peak[i]:+.1f} % in the run (vertical, up +)")
    print(f"  airspeed    : {airspeed.min():.2f} to {airspeed.max():.2f} m/s; altitude {-run.position_m[-1, 2]:.1f} m "
          f"at t = {run.t[-1]:g} s")
    for note in run.warnings:
        print(f"  neglected   : {note}")
    if log_path is not None:
        write_flexible_log(run, log_path, metadata={"manoeuvre": setup.name, "description": setup.description})
        print(f"  flight log  : {log_path} (flexsim view {log_path})")
    return 0


def _run_script(path: Path, args: argparse.Namespace) -> int:
    if not path.is_file():
        raise FileNotFoundError(f"script {str(path)!r} not found")
    named = [flag for flag, given in (("--no-log", args.no_log), ("--method", args.method != "auto"),
                                      ("--rtol", args.rtol is not None), ("--formulation", args.formulation is not None),
                                      ("--aircraft", args.aircraft is not None), ("--altitude-m", args.altitude_m is not None),
                                      ("--mach", args.mach is not None), ("--speed-m-s", args.speed_m_s is not None)) if given]
    if named:
        raise ValueError(f"{', '.join(named)}: apply to named manoeuvres and aircraft; a script takes --duration, --log, --aero")
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


#: The form of a ``--connect`` URL: a Rerun viewer's or server's gRPC proxy.
_CONNECT_URL = re.compile(r"rerun\+https?://[^\s/:]+(:\d{1,5})?/proxy")


def _view(args: argparse.Namespace) -> int:
    if args.connect is not None and not _CONNECT_URL.fullmatch(args.connect):
        raise ValueError(f"--connect = {args.connect!r}: must be the URL of a running Rerun viewer, "
                         "rerun+http://HOST:PORT/proxy (e.g. rerun+http://127.0.0.1:9876/proxy)")
    starts_viewer = args.connect is None and not args.save
    unused = [flag for flag, given in (("--port", args.port is not None), ("--viewer", args.viewer is not None)) if given]
    if unused and not starts_viewer:
        raise ValueError(f"{', '.join(unused)}: apply to the viewer that flexsim view starts; with "
                         f"{'--connect' if args.connect is not None else '--save alone'} none is started")
    args.port = VIEWER_PORT if args.port is None else args.port
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
    p_sim.add_argument("manoeuvre", metavar="MANOEUVRE|SCRIPT.py|AIRCRAFT",
                       help=f"one of: {names}; or a Python script (executed as code); or an aircraft (bundled name or "
                            f".toml): its {DEFAULT_MANOEUVRE} from level flight at its cruise point")
    p_sim.add_argument("--aircraft", metavar="AIRCRAFT", default=None,
                       help="fly the named manoeuvre with this aircraft (bundled name or .toml) from level flight at its "
                            "cruise point [the GTM at 9144 m, M 0.75; flutter-onset: the Goland wing]")
    p_sim.add_argument("--altitude-m", type=float, default=None, metavar="H",
                       help="altitude of the starting level trim [m] [the aircraft file's envelope.cruise_altitude_m]")
    p_sim.add_argument("--mach", type=float, default=None, metavar="M", help="Mach number of the starting level trim "
                       "[the aircraft file's cruise speed]")
    p_sim.add_argument("--speed-m-s", type=float, default=None, metavar="V",
                       help="true airspeed of the starting level trim [m/s] instead of --mach")
    p_sim.add_argument("--duration", type=float, metavar="S", help="simulated time [s] (default: the manoeuvre's)")
    p_sim.add_argument("--log", metavar="PATH", help="flight log (.mcap) [logs/<manoeuvre>-<time>.mcap]")
    p_sim.add_argument("--no-log", action="store_true", help="do not write a flight log")
    p_sim.add_argument("--aero", choices=_AERO, default=None,
                       help="aerodynamic model [unsteady; quasi-steady with --nonlinear-beams]")
    p_sim.add_argument("--formulation", choices=FORMULATIONS, default=None,
                       help="force resolution of the strip airloads (physical or paper, docs/design.md) [the aircraft file's]")
    p_sim.add_argument("--method", choices=["auto", *METHODS], default="auto", help="integration method [auto: ETD2RK (20 ms steps) with aerodynamics, DOP853 without]")
    p_sim.add_argument("--rtol", type=float, help="relative tolerance [method's default]")
    p_sim.add_argument("--nonlinear-beams", type=int, nargs="?", const=8, default=None, metavar="N",
                       help="fly the geometrically nonlinear aircraft with N elements per flexible component [8] "
                            "(with --aircraft; elevator-doublet, aileron-roll, gust-encounter; docs/nonlinear-beams.md)")
    p_sim.set_defaults(func=_simulate)

    p_view = subparsers.add_parser("view", help="show a flight log in Rerun, or save it as a Rerun recording")
    p_view.add_argument("log", metavar="LOG.mcap", help="flight log written by flexsim simulate, or a Rerun recording (.rrd)")
    p_view.add_argument("--save", metavar="FILE.rrd", help="write a Rerun recording instead of opening a viewer")
    p_view.add_argument("--connect", metavar="URL",
                        help="stream to a Rerun viewer or server already running at URL (rerun+http://HOST:9876/proxy) "
                             "instead of starting one (with --save: both)")
    p_view.add_argument("--port", type=_port, default=None, metavar="N",
                        help="port of the viewer to start (a viewer already listening there is reused) [9876]")
    p_view.add_argument("--viewer", type=_executable, metavar="PATH",
                        help="the rerun executable to start [the one installed with rerun-sdk]")
    p_view.set_defaults(func=_view)
