"""Figures of docs/options.md, docs/validation.md, docs/simulation.md and the Goland figures (trims, ``flexsim
validate``, single flutter searches and simulations: seconds each; speeds are measured by ``benchmarks/``)."""

from __future__ import annotations

import functools
import math

from figure_text import exponent, figure, num, table


@functools.cache
def _cruise_trim(altitude_m: float, mach: float, glide: bool = False, **switches) -> tuple[dict, object]:
    """Quasi-steady trim of the bundled gtm (``flexsim trim gtm --json``) with ``AeroOptions`` switches:
    ``(summary, static margin)``; level flight or, with ``glide``, thrust zero and gamma unknown."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.atmosphere import mach_to_true_airspeed
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.trimming import SteadyManoeuvre, trim
    from flexsim.trimming.margin import static_margin

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
    rows = []
    for label, switches in MARGIN_ROWS:
        s, m = _cruise_trim(9144.0, 0.78, **switches)
        bold = "**" if not switches else ""
        rows.append([label, f"{bold}{m.neutral_point_aft_of_cg_m:.2f} m{bold}", f"{bold}{100 * m.fraction_of_mac:.1f} %{bold}",
                     f"{num(s['elevator_deg'], '.2f')}°", f"{s['lift_to_drag']:.1f}"])
    others = "; ".join(f"{'sea level' if h == 0 else f'{h:g} m'} M {mach:g}: {100 * _cruise_trim(h, mach)[1].fraction_of_mac:.1f} %"
                       for h, mach in ((0.0, 0.5), (6000.0, 0.6)))
    return (table("| bundled GTM, 9144 m, M 0.78 | neutral point behind the CG | static margin | trim elevator | L/D |", rows)
            + f"\nDefault aircraft at other conditions: {others}.\n")


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
    return (f"γ = {num(s['gamma_deg'], '.3f')}° = −atan(D/L) with L/D = {s['lift_to_drag']:.2f} (without the parasite "
            f"drag {num(bare['gamma_deg'], '.2f')}°)")


def _validate_value(x: float, floor: float, fmt: str = ".5g", exact_zero: bool = True) -> str:
    """A value of the validation table (``fmt``), ``0`` (``exact_zero``), or ``< floor`` for round-off-sized magnitudes."""
    if x == 0.0 and exact_zero:
        return "0"
    return f"< {exponent(floor)}" if abs(x) < floor else num(x, fmt)


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
    rows = []
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
            rows.append([case["case"] if i == 0 else "", c["quantity"].replace("|", "\\|") + unit,
                         _validate_value(c["reference"], 1e-12), _validate_value(c["flexsim"], 1e-12), error + mark, tol,
                         source.replace("|", "\\|")])
    passed = sum(case["passed"] for case in doc["cases"])
    return (table("| case | quantity | reference | flexsim | error | tol. | source of the reference |", rows)
            + f"\n{passed}/{len(doc['cases'])} cases pass (`flexsim validate` exits with status {code}).\n")


@functools.cache
def _turn_trim(coordinated: bool, altitude_m: float = 9144.0, mach: float = 0.78, radius_m: float = 5000.0):
    """Quasi-steady trim of a level turn of the bundled gtm (``flexsim trim --turn-radius-m R [--coordinated]``):
    ``(trim point, V^2/(gR))`` with the manoeuvre's speed (as ``studies/coordinated_turn.py``)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre, trim

    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    man = SteadyManoeuvre.turn(altitude_m, radius_m, mach=mach, coordinated=coordinated)
    # the paper's (uncoordinated) 5 km turn puts the fin's tip strip beyond max_alpha_deg: compared as the paper flies it
    return trim(model, man, check_limits=False), man.speed_m_s ** 2 / (model.terms.gravity_m_s2 * radius_m)


