"""Command-line interface: thin commands over the Python API.

    flexsim info  [AIRCRAFT] [--json]
    flexsim modes [AIRCRAFT] [--variant free|restrained|quasi-rigid] [--components NAME ...]
                  [--bending-modes M] [--torsion-modes N] [--count K] [--json]
    flexsim aero  [AIRCRAFT] [--mach M] [--plot FILE.png] [--json]
    flexsim trim  [AIRCRAFT] [--altitude-m H] [--mach M | --speed-m-s V] [--turn-radius-m R] [--climb-deg G | --glide]
                  [--load-factor N] [--nonlinear-beams [N]]
    flexsim flutter [AIRCRAFT] [--altitudes H ...] [--models QS,US] [--workers N] [--load-factor N]
                    [--nonlinear-beams [N]] [--json]
    flexsim linearize [AIRCRAFT] [--altitude-m H] [--mach M | --speed-m-s V] [--turn-radius-m R | --climb-deg G] --out FILE.npz
    flexsim validate [CASE ...] [--json]
    flexsim sweep (--turn | --climb | --pull-up) [AIRCRAFT] [--altitudes H ...] [--scheduler ADDRESS] [--out DIR]
                  [--load-factors N ...] [--nonlinear-beams [N]]

AIRCRAFT is a bundled name (``gtm``, ``goland_wing``) or the path of a TOML file (default ``gtm``).
"""

from __future__ import annotations

import os

# Small dense linear algebra: BLAS threads only oversubscribe the cores (docs/design.md, Performance).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import sys  # noqa: E402
from typing import Sequence

import numpy as np

from flexsim.aircraft.definition import Aircraft
from flexsim.aircraft.toml_loader import bundled_aircraft_names, load_aircraft
from flexsim.cli.validation import CliError, SanitisedStream, in_user_words, check_count, check_mach, check_plot_path, json_text, printable
from flexsim.errors import FlexsimError
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel, Variant
from flexsim.model.linear_range import nonlinear_fields_note
from flexsim.structure.model import StructuralModel

__all__ = ["main"]


def _aircraft(args: argparse.Namespace) -> Aircraft:
    aircraft = load_aircraft(args.aircraft)
    if getattr(args, "components", None):
        aircraft = aircraft.subset(args.components)
    m, n = getattr(args, "bending_modes", None), getattr(args, "torsion_modes", None)
    for flag, value in (("--bending-modes", m), ("--torsion-modes", n)):
        if value is not None and not 0 <= value <= 10:
            raise CliError(f"{flag} = {value}: must be an integer in [0, 10] (shape functions per component)")
    if m is not None or n is not None:
        first = next(c for c in aircraft.components)
        aircraft = aircraft.with_modes(
            first.bending_modes if m is None else m, first.torsion_modes if n is None else n
        )
    return aircraft


def _info(args: argparse.Namespace) -> int:
    aircraft = _aircraft(args)
    mp = StructuralModel(aircraft).mass_properties
    ixx, iyy, izz, ixz = mp.ixx_iyy_izz_ixz
    out = {
        "aircraft": aircraft.name,
        "source": aircraft.source,
        "components": list(aircraft.component_names),
        "mass_kg": mp.mass_kg,
        "cg_body_m": mp.cg_m.tolist(),
        "inertia_cg_body_kg_m2": mp.inertia_cg_kg_m2.tolist(),
        "ixx_iyy_izz_ixz_kg_m2": [ixx, iyy, izz, ixz],
        "nonlinear_beam_fields": list(aircraft.nonlinear_beam_fields),
    }
    if aircraft.design_origin_m is not None:
        out["cg_design_m"] = aircraft.to_design_frame(mp.cg_m).tolist()
    if args.json:
        print(json_text(out))
        return 0
    print(f"{aircraft.name}  ({aircraft.source})")
    print(f"  components       : {', '.join(aircraft.component_names)}")
    print(f"  mass             : {mp.mass_kg:12.1f} kg")
    print("  CG (body axes)   : x = {:.4f} m, y = {:.4f} m, z = {:.4f} m  (from o; x fwd, z down)".format(*mp.cg_m))
    if "cg_design_m" in out:
        print("  CG (design axes) : x = {:.4f} m, y = {:.4f} m, z = {:.4f} m  (x aft, z up)".format(*out["cg_design_m"]))
    print("  inertia about CG (body axes) [kg m^2]:")
    print(f"    Ixx = {ixx:12.5e}   Iyy = {iyy:12.5e}   Izz = {izz:12.5e}   Ixz = {ixz:12.5e}")
    note = nonlinear_fields_note(aircraft)
    if note is not None:
        print(note)
    return 0


