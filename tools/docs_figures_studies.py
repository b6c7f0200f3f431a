"""Figures of docs/flutter.md, docs/calibration.md and docs/validation.md computed by the library's validation cases
and the ``studies/`` scripts (their own functions, imported, never copied); registered in
``regenerate_docs_figures.py``."""

from __future__ import annotations

import functools
import math
import re

from docs_figures_flutter import _level
from figure_text import ROOT, figure, num, span

#: Altitudes of Tables 2-3 [m].
PAPER_ALTITUDES_M = (0.0, 3048.0, 6096.0, 9144.0)


def calibration_uncalibrated() -> str:
    """The finite-state sea-level flutter point of ``gtm_uncalibrated`` (elastic axis at 0.375 c, every factor 1)."""
    from flexsim.linear.study import StudyCase, run_case

    r = run_case(StudyCase("gtm_uncalibrated", "FS", 0.0))
    if r.get("error"):
        raise RuntimeError(f"calibration-uncalibrated: {r['error']}")
    return f"M {r['mach']:.3f} at sea level, {r['omega_rad_s']:.0f} rad/s in {r['mode']}"


def calibration_structure() -> str:
    """The fitted factors (``tools/gtm_calibration.toml``), the resulting stiffness of the bundled gtm and its
    in-vacuo frequencies (``flexsim modes gtm``)."""
    import tomllib

    from flexsim.aircraft.toml_loader import load_aircraft

    factors = tomllib.loads((ROOT / "tools" / "gtm_calibration.toml").read_text(encoding="utf-8"))["scaling"]
    gtm = load_aircraft("gtm")
    sections = {c.name: c.sections for c in gtm.components}
    wing, fuselage = sections["right_wing"], sections["fuselage"]

    def freq(label: str) -> str:
        return f"{_vacuo('gtm', label):.1f}"

    return (f"wing GJ × {factors['wing_gj']:.3f}, wing EI × {factors['wing_ei']:.3f}, fuselage EI × "
            f"{factors['fuselage_ei']:.2f}; wing root EI {wing.ei_nm2[0] / 1e9:.2f} GN m², GJ {wing.gj_nm2[0] / 1e9:.3f} GN m², "
            f"fuselage EI peak {max(fuselage.ei_nm2) / 1e9:.1f} GN m². In-vacuo frequencies (`flexsim modes`): wing "
            f"bending 1 {freq('wings bending 1 (symmetric)')} (sym.) and {freq('wings bending 1 (antisymmetric)')} "
            f"(antisym.), fuselage bending 1 {freq('fuselage bending 1 (symmetric)')}, wing torsion 1 "
            f"{freq('wings torsion 1 (symmetric)')} (sym.) and {freq('wings torsion 1 (antisymmetric)')} (antisym.) rad/s")


@figure(fast=False)
def calibration_summary() -> str:
    """What the calibration meets, from the level-flight rows of the bundled gtm (US, FS, QS)."""
    from flexsim.linear.paper_data import TABLE_US

    us, fs = _level("US"), _level("FS")
    paper = {row[0]: row for row in TABLE_US}
    dm = {h: 100 * (us[h]["mach"] / paper[h][1] - 1) for h in PAPER_ALTITUDES_M}
    dw = [100 * (us[h]["omega_rad_s"] / paper[h][2] - 1) for h in PAPER_ALTITUDES_M[1:]]
    met = [h for h in PAPER_ALTITUDES_M if abs(dm[h]) <= 3.0]
    missed = [h for h in PAPER_ALTITUDES_M if abs(dm[h]) > 3.0]
    pkfs = max(abs(fs[h]["mach"] / us[h]["mach"] - 1) for h in PAPER_ALTITUDES_M)

    def at(hs) -> str:
        return ", ".join(f"{num(dm[h], '+.2f')} % at {h:g} m" for h in hs) or "none"

    def trim(key: str, fmt: str) -> str:
        return span([us[h][key] for h in PAPER_ALTITUDES_M], fmt, " to ")

    return (f"US M_F within 3 %: {at(met)}; outside: {at(missed)}. US ω_F {num(min(dw), '+.1f')} to "
            f"{num(max(dw), '+.1f')} % at 3048-9144 m (target 10 %). p-k and finite state within {100 * pkfs:.1f} % in M_F at "
            f"all four altitudes. Trim at the US flutter points: θ {trim('theta_deg', '.1f')}°, thrust "
            f"{trim('thrust_kN', '.0f')} kN, elevator {trim('elevator_deg', '+.1f')}°")


