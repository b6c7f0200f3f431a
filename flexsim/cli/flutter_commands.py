"""`flexsim trim` and `flexsim flutter`: thin commands over flexsim.trimming and flexsim.linear.flutter."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path
from dataclasses import replace

from flexsim.aircraft.definition import FORMULATIONS
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.validation import CliError, check_writable_dir, flight_condition, in_user_words, check_altitudes, check_damping, check_mach_range, check_out_dir, check_trim_options, check_workers, json_text
from flexsim.io.output_paths import check_not_link, unique_names
from flexsim.cli.nonlinear_commands import (NONLINEAR_HELP, check_load_factor, nonlinear_flutter, nonlinear_trim,
                                            pull_up_sweep)
from flexsim.cli.paper_report import PAPER_REPLICATION, RunSettings, flutter_report, flutter_table, mode_matches_paper, physical_settings, sweep_report
from flexsim.linear.study import MODELS as _MODELS
from flexsim.linear.study import StudyCase, StudyRecord, case_key, climb_cases, plot_study, plot_trim, run_study, turn_cases, write_results
from flexsim.errors import FlexsimError
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.linear_range import nonlinear_fields_note
from flexsim.atmosphere import mach_to_true_airspeed, speed_of_sound
from flexsim.trimming import SteadyManoeuvre, TrimError, trim

__all__ = ["add_flutter_commands"]


def _manoeuvre(args: argparse.Namespace, altitude: float, mach: float) -> SteadyManoeuvre:
    gamma = None if getattr(args, "glide", False) else math.radians(getattr(args, "climb_deg", None) or 0.0)
    radius = args.turn_radius_m if getattr(args, "turn_radius_m", None) is not None else math.inf
    coordinated = bool(getattr(args, "coordinated", False))
    if coordinated and radius == math.inf:
        raise ValueError("--coordinated: applies to turns only; give --turn-radius-m")
    n = getattr(args, "load_factor", None)
    if n is not None:
        check_load_factor(n)
        if radius != math.inf or gamma is None or gamma != 0.0:
            raise CliError(f"--load-factor {n:g}: the bottom of a symmetric pull-up (wings level, gamma = 0); not with "
                           "--turn-radius-m, --climb-deg or --glide")
        return SteadyManoeuvre.pull_up(altitude, n, speed_m_s=float(mach_to_true_airspeed(mach, altitude)))
    return SteadyManoeuvre(float(mach_to_true_airspeed(mach, altitude)), altitude, radius, gamma, coordinated)


def _trim(args: argparse.Namespace) -> int:
    check_trim_options(args)
    condition = flight_condition("trim", args)
    aircraft = load_aircraft(args.aircraft)
    if args.components:
        aircraft = aircraft.subset(args.components)
    if args.nonlinear_beams is not None:
        return nonlinear_trim(args, aircraft, _manoeuvre(args, condition.altitude_m, condition.mach), condition)
    model = AircraftModel(aircraft, aero=AeroOptions("quasi-steady", formulation=args.formulation))
    try:
        point = trim(model, _manoeuvre(args, condition.altitude_m, condition.mach), check_limits=not args.no_limits)
    except TrimError as exc:
        if not condition.derived:
            raise
        raise TrimError(f"{exc}; the flight condition was not given: {condition.describe()}; give --altitude-m and --mach "
                        "or --speed-m-s, or the file's envelope.cruise_altitude_m and cruise_mach") from None
    out = point.summary()
    out["weight_kN"] = model.structure.mass_properties.mass_kg * model.terms.gravity_m_s2 / 1e3
    if model.aero is not None and "right_wing" in aircraft.component_names:
        from flexsim.trimming.margin import static_margin

        margin = static_margin(model, point)
        out = {**out, "static_margin_mac": margin.fraction_of_mac, "neutral_point_aft_of_cg_m": margin.neutral_point_aft_of_cg_m}
    roots = None
    if args.roots:  # the verdict then comes from the roots printed beside it (their aerodynamic model)
        roots, spec = _roots(aircraft, point, args.roots, args.formulation)
        from flexsim.trimming.equilibrium import with_stability

        point = with_stability(model, point, spec)
    local = point.max_local_alpha
    notes = [n for n in (nonlinear_fields_note(aircraft), point.linear_range) if n is not None]
    if args.json:
        extra = {"roots": roots} if roots is not None else {}
        print(json_text({**out, "flight_condition": condition.describe(), "formulation": model.formulation,
                         "terms": model.terms.record(),
                         "stability": point.stability.as_dict(),
                         "max_local_alpha": local.as_dict() if local is not None else None,
                         "linear_range": point.linear_range, **extra}))
        return 0
    print(f"Trim of {aircraft.name} ({model.formulation} force resolution): {point.manoeuvre.describe()}")
    if condition.derived:
        print(f"  flight condition : {condition.describe()}")
    for key, value in out.items():
        print(f"  {key:<18} {value: .6g}")
    if local is not None:
        print(f"  {'max_local_alpha':<18} {local.describe()}")
    print(f"  {'equilibrium':<18} {point.stability.verdict} ({point.stability.aero_model} roots)")
    for note in notes:
        print(note)
    if roots is not None:
        counts = {k: sum(r["kind"] == k for r in roots["modes"]) for k in ("rigid", "elastic", "aerodynamic")}
        print(f"Roots of the linearised trim ({roots['aero_model']}): {counts['rigid']} rigid-body, {counts['elastic']} elastic, "
              f"{counts['aerodynamic']} aerodynamic-lag")
        print(f"  {'kind':<12} {'real [1/s]':>11} {'imag [rad/s]':>12} {'zeta':>8}  mode")
        for r in roots["modes"]:
            if r["kind"] != "aerodynamic" and r["imag"] >= 0.0:
                print(f"  {r['kind']:<12} {r['real']:11.5f} {r['imag']:12.5f} {r['damping_ratio']:8.4f}  {r['name']}")
        print("  (aerodynamic-lag roots: --json lists them)")
    if not point.stability.is_stable:
        print(f"{point.stability.message} ({point.stability.aero_model} roots)")
    return 0


def _check_replication(args: argparse.Namespace, default_aircraft: str = "gtm") -> None:
    """``--paper-replication`` fixes the aircraft, the formulation and the linearised density itself: giving any of
    them beside it is refused (it would be ignored)."""
    if not args.paper_replication:
        return
    given = [flag for flag, value in (("AIRCRAFT", args.aircraft not in (default_aircraft, PAPER_REPLICATION.aircraft)),
                                      ("--formulation", args.formulation),
                                      ("--linear-density-altitude-m", args.linear_density_altitude_m)) if value]
    if given:
        raise CliError(f"--paper-replication and {', '.join(given)}: the paper-replication settings fix the aircraft, "
                       f"the formulation and the linearised density ({PAPER_REPLICATION.describe()}); give one or the other")


def _settings(args: argparse.Namespace, default_aircraft: str = "gtm") -> list[RunSettings]:
    """The labelled settings of a run: the paper-replication and the physical ones on the default aircraft,
    or the aircraft and options as given (``--formulation``, ``--linear-density-altitude-m``)."""
    if args.paper_replication:
        return [PAPER_REPLICATION]
    if args.aircraft == default_aircraft and args.formulation is None and args.linear_density_altitude_m is None:
        return [PAPER_REPLICATION, physical_settings(default_aircraft)]
    return [RunSettings("as given", args.aircraft, args.formulation, args.linear_density_altitude_m)]


def _roots(aircraft, point, aero_model: str, formulation: str | None = None) -> tuple[dict, object]:
    """Eigenvalues of the linearised trim with their classification (rigid-body, elastic, aerodynamic-lag), and their
    :class:`~flexsim.trimming.roots.Spectrum` (the trim's verdict is then classified from it)."""
    import numpy as np

    from flexsim.linear.stability import spectrum

    model = AircraftModel(aircraft, aero=AeroOptions(aero_model, formulation=formulation))
    x = np.concatenate([point.x, np.zeros(model.layout.n_inflow)])
    spec = spectrum(model, x, point.u, aero_model=aero_model)
    modes = sorted(spec.modes, key=lambda m: ({"rigid": 0, "elastic": 1, "aerodynamic": 2}[m.kind], abs(m.eigenvalue)))
    return {"aero_model": aero_model, "modes": [
        {"kind": m.kind, "real": m.eigenvalue.real, "imag": m.eigenvalue.imag, "damping_ratio": m.damping_ratio,
         "name": m.name, "dominant_dof": m.dominant_dof, "elastic_fraction": m.elastic_fraction,
         "inflow_participation": m.inflow_participation} for m in modes]}, spec


def _model_keys(text: str) -> list[str]:
    """``--models``: a comma list of distinct model keys (QS, US, FS)."""
    keys = [k.strip().upper() for k in text.split(",")]
    for k in keys:
        if k not in _MODELS:
            raise CliError(f"--models entry {k!r}: must be one of {', '.join(_MODELS)}")
    if len(set(keys)) != len(keys):
        raise CliError(f"--models {text!r}: names a model twice; give each once")
    return keys


def _flutter(args: argparse.Namespace) -> int:
    if args.nonlinear_beams is not None or args.load_factor is not None:
        _check_vg_options(args)
        return nonlinear_flutter(args, vg_paths)
    if args.free_aircraft:
        raise CliError("--free-aircraft: applies to --nonlinear-beams (the linear model's flutter is always the free "
                       "aircraft's)")
    keys = _model_keys(args.models)
    if args.wind_tunnel:
        return _wind_tunnel(args, keys)
    tunnel = [flag for flag, value in (("--speed-range-m-s", args.speed_range_m_s), ("--components", args.components))
              if value is not None]
    if tunnel:
        raise CliError(f"{', '.join(tunnel)}: apply to --wind-tunnel (a structure clamped in an airflow); a flight "
                       "searches the whole aircraft over its flight envelope (give --mach-min, --mach-max)")
    altitude_source = "given"
    if args.altitudes is None:  # the aircraft's: sea level to its ceiling (the paper's four for the GTM), else sea level
        from flexsim.linear.envelope import flutter_altitudes

        args.altitudes, altitude_source = flutter_altitudes(args.aircraft)
    if args.mach_min is not None and args.mach_max is not None:
        check_mach_range(args.mach_min, args.mach_max)
    check_altitudes(args.altitudes)
    args.workers = _WORKERS if args.workers is None else args.workers
    check_workers(args.workers)
    check_damping(args.structural_damping)
    if args.mode:  # the critical mode's recording: its path checked before the search
        from flexsim.linear.mode_animation import check_recording_path, record_critical_mode

        check_not_link("--mode", args.mode)
        check_recording_path(args.mode, "--mode")
    _check_vg_options(args)
    _check_replication(args)
    if args.vg is not None:  # every PNG's path checked before the search: no link, a writable folder
        for path in vg_paths(args.vg, list(args.altitudes or [])):
            check_not_link("--vg", path)
            check_writable_dir("--vg", str(path), path.parent if str(path.parent) else Path("."))
    if args.glide and args.climb_deg is not None:
        raise CliError("--glide, --climb-deg: a glide finds its own flight-path angle; give one of them")
    if args.speed_step_m_s is not None:
        raise CliError("--speed-step-m-s: the scan step of --wind-tunnel; a flight's search steps in Mach (--mach-step)")
    settings = _settings(args)
    shape = _manoeuvre(args, args.altitudes[0], 0.5)  # the kind of manoeuvre (its speed is searched)
    # the aircraft file's [envelope] sets the search range (the aircraft itself is loaded where it is searched)
    try:
        ranges = {(s.label, h): _search_range(s.aircraft, h, shape, args) for s in settings for h in args.altitudes}
    except ValueError as exc:
        raise CliError(f"{exc}; for a structure clamped in an airflow (e.g. goland_wing) give --wind-tunnel") from None
    labelled = [(s.label, StudyCase(s.aircraft, k, h, mach_min=ranges[s.label, h].mach_min,
                                    mach_max=ranges[s.label, h].mach_max, turn_radius_m=shape.turn_radius_m,
                                    climb_angle_deg=None if shape.is_glide else math.degrees(shape.climb_angle_rad),
                                    coordinated=shape.coordinated, structural_damping=args.structural_damping,
                                    formulation=s.formulation, linear_density_altitude_m=s.linear_density_altitude_m,
                                    mach_step=args.mach_step))
                for s in settings for k in keys for h in args.altitudes]
    rows = run_study([c for _, c in labelled], workers=args.workers, progress=not args.json)
    paper = _is_paper_aircraft(settings) and shape.turn_radius_m == math.inf and shape.climb_angle_rad == 0.0
    for (label, _), row in zip(labelled, rows):
        if "error" in row:
            row["error"] = in_user_words(row["error"])
        row["settings"] = label
        row["search_range"] = ranges[label, row["altitude_m"]].describe()
        if "mach" in row and paper:
            row["mode_matches_paper"] = mode_matches_paper(row)
    condition = shape.describe().split(" at M ")[0]
    lines, doc = flutter_report(rows, settings, keys) if paper else flutter_table(rows, settings, keys, condition)
    lines += [f"warning: {r['model']} h={r['altitude_m']:.0f} m: {w}" for r in rows for w in r.get("warnings", ())]
    if args.vg is not None:
        diagrams = _vg(args, shape, keys)
        doc["vg"] = [d.as_dict() for d, _ in diagrams]
        lines += _vg_lines(diagrams)
    if args.mode:
        print(record_critical_mode([c for _, c in labelled], rows, args.mode), file=sys.stderr if args.json else sys.stdout)
    unused = {n for n in (nonlinear_fields_note(load_aircraft(s.aircraft)) for s in settings) if n is not None}
    lines += sorted(unused)
    beyond = [r for r in rows if r.get("linear_range")]
    if beyond:  # one line: the first flutter point beyond the linear structure's range, and how many more
        r = beyond[0]
        more = f" (and {len(beyond) - 1} more of the {len(rows)} flutter points)" if len(beyond) > 1 else ""
        lines.append(f"{r['linear_range']} — at the flutter point of {r['model']} h = {r['altitude_m']:.0f} m{more}")
    doc["altitudes_source"] = altitude_source
    if args.json:
        print(json_text(doc))
        return 0
    if not altitude_source.startswith(("given", "sea level to envelope.")):
        lines = [f"altitudes: {altitude_source}", *lines]
    print("\n".join(lines))
    return 0


def _vg_lines(diagrams: list) -> list[str]:
    """The V-g summary printed under a flutter table: per diagram, its file and every crossing."""
    lines = ["", "V-g / V-f diagrams (damping g = 2 Re(lambda)/|Im(lambda)|, > 0 unstable; branches tracked by "
             "eigenvector correlation):"]
    for d, path in diagrams:
        lines.append(f"  {path}: {d.aircraft}, {d.condition}, {len(d.tracks)} branches, "
                     f"{d.speeds_m_s[0]:.1f}-{d.speeds_m_s[-1]:.1f} m/s")
        for c in d.crossings:
            lines.append(f"    {_MODEL_KEY[c.aero_model]:<3} {c.label:<34} crosses {'into instability' if c.direction == 'unstable' else 'back to stability':<18} "
                         f"at {c.speed_m_s:8.2f} m/s (M {c.mach:.4f}), {c.frequency_rad_s:8.3f} rad/s")
        if not d.crossings:
            lines.append("    no branch crosses in the range")
        for model in dict.fromkeys(t.aero_model for t in d.tracks):
            above = d.unstable_throughout(model)
            if above:
                lines.append(f"    {_MODEL_KEY[model]:<3} unstable throughout the range (below its lower end already): "
                             f"{', '.join(above)}")
        lines += [f"    warning: {w}" for w in d.warnings]
    return lines


def _check_vg_options(args: argparse.Namespace) -> None:
    if args.vg is not None and not str(args.vg).lower().endswith(".png"):
        raise CliError(f"--vg {args.vg!r}: must name a .png file")
    if args.vg_points < 3:
        raise CliError(f"--vg-points = {args.vg_points}: must be an integer >= 3")
    if args.vg is None and args.vg_points != _VG_POINTS:
        raise CliError(f"--vg-points {args.vg_points}: applies to --vg (the speeds of the V-g diagram)")

#: Speeds a wind-tunnel run searches without --speed-range-m-s [m/s].
WIND_TUNNEL_SPEEDS_M_S = (10.0, 300.0)
#: Speeds of a V-g diagram without --vg-points.
_VG_POINTS = 25
#: Local processes of a flight search without --workers.
_WORKERS = os.cpu_count() or 1

#: The options of a flight that a wind-tunnel run (``--wind-tunnel``) has no use for: (attribute, flag).
_FLIGHT_ONLY = (("turn_radius_m", "--turn-radius-m"), ("climb_deg", "--climb-deg"), ("glide", "--glide"),
                ("coordinated", "--coordinated"), ("mach_min", "--mach-min"), ("mach_max", "--mach-max"),
                ("mach_step", "--mach-step"),
                ("mode", "--mode"), ("structural_damping", "--structural-damping"), ("formulation", "--formulation"),
                ("linear_density_altitude_m", "--linear-density-altitude-m"), ("paper_replication", "--paper-replication"))


def _wind_tunnel(args: argparse.Namespace, keys: list[str]) -> int:
    """``flexsim flutter --wind-tunnel``: flutter and divergence speeds of the aircraft (or of the components asked with
    ``--components``) clamped at its body origin in an airflow (:func:`flexsim.linear.flutter.wind_tunnel`), per model
    and altitude (default sea level). A model that fails is reported in its own row; the others' results stand."""
    from flexsim.linear.flutter import wind_tunnel

    given = [flag for name, flag in _FLIGHT_ONLY if getattr(args, name, None) not in (None, False)]
    if args.workers is not None:
        given.append("--workers")
    if given:
        raise CliError(f"--wind-tunnel: {', '.join(given)} describe a flight; a wind tunnel holds the structure still "
                       "(give --altitudes, --models, --components, --speed-range-m-s)")
    lo, hi = args.speed_range_m_s if args.speed_range_m_s is not None else WIND_TUNNEL_SPEEDS_M_S
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise CliError(f"--speed-range-m-s {lo:g} {hi:g}: must satisfy 0 < LO < HI [m/s]")
    step = _TUNNEL_STEP_M_S if args.speed_step_m_s is None else args.speed_step_m_s
    if not (math.isfinite(step) and 0.0 < step <= hi - lo):
        raise CliError(f"--speed-step-m-s {step:g}: must be in (0, {hi - lo:g}] m/s (the width of --speed-range-m-s)")
    _check_vg_options(args)
    altitudes = [0.0] if args.altitudes is None else args.altitudes
    check_altitudes(altitudes)
    if args.vg is not None:  # every PNG's path checked before the search: no link, a writable folder
        for path in vg_paths(args.vg, altitudes):
            check_not_link("--vg", path)
            check_writable_dir("--vg", str(path), path.parent if str(path.parent) else Path("."))
    aircraft = load_aircraft(args.aircraft)
    if args.components:
        aircraft = aircraft.subset(args.components)
    rows = []
    for h in altitudes:
        for k in keys:
            row = {"model": k, "aero_model": _MODELS[k], "altitude_m": h, "speed_range_m_s": [lo, hi],
                   "speed_step_m_s": step}
            try:
                r = wind_tunnel(aircraft, aero_model=_MODELS[k], speed_range=(lo, hi), altitude_m=h, speed_step=step)
            except (FlexsimError, ValueError, ArithmeticError) as exc:  # this model's failure, in its own row
                row["error"] = in_user_words(str(exc))
            else:
                row.update({"density_kg_m3": r.density_kg_m3, "compressibility": r.compressibility,
                            "flutter_speed_m_s": r.flutter_speed_m_s, "flutter_frequency_rad_s": r.flutter_frequency_rad_s,
                            "divergence_speed_m_s": r.divergence_speed_m_s, "first_instability": r.first_instability,
                            "warnings": list(r.warnings)})
            rows.append(row)
    diagrams = _tunnel_vg(args, aircraft, altitudes, keys) if args.vg is not None else []
    if args.json:
        extra = {"vg": [d.as_dict() for d, _ in diagrams]} if diagrams else {}
        print(json_text({"aircraft": aircraft.name, "components": list(aircraft.component_names), "wind_tunnel": rows,
                         **extra}))
        return 0

    def speed(v):
        return f"{v:10.2f}" if v is not None else f"{'none':>10}"

    print(f"{aircraft.name} in a wind tunnel: clamped at the body origin, air along body -x at zero angle of attack, no "
          f"gravity; searched {lo:g}-{hi:g} m/s")
    print(f"{'model':<6}{'h [m]':>7}{'rho [kg/m^3]':>14}{'U_F [m/s]':>11}{'w_F [rad/s]':>13}{'U_D [m/s]':>11}  first")
    for r in rows:
        if "error" in r:
            print(f"{r['model']:<6}{r['altitude_m']:7.0f}  no result: {r['error']}")
            continue
        w = f"{r['flutter_frequency_rad_s']:13.3f}" if r["flutter_frequency_rad_s"] is not None else f"{'':>13}"
        print(f"{r['model']:<6}{r['altitude_m']:7.0f}{r['density_kg_m3']:14.4f}{speed(r['flutter_speed_m_s'])}{w}"
              f"{speed(r['divergence_speed_m_s'])}  {r['first_instability']}")
    if (note := nonlinear_fields_note(aircraft)) is not None:
        print(note)
    for r in rows:
        for w in r.get("warnings", ()):
            print(f"warning: {r['model']} h={r['altitude_m']:.0f} m: {w}")
    if diagrams:
        print("\n".join(_vg_lines(diagrams)))
    return 0


#: Default scan step of ``--wind-tunnel`` [m/s] (:func:`flexsim.linear.flutter.wind_tunnel`'s).
_TUNNEL_STEP_M_S = 5.0


def _tunnel_vg(args: argparse.Namespace, aircraft, altitudes: list[float], keys: list[str]) -> list[tuple[object, Path]]:
    """The V-g diagram of the clamped structure in the stream at every altitude, over --speed-range-m-s."""
    from flexsim.linear.vg import vg_diagram

    lo, hi = args.speed_range_m_s if args.speed_range_m_s is not None else WIND_TUNNEL_SPEEDS_M_S
    out = []
    for h, path in zip(altitudes, vg_paths(args.vg, altitudes)):
        model = AircraftModel(aircraft, variant="restrained", aero=AeroOptions("quasi-steady"), gravity_m_s2=0.0,
                              altitude_m=h, restrained_velocity_m_s=[lo, 0.0, 0.0])
        d = vg_diagram(model, speeds_m_s=_linspace(lo, hi, args.vg_points), models=keys)
        out.append((d, d.plot(path)))
    return out


_MODEL_KEY = {v: k for k, v in _MODELS.items()}
#: The paper's aircraft, whose results are printed beside its Tables 2-3.
PAPER_AIRCRAFT = ("gtm", "gtm_paper")


def _is_paper_aircraft(settings: list[RunSettings]) -> bool:
    """True when every setting flies one of :data:`PAPER_AIRCRAFT` (by bundled name or the bundled file's path)."""
    from flexsim.aircraft.toml_loader import resolve_aircraft_path

    paper = {resolve_aircraft_path(n).resolve() for n in PAPER_AIRCRAFT}
    return all(resolve_aircraft_path(s.aircraft).resolve() in paper for s in settings)


def _at(shape: SteadyManoeuvre, altitude_m: float) -> SteadyManoeuvre:
    """The manoeuvre ``shape`` (turn, climb, glide) at another altitude (speed M 0.5, replaced by the search)."""
    return SteadyManoeuvre(float(mach_to_true_airspeed(0.5, altitude_m)), altitude_m, shape.turn_radius_m,
                           shape.climb_angle_rad, shape.coordinated)


def _search_range(model: str | AircraftModel, altitude_m: float, shape: SteadyManoeuvre, args: argparse.Namespace):
    """The Mach range searched at one altitude: --mach-min/--mach-max, else the aircraft's envelope."""
    from flexsim.linear.envelope import search_range

    return search_range(model, _at(shape, altitude_m), mach_min=args.mach_min, mach_max=args.mach_max)


def _vg(args: argparse.Namespace, shape: SteadyManoeuvre, keys: list[str]) -> list[tuple[object, Path]]:
    """The V-g diagram of the aircraft as given at every altitude: (VgDiagram, PNG path written)."""
    from flexsim.linear.vg import vg_diagram

    model = AircraftModel(load_aircraft(args.aircraft), aero=AeroOptions("quasi-steady", formulation=args.formulation),
                          structural_damping=args.structural_damping)
    out = []
    for h, path in zip(args.altitudes, vg_paths(args.vg, args.altitudes)):
        man = _at(shape, h)
        rng = _search_range(model, h, shape, args)
        speeds = [m * speed_of_sound(h) for m in _linspace(rng.mach_min, rng.mach_max, args.vg_points)]
        d = vg_diagram(model, manoeuvre=man, speeds_m_s=speeds, models=keys)
        out.append((d, d.plot(path)))
    return out


def vg_paths(vg: str, altitudes: list[float]) -> list[Path]:
    """The PNG of each altitude's V-g diagram: ``--vg`` itself for one altitude, else ``STEM_<h>m.png`` per altitude,
    distinct even for altitudes that print alike (9144 and 9144.4 m: ``_9144m`` and ``_9144m-2``)."""
    target = Path(vg)
    if len(altitudes) == 1:
        return [target]
    return unique_names([target.with_name(f"{target.stem}_{h:.0f}m{target.suffix}") for h in altitudes])


def _linspace(lo: float, hi: float, n: int) -> list[float]:
    return [lo + (hi - lo) * i / (n - 1) for i in range(n)]


def _sweep(args: argparse.Namespace) -> int:
    if args.pull_up:
        return pull_up_sweep(args, _model_keys(args.models))
    for flag, value in (("--load-factors", args.load_factors), ("--nonlinear-beams", args.nonlinear_beams)):
        if value is not None:
            raise CliError(f"{flag}: applies to --pull-up sweeps (flutter against load factor)")
    kind = "turn" if args.turn else "climb"
    _check_replication(args)
    if args.components is not None:
        raise CliError("--components: a sweep flies the whole aircraft (a component alone: flexsim flutter --wind-tunnel "
                       "--components NAME ...)")
    models = _model_keys(args.models)
    if args.altitudes is None:  # the aircraft's, as flexsim flutter's
        from flexsim.linear.envelope import flutter_altitudes

        args.altitudes = flutter_altitudes(PAPER_REPLICATION.aircraft if args.paper_replication else args.aircraft)[0]
    if args.coordinated and kind != "turn":
        raise ValueError("--coordinated: applies to --turn sweeps only")
    check_altitudes(args.altitudes)
    if args.scheduler is not None and args.workers is not None:
        raise CliError(f"--scheduler, --workers {args.workers}: the processes are the Dask cluster's at "
                       f"{args.scheduler!r}; --workers sets local processes (give one of them)")
    args.workers = _WORKERS if args.workers is None else args.workers
    check_workers(args.workers)
    wrong = {"turn": ("--angles-deg", args.angles_deg, "--climb"), "climb": ("--radii-m", args.radii_m, "--turn")}[kind]
    if wrong[1] is not None:
        raise CliError(f"{wrong[0]}: applies to {wrong[2]} sweeps (this is a --{kind} sweep)")
    if args.chain_length is not None and args.chain_length < 1:
        raise CliError(f"--chain-length = {args.chain_length}: must be an integer >= 1 (points per chain)")
    check_damping(args.structural_damping)
    points = {}
    if kind == "turn" and args.radii_m is not None:
        bad = [r for r in args.radii_m if not (math.isfinite(r) and r > 0.0)]
        if bad:
            raise ValueError(f"--radii-m {bad[0]!r}: turn radii must be finite numbers > 0 [m]")
        points = {"radii_m": args.radii_m}
    if kind == "climb" and args.angles_deg is not None:
        bad = [g for g in args.angles_deg if not (math.isfinite(g) and -90.0 < g < 90.0)]
        if bad:
            raise ValueError(f"--angles-deg {bad[0]!r}: flight-path angles must be in (-90, 90) deg")
        points = {"angles_deg": args.angles_deg}
    out = check_out_dir(args.out)
    stem = f"flutter_{kind}_coordinated" if args.coordinated else f"flutter_{kind}"
    record = StudyRecord(out / f"{stem}.jsonl", resume=args.resume)
    if record.done:
        print(f"resuming: {len(record.done)} finished points read from {record.path}", file=sys.stderr)
    setting = PAPER_REPLICATION if args.paper_replication else RunSettings("as given", args.aircraft, args.formulation,
                                                                            args.linear_density_altitude_m)
    make = turn_cases if kind == "turn" else climb_cases
    cases = make(setting.aircraft, altitudes_m=args.altitudes, models=models, structural_damping=args.structural_damping,
                 formulation=setting.formulation, linear_density_altitude_m=setting.linear_density_altitude_m,
                 **({"coordinated": True} if args.coordinated else {}), **points)
    if args.mach_min is not None and args.mach_max is not None:
        check_mach_range(args.mach_min, args.mach_max)
    # each case searched over the aircraft's envelope for its manoeuvre ([envelope], else the stall estimate)
    ranges = {}
    for c in cases:
        key = (c.altitude_m, c.turn_radius_m, c.climb_angle_deg, c.coordinated)
        if key not in ranges:
            shape = SteadyManoeuvre(float(mach_to_true_airspeed(0.5, c.altitude_m)), c.altitude_m, c.turn_radius_m,
                                    math.radians(c.climb_angle_deg), c.coordinated)
            ranges[key] = _search_range(setting.aircraft, c.altitude_m, shape, args)
    keys = [(c.altitude_m, c.turn_radius_m, c.climb_angle_deg, c.coordinated) for c in cases]
    cases = [replace(c, mach_min=ranges[k].mach_min, mach_max=ranges[k].mach_max) for c, k in zip(cases, keys)]
    try:
        rows = run_study(cases, scheduler=args.scheduler, workers=args.workers, progress=True, record=record,
                         chain_length=args.chain_length)
    except KeyboardInterrupt:
        record.close()
        kept = sum(1 for _ in record.path.open()) if record.path.exists() else 0
        print(f"flexsim sweep: interrupted; {kept} finished points are kept in {record.path} "
              f"(run the same command with --resume to continue)", file=sys.stderr)
        raise
    record.close()
    for row, k in zip(rows, keys):
        if "error" in row:
            row["error"] = in_user_words(row["error"])
        row["settings"] = setting.label
        row["search_range"] = ranges[k].describe()
    asked = {case_key(c) for c in cases}
    earlier = [r for key, r in record.done.items() if key not in asked]
    if earlier:  # points of an earlier sweep into this --out (resumed with other points): its results keep them
        rows = rows + earlier
        print(f"flexsim sweep: the results keep the {len(earlier)} points of the earlier sweep in {record.path} too",
              file=sys.stderr)
    csv_path, json_path = write_results(rows, out, stem)
    png = plot_study(rows, kind, out / f"{stem}.png")
    figures = [png]
    top = max(args.altitudes)
    if any(r["altitude_m"] == top and "mach" in r for r in rows):
        figures.append(plot_trim(rows, kind, out / f"{stem}_trim_{top:.0f}m.png", altitude_m=top))
    lines, doc = sweep_report(rows, kind, paper_aircraft=_is_paper_aircraft([setting]))
    doc["settings"] = setting.__dict__
    score_path = out / f"flutter_{kind}_scorecard.json"
    score_path.write_text(json.dumps(doc, indent=2, default=str))
    if args.json:
        print(json_text({"rows": rows, **doc}))
        return 0
    ok = sum("mach" in r for r in rows)
    print(f"{setting.describe()}")
    print(f"{ok}/{len(rows)} flutter points; results: {csv_path}, {json_path}, {score_path} (points as they finished: "
          f"{record.path}); figures: {', '.join(map(str, figures))}")
    print("\n".join(lines))
    for r in rows:
        if "error" in r:
            print(f"  no flutter point: {r['model']} h={r['altitude_m']:.0f} R={r['turn_radius_m']} gamma={r['climb_angle_deg']}: {r['error'][:100]}")
    return 0


def _add_formulation(parser: argparse.ArgumentParser, replication: bool = False) -> None:
    parser.add_argument("--formulation", choices=FORMULATIONS, default=None,
                        help="force resolution of the strip airloads: physical (lift normal to the local wind) or paper "
                             "(eq. 28, no body-x component: T_e = W sin theta) [the aircraft file's; physical unless it says]")
    if replication:
        parser.add_argument("--linear-density-altitude-m", type=float, default=None, metavar="H",
                            help="paper-replication setting: linearised aerodynamics of the flutter search at the ISA density of "
                                 "altitude H [m] (trims keep the true density) [the flight's true density]")
        parser.add_argument("--paper-replication", action="store_true",
                            help=f"run only the paper-replication settings ({PAPER_REPLICATION.describe()})")


def add_flutter_commands(sub: argparse._SubParsersAction, add_aircraft) -> None:
    """Register ``trim`` and ``flutter`` on the CLI's subparsers."""
    p_trim = sub.add_parser("trim", help="trim the aircraft in a steady manoeuvre")
    add_aircraft(p_trim)
    p_trim.add_argument("--altitude-m", type=float, default=None, metavar="H",
                        help="altitude [m] [the aircraft file's envelope.cruise_altitude_m, else sea level]")
    speed = p_trim.add_mutually_exclusive_group()
    speed.add_argument("--mach", type=float, default=None, metavar="M",
                       help="Mach number [the aircraft file's cruise speed, else 1.3 x its stall speed]")
    speed.add_argument("--speed-m-s", type=float, default=None, metavar="V",
                       help="true airspeed [m/s] instead of --mach")
    p_trim.add_argument("--turn-radius-m", type=float, default=None, help="steady turn of this radius [m]")
    p_trim.add_argument("--climb-deg", type=float, default=None, help="flight-path angle [deg] [0]")
    p_trim.add_argument("--glide", action="store_true", help="thrust zero, flight-path angle unknown")
    p_trim.add_argument("--load-factor", type=float, default=None, metavar="N",
                        help="bottom of a steady symmetric pull-up at load factor N [1: level]")
    p_trim.add_argument("--nonlinear-beams", type=int, nargs="?", const=8, default=None, metavar="N", help=NONLINEAR_HELP)
    p_trim.add_argument("--coordinated", action="store_true",
                        help="coordinated turn: zero sideslip at the CG, heading free (default: the paper's turn, heading on track)")
    p_trim.add_argument("--no-limits", action="store_true",
                        help="do not enforce the thrust/surface limits nor the angle-of-attack limit of the linear aerodynamics "
                             "([aero] max_alpha_deg): print the solution of the trim equations as asked")
    _add_formulation(p_trim)
    p_trim.add_argument("--roots", nargs="?", const="unsteady", choices=["unsteady", "quasi-steady"], default=None,
                        help="also list the roots of the linearised trim, told apart as rigid-body, elastic and "
                             "aerodynamic-lag [unsteady]")
    p_trim.set_defaults(func=_trim)

    p_fl = sub.add_parser("flutter", help="flutter Mach and frequency of a steady manoeuvre (level flight: paper Tables 2-3)")
    add_aircraft(p_fl)
    p_fl.add_argument("--altitudes", type=float, nargs="+", default=None, metavar="H",
                      help="altitudes [m] [sea level to the aircraft file's envelope.max_altitude_m in 4 levels (the GTM: 0 "
                           "3048 6096 9144), else sea level; with --wind-tunnel: 0]")
    p_fl.add_argument("--models", default="QS,US", help="comma list of QS (quasi-steady), US (Theodorsen p-k), FS (finite-state)")
    p_fl.add_argument("--mach-min", type=float, default=None,
                      help="lower end of the search [the aircraft file's [envelope], else the estimated stall speed]")
    p_fl.add_argument("--mach-max", type=float, default=None,
                      help="upper end of the search [the aircraft file's [envelope], else M 0.95]")
    p_fl.add_argument("--turn-radius-m", type=float, default=None, metavar="R", help="steady level turn of radius R [m]")
    p_fl.add_argument("--climb-deg", type=float, default=None, metavar="G", help="steady climb (G > 0) or descent [deg] [0]")
    p_fl.add_argument("--glide", action="store_true", help="steady glide: thrust zero, flight-path angle found by trim")
    p_fl.add_argument("--load-factor", type=float, default=None, metavar="N",
                      help="steady symmetric pull-up at load factor N (with --nonlinear-beams) [1: level]")
    p_fl.add_argument("--nonlinear-beams", type=int, nargs="?", const=8, default=None, metavar="N", help=NONLINEAR_HELP)
    p_fl.add_argument("--free-aircraft", action="store_true",
                      help="with --nonlinear-beams: the flutter of the whole free aircraft (six rigid-body degrees of "
                           "freedom, Peters strips on every lifting strip) about each nonlinear trim, instead of the "
                           "wing clamped at its trimmed root")
    p_fl.add_argument("--coordinated", action="store_true",
                      help="with --turn-radius-m: coordinated turn (zero sideslip, heading free)")
    p_fl.add_argument("--vg", default=None, metavar="FILE.png",
                      help="also draw the V-g / V-f diagram (damping and frequency of every branch against speed) of the "
                           "aircraft as given (with --wind-tunnel: of the clamped structure over --speed-range-m-s), one "
                           "file per altitude (FILE_<H>m.png for several); --json carries the tracks")
    p_fl.add_argument("--vg-points", type=int, default=_VG_POINTS, metavar="N", help="speeds of the V-g diagram [25]")
    p_fl.add_argument("--workers", type=int, default=None, help="local processes of a flight search [all cores]")
    p_fl.add_argument("--wind-tunnel", action="store_true",
                      help="instead of a flight: the structure clamped at its body origin in an airflow (a wing alone, "
                           "e.g. goland_wing): flutter and divergence speeds")
    p_fl.add_argument("--speed-range-m-s", type=float, nargs=2, default=None, metavar=("LO", "HI"),
                      help="with --wind-tunnel: the speeds searched [10 300]")
    p_fl.add_argument("--speed-step-m-s", type=float, default=None, metavar="DV",
                      help="with --wind-tunnel: the scan step [m/s]; an interval whose damping curvature could hide an "
                           "instability is halved down to DV/16 [5]")
    p_fl.add_argument("--mach-step", type=float, default=None, metavar="DM",
                      help="scan step of the flight search in Mach; an interval whose damping curvature could hide an "
                           "instability is halved down to DM/16 [0.05, or an eighth of a narrower range]")
    p_fl.add_argument("--structural-damping", type=float, default=None, metavar="ZETA",
                      help="modal damping ratio of the elastic modes [the aircraft file's; 0 = the paper's undamped structure]")
    _add_formulation(p_fl, replication=True)
    p_fl.add_argument("--mode", metavar="FILE.rrd", help="write a Rerun recording of the lowest flutter point's mode: the "
                      "aircraft oscillating (amplitude scaled for display) and the mode's participation as bar charts")
    p_fl.set_defaults(func=_flutter)

    p_sw = sub.add_parser("sweep", help="flutter versus turn radius or climb angle (paper Figs. 7-16)")
    add_aircraft(p_sw)
    group = p_sw.add_mutually_exclusive_group(required=True)
    group.add_argument("--turn", action="store_true", help="level turns, R = 5-12 km")
    group.add_argument("--climb", action="store_true", help="climbs and descents, gamma = -15..15 deg")
    group.add_argument("--pull-up", action="store_true",
                       help="steady symmetric pull-ups, load factors --load-factors [1, 1.1, 1.2, 1.3, 1.5, 2]")
    p_sw.add_argument("--altitudes", type=float, nargs="+", default=None, metavar="H",
                      help="altitudes [m] [sea level to the aircraft file's envelope.max_altitude_m in 4 levels (the GTM: "
                           "0 3048 6096 9144), else sea level]")
    p_sw.add_argument("--mach-min", type=float, default=None,
                      help="lower end of each search [the aircraft file's [envelope], else the estimated stall speed]")
    p_sw.add_argument("--mach-max", type=float, default=None,
                      help="upper end of each search [the aircraft file's [envelope], else M 0.95]")
    p_sw.add_argument("--models", default="QS,US")
    p_sw.add_argument("--coordinated", action="store_true", help="with --turn: coordinated turns (zero sideslip, heading free)")
    p_sw.add_argument("--radii-m", type=float, nargs="+", default=None, metavar="R",
                      help="turn radii [m] with --turn [the paper's 5000-12000 m in 1 km steps]")
    p_sw.add_argument("--load-factors", type=float, nargs="+", default=None, metavar="N",
                      help="load factors of a --pull-up sweep")
    p_sw.add_argument("--nonlinear-beams", type=int, nargs="?", const=8, default=None, metavar="N",
                      help="with --pull-up: the wing's flutter about the nonlinear trim too, " + NONLINEAR_HELP)
    p_sw.add_argument("--angles-deg", type=float, nargs="+", default=None, metavar="G",
                      help="flight-path angles [deg] with --climb [the paper's -15..15 deg in 5 deg steps]")
    p_sw.add_argument("--scheduler", metavar="ADDRESS", help="Dask distributed scheduler (default: local processes); "
                      "tasks and results are exchanged pickled: give only the address of a cluster you trust")
    p_sw.add_argument("--workers", type=int, default=None, help="local processes [all cores]; not with --scheduler")
    p_sw.add_argument("--chain-length", type=int, default=None, metavar="K",
                      help="points per chain: each model/altitude chain (each point seeded with the previous flutter "
                      "Mach) is cut into runs of at most K points, 1 = every point its own task, so that more workers "
                      "than chains (8 in a paper study) are used; the same K gives the same results everywhere [whole chains]")
    p_sw.add_argument("--structural-damping", type=float, default=None, metavar="ZETA",
                      help="modal damping ratio of the elastic modes [the aircraft file's]")
    p_sw.add_argument("--out", default="logs/study", help="output folder for CSV, JSON and PNG [logs/study]; every "
                      "point is also written to flutter_<kind>.jsonl as it finishes")
    p_sw.add_argument("--resume", action="store_true", help="skip the points already in --out (after an interrupted run)")
    _add_formulation(p_sw, replication=True)
    p_sw.set_defaults(func=_sweep)