def options_coordinated_turn() -> str:
    """The coordinated turn at 9144 m, M 0.78, R = 5 km against its closed forms."""
    p, ratio = _turn_trim(True)
    beta = math.degrees(p.sideslip_cg)
    beta_text = "below 1e-10°" if abs(beta) < 1e-10 else f"{num(beta, '.2e')}°"
    mu, closed = p.bank_wind, math.hypot(1.0, ratio)
    return (f"sideslip at the CG {beta_text} (at o {num(math.degrees(p.beta), '.3f')}°), φ = {math.degrees(p.phi):.3f}°, "
            f"heading {math.degrees(p.heading_offset):.2f}° ahead of the track, rudder {num(math.degrees(p.u[3]), '.2f')}°, "
            f"aileron {num(math.degrees(p.u[1]), '.2f')}°, elevator {num(math.degrees(p.u[2]), '.2f')}°, thrust "
            f"{p.u[0] / 1e3:.1f} kN; μ = {math.degrees(mu):.3f}° with tan μ / (V²/gR) = {math.tan(mu) / ratio:.5f}; "
            f"|F|/W = {p.load_factor_total:.5f} against 1/cos μ = {1 / math.cos(mu):.5f} "
            f"({num(100 * (p.load_factor_total * math.cos(mu) - 1), '+.3f')} %) and the closed form √(1 + (V²/gR)²) = "
            f"{closed:.5f} ({num(100 * (p.load_factor_total / closed - 1), '+.2f')} %); n_z = {p.load_factor:.5f}")


def options_which_bank() -> str:
    """Euler bank against wind-axis bank in the coordinated turn: the size of the difference."""
    p, ratio = _turn_trim(True)
    return (f"with θ = {math.degrees(p.theta):.2f}° φ exceeds μ by {math.degrees(p.phi - p.bank_wind):.2f}°: "
            f"1/cos φ = {1 / math.cos(p.phi):.5f} is {100 * (1 / (math.cos(p.phi) * p.load_factor_total) - 1):.2f} % "
            f"above |F|/W, and tan φ is {100 * (math.tan(p.phi) / ratio - 1):.2f} % above V²/(gR)")


def options_paper_turn() -> str:
    """The paper's turn (heading on the track) at 9144 m, M 0.78, R = 5 km: its sideslip and cross controls."""
    p, _ = _turn_trim(False)
    return (f"{num(math.degrees(p.beta), '.1f')}° with {num(math.degrees(p.u[3]), '.1f')}° of rudder and "
            f"{num(math.degrees(p.u[1]), '.1f')}° of aileron")


def options_bending_incidence() -> str:
    """Static aeroelastic figures at 9144 m, M 0.78 with the swept-wing bending incidence off and on
    (``python studies/options_effects.py --skip-flutter``; its ``static_figures`` computes them)."""
    import options_effects

    from flexsim.aircraft.toml_loader import load_aircraft

    cols = []
    for bending in (False, True):
        f = options_effects.static_figures(load_aircraft("gtm"), bending)
        pitch = math.degrees(f.tip_strip_pitch_rad)
        cols.append([f"{math.degrees(f.theta_rad):.3f}° / {num(math.degrees(f.elevator_rad), '.3f')}°",
                     f"{num(f.tip_deflection_m, '.3f')} m / {num(math.degrees(f.tip_twist_rad), '+.3f')}°",
                     f"{num(pitch, '+.3f')}° ({'wash-in' if pitch > 0 else 'wash-out'})",
                     f"{num(f.roll_subsidence_1_s, '.3f')} 1/s",
                     f"{f.aileron_effectiveness:.3f}"])
    labels = ["trim pitch θ / elevator", "tip deflection / tip torsion",
              "pitch of the tip strip (torsion + bending slope + rigging)", "roll-subsidence root (free aircraft)",
              "aileron effectiveness: rolling moment flexible / rigid (restrained at the cruise trim's α, static "
              "elastic equilibrium)"]
    return table("| | off (paper) | on |", zip(labels, *cols))