def typical_section_kf() -> str:
    """Reduced flutter frequency of the Theodorsen typical section and Peters N = 6's change of U_F."""
    from flexsim.aero.typical_section import TypicalSection, flutter_analysis

    section = TypicalSection(a=-0.2, e=-0.1, mu=20.0, r2=0.24, sigma=0.4)  # docs/validation.md, the case's section
    t, p = flutter_analysis(section, "theodorsen"), flutter_analysis(section, "peters", 6)
    return (f"k_F = {t.flutter_frequency / t.flutter_speed:.4f}; Peters' N = 6 approximation changes U_F by "
            f"{num(100 * (p.flutter_speed / t.flutter_speed - 1), '+.2f')} %")


def validation_phugoid() -> str:
    """The ``phugoid-lanchester`` case's aircraft (6000 m, M 0.6) with the body moments and tail downwash on, against
    Lanchester."""
    from flexsim.sim.validation import phugoid_point

    p = phugoid_point(6000.0, 0.6, body_moments=True, downwash=True)
    return (f"With them (static margin {100 * p.static_margin:.1f} % at this point) the frequency is "
            f"{100 * (1 - p.omega_rad_s / p.lanchester_omega_rad_s):.1f} % and the damping "
            f"{100 * (1 - p.damping_ratio / p.lanchester_damping_ratio):.0f} % below Lanchester's ({p.omega_rad_s:.5f} rad/s, "
            f"ζ = {p.damping_ratio:.4f} against {p.lanchester_omega_rad_s:.5f}, {p.lanchester_damping_ratio:.4f})")


def goland_lift_slope_085() -> str:
    """The Goland wing at 1.02 kg/m^3 with Prandtl-Glauert and a lift slope of 0.85 * 2 pi (the source's own run)."""
    from dataclasses import replace

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import wind_tunnel_flutter

    wing = load_aircraft("goland_wing")
    wing = replace(wing, components=tuple(replace(c, aero=replace(c.aero, lift_slope=0.85 * 2 * math.pi))
                                          if c.aero is not None else c for c in wing.components))
    u_f, _ = wind_tunnel_flutter(wing, aero_model="theodorsen", density_kg_m3=1.02, compressibility="prandtl-glauert",
                                 speed_range=(100.0, 250.0), speed_step=10.0, tol_m_s=1e-2)
    return f"{u_f:.0f} m/s (Theodorsen)"


@functools.cache
def _in_vacuo(aircraft: str) -> dict[str, float]:
    """In-vacuo natural frequencies [rad/s] of a bundled aircraft by dominant degree of freedom (``flexsim modes``)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.modes import in_vacuo_modes
    from flexsim.model.aircraft_model import AircraftModel

    out: dict[str, float] = {}
    for m in in_vacuo_modes(AircraftModel(load_aircraft(aircraft), gravity_m_s2=0.0)).modes:
        out.setdefault(m.dominant_dof, m.frequency_rad_s)
    return out


def _vacuo(aircraft: str, label: str) -> float:
    f = _in_vacuo(aircraft)
    if label not in f:
        raise RuntimeError(f"no in-vacuo mode {label!r} of {aircraft} (modes: {', '.join(f)})")
    return f[label]


def flutter_mode_frequencies() -> str:
    """The US flutter frequencies of the bundled gtm against its in-vacuo fuselage bending 1 and wing torsion 1."""
    w = [r["omega_rad_s"] for r in _level("US").values()]
    fus, t_s, t_a = (_vacuo("gtm", k) for k in ("fuselage bending 1 (symmetric)", "wings torsion 1 (symmetric)",
                                                "wings torsion 1 (antisymmetric)"))
    if not fus < min(w) <= max(w) < min(t_s, t_a):
        raise RuntimeError("flutter-mode-frequencies: the flutter frequency is no longer between the fuselage's first "
                           "bending and the wings' first torsion")
    return (f"{span(w, '.1f')} rad/s (US), between the fuselage's first bending ({fus:.1f} rad/s in vacuo) and the "
            f"wings' first torsion ({t_s:.1f}/{t_a:.1f} rad/s, symmetric/antisymmetric)")


# --- docs/replication.md: what the paper's tables imply, and the decomposition at 9144 m ----------------------------

def density_paper() -> str:
    """What the paper's Tables 2-3 imply (``python studies/density_finding.py --paper``; printed values only)."""
    import density_finding

    return "\n" + density_finding.paper_table() + "\n"


