"""Figures of docs/options.md, docs/validation.md and the Goland figures (trims, ``flexsim validate``, single
flutter searches: seconds each), for ``regenerate_docs_figures.py``."""

from __future__ import annotations

import functools
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _num(x: float, fmt: str) -> str:
    """``format(x, fmt)`` with a typographic minus (as the docs write negative numbers)."""
    return format(x, fmt).replace("-", "−")


def bound(x: float, limit: float, what: str) -> str:
    """``limit`` as the docs print it (``1e-12``) once ``|x| < limit`` is checked: a round-off residual is stated as
    the bound it meets, never by its digits, which differ between machines and BLAS builds."""
    if not abs(x) < limit:
        raise RuntimeError(f"{what}: {x:.3g} is not below {limit:g}")
    return f"{limit:.0e}".replace("e-0", "e-")


@functools.cache
def _cruise_trim(altitude_m: float, mach: float, glide: bool = False, **switches) -> tuple[dict, object]:
    """Quasi-steady trim of the bundled gtm (``flexsim trim gtm --json``) with ``AeroOptions`` switches:
    ``(summary, static margin)``; level flight or, with ``glide``, thrust zero and gamma unknown."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.atmosphere import mach_to_true_airspeed
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.trim import SteadyManoeuvre, trim
    from flexsim.trim.margin import static_margin

    model = AircraftModel(load_aircraft("gtm"), aero=AeroOptions("quasi-steady", **switches))
    manoeuvre = SteadyManoeuvre(float(mach_to_true_airspeed(mach, altitude_m)), altitude_m, math.inf,
                                None if glide else 0.0)
    point = trim(model, manoeuvre)
    return point.summary(), static_margin(model, point)


#: The rows of the static-margin table of docs/options.md: label, AeroOptions switches.
MARGIN_ROWS = (("strips only (the paper's aircraft)", {"body_moments": False, "downwash": False}),
               ("+ fuselage and nacelle moments", {"downwash": False}),
               ("+ tail downwash", {"body_moments": False}),
               ("+ both (default)", {}))


def options_static_margin() -> str:
    """Static margin, neutral point, trim elevator and L/D at 9144 m, M 0.78 with the body options on and off."""
    lines = ["", "| bundled GTM, 9144 m, M 0.78 | neutral point behind the CG | static margin | trim elevator | L/D |",
             "|---|---|---|---|---|"]
    for label, switches in MARGIN_ROWS:
        s, m = _cruise_trim(9144.0, 0.78, **switches)
        bold = "**" if not switches else ""
        lines.append(f"| {label} | {bold}{m.neutral_point_aft_of_cg_m:.2f} m{bold} | {bold}{100 * m.fraction_of_mac:.1f} %{bold} | "
                     f"{_num(s['elevator_deg'], '.2f')}° | {s['lift_to_drag']:.1f} |")
    others = "; ".join(f"{'sea level' if h == 0 else f'{h:g} m'} M {mach:g}: {100 * _cruise_trim(h, mach)[1].fraction_of_mac:.1f} %"
                       for h, mach in ((0.0, 0.5), (6000.0, 0.6)))
    return "\n".join(lines) + f"\n\nDefault aircraft at other conditions: {others}.\n"


def options_lift_drag() -> str:
    """Lift, drag, L/D and thrust of the cruise trim at 9144 m, M 0.78 (and L/D without the parasite drag)."""
    s, _ = _cruise_trim(9144.0, 0.78)
    bare, _ = _cruise_trim(9144.0, 0.78, parasite_drag=False)
    return (f"L = {s['lift_kN']:.1f} kN, D = {s['drag_kN']:.1f} kN, **L/D = {s['lift_to_drag']:.1f}** (without the "
            f"parasite drag: {bare['lift_to_drag']:.1f}), thrust {s['thrust_kN']:.1f} kN")


def options_glide() -> str:
    """The glide trim at 9144 m, M 0.78, with and without the parasite drag."""
    s, _ = _cruise_trim(9144.0, 0.78, glide=True)
    bare, _ = _cruise_trim(9144.0, 0.78, glide=True, parasite_drag=False)
    return (f"γ = {_num(s['gamma_deg'], '.3f')}° = −atan(D/L) with L/D = {s['lift_to_drag']:.2f} (without the parasite "
            f"drag {_num(bare['gamma_deg'], '.2f')}°)")


def _validate_value(x: float, floor: float, fmt: str = ".5g", exact_zero: bool = True) -> str:
    """A value of the validation table (``fmt``), ``0`` (``exact_zero``), or ``< floor`` for round-off-sized magnitudes."""
    if x == 0.0 and exact_zero:
        return "0"
    return f"< {floor:.0e}".replace("e-0", "e-") if abs(x) < floor else _num(x, fmt)


def validation_table() -> str:
    """Every check of ``flexsim validate --json`` (all built-in cases): reference, flexsim, error, tolerance."""
    import contextlib
    import io
    import json

    from flexsim.cli.main import main as flexsim_main

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = flexsim_main(["validate", "--json"])
    doc = json.loads(out.getvalue())
    lines = ["", "| case | quantity | reference | flexsim | error | tol. | source of the reference |",
             "|---|---|---|---|---|---|---|"]
    for case in doc["cases"]:
        if case["error"]:
            raise RuntimeError(f"validation-table: case {case['case']} failed to run: {case['error']}")
        for i, c in enumerate(case["checks"]):
            unit = "" if c["unit"] == "-" else f" [{c['unit']}]"
            relative = c["error_kind"] == "relative"
            error = (_validate_value(100 * c["error"], 1e-4, "+.2g", exact_zero=False) + " %" if relative else
                     f"{_validate_value(c['error'], 1e-12, exact_zero=False)} (abs.)")
            tol = f"{100 * c['tolerance']:g} %" if relative else f"{c['tolerance']:g}{unit.strip(' []') and ' ' + c['unit']}"
            source = c["source"] if i == 0 or c["source"] != case["checks"][i - 1]["source"] else "as above"
            mark = "" if c["pass"] else " ✘"
            lines.append(f"| {case['case'] if i == 0 else ''} | {c['quantity'].replace('|', chr(92) + '|')}{unit} | "
                         f"{_validate_value(c['reference'], 1e-12)} | {_validate_value(c['flexsim'], 1e-12)} | "
                         f"{error}{mark} | {tol} | {source.replace('|', chr(92) + '|')} |")
    passed = sum(case["passed"] for case in doc["cases"])
    return "\n".join(lines) + (f"\n\n{passed}/{len(doc['cases'])} cases pass "
                               f"(`flexsim validate` exits with status {code}).\n")


@functools.cache
def _turn_trim(coordinated: bool, altitude_m: float = 9144.0, mach: float = 0.78, radius_m: float = 5000.0):
    """Quasi-steady trim of a level turn of the bundled gtm (``flexsim trim --turn-radius-m R [--coordinated]``):
    ``(trim point, V^2/(gR))`` with the manoeuvre's speed (as ``studies/coordinated_turn.py``)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trim import SteadyManoeuvre, trim

    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    man = SteadyManoeuvre.turn(altitude_m, radius_m, mach=mach, coordinated=coordinated)
    # the paper's (uncoordinated) 5 km turn puts the fin's tip strip beyond max_alpha_deg: compared as the paper flies it
    return trim(model, man, check_limits=False), man.speed_m_s ** 2 / (model.gravity_m_s2 * radius_m)