def options_effects_flutter() -> str:
    """Sea-level finite-state flutter of the bundled gtm with each body option switched (docs/flutter.md),
    the cases and search of ``python studies/options_effects.py``."""
    import options_effects as study

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trimming import SteadyManoeuvre

    gtm = load_aircraft("gtm")
    level = SteadyManoeuvre.level(0.0, mach=0.65)
    cases = [("level flight, bundled `gtm`", gtm, level),
             ("level flight, parasite drag off (the paper's induced drag only)", study._with(gtm, drag=()), level),
             ("level flight, body moments and downwash off (the paper's strips)",
              study._with(gtm, bodies=(), downwash_gradient=0.0), level),
             ("level flight, bending incidence on", study._with(gtm, bending_incidence=True), level),
             ("turn R = 5 km, the paper's (heading on track)", gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65)),
             ("turn R = 5 km, coordinated", gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65, coordinated=True))]

    def small(x: float, unit: str = "°") -> str:
        return "0" if abs(x) < 0.005 else f"{num(x, '+.2f')}{unit}"

    def change(x: float, ref: float, floor: float) -> str:
        return f" (< {exponent(floor)})" if abs(x - ref) < floor else f" ({num(100 * (x / ref - 1), '+.2g')} %)"

    rows, ref = [], None
    for label, aircraft, manoeuvre in cases:
        fp = FlutterAnalysis(aircraft, "unsteady").search(manoeuvre, mach_range=(0.6, 0.8), mach_step=0.05)
        t = fp.trim
        mach_text, omega_text = f"{fp.mach:.4f}", f"{fp.frequency_rad_s:.3f}"
        if ref is None:
            ref = fp
        else:
            mach_text += change(fp.mach, ref.mach, 1e-4)
            if abs(fp.frequency_rad_s / ref.frequency_rad_s - 1) >= 0.01:
                omega_text += change(fp.frequency_rad_s, ref.frequency_rad_s, 1e-3)
        rows.append([label, mach_text, omega_text, f"{t.thrust_n / 1e3:.1f} kN", f"{num(t.tip_deflection_m, '.3f')} m",
                     f"{small(math.degrees(t.sideslip_cg))} / {small(math.degrees(t.u[3]))}"])
    return table("| case | M_F | ω_F [rad/s] | trim thrust | tip deflection | sideslip at the CG / rudder |", rows)


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
            f"M = {u_t / float(speed_of_sound(0.0)):.2f}: {num(100 * (u_t / GOLAND_U_F_M_S - 1), '+.1f')} % and "
            f"{num(100 * (u_p / GOLAND_U_F_M_S - 1), '+.1f')} % against Goland's {GOLAND_U_F_M_S} m/s")


def goland_pk_fs() -> str:
    """Peters N = 6 against Theodorsen p-k on the Goland wing (1.225 kg/m^3, its file's incompressible strips)."""
    (u_t, _), (u_p, _) = _goland("theodorsen", "none"), _goland("unsteady", "none")
    return f"{100 * abs(u_p / u_t - 1):.1f} %"


def goland_incompressible_102() -> str:
    """The Goland wing at 1.02 kg/m^3 without the Prandtl-Glauert factor."""
    (u_t, _), (u_p, _) = _goland("theodorsen", "none", 1.02), _goland("unsteady", "none", 1.02)
    return f"{u_t:.1f} m/s (Theodorsen) and {u_p:.1f} m/s (Peters)"


# --- docs/simulation.md ------------------------------------------------------------------------------------------

#: Errors below this are printed as the bound: the reference itself (DOP853 at rtol 1e-9) does not resolve them,
#: and their digits are round-off (a symmetric manoeuvre's bank).
ERROR_FLOOR = 1e-6


def _e(x: float) -> str:
    return f"{x:.1e}" if abs(x) >= ERROR_FLOOR else f"< {exponent(ERROR_FLOOR)}"


def _cell(e, rigid_parts: bool) -> str:
    tip = f"tip {_e(e.tip_m)} m ({_e(e.tip_relative)})"
    if e.altitude_m is None or not rigid_parts:
        return tip if e.altitude_m is None else f"{_e(e.altitude_m)} m / {tip}"
    return f"{_e(e.altitude_m)} m / {_e(e.airspeed_m_s)} m/s / {_e(e.bank_deg)} deg / {tip}"


