"""`flexsim trim` and `flexsim flutter`: thin commands over flexsim.trim and flexsim.linear.flutter."""

from __future__ import annotations

import argparse
import json
import math
import os
from pathlib import Path

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.paper_data import GLIDE_9144, TABLE_QS, TABLE_US
from flexsim.linear.study import MODELS as _MODELS
from flexsim.linear.study import StudyCase, climb_cases, glide_from_climb, plot_study, plot_trim, run_study, turn_cases, write_results
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trim import SteadyManoeuvre, trim

__all__ = ["add_flutter_commands"]


def _manoeuvre(args: argparse.Namespace, altitude: float, mach: float) -> SteadyManoeuvre:
    gamma = None if getattr(args, "glide", False) else math.radians(getattr(args, "climb_deg", 0.0) or 0.0)
    radius = args.turn_radius_m if getattr(args, "turn_radius_m", None) else math.inf
    return SteadyManoeuvre(mach * SteadyManoeuvre.level(altitude, mach=0.5).speed_m_s / 0.5, altitude, radius, gamma)


def _trim(args: argparse.Namespace) -> int:
    aircraft = load_aircraft(args.aircraft)
    model = AircraftModel(aircraft, aero="quasi-steady")
    point = trim(model, _manoeuvre(args, args.altitude_m, args.mach), check_limits=not args.no_limits)
    out = point.summary()
    if args.json:
        print(json.dumps(out, indent=2))
        return 0
    print(f"Trim of {aircraft.name}: {point.manoeuvre.describe()}")
    for key, value in out.items():
        print(f"  {key:<18} {value: .6g}")
    return 0


def _flutter(args: argparse.Namespace) -> int:
    keys = [k.strip().upper() for k in args.models.split(",")]
    for k in keys:
        if k not in _MODELS:
            raise ValueError(f"--models entry {k!r}: must be one of {', '.join(_MODELS)}")
    cases = [StudyCase(args.aircraft, k, h, mach_min=args.mach_min, mach_max=args.mach_max, structural_damping=args.structural_damping)
             for k in keys for h in args.altitudes]
    rows = run_study(cases, workers=args.workers, progress=not args.json)
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    paper = {"QS": TABLE_QS, "US": TABLE_US, "FS": TABLE_US}
    print(f"Flutter in steady level flight, {args.aircraft} (the bundled GTM is notional: structure estimated from public data, "
          "calibrated to Table 3 — docs/calibration.md)")
    header = f"{'':>4} {'h [m]':>7} {'M_F':>7} {'w_F':>8} {'theta':>7} {'T_e kN':>8} {'d_e':>7} {'w_tip m':>8} {'psi_tip':>8}"
    for key in keys:
        print(f"\n{key} ({_MODELS[key]}) — flexsim vs paper Table {'2' if key == 'QS' else '3'}")
        print(header)
        for row in [r for r in rows if r["model"] == key]:
            ref = next(p for p in paper[key] if p[0] == row["altitude_m"]) if row["altitude_m"] in [p[0] for p in paper[key]] else None
            if "error" in row:
                print(f"{'ours':>4} {row['altitude_m']:7.0f}  no flutter point: {row['error'][:110]}")
            else:
                print(f"{'ours':>4} {row['altitude_m']:7.0f} {row['mach']:7.4f} {row['omega_rad_s']:8.3f} {row['theta_deg']:7.3f} "
                      f"{row['thrust_kN']:8.2f} {row['elevator_deg']:7.3f} {row['tip_deflection_m']:8.4f} {row['tip_twist_deg']:8.4f}   ({row['mode_symmetry']}: {row['mode']})")
            if ref:
                print(f"{'pap.':>4} {ref[0]:7.0f} {ref[1]:7.4f} {ref[2]:8.3f} {ref[3]:7.3f} {ref[4]:8.2f} {ref[5]:7.3f} {ref[6]:8.4f} {ref[7]:8.4f}")
                if "error" not in row:
                    print(f"{'diff':>4} {'':7} {100 * (row['mach'] / ref[1] - 1):+6.1f}% {100 * (row['omega_rad_s'] / ref[2] - 1):+7.1f}%")
    return 0