def _modes(args: argparse.Namespace) -> int:
    check_count(args.count)
    aircraft = _aircraft(args)
    model = AircraftModel(aircraft, variant=args.variant, gravity_m_s2=0.0)
    analysis = in_vacuo_modes(model)
    modes = analysis.modes[: args.count] if args.count else analysis.modes
    if args.json:
        print(
            json_text(
                {
                    "aircraft": aircraft.name,
                    "variant": model.variant.kind.value,
                    "n_rigid": analysis.n_rigid,
                    "modes": [
                        {
                            "frequency_rad_s": m.frequency_rad_s,
                            "frequency_hz": m.frequency_hz,
                            "component": m.component,
                            "dof": m.dominant_dof,
                            "energy_fraction": m.dominant_fraction,
                        }
                        for m in modes
                    ],
                },
            )
        )
        return 0
    print(f"In-vacuo modes of {aircraft.name} ({model.variant.kind.value}; {analysis.n_rigid} rigid-body modes)")
    print(f"{'#':>3} {'omega [rad/s]':>14} {'f [Hz]':>10}  {'dominant DOF':<34} {'KE share':>8}")
    for i, m in enumerate(modes, 1):
        print(f"{i:>3} {m.frequency_rad_s:14.4f} {m.frequency_hz:10.4f}  {m.dominant_dof:<34} {m.dominant_fraction:8.1%}")
    note = nonlinear_fields_note(aircraft)
    if note is not None:
        print(note)
    return 0


def _aero(args: argparse.Namespace) -> int:
    from flexsim.aero.lift_slopes import vlm_surfaces
    from flexsim.model.strips import StripSet
    from flexsim.aero.vlm import plot_lift_slope, solve_vlm

    from flexsim.cli.validation import PRANDTL_GLAUERT_MACH_MAX

    check_mach("aero", args.mach, allow_zero=True)
    plot = check_plot_path(args.plot) if args.plot else None
    aircraft = _aircraft(args)
    strips = StripSet.from_model(StructuralModel(aircraft))
    mach = min(args.mach, PRANDTL_GLAUERT_MACH_MAX)  # the model's cap (flexsim.model.coupling)
    factor = 1.0 / np.sqrt(1.0 - mach**2)  # Prandtl-Glauert (paper, "Numerical Model")
    rows = [
        {
            "component": name,
            "station_m": float(strips.station_m[j]),
            "y_m": float(strips.position_body_m[j, 1]),
            "chord_m": float(2 * strips.semichord_m[j]),
            "a": float(strips.a[j]),
            "lift_slope_per_rad": float(strips.lift_slope0[j] * factor),
        }
        for j, name in enumerate(strips.component)
    ]
    if args.plot:
        lattice = [s for s in vlm_surfaces(aircraft)]
        if not lattice:
            raise ValueError(f"aircraft {aircraft.name!r} has no wing or stabilizer strips for the vortex lattice")
        plot_lift_slope(solve_vlm(lattice, mach=mach, compressibility="prandtl_glauert"), plot)
    if args.json:
        print(json_text({"aircraft": aircraft.name, "mach": args.mach, "strips": rows}))
        return 0
    print(f"Aerodynamic strips of {aircraft.name} at M = {args.mach:.3f} (Cl_alpha with Prandtl-Glauert)")
    print(f"{'component':<12} {'x_i [m]':>8} {'y [m]':>8} {'chord [m]':>9} {'a':>6} {'Cl_alpha':>9}")
    for r in rows:
        print(f"{r['component']:<12} {r['station_m']:8.3f} {r['y_m']:8.3f} {r['chord_m']:9.3f} {r['a']:6.3f} {r['lift_slope_per_rad']:9.4f}")
    if args.plot:
        print(f"Cl_alpha distribution plotted to {args.plot}")
    return 0


#: Commands registered by the other CLI modules; ``simulate`` and ``view`` import flexsim.sim (manoeuvre names and
#: integration methods for their help), which the other commands do not need.
_MODULE_COMMANDS = {"trim": "flutter", "flutter": "flutter", "sweep": "flutter", "simulate": "sim", "view": "sim",
                    "validate": "validate", "linearize": "linear"}


