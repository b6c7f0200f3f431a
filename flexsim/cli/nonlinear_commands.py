"""`flexsim trim --nonlinear-beams` and `flexsim flutter --nonlinear-beams`: the model with the geometrically nonlinear
beams (:class:`flexsim.model.terms.NonlinearBeams`), through ``fs.trim`` and ``fs.flutter`` as a script would."""

from __future__ import annotations

import argparse
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import speed_of_sound
from flexsim.linear.flexible_flutter import MAX_FREQUENCY_RAD_S
from flexsim.cli.validation import CliError, check_altitudes, check_mach_range, check_writable_dir, json_text
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.terms import NonlinearBeams, Terms
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.trimming.manoeuvre import LOAD_FACTOR_RANGE

__all__ = ["beams_option", "check_load_factor", "nonlinear_trim", "nonlinear_flutter", "NONLINEAR_HELP"]

#: Help of ``--nonlinear-beams`` (trim and flutter).
NONLINEAR_HELP = ("geometrically nonlinear beams with N elements per flexible component [8] "
                  "(the aircraft file's ei_chord_nm2 needed; docs/nonlinear-beams.md)")


def beams_option(n: int | None) -> NonlinearBeams:
    """``--nonlinear-beams N`` as the model's term, or a CliError in the option's words."""
    try:
        return NonlinearBeams(n)
    except ValueError:
        raise CliError(f"--nonlinear-beams = {n!r}: must be an integer in 1-64 (elements per flexible component)") from None


def check_load_factor(n: float | None) -> None:
    """``--load-factor`` inside :data:`LOAD_FACTOR_RANGE`."""
    lo, hi = LOAD_FACTOR_RANGE
    if n is not None and not (math.isfinite(n) and lo <= n <= hi):
        raise CliError(f"--load-factor = {n!r}: must be a load factor in [{lo:g}, {hi:g}] (1: level flight)")


def _refuse(args: argparse.Namespace, flags: dict[str, bool], why: str) -> None:
    given = [flag for flag, on in flags.items() if on]
    if given:
        raise CliError(f"{', '.join(given)}: {why}")


def nonlinear_trim(args: argparse.Namespace, aircraft, manoeuvre: SteadyManoeuvre, condition) -> int:
    """``flexsim trim --nonlinear-beams``: the nonlinear trim's angles, controls and tip deflections."""
    _refuse(args, {"--formulation": args.formulation is not None},
            "applies to the linear structure's trim; with --nonlinear-beams the strips resolve the full force on their "
            "deformed sections")
    beams = beams_option(args.nonlinear_beams)
    model = AircraftModel(aircraft, terms=Terms(nonlinear_beams=beams))
    point = trim(model, manoeuvre, check_limits=not args.no_limits, classify=False)
    spectrum = None
    if args.roots == "quasi-steady":
        from flexsim.linear.flexible_stability import free_aircraft_spectrum

        spectrum = free_aircraft_spectrum(model, point)
    elif args.roots:
        from flexsim.linear.flexible_unsteady import free_aircraft_unsteady

        spectrum = free_aircraft_unsteady(model, point).spectrum()
    flex = point.aircraft
    tips = {name: float(f) for name, f in zip(flex.beam_components, point.tip_deflection_fraction)}
    u = point.controls
    out = {"alpha_deg": math.degrees(point.alpha_rad), "theta_deg": math.degrees(point.theta_rad),
           "gamma_deg": math.degrees(point.climb_angle_rad), "thrust_N": float(u[0]),
           "aileron_deg": math.degrees(u[1]), "elevator_deg": math.degrees(u[2]), "rudder_deg": math.degrees(u[3]),
           "max_strip_alpha_deg": point.max_strip_alpha_deg, "residual": point.residual}
    roots = None if spectrum is None else [
        {"name": m.name, "kind": m.kind, "real": m.eigenvalue.real, "imag": m.eigenvalue.imag,
         "rigid_share": m.rigid_share} for m in spectrum.modes]
    if args.json:
        extra = {} if spectrum is None else {"roots": roots, "verdict": spectrum.verdict()}
        print(json_text({**out, "tip_deflection_fraction": tips, "flight_condition": condition.describe(),
                         "manoeuvre": manoeuvre.describe(), "terms": point.terms, **extra}))
        return 0
    print(f"Trim of {aircraft.name} (geometrically nonlinear beams, {beams.elements_per_beam} elements per flexible "
          f"component): {manoeuvre.describe()}")
    if condition.derived:
        print(f"  flight condition : {condition.describe()}")
    for key, value in out.items():
        print(f"  {key:<20} {value: .6g}")
    for name, fraction in tips.items():
        print(f"  {'tip ' + name:<20} {100.0 * fraction:+.1f} % of its length (vertical, up +)")
    if spectrum is not None:
        band = MAX_FREQUENCY_RAD_S
        print(f"Roots of the free aircraft linearised about the nonlinear trim ({spectrum.aero} strips; below {band:g} "
              "rad/s, the beams' converged band):")
        print(f"  {'kind':<8} {'real [1/s]':>11} {'imag [rad/s]':>12}  mode")
        for r in roots:
            if abs(complex(r["real"], r["imag"])) <= band:
                print(f"  {r['kind']:<8} {r['real']:11.5f} {r['imag']:12.5f}  {r['name']}")
        print(spectrum.verdict())
    return 0