def options_coordinated_turn() -> str:
    """The coordinated turn at 9144 m, M 0.78, R = 5 km against its closed forms."""
    p, ratio = _turn_trim(True)
    beta = math.degrees(p.sideslip_cg)
    beta_text = "below 1e-10°" if abs(beta) < 1e-10 else f"{_num(beta, '.2e')}°"
    mu, closed = p.bank_wind, math.hypot(1.0, ratio)
    return (f"sideslip at the CG {beta_text} (at o {_num(math.degrees(p.beta), '.3f')}°), φ = {math.degrees(p.phi):.3f}°, "
            f"heading {math.degrees(p.heading_offset):.2f}° ahead of the track, rudder {_num(math.degrees(p.u[3]), '.2f')}°, "
            f"aileron {_num(math.degrees(p.u[1]), '.2f')}°, elevator {_num(math.degrees(p.u[2]), '.2f')}°, thrust "
            f"{p.u[0] / 1e3:.1f} kN; μ = {math.degrees(mu):.3f}° with tan μ / (V²/gR) = {math.tan(mu) / ratio:.5f}; "
            f"|F|/W = {p.load_factor_total:.5f} against 1/cos μ = {1 / math.cos(mu):.5f} "
            f"({_num(100 * (p.load_factor_total * math.cos(mu) - 1), '+.3f')} %) and the closed form √(1 + (V²/gR)²) = "
            f"{closed:.5f} ({_num(100 * (p.load_factor_total / closed - 1), '+.2f')} %); n_z = {p.load_factor:.5f}")