# the accuracy table's errors of adaptive runs within a factor of 2 (their step sequences follow error estimates that
# round-off moves)
@figure(fast=False, rtol=0.5)
def simulation_accuracy() -> str:
    """The table of the default, the previous default and Radau against DOP853 (rtol 1e-9) on every named manoeuvre."""
    from flexsim.sim.accuracy import DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE, RUN_OPTIONS, manoeuvre_errors
    from flexsim.sim.manoeuvres import manoeuvre_names

    rows = []
    for name in manoeuvre_names():
        default, previous, radau = manoeuvre_errors(name, (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE))
        label = f"`{name}` ({RUN_OPTIONS.get(name, {}).get('t_end_s', default.duration_s):g} s)"
        rows.append([label, _cell(default, True), _cell(previous, False), _cell(radau, True)])
    return table(f"| manoeuvre | default, {DEFAULT_CHOICE.name}: altitude / airspeed / bank / tip | previous default, "
                 f"{PREVIOUS_CHOICE.name}: altitude / tip | {RADAU_CHOICE.name}: altitude / airspeed / bank / tip |", rows)


def simulation_structural_limits() -> str:
    """The default structural limit (``STRUCTURAL_LIMIT_FRACTION`` x the wing's length) of the GTM and the Goland wing."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.sim.simulate import STRUCTURAL_LIMIT_FRACTION

    gtm, goland = (STRUCTURAL_LIMIT_FRACTION * load_aircraft(name).component("right_wing").length_m
                   for name in ("gtm", "goland_wing"))
    return f"{STRUCTURAL_LIMIT_FRACTION:g} x the wing's length: {gtm:.2f} m on the GTM, {goland:.2f} m on the Goland wing"


def simulation_goland_flutter() -> str:
    """The clamped Goland wing's flutter speed and frequency with this model (``wind_tunnel_flutter``, Peters N = 6
    inflow and quasi-steady) and the tunnel speed of ``flutter-onset`` (its setup's metadata)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import wind_tunnel_flutter
    from flexsim.sim.manoeuvres import build_manoeuvre

    goland = load_aircraft("goland_wing")
    v, w = wind_tunnel_flutter(goland, aero_model="unsteady")
    v_qs, _ = wind_tunnel_flutter(goland, aero_model="quasi-steady")
    meta = build_manoeuvre("flutter-onset").metadata
    tunnel, flutter = float(meta["tunnel_speed_m_s"]), float(meta["flutter_speed_m_s"])
    return (f"{v:.1f} m/s at {w:.1f} rad/s with Peters N = 6 inflow, {v_qs:.1f} m/s quasi-steady; `flutter-onset` "
            f"flies at {tunnel / flutter:.2f} x {flutter:.1f} = {tunnel:.1f} m/s for either aerodynamic model")


def simulation_eigenvalues() -> str:
    """The stiff end of the spectrum of the unsteady GTM (m = n = 2, N = 6) linearised at the named manoeuvres' level
    trim (9144 m, M 0.75): the most negative real part and the largest |lambda|."""
    import numpy as np

    from flexsim.model.jacobian import jacobian
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("elevator-doublet")
    lam = np.linalg.eigvals(jacobian(setup.model, setup.initial.x, setup.initial.u)[0])
    big = lam[np.argmax(np.abs(lam))]
    return (f"{lam.size} states) has well-damped aero-lag eigenvalues down to {lam.real.min():.0f} s^-1 and |lambda| "
            f"up to {abs(big):.0f} s^-1 ({big.real:.0f} +- {abs(big.imag):.0f}j)")


def simulation_flutter_onset_growth() -> str:
    """The tip amplitude of the growing Goland oscillation over the accuracy comparison's window (no structural
    limit, ``flexsim.sim.accuracy.RUN_OPTIONS``)."""
    import numpy as np

    from flexsim.sim.accuracy import RUN_OPTIONS
    from flexsim.sim.manoeuvres import build_manoeuvre

    opts = RUN_OPTIONS["flutter-onset"]
    r = build_manoeuvre("flutter-onset").simulate(events=opts["events"], t_end_s=opts["t_end_s"])
    tip = np.abs(r.tip_deflection_m("right_wing"))
    return f"grows to {tip.max():.2f} m in {opts['t_end_s']:g} s"