def _parser(command: str | None = None) -> argparse.ArgumentParser:
    """The CLI's parser; with ``command`` (the name given on the command line), the other modules' commands are
    left out, so that running e.g. ``flexsim flutter`` does not import what only ``flexsim simulate`` needs."""
    group = _MODULE_COMMANDS.get(command, "main" if command in ("info", "modes", "aero") else None)
    parser = argparse.ArgumentParser(prog="flexsim", description="Flexible aircraft in manoeuvring flight.")
    sub = parser.add_subparsers(dest="command", required=True)
    bundled = ", ".join(bundled_aircraft_names())

    def add_aircraft(p: argparse.ArgumentParser) -> None:
        p.add_argument("aircraft", nargs="?", default="gtm", help=f"bundled aircraft ({bundled}) or TOML path [gtm]")
        p.add_argument("--json", action="store_true", help="print machine-readable JSON")
        p.add_argument("--components", nargs="+", metavar="NAME", help="keep only these components")

    p_info = sub.add_parser("info", help="mass, centre of gravity and inertia tensor")
    add_aircraft(p_info)
    p_info.set_defaults(func=_info)

    p_modes = sub.add_parser("modes", help="in-vacuo natural frequencies and dominant DOFs")
    add_aircraft(p_modes)
    p_modes.add_argument("--variant", default="free", choices=[v.value for v in Variant])
    p_modes.add_argument("--bending-modes", type=int, metavar="M", help="bending shape functions per component")
    p_modes.add_argument("--torsion-modes", type=int, metavar="N", help="torsion shape functions per component")
    p_modes.add_argument("--count", type=int, default=0, metavar="K", help="print only the first K modes")
    p_modes.set_defaults(func=_modes)

    p_aero = sub.add_parser("aero", help="aerodynamic strips and their lift-curve slopes (vortex lattice)")
    add_aircraft(p_aero)
    p_aero.add_argument("--mach", type=float, default=0.0, help="flight Mach number for Prandtl-Glauert [0]")
    p_aero.add_argument("--plot", metavar="FILE.png", help="draw the Cl_alpha distribution (cf. paper Fig. 6)")
    p_aero.set_defaults(func=_aero)

    if group in (None, "flutter"):
        from flexsim.cli.flutter_commands import add_flutter_commands

        add_flutter_commands(sub, add_aircraft)
    if group in (None, "sim"):
        from flexsim.cli.sim_commands import add_sim_commands

        add_sim_commands(sub)
    if group in (None, "linear"):
        from flexsim.cli.linear_commands import add_linear_commands

        add_linear_commands(sub, add_aircraft)
    if group in (None, "validate"):
        from flexsim.cli.validate_command import add_validate_command

        add_validate_command(sub)
    return parser


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP received: raised in the main thread, so that the command ends as on Ctrl-C (worker
    processes stopped, finished points kept, files closed) instead of dying with its children left running."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def _terminate(signum: int, frame) -> None:
    raise Terminated(signum)


def _end_on_signals() -> dict:
    """Raise :class:`Terminated` on SIGTERM and SIGHUP (main thread only); returns the handlers it replaced."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return {}
    old = {}
    for name in ("SIGTERM", "SIGHUP"):
        sig = getattr(signal, name, None)
        if sig is not None and signal.getsignal(sig) in (signal.SIG_DFL, None):
            old[sig] = signal.signal(sig, _terminate)
    return old


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``flexsim`` command; returns the process exit code."""
    import signal

    argv = sys.argv[1:] if argv is None else list(argv)
    parser = _parser(argv[0] if argv else None)
    args = parser.parse_args(argv)
    np.set_printoptions(precision=5)
    stdout = sys.stdout
    sys.stdout = SanitisedStream(stdout)  # names from files are printed with escape sequences shown, not run
    handlers = _end_on_signals()
    try:
        return int(args.func(args))  # first compiles show their progress (flexsim._numba_cache.CompileProgress)
    except BrokenPipeError:  # output piped into e.g. `head`
        sys.stderr.close()
        return 0
    except Terminated as exc:
        print(f"flexsim {args.command}: terminated by {signal.Signals(exc.signum).name}", file=sys.stderr)
        return 128 + exc.signum
    except KeyboardInterrupt:
        print(f"flexsim {args.command}: interrupted", file=sys.stderr)
        return 130
    except (FlexsimError, OSError, KeyError, ValueError, RuntimeError) as exc:
        text = str(exc.args[0]) if isinstance(exc, KeyError) and exc.args else str(exc)  # a KeyError's str() is quoted
        print(f"flexsim {args.command}: error: {printable(in_user_words(text))}", file=sys.stderr)
        return 2
    finally:
        sys.stdout = stdout
        for sig, handler in handlers.items():
            signal.signal(sig, handler)


#: Commands that leave nothing to finish at exit (they print; they open no file, log or pool that outlives them).
_QUICK_EXIT = ("info", "modes", "trim", "flutter")


def run(argv: Sequence[str] | None = None) -> None:
    """Run :func:`main` as a program and end the process with its exit code.

    After a command of :data:`_QUICK_EXIT` the process ends with ``os._exit`` once stdout and stderr are flushed,
    without the interpreter's teardown: freeing numba's, scipy's and flexsim's module state takes longer than
    ``flexsim info`` itself (measured 0.6 s of wall time at load 7 after importing scipy, 1.1-1.7 s after
    importing flexsim's CLI and calling one compiled function, against 0.15 s after numpy alone).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    code = main(argv)
    if not argv or argv[0] not in _QUICK_EXIT:
        sys.exit(code)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # output piped into e.g. `head` (closed), or stderr closed by main
            pass
    os._exit(code)


if __name__ == "__main__":
    run()