def nonlinear_flutter(args: argparse.Namespace, vg_paths) -> int:
    """``flexsim flutter --nonlinear-beams [--load-factor n] [--vg FILE.png]``: the wing's flutter about the nonlinear
    trim at each altitude (:func:`flexsim.linear.flexible_flutter.flexible_flutter` through ``fs.flutter``) and its V-g
    diagram (``fs.vg_diagram``); ``vg_paths(vg, altitudes)`` names each altitude's PNG."""
    from flexsim.io.output_paths import check_not_link
    from flexsim.linear.envelope import flutter_altitudes, search_range
    from flexsim.linear.flutter import flutter
    from flexsim.linear.vg import vg_diagram

    if args.nonlinear_beams is None:
        raise CliError(f"--load-factor {args.load_factor:g}: the pull-up's flutter is searched with the geometrically "
                       "nonlinear beams (--nonlinear-beams); for the linear model use "
                       "fs.flutter(model, fs.SteadyManoeuvre.pull_up(h, n)) in Python")
    _refuse(args, {"--wind-tunnel": args.wind_tunnel, "--mode": bool(args.mode),
                   "--components": args.components is not None,
                   "--glide": args.glide, "--formulation": args.formulation is not None,
                   "--paper-replication": args.paper_replication,
                   "--linear-density-altitude-m": args.linear_density_altitude_m is not None,
                   "--speed-range-m-s": args.speed_range_m_s is not None,
                   "--speed-step-m-s": args.speed_step_m_s is not None,
                   "--structural-damping": args.structural_damping is not None},
            "not available with --nonlinear-beams (the flutter of a free-flying aircraft's wing about its nonlinear "
            "trim in level flight, climb, pull-up or turn; a clamped wing in a tunnel is fs.nonlinear_wing_tunnel)")
    if args.models not in ("FS", "QS,US"):  # QS,US: the option's default, not chosen
        raise CliError(f"--models {args.models}: with --nonlinear-beams the flutter is solved with Peters finite-state "
                       "strips only (--models FS)")
    check_load_factor(args.load_factor)
    if args.load_factor is not None and args.load_factor != 1.0 and args.climb_deg:
        raise CliError(f"--load-factor {args.load_factor:g}, --climb-deg {args.climb_deg:g}: a pull-up's bottom has "
                       "gamma = 0; give one of them")
    radius = math.inf if args.turn_radius_m is None else float(args.turn_radius_m)
    if args.load_factor is not None and args.load_factor != 1.0 and radius != math.inf:
        raise CliError(f"--load-factor {args.load_factor:g}, --turn-radius-m {radius:g}: a turn's load factor follows "
                       "from its radius and speed; give one of them")
    if args.coordinated and radius == math.inf:
        raise CliError("--coordinated: applies to turns only; give --turn-radius-m")
    if radius != math.inf and not abs(radius) >= 100.0:
        raise CliError(f"--turn-radius-m = {radius:g}: must be at least 100 m in magnitude")
    beams = beams_option(args.nonlinear_beams)
    if args.free_aircraft:
        if args.vg is not None:
            raise CliError("--vg with --free-aircraft: the V-g diagram of the nonlinear beams tracks the wing clamped at "
                           "its trimmed root; leave out one of them")
        beams = replace(beams, stability="free-aircraft")
    aircraft = load_aircraft(args.aircraft)
    altitudes = args.altitudes if args.altitudes is not None else flutter_altitudes(aircraft)[0]
    check_altitudes(altitudes)
    if args.mach_min is not None and args.mach_max is not None:
        check_mach_range(args.mach_min, args.mach_max)
    paths = vg_paths(args.vg, list(altitudes)) if args.vg is not None else []
    for path in paths:  # every PNG's path checked before the search
        check_not_link("--vg", path)
        check_writable_dir("--vg", str(path), path.parent if str(path.parent) else Path("."))
    model = AircraftModel(aircraft, terms=Terms(nonlinear_beams=beams))
    n = 1.0 if args.load_factor is None else float(args.load_factor)
    gamma = math.radians(args.climb_deg or 0.0)
    rows, vg_lines = [], []
    for i, h in enumerate(altitudes):
        shape = (SteadyManoeuvre.pull_up(h, n, mach=0.5) if n != 1.0
                 else SteadyManoeuvre(0.5 * speed_of_sound(h), h, radius, gamma, bool(args.coordinated)))
        # the envelope (or stall estimate) of the model's linear sibling, or the range given
        found = search_range(model.replace(nonlinear_beams=None), shape, mach_min=args.mach_min, mach_max=args.mach_max)
        rng = (found.mach_min, found.mach_max)
        point = flutter(model, shape, "unsteady", mach_range=rng, mach_step=args.mach_step)
        if paths:
            speeds = np.linspace(rng[0], rng[1], args.vg_points) * speed_of_sound(h)
            diagram = vg_diagram(model, manoeuvre=shape, models=("FS",), speeds_m_s=speeds)
            diagram.plot(paths[i])
            first = diagram.flutter("unsteady")
            said = (f"{first.label} crosses at {first.speed_m_s:.3f} m/s, {first.frequency_rad_s:.3f} rad/s"
                    if first is not None else "no branch crosses into instability")
            vg_lines.append(f"V-g diagram H = {h:.0f} m: {paths[i]} ({said})")
        rows.append({"altitude_m": float(h), "load_factor": n, "climb_deg": float(args.climb_deg or 0.0),
                     "turn_radius_m": radius if radius != math.inf else None, "component": point.component,
                     "speed_m_s": point.speed_m_s, "mach": point.mach, "frequency_rad_s": point.frequency_rad_s,
                     "tip_deflection_fraction": point.tip_deflection_fraction,
                     "scanned_m_s": [float(v) for v in point.speeds_m_s], "warnings": list(point.warnings),
                     "terms": point.terms})
    if args.json:
        print(json_text({"aircraft": aircraft.name, "rows": rows, "vg": vg_lines}))
        return 0
    whose = "the free aircraft" if args.free_aircraft else f"{aircraft.name}'s wing"
    print(f"Flutter of {whose} about the nonlinear trim (geometrically nonlinear beams, "
          f"{beams.elements_per_beam} elements per flexible component; Peters finite-state strips), "
          + (f"load factor {n:g}" if radius == math.inf else
             f"{'coordinated ' if args.coordinated else ''}turn R = {radius:g} m (the less stable wing)"))
    print(f"  {'H [m]':>8} {'V_F [m/s]':>10} {'M_F':>8} {'w_F [rad/s]':>12} {'tip [%]':>8}")
    for r in rows:
        if np.isfinite(r["speed_m_s"]):
            print(f"  {r['altitude_m']:8.0f} {r['speed_m_s']:10.3f} {r['mach']:8.4f} {r['frequency_rad_s']:12.3f} "
                  f"{100.0 * r['tip_deflection_fraction']:+8.1f}")
        else:
            scanned = r["scanned_m_s"]
            where = f"{scanned[0]:.1f}-{scanned[-1]:.1f} m/s" if scanned else "no trimmable speed"
            print(f"  {r['altitude_m']:8.0f}   no flutter in the trimmed scan ({where})")
    for line in vg_lines:
        print(line)
    for note in dict.fromkeys(w for r in rows for w in r["warnings"]):
        print(f"note: {note}")
    return 0