@functools.cache
def _decomposition_gtm() -> tuple[dict, ...]:
    """``python studies/manoeuvre_decomposition.py --altitude 9144`` on the bundled gtm (US p-k, true density), every
    default switch (each a term of today's model or a change of the linearisation point)."""
    import manoeuvre_decomposition as md

    ac = md.configure("gtm", None, 1.0, None, None)
    return tuple(md.run(ac, "gtm", 9144.0, tuple(md.SWITCHES), 3048.0, 0.91))


@figure(fast=False)
def decomposition_gtm() -> str:
    """The decomposition table of the bundled gtm at 9144 m and its summary."""
    import manoeuvre_decomposition as md

    rows = {r["switch"]: r for r in _decomposition_gtm()}
    ref, damp, dens = rows["none"], rows["damping"], rows["density"]
    small = [s for s in ("rotation", "static_deformation", "thrust", "gravity")
             if abs(rows[s]["turn_dM"] - ref["turn_dM"]) <= 1.5e-4]
    climbs = [r["climb_dM"] for s, r in rows.items() if s != "damping"]
    study_table = re.sub(r"(?<![\w.])-(?=\d)", "−", md.table(list(rows.values())))  # typographic minus, as the docs
    return ("\n" + study_table + "\n\n"
            f"The turn effect is {num(ref['turn_dM'], '+.4f')}; {', '.join(small)} each change it by 0.0001 or less. "
            f"Without structural damping (`damping`) the critical mode is another one, at {damp['w_level']:.1f} rad/s "
            f"(M {damp['M_level']:.4f}), and the turn row compares different modes. With the linearised aerodynamics at "
            f"ρ(3048 m) (`density`) flutter moves to M {dens['M_level']:.2f} and the turn effect becomes "
            f"{num(dens['turn_dM'], '+.4f')} ({num(100 * (dens['turn_dM'] / ref['turn_dM'] - 1), '+.0f')} %). "
            f"M_F(+15°) − M_F(−15°) stays between {num(min(climbs), '+.5f')} and {num(max(climbs), '+.5f')} in every "
            f"row but `damping` ({num(damp['climb_dM'], '+.5f')}, another mode).\n")


def _pg_slope(mach: float) -> float:
    """d[1/sqrt(1 - M^2)]/dM = M / (1 - M^2)^1.5, the Prandtl-Glauert factor's slope [-]."""
    return mach / (1.0 - mach * mach) ** 1.5


@figure(fast=False)
def decomposition_reading() -> str:
    """The reading of the decomposition table; raises when the rows no longer support it."""
    rows = {r["switch"]: r for r in _decomposition_gtm()}
    ref, aa, pg, dens = (rows[s] for s in ("none", "aero_alpha", "prandtl_glauert", "density"))
    t0 = ref["turn_dM"]
    small = max(abs(rows[s]["turn_dM"] - t0) for s in ("mass_matrix", "force_resolution"))
    if small > 1.5e-4 or not pg["turn_dM"] > t0 or not abs(aa["turn_dM"]) < 0.5 * abs(t0):
        raise RuntimeError("decomposition-reading: aero_alpha no longer carries the turn effect, or P-G no longer "
                           f"compresses it, or M(q) / the force resolution move it: { {s: r['turn_dM'] for s, r in rows.items()} }")
    carried = "**entirely**" if abs(aa["turn_dM"]) <= 1.5e-4 else f"**{100 * (1 - aa['turn_dM'] / t0):.0f} %**"
    return (f"Reading: the turn effect is carried {carried} by the aerodynamics linearised about the turn's larger angle "
            f"of attack and its sideslip (`aero_alpha`: {num(t0, '+.4f')} → {num(aa['turn_dM'], '+.4f')}); "
            "rotation rates, the whole static deformation, thrust, gravity, the static deflection's effect on M(q) and "
            f"the force resolution's trim-α terms each change it by {small:.4f} or less. "
            f"The **Prandtl–Glauert factor compresses it** (frozen at the level flutter Mach the turn effect is "
            f"{num(pg['turn_dM'], '+.4f')}, {pg['turn_dM'] / t0:.1f}× larger) — at M {ref['M_level']:.2f} the P-G "
            f"factor's slope (d[1/√(1−M²)]/dM = M/(1−M²)^1.5 = {_pg_slope(ref['M_level']):.1f}) makes the aerodynamic "
            "stiffness rise so fast with Mach that any destabilising change is met within a few thousandths in Mach. "
            f"The **density** of the linearised aerodynamics raises it (row `density`: flutter moves to M "
            f"{dens['M_level']:.2f}, where that slope is {_pg_slope(ref['M_level']) / _pg_slope(dens['M_level']):.1f}× "
            "smaller).")