def options_which_bank() -> str:
    """Euler bank against wind-axis bank in the coordinated turn: the size of the difference."""
    p, ratio = _turn_trim(True)
    return (f"with θ = {math.degrees(p.theta):.2f}° φ exceeds μ by {math.degrees(p.phi - p.bank_wind):.2f}°: "
            f"1/cos φ = {1 / math.cos(p.phi):.5f} is {100 * (1 / (math.cos(p.phi) * p.load_factor_total) - 1):.2f} % "
            f"above |F|/W, and tan φ is {100 * (math.tan(p.phi) / ratio - 1):.2f} % above V²/(gR)")


def options_paper_turn() -> str:
    """The paper's turn (heading on the track) at 9144 m, M 0.78, R = 5 km: its sideslip and cross controls."""
    p, _ = _turn_trim(False)
    return (f"{_num(math.degrees(p.beta), '.1f')}° with {_num(math.degrees(p.u[3]), '.1f')}° of rudder and "
            f"{_num(math.degrees(p.u[1]), '.1f')}° of aileron")


def options_bending_incidence() -> str:
    """Static aeroelastic figures at 9144 m, M 0.78 with the swept-wing bending incidence off and on
    (``python studies/options_effects.py --skip-flutter``; its ``static_figures`` computes them)."""
    from flexsim.aircraft.toml_loader import load_aircraft

    study = _options_study()
    gtm = load_aircraft("gtm")
    cols = []
    for bending in (False, True):
        f = study.static_figures(gtm, bending)
        pitch = math.degrees(f.tip_strip_pitch_rad)
        cols.append([f"{math.degrees(f.theta_rad):.3f}° / {_num(math.degrees(f.elevator_rad), '.3f')}°",
                     f"{_num(f.tip_deflection_m, '.3f')} m / {_num(math.degrees(f.tip_twist_rad), '+.3f')}°",
                     f"{_num(pitch, '+.3f')}° ({'wash-in' if pitch > 0 else 'wash-out'})",
                     f"{_num(f.roll_subsidence_1_s, '.3f')} 1/s",
                     f"{f.aileron_effectiveness:.3f}"])
    labels = ["trim pitch θ / elevator", "tip deflection / tip torsion",
              "pitch of the tip strip (torsion + bending slope + rigging)", "roll-subsidence root (free aircraft)",
              "aileron effectiveness: rolling moment flexible / rigid (restrained at the cruise trim's α, static "
              "elastic equilibrium)"]
    lines = ["", "| | off (paper) | on |", "|---|---|---|"]
    lines += [f"| {label} | {off} | {on} |" for label, off, on in zip(labels, *cols)]
    return "\n".join(lines) + "\n"


def _options_study():
    """``studies/options_effects.py`` as a module (its ``_with`` builds the option variants of the aircraft)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("options_effects", ROOT / "studies" / "options_effects.py")
    study = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = study  # its dataclasses resolve their module by name while the module executes
    spec.loader.exec_module(study)
    return study


@functools.cache
def options_effects_points() -> tuple:
    """Sea-level finite-state flutter points of the bundled gtm with each body option switched, the cases and
    search of ``python studies/options_effects.py``: ``((label, FlutterPoint), ...)``, the bundled gtm first and the
    parasite drag off second."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trim import SteadyManoeuvre

    study, gtm = _options_study(), load_aircraft("gtm")
    level = SteadyManoeuvre.level(0.0, mach=0.65)
    cases = [("level flight, bundled `gtm`", gtm, level),
             ("level flight, parasite drag off (the paper's induced drag only)", study._with(gtm, drag=()), level),
             ("level flight, body moments and downwash off (the paper's strips)",
              study._with(gtm, bodies=(), downwash_gradient=0.0), level),
             ("level flight, bending incidence on", study._with(gtm, bending_incidence=True), level),
             ("turn R = 5 km, the paper's (heading on track)", gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65)),
             ("turn R = 5 km, coordinated", gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65, coordinated=True))]
    return tuple((label, FlutterAnalysis(aircraft, "unsteady").search(manoeuvre, mach_range=(0.6, 0.8), mach_step=0.05))
                 for label, aircraft, manoeuvre in cases)


