"""`flexsim linearize`: the linear model of a trimmed aircraft for control design, written to an ``.npz`` file.

    flexsim linearize [AIRCRAFT] [--altitude-m H] [--mach M | --speed-m-s V] [--turn-radius-m R [--coordinated] | --climb-deg G]
                      [--aero quasi-steady|unsteady] [--n-inflow N] [--formulation F] [--state-outputs]
                      [--no-limits] --out FILE.npz [--json]

A thin command over :func:`flexsim.trimming.trim` and :func:`flexsim.linear.control.linear_system`; the file holds A, B,
C, D with the state, input and output names, the trim point and the model options (:meth:`LinearSystem.save`).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from flexsim.cli.validation import CliError, check_trim_options, flight_condition, check_writable_dir, json_text

__all__ = ["add_linear_commands"]

#: Inflow states per strip of ``--aero unsteady`` without ``--n-inflow`` (Peters' N = 6, as the flutter searches).
N_INFLOW = 6


def _check_out(path: str) -> Path:
    """``--out``: a new or existing ``.npz`` file in an existing, writable directory."""
    p = Path(path)
    if p.is_dir():
        raise CliError(f"--out = {path!r}: is a directory; give a file name such as {str(p / 'linear.npz')!r}")
    if p.suffix != ".npz":
        raise CliError(f"--out = {path!r}: must end in .npz (the numpy archive the linear model is written to)")
    check_writable_dir("--out", path, p.parent)
    return p


def _linearize(args: argparse.Namespace) -> int:
    check_trim_options(args)
    if args.coordinated and args.turn_radius_m is None:
        raise CliError("--coordinated: applies to turns only; give --turn-radius-m")
    if args.n_inflow is not None and args.aero != "unsteady":
        raise CliError(f"--n-inflow {args.n_inflow}: applies to --aero unsteady (inflow states of the finite-state model); "
                       f"the {args.aero} model has none")
    args.n_inflow = N_INFLOW if args.n_inflow is None else args.n_inflow
    if not 1 <= args.n_inflow <= 10:
        raise CliError(f"--n-inflow = {args.n_inflow}: must be an integer in [1, 10] (inflow states per strip)")
    out = _check_out(args.out)
    condition = flight_condition("linearize", args)

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.control import linear_system
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.trimming import SteadyManoeuvre, trim

    aircraft = load_aircraft(args.aircraft)
    if args.components:
        aircraft = aircraft.subset(args.components)
    radius = math.inf if args.turn_radius_m is None else float(args.turn_radius_m)
    climb = math.radians(args.climb_deg or 0.0)
    manoeuvre = SteadyManoeuvre(condition.speed_m_s, condition.altitude_m, radius, climb, bool(args.coordinated))
    qs = AircraftModel(aircraft, aero=AeroOptions("quasi-steady", formulation=args.formulation))
    point = trim(qs, manoeuvre, check_limits=not args.no_limits)
    model = qs if args.aero == "quasi-steady" else AircraftModel(
        aircraft, aero=AeroOptions("unsteady", args.n_inflow, formulation=args.formulation))
    system = linear_system(model, point, state_outputs=args.state_outputs)
    system.save(out)
    poles = system.poles()
    unstable = sorted((p for p in poles if p.real > 0.0), key=lambda p: -p.real)
    doc = {"aircraft": aircraft.name, "manoeuvre": manoeuvre.describe(), "flight_condition": condition.describe(), "aero_model": args.aero,
           "formulation": model.formulation, "out": str(out), "bytes": out.stat().st_size,
           "states": len(system.state_names), "inputs": list(system.input_names), "outputs": len(system.output_names),
           "trim": {"alpha_rad": point.alpha, "theta_rad": point.theta, "phi_rad": point.phi,
                    "controls": dict(zip(system.input_names[:4], point.u.tolist()))},
           "unstable_poles": [[p.real, p.imag] for p in unstable]}
    if args.json:
        print(json_text(doc))
        return 0
    print(f"Linear model of {aircraft.name} ({args.aero} aerodynamics, {model.formulation} force resolution): "
          f"{manoeuvre.describe()}")
    if condition.derived:
        print(f"  flight condition : {condition.describe()}")
    print(f"  states  : {doc['states']} (X, Y, Z and psi removed: the density is frozen at the trim altitude)")
    print(f"  inputs  : {', '.join(system.input_names)}")
    print(f"  outputs : {doc['outputs']} ({'sensor bank and states' if args.state_outputs else 'sensor bank'})")
    print(f"  trim    : alpha = {math.degrees(point.alpha):.4f} deg, elevator = {math.degrees(point.u[2]):.4f} deg, "
          f"thrust = {point.u[0]:.6g} N")
    if unstable:
        worst = unstable[0]
        print(f"  poles   : {len(unstable)} with a positive real part, the largest {worst.real:.5g} "
              f"{'+-' if worst.imag else '+'} {abs(worst.imag):.5g}j 1/s")
    else:
        print("  poles   : none with a positive real part")
    print(f"written to {out} ({doc['bytes']} bytes; read it with flexsim.linear.control.LinearSystem.load)")
    return 0


def add_linear_commands(sub: argparse._SubParsersAction, add_aircraft) -> None:
    """Register ``linearize`` on the CLI's subparsers."""
    p = sub.add_parser("linearize", help="linear model (A, B, C, D with names) of a trim, for control design")
    add_aircraft(p)
    p.add_argument("--altitude-m", type=float, default=None, metavar="H",
                   help="trim altitude [m] [the aircraft file's envelope.cruise_altitude_m, else sea level]")
    speed = p.add_mutually_exclusive_group()
    speed.add_argument("--mach", type=float, default=None, metavar="M",
                       help="trim Mach number [the aircraft file's cruise speed, else 1.3 x its stall speed]")
    speed.add_argument("--speed-m-s", type=float, default=None, metavar="V", help="trim true airspeed [m/s] instead of --mach")
    flight = p.add_mutually_exclusive_group()
    flight.add_argument("--turn-radius-m", type=float, default=None, metavar="R",
                        help="steady level turn of this radius [m] (negative: to the left)")
    flight.add_argument("--climb-deg", type=float, default=None, metavar="G", help="flight-path angle [deg] [0]")
    p.add_argument("--coordinated", action="store_true",
                   help="coordinated turn: zero sideslip at the CG, heading free (default: the paper's turn)")
    p.add_argument("--aero", choices=("quasi-steady", "unsteady"), default="quasi-steady",
                   help="aerodynamics of the linear model: quasi-steady, or finite-state unsteady (its inflow states "
                        "become states of the model) [quasi-steady]")
    p.add_argument("--n-inflow", type=int, default=None, metavar="N", help="inflow states per strip with --aero unsteady [6]")
    from flexsim.aircraft.definition import FORMULATIONS

    p.add_argument("--formulation", choices=FORMULATIONS, default=None,
                   help="force resolution of the strip airloads [the aircraft file's]")
    p.add_argument("--state-outputs", action="store_true", help="append every state to the outputs (C = [S; I])")
    p.add_argument("--no-limits", action="store_true",
                   help="do not enforce the thrust/surface and angle-of-attack limits of the trim")
    p.add_argument("--out", required=True, metavar="FILE.npz", help="file to write the linear model to")
    p.set_defaults(func=_linearize)