# --- docs/calibration.md: what the paper's Tables 2-3 say by themselves --------------------------------------------

def calibration_paper_qs_us() -> str:
    """The paper's QS flutter Mach against its US one (Table 2 / Table 3 - 1) at the four altitudes."""
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    d = [100.0 * (qs[1] / us[1] - 1.0) for qs, us in zip(TABLE_QS, TABLE_US)]
    return (f"within {max(abs(d[0]), abs(d[1])):.1f} % of the US ones at 0 and 3048 m; {num(d[2], '.1f')} % and "
            f"{num(d[3], '.1f')} % at 6096 and 9144 m")


def calibration_paper_thrust() -> str:
    """W = T_e / sin(theta) over the 8 rows of Tables 2-3, and how much T_e q would vary (an induced-drag reading)."""
    from flexsim.atmosphere import isa_density, mach_to_true_airspeed
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    rows = TABLE_QS + TABLE_US
    w = [r[4] / math.sin(math.radians(r[3])) for r in rows]
    tq = [r[4] * 0.5 * float(isa_density(r[0])) * float(mach_to_true_airspeed(r[1], r[0])) ** 2 for r in rows]
    mean_w = sum(w) / len(w)
    spread = 100.0 * max(abs(x / mean_w - 1.0) for x in w)
    tq_spread = 100.0 * (max(tq) - min(tq)) / (max(tq) + min(tq))  # half the range about its middle
    return (f"T_e = {mean_w:.1f} kN × sin θ in all {len(rows)} rows of Tables 2-3 (to {spread:.3f} %; an induced drag "
            f"growing as 1/q would keep T_e·q constant, which varies by ±{tq_spread:.0f} %): its aerodynamic resultant has "
            f"no body-x component and its aircraft weighs {mean_w:.1f} kN ({1e3 * mean_w / 9.80665 / 1e3:.1f} t)")


def calibration_speeds() -> str:
    """The paper's US flutter speeds (Table 3) and the dynamic pressure at them, beside flexsim's US speeds."""
    from flexsim.atmosphere import isa_density, mach_to_true_airspeed
    from flexsim.linear.paper_data import TABLE_US

    v = [float(mach_to_true_airspeed(r[1], r[0])) for r in TABLE_US]
    q = [0.5 * float(isa_density(r[0])) * x * x / 1e3 for r, x in zip(TABLE_US, v)]
    us = _level("US")
    ours = [float(mach_to_true_airspeed(us[r[0]]["mach"], r[0])) for r in TABLE_US]
    m = [r[1] for r in TABLE_US]
    return (f"{', '.join(f'{x:.0f}' for x in v)} m/s at 0-9144 m (M_F(9144)/M_F(0) = {m[3] / m[0]:.3f}; "
            f"{m[3] / m[1]:.3f} from 3048 to 9144 m), while the dynamic pressure at flutter falls from {q[0]:.1f} to "
            f"{q[3]:.1f} kPa. On the notional aircraft the flutter point follows the dynamic pressure more closely "
            f"({', '.join(f'{x:.0f}' for x in ours)} m/s, US)")