def options_effects_flutter() -> str:
    """Sea-level finite-state flutter of the bundled gtm with each body option switched (docs/flutter.md),
    the cases and search of ``python studies/options_effects.py``."""
    def small(x: float, unit: str = "°") -> str:
        return "0" if abs(x) < 0.005 else f"{_num(x, '+.2f')}{unit}"

    def change(x: float, ref: float, floor: float) -> str:
        return f" (< {floor:.0e})".replace("e-0", "e-") if abs(x - ref) < floor else f" ({_num(100 * (x / ref - 1), '+.2g')} %)"

    lines = ["", "| case | M_F | ω_F [rad/s] | trim thrust | tip deflection | sideslip at the CG / rudder |",
             "|---|---|---|---|---|---|"]
    ref = None
    for label, fp in options_effects_points():
        t = fp.trim
        mach_text, omega_text = f"{fp.mach:.4f}", f"{fp.frequency_rad_s:.3f}"
        if ref is None:
            ref = fp
        else:
            mach_text += change(fp.mach, ref.mach, 1e-4)
            if abs(fp.frequency_rad_s / ref.frequency_rad_s - 1) >= 0.01:
                omega_text += change(fp.frequency_rad_s, ref.frequency_rad_s, 1e-3)
        lines.append(f"| {label} | {mach_text} | {omega_text} | {t.thrust_n / 1e3:.1f} kN | {_num(t.tip_deflection_m, '.3f')} m | "
                     f"{small(math.degrees(t.sideslip_cg))} / {small(math.degrees(t.u[3]))} |")
    return "\n".join(lines) + "\n"


#: Goland's flutter speed at 1.225 kg/m^3 [m/s] (Goland 1945; the validation case's reference).
GOLAND_U_F_M_S = 137.2


@functools.cache
def _goland(model: str, compressibility: str, density_kg_m3: float | None = None) -> tuple[float, float]:
    """Wind-tunnel flutter speed [m/s] and frequency [rad/s] of the bundled goland_wing."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import wind_tunnel_flutter

    return wind_tunnel_flutter(load_aircraft("goland_wing"), aero_model=model, compressibility=compressibility,
                               density_kg_m3=density_kg_m3)


def goland_compressible() -> str:
    """The Goland wing at 1.225 kg/m^3 with the Prandtl-Glauert factor on (its file has it off)."""
    from flexsim.atmosphere import speed_of_sound

    (u_t, w_t), (u_p, _) = _goland("theodorsen", "prandtl-glauert"), _goland("unsteady", "prandtl-glauert")
    return (f"{u_t:.2f} m/s (Theodorsen) and {u_p:.2f} m/s (Peters N = 6) at {w_t:.2f} rad/s, "
            f"M = {u_t / float(speed_of_sound(0.0)):.2f}: {_num(100 * (u_t / GOLAND_U_F_M_S - 1), '+.1f')} % and "
            f"{_num(100 * (u_p / GOLAND_U_F_M_S - 1), '+.1f')} % against Goland's {GOLAND_U_F_M_S} m/s")


def goland_incompressible_102() -> str:
    """The Goland wing at 1.02 kg/m^3 without the Prandtl-Glauert factor."""
    (u_t, _), (u_p, _) = _goland("theodorsen", "none", 1.02), _goland("unsteady", "none", 1.02)
    return f"{u_t:.1f} m/s (Theodorsen) and {u_p:.1f} m/s (Peters)"