def _sweep(args: argparse.Namespace) -> int:
    kind = "turn" if args.turn else "climb"
    models = [k.strip().upper() for k in args.models.split(",")]
    if kind == "turn":
        cases = turn_cases(args.aircraft, altitudes_m=args.altitudes, models=models, structural_damping=args.structural_damping)
    else:
        cases = climb_cases(args.aircraft, altitudes_m=args.altitudes, models=models, structural_damping=args.structural_damping)
    rows = run_study(cases, scheduler=args.scheduler, workers=args.workers, progress=True)
    out = Path(args.out)
    csv_path, json_path = write_results(rows, out, f"flutter_{kind}")
    png = plot_study(rows, kind, out / f"flutter_{kind}.png")
    figures = [png]
    top = max(args.altitudes)
    if any(r["altitude_m"] == top and "mach" in r for r in rows):
        figures.append(plot_trim(rows, kind, out / f"flutter_{kind}_trim_{top:.0f}m.png", altitude_m=top))
    ok = sum("mach" in r for r in rows)
    print(f"{ok}/{len(rows)} flutter points; results: {csv_path}, {json_path}; figures: {', '.join(map(str, figures))}")
    if kind == "climb":
        for model in models:
            for h in args.altitudes:
                glide = glide_from_climb(rows, model=model, altitude_m=h)
                if glide:
                    paper = f" (paper: {GLIDE_9144[0]} deg, {GLIDE_9144[1]}, {GLIDE_9144[2]} rad/s)" if h == 9144.0 and model == "US" else ""
                    print(f"glide at {h:.0f} m (T_e = 0 on the {model} climb curve): gamma = {glide['gamma_deg']:.2f} deg, "
                          f"M_F = {glide['mach']:.4f}, omega_F = {glide['omega_rad_s']:.3f} rad/s{paper}")
    for r in rows:
        if "error" in r:
            print(f"  no flutter point: {r['model']} h={r['altitude_m']:.0f} R={r['turn_radius_m']} gamma={r['climb_angle_deg']}: {r['error'][:100]}")
    return 0


def add_flutter_commands(sub: argparse._SubParsersAction, add_aircraft) -> None:
    """Register ``trim`` and ``flutter`` on the CLI's subparsers."""
    p_trim = sub.add_parser("trim", help="trim the aircraft in a steady manoeuvre")
    add_aircraft(p_trim)
    p_trim.add_argument("--altitude-m", type=float, default=9144.0)
    p_trim.add_argument("--mach", type=float, default=0.78)
    p_trim.add_argument("--turn-radius-m", type=float, default=None, help="steady turn of this radius [m]")
    p_trim.add_argument("--climb-deg", type=float, default=0.0, help="flight-path angle [deg]")
    p_trim.add_argument("--glide", action="store_true", help="thrust zero, flight-path angle unknown")
    p_trim.add_argument("--no-limits", action="store_true", help="do not enforce thrust/surface limits")
    p_trim.set_defaults(func=_trim)

    p_fl = sub.add_parser("flutter", help="flutter Mach and frequency in level flight (paper Tables 2-3)")
    add_aircraft(p_fl)
    p_fl.add_argument("--altitudes", type=float, nargs="+", default=[0.0, 3048.0, 6096.0, 9144.0], metavar="H")
    p_fl.add_argument("--models", default="QS,US", help="comma list of QS (quasi-steady), US (Theodorsen p-k), FS (finite-state)")
    p_fl.add_argument("--mach-min", type=float, default=0.5)
    p_fl.add_argument("--mach-max", type=float, default=0.95)
    p_fl.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="local processes [all cores]")
    p_fl.add_argument("--structural-damping", type=float, default=None, metavar="ZETA",
                      help="modal damping ratio of the elastic modes [the aircraft file's; 0 = the paper's undamped structure]")
    p_fl.set_defaults(func=_flutter)

    p_sw = sub.add_parser("sweep", help="flutter versus turn radius or climb angle (paper Figs. 7-16)")
    add_aircraft(p_sw)
    group = p_sw.add_mutually_exclusive_group(required=True)
    group.add_argument("--turn", action="store_true", help="level turns, R = 5-12 km")
    group.add_argument("--climb", action="store_true", help="climbs and descents, gamma = -15..15 deg")
    p_sw.add_argument("--altitudes", type=float, nargs="+", default=[0.0, 3048.0, 6096.0, 9144.0], metavar="H")
    p_sw.add_argument("--models", default="QS,US")
    p_sw.add_argument("--scheduler", metavar="ADDRESS", help="Dask distributed scheduler (default: local processes)")
    p_sw.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    p_sw.add_argument("--structural-damping", type=float, default=None, metavar="ZETA",
                      help="modal damping ratio of the elastic modes [the aircraft file's]")
    p_sw.add_argument("--out", default="logs/study", help="output folder for CSV, JSON and PNG [logs/study]")
    p_sw.set_defaults(func=_sweep)