#: Load factors of ``flexsim sweep --pull-up`` without ``--load-factors``.
DEFAULT_LOAD_FACTORS = (1.0, 1.1, 1.2, 1.3, 1.5, 2.0)


def pull_up_sweep(args: argparse.Namespace, models: list[str]) -> int:
    """``flexsim sweep --pull-up``: flutter against load factor, each linear model of ``--models`` and, with
    ``--nonlinear-beams``, the wing about the nonlinear trim, side by side; rows to CSV and JSON in ``--out``."""
    from flexsim.cli.validation import check_out_dir
    from flexsim.linear.envelope import flutter_altitudes, search_range
    from flexsim.linear.flexible_flutter import FlexibleFlutterPoint
    from flexsim.linear.flutter import FlutterNotFound, flutter
    from flexsim.linear.study import MODELS, write_results
    from flexsim.errors import FlexsimError

    _refuse(args, {"--coordinated": args.coordinated, "--radii-m": args.radii_m is not None,
                   "--angles-deg": args.angles_deg is not None, "--scheduler": args.scheduler is not None,
                   "--workers": args.workers is not None, "--chain-length": args.chain_length is not None,
                   "--resume": args.resume, "--structural-damping": args.structural_damping is not None,
                   "--paper-replication": args.paper_replication, "--formulation": args.formulation is not None,
                   "--linear-density-altitude-m": args.linear_density_altitude_m is not None,
                   "--components": args.components is not None},
            "not available with --pull-up (a serial sweep of the whole aircraft's flutter against load factor)")
    factors = list(DEFAULT_LOAD_FACTORS if args.load_factors is None else args.load_factors)
    for n in factors:
        check_load_factor(n)
    beams = beams_option(args.nonlinear_beams) if args.nonlinear_beams is not None else None
    aircraft = load_aircraft(args.aircraft)
    altitudes = args.altitudes if args.altitudes is not None else flutter_altitudes(aircraft)[0]
    check_altitudes(altitudes)
    if args.mach_min is not None and args.mach_max is not None:
        check_mach_range(args.mach_min, args.mach_max)
    out = check_out_dir(args.out)
    linear = AircraftModel(aircraft)
    runs = [(key, MODELS[key], linear) for key in models]
    if beams is not None:
        runs.append(("FS nonlinear", "unsteady", linear.replace(nonlinear_beams=beams)))
    rows = []
    for h in altitudes:
        for n in factors:
            shape = SteadyManoeuvre.pull_up(h, n, mach=0.5)
            found = search_range(linear, shape, mach_min=args.mach_min, mach_max=args.mach_max)
            for label, aero, model in runs:
                row = {"model": label, "altitude_m": float(h), "load_factor": float(n)}
                try:
                    point = flutter(model, shape, aero, mach_range=(found.mach_min, found.mach_max))
                except (FlutterNotFound, FlexsimError, ValueError) as exc:
                    rows.append({**row, "error": str(exc)})
                    continue
                if isinstance(point, FlexibleFlutterPoint):  # the wing about the nonlinear trim
                    if not np.isfinite(point.speed_m_s):
                        skipped = [w for w in point.warnings if w.startswith("speeds not trimmable")]
                        why = "no trimmable speed in the range" if not len(point.speeds_m_s) else \
                            "no crossing in the trimmed scan"
                        rows.append({**row, "error": "; ".join([why, *skipped])})
                        continue
                    tip = point.tip_deflection_fraction
                else:  # the linear model: the right wing's tip at the flutter point, up positive
                    tip = (-point.trim.tip_deflection_m / model.aircraft.component("right_wing").length_m
                           if "right_wing" in model.aircraft.component_names else float("nan"))
                said = list(point.warnings)
                if not isinstance(point, FlexibleFlutterPoint) and point.trim is not None and point.trim.linear_range:
                    said.append(point.trim.linear_range)
                row.update(speed_m_s=point.speed_m_s, mach=point.mach, omega_rad_s=point.frequency_rad_s,
                           tip_deflection_fraction=tip, warnings=said)
                rows.append(row)
    csv_path, json_path = write_results(rows, out, "flutter_pull_up")
    if args.json:
        print(json_text({"rows": rows}))
        return 0
    print(f"Flutter of {aircraft.name} against load factor (bottom of a steady symmetric pull-up); results: {csv_path}, "
          f"{json_path}")
    print(f"  {'model':<13} {'H [m]':>7} {'n':>5} {'V_F [m/s]':>10} {'M_F':>8} {'w_F [rad/s]':>12} {'tip [%]':>8}")
    for r in rows:
        head = f"  {r['model']:<13} {r['altitude_m']:7.0f} {r['load_factor']:5.2f}"
        if "error" in r:
            print(f"{head}   no flutter point: {r['error'][:60]}")
        else:
            print(f"{head} {r['speed_m_s']:10.3f} {r['mach']:8.4f} {r['omega_rad_s']:12.3f} "
                  f"{100.0 * r['tip_deflection_fraction']:+8.1f}")
    for note in dict.fromkeys(w for r in rows for w in r.get("warnings", ())):
        print(f"note: {note}")
    return 0
