"""`flexsim trim` and `flexsim flutter`: thin commands over flexsim.trim and flexsim.linear.flutter."""

from __future__ import annotations

import argparse
import json
import math
import os
from concurrent.futures import ProcessPoolExecutor

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import FlutterAnalysis, FlutterNotFound
from flexsim.linear.paper_data import TABLE_QS, TABLE_US
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trim import SteadyManoeuvre, TrimError, trim

__all__ = ["add_flutter_commands", "flutter_row"]

_MODELS = {"QS": "quasi-steady", "US": "theodorsen", "FS": "unsteady"}


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


def flutter_row(aircraft_name: str, model_key: str, altitude: float, mach_lo: float, mach_hi: float,
                turn_radius_m: float = math.inf, climb_angle_rad: float | None = 0.0) -> dict:
    """One flutter point as a plain dict (picklable worker for process pools)."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    aircraft = load_aircraft(aircraft_name)
    analysis = FlutterAnalysis(aircraft, _MODELS[model_key])
    man = SteadyManoeuvre(SteadyManoeuvre.level(altitude, mach=mach_lo).speed_m_s, altitude, turn_radius_m, climb_angle_rad)
    row = {"model": model_key, "altitude_m": altitude, "turn_radius_m": turn_radius_m,
           "climb_angle_deg": None if climb_angle_rad is None else math.degrees(climb_angle_rad)}
    try:
        fp = analysis.search(man, mach_range=(mach_lo, mach_hi))
    except (FlutterNotFound, TrimError) as exc:
        row["error"] = str(exc)
        return row
    s = fp.trim.summary()
    row.update(mach=fp.mach, omega_rad_s=fp.frequency_rad_s, theta_deg=s["theta_deg"], thrust_kN=s["thrust_kN"],
               elevator_deg=s["elevator_deg"], tip_deflection_m=s["tip_deflection_m"], tip_twist_deg=s["tip_twist_deg"],
               gamma_deg=s["gamma_deg"], phi_deg=s["phi_deg"], mode=fp.mode.dominant_dof, evaluations=fp.evaluations,
               rigid_instabilities=[(m, str(ev), dof) for m, ev, dof in fp.rigid_instabilities[:3]])
    return row


def _flutter(args: argparse.Namespace) -> int:
    keys = [k.strip().upper() for k in args.models.split(",")]
    for k in keys:
        if k not in _MODELS:
            raise ValueError(f"--models entry {k!r}: must be one of {', '.join(_MODELS)}")
    jobs = [(args.aircraft, k, h, args.mach_min, args.mach_max) for k in keys for h in args.altitudes]
    workers = max(1, min(args.workers, len(jobs)))
    if workers > 1:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            rows = list(pool.map(flutter_row, *zip(*jobs)))
    else:
        rows = [flutter_row(*job) for job in jobs]
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    paper = {"QS": TABLE_QS, "US": TABLE_US, "FS": TABLE_US}
    print(f"Flutter in steady level flight, {args.aircraft} (notional GTM: structure estimated from public data)")
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
                      f"{row['thrust_kN']:8.2f} {row['elevator_deg']:7.3f} {row['tip_deflection_m']:8.4f} {row['tip_twist_deg']:8.4f}   ({row['mode']})")
            if ref:
                print(f"{'pap.':>4} {ref[0]:7.0f} {ref[1]:7.4f} {ref[2]:8.3f} {ref[3]:7.3f} {ref[4]:8.2f} {ref[5]:7.3f} {ref[6]:8.4f} {ref[7]:8.4f}")
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
    p_fl.set_defaults(func=_flutter)
