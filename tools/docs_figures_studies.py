"""Figures of docs/flutter.md, docs/calibration.md and docs/validation.md computed by the ``studies/`` scripts,
for ``regenerate_docs_figures.py``.

Each function returns the text of one ``<!-- figures:NAME -->`` region; the registry (and which are fast) is in
``tools/regenerate_docs_figures.py``. The computations are the studies' own functions (imported from
``studies/``, never copied): ``density_finding.paper_table`` and ``run``, ``symmetric_mode.census_modes``,
``paper_residuals.trims_at_paper``, ``manoeuvre_decomposition.run``, and the library's validation cases.
"""

from __future__ import annotations

import functools
import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_static import _num  # noqa: E402

#: Altitudes of Tables 2-3 [m].
PAPER_ALTITUDES_M = (0.0, 3048.0, 6096.0, 9144.0)


def _minus(text: str) -> str:
    """A study's markdown with a typographic minus before numbers (as the docs write them)."""
    return re.sub(r"(?<![\w.])-(?=\d)", "−", text)


def _join(values, fmt: str) -> str:
    return " / ".join(format(v, fmt) for v in values)


def _v2(x: float) -> str:
    """V^2/sqrt(1-M^2) in 10^3 m^2/s^2: three significant digits, at least one decimal below 100."""
    return f"{x:.0f}" if x >= 100 else f"{x:.1f}"


# --- docs/flutter.md: the density section ---------------------------------------------------------------------

def density_paper() -> str:
    """What the paper's Tables 2-3 imply (``python studies/density_finding.py --paper``; printed values only)."""
    import density_finding

    return "\n" + density_finding.paper_table() + "\n"


@functools.cache
def _density_rows() -> tuple[dict, ...]:
    """``python studies/density_finding.py --fixed 0 3048``: US level flutter of the bundled gtm at 0-9144 m with
    the linearised aerodynamics at the true density, rho(0) and rho(3048 m)."""
    import density_finding

    from flexsim.aircraft.toml_loader import load_aircraft

    rows = density_finding.run(load_aircraft("gtm"), "gtm", "US", ["true", "0", "3048"], [0.70] * 4)
    if len(rows) != 12:
        raise RuntimeError(f"density-fixed: {12 - len(rows)} of 12 points without a crossing")
    return tuple(rows)


def density_fixed() -> str:
    """The density table of docs/flutter.md and the figures read from it."""
    from flexsim.atmosphere import isa_density
    from flexsim.linear.paper_data import TABLE_US

    rows = _density_rows()
    by = {}
    for r in rows:
        by.setdefault(r["density"], {})[r["altitude_m"]] = r
    labels = {"true": "true density (flexsim default)", "rho(0 m)": f"ρ(0 m) = {isa_density(0.0):.3f} kg/m³",
              "rho(3048 m)": f"ρ(3048 m) = {isa_density(3048.0):.3f} kg/m³"}
    lines = ["", "| linearised aerodynamics at | M_F at 0 / 3048 / 6096 / 9144 m | ω_F [rad/s] | V_F²/√(1−M²) [10³ m²/s²] | "
             "M_F(9144)/M_F(3048) |", "|---|---|---|---|---|"]
    ratio = {}
    for key, label in labels.items():
        r = [by[key][h] for h in PAPER_ALTITUDES_M]
        ratio[key] = r[3]["M_F"] / r[1]["M_F"]
        lines.append(f"| {label} | {_join([x['M_F'] for x in r], '.4f')} | {_join([x['omega_F'] for x in r], '.2f')} | "
                     f"{' / '.join(_v2(x['V2PG_k']) for x in r)} | {ratio[key]:.3f} |")
    paper_v2 = []
    from flexsim.atmosphere import speed_of_sound

    for h, m, *_ in TABLE_US:
        v = m * float(speed_of_sound(h))
        paper_v2.append(v * v / math.sqrt(1 - m * m) / 1e3)
    lines.append(f"| paper (Table 3) | {_join([p[1] for p in TABLE_US], '.4f')} | {_join([p[2] for p in TABLE_US], '.2f')} | "
                 f"{' / '.join(_v2(x) for x in paper_v2)} | {TABLE_US[3][1] / TABLE_US[1][1]:.3f} |")
    fixed = [by[k] for k in ("rho(0 m)", "rho(3048 m)")]
    spread = max(max(r[h]["V2PG_k"] for h in PAPER_ALTITUDES_M) / min(r[h]["V2PG_k"] for h in PAPER_ALTITUDES_M) - 1
                 for r in fixed)
    rise = [100 * (r[9144.0]["omega_F"] / r[3048.0]["omega_F"] - 1) for r in fixed]
    r0 = by["rho(0 m)"]
    fixed_ratios = sorted(ratio[k] for k in ("rho(0 m)", "rho(3048 m)"))
    q_true = ", ".join(f"{by['true'][h]['qPG_kPa']:.1f}" for h in PAPER_ALTITUDES_M)
    return ("\n".join(lines) + f"\n\nWith any single density the boundary keeps V²/√(1−M²) constant within {100 * spread:.1f} % "
            f"from 0 to 9144 m, the true airspeed falls slightly with altitude ({r0[0.0]['V_F']:.1f} → {r0[9144.0]['V_F']:.1f} m/s "
            f"at ρ(0)), ω_F rises by {min(rise):.1f}-{max(rise):.1f} % from 3048 to 9144 m and M_F(9144)/M_F(3048) becomes "
            f"{fixed_ratios[0]:.3f}-{fixed_ratios[1]:.3f} against the paper's {TABLE_US[3][1] / TABLE_US[1][1]:.3f} — with the "
            f"true density {ratio['true']:.3f}, where q_F/√(1−M²) = {q_true} kPa from 0 to 9144 m.\n")


# --- docs/flutter.md and docs/calibration.md: the paper's 17.8 rad/s sea-level mode --------------------------

@functools.cache
def _census(model: str, altitude_m: float, mach: float):
    """``python studies/symmetric_mode.py census --aircraft gtm_paper --altitude H --mach M [--model QS]``."""
    import symmetric_mode
    from manoeuvre_decomposition import configure

    ac = configure("gtm_paper", None, 1.0, None, None)
    return symmetric_mode.census_modes(ac, model, ac.formulation, None, altitude_m, mach, 45.0)


def _wing_bending_sym(modes):
    """The symmetric elastic mode of lowest frequency whose largest linear coordinate is the wing's first bending."""
    cands = [m for m in modes if m.kind == "elastic" and m.symmetric and m.largest.endswith("wing bending 1")]
    if not cands:
        raise RuntimeError("symmetric-census: no symmetric wing-bending mode in the census")
    return cands[0]


def symmetric_census() -> str:
    """The symmetric wing first bending mode (the only one near the paper's 17.8 rad/s) and the short period."""
    us0, qs0, us9 = _census("US", 0.0, 0.6742), _census("QS", 0.0, 0.6742), _census("US", 9144.0, 0.78)
    a, b, c = _wing_bending_sym(us0), _wing_bending_sym(qs0), _wing_bending_sym(us9)
    sp = [m for m in us0 if m.kind == "rigid" and m.symmetric and m.frequency_rad_s > 1.0]
    if not sp:
        raise RuntimeError("symmetric-census: no short-period mode in the census")
    return (f"{a.frequency_rad_s:.2f} rad/s, ζ = {a.damping_ratio:.3f} at sea level, M 0.6742 (p-k; QS: "
            f"{b.frequency_rad_s:.2f} rad/s, ζ = {b.damping_ratio:.3f}) and {c.frequency_rad_s:.2f} rad/s, "
            f"ζ = {c.damping_ratio:.3f} at 9144 m, M 0.78 (q_f1 {a.qf1_ratio:.2f} / {b.qf1_ratio:.2f} / {c.qf1_ratio:.2f} of the wing "
            f"bending in these three); "
            f"the short period is at {sp[0].frequency_rad_s:.2f} rad/s (ζ {sp[0].damping_ratio:.2f})")


# --- docs/flutter.md: the two mirror classes apart -------------------------------------------------------------

@functools.cache
def _class_bounds(aircraft: str) -> tuple[dict, ...]:
    """``python studies/symmetric_mode.py bounds --aircraft NAME --model US`` (3048-9144 m, true density)."""
    import numpy as np
    import symmetric_mode
    from manoeuvre_decomposition import configure

    ac = configure(aircraft, None, 1.0, None, None)
    rows = symmetric_mode.bounds(ac, f"`{aircraft}` ({ac.formulation})", "US", ac.formulation, None,
                                 PAPER_ALTITUDES_M[1:], np.arange(0.55, 0.95 + 1e-9, 0.025))
    for r in rows:
        if not (r["symmetric"] and r["antisymmetric"] and "omega_F" in r["symmetric"] and "omega_F" in r["antisymmetric"]):
            raise RuntimeError(f"symmetric-bounds-us: {aircraft} at {r['altitude_m']:g} m: a class without a crossing "
                               f"inside the grid")
    return tuple(rows)


def symmetric_bounds_us() -> str:
    """The symmetric and antisymmetric US flutter boundaries of ``gtm`` and ``gtm_paper`` apart, and their gaps."""
    import symmetric_mode

    rows = {name: _class_bounds(name) for name in ("gtm", "gtm_paper")}
    table = symmetric_mode.bounds_table([r for name in rows for r in rows[name]])
    table = table.split("\n\n")[0]  # the table without the per-config trend lines

    def span(name: str, get, fmt: str) -> str:
        vals = [get(r) for r in rows[name]]
        return f"{_num(min(vals), fmt)} to {_num(max(vals), fmt)}"

    gap = lambda r: r["gap_sym_minus_anti"]  # noqa: E731
    dw = lambda r: r["antisymmetric"]["omega_F"] - r["symmetric"]["omega_F"]  # noqa: E731
    q = lambda r: r["symmetric"]["qf1_ratio"]  # noqa: E731
    return ("\n" + _minus(table) + "\n\nThe symmetric boundary lies " + span("gtm", gap, "+.4f") + " in Mach above the "
            f"antisymmetric one on `gtm` and {span('gtm_paper', gap, '+.4f')} on `gtm_paper`, "
            f"{span('gtm', dw, '.2f')} rad/s (`gtm`) and {span('gtm_paper', dw, '.2f')} rad/s (`gtm_paper`) lower in "
            f"frequency, with q_f1 {span('gtm', q, '.2f')} (`gtm`) and {span('gtm_paper', q, '.2f')} (`gtm_paper`) of "
            "the largest linear coordinate.\n")


@functools.cache
def _bounds(aircraft: str, factors: tuple[tuple[str, float], ...], fixed_density_alt_m: float | None, model: str,
            altitude_m: float) -> dict:
    """One row of ``python studies/symmetric_mode.py bounds --aircraft NAME [--factor N=V ...] [--fixed-density
    ALT] --model MODEL --altitudes H`` (the aircraft file's formulation, its damping)."""
    import numpy as np
    import symmetric_mode
    from manoeuvre_decomposition import configure

    ac = configure(aircraft, None, 1.0, None, None)
    for name, value in factors:
        ac = symmetric_mode.apply_factor(ac, name, value)
    (row,) = symmetric_mode.bounds(ac, "", model, ac.formulation, fixed_density_alt_m, [altitude_m],
                                   np.arange(0.55, 0.95 + 1e-9, 0.025))
    return row


def _bounds_label(aircraft: str, factors, fixed) -> str:
    names = {"fuselage.ei": "fuselage EI", "wing.ei": "wing EI", "wing.gj": "wing GJ"}
    parts = [f"`{aircraft}`"] + [f"{names.get(n, n)} × {v:g}" for n, v in factors]
    return ", ".join(parts) + ("" if fixed is None else f", ρ({fixed:g} m)")


#: The stiffness variants of gtm_paper in docs/flutter.md's class-boundary table (US; its finite-state rows, about
#: 1.5 min per altitude on a loaded machine, are recorded output):
#: (aircraft, factors, fixed density altitude, model, altitudes).
MORE_BOUNDS = (("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.7)), None, "US", PAPER_ALTITUDES_M[1:]),
               ("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.8)), None, "US", PAPER_ALTITUDES_M[1:]),
               ("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.8)), 3048.0, "US", PAPER_ALTITUDES_M[2:]),
               ("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.85), ("wing.gj", 1.04)), None, "US", PAPER_ALTITUDES_M[2:]))


def symmetric_bounds_more() -> str:
    """The class boundaries of the stiffness variants of ``gtm_paper`` (US p-k)."""
    import symmetric_mode

    rows = []
    for aircraft, factors, fixed, model, altitudes in MORE_BOUNDS:
        for h in altitudes:
            r = _bounds(aircraft, factors, fixed, model, h)
            if not (r["symmetric"] and r["antisymmetric"]):
                raise RuntimeError(f"symmetric-bounds-more: {aircraft} {factors} at {h:g} m: a class without a crossing")
            rows.append({**r, "config": _bounds_label(aircraft, factors, fixed)})
    return "\n" + _minus(symmetric_mode.bounds_table(rows).split("\n\n")[0]) + "\n"


def _bounds_rows(configs) -> list[dict]:
    """Rows of ``_bounds`` for (aircraft, factors, fixed density altitude, model, altitudes) configurations, each
    labelled as its config; a fixed rho(h*) at h* is the true-density row there (as ``symmetric_mode.py table``)."""
    rows = []
    for aircraft, factors, fixed, model, altitudes in configs:
        for h in altitudes:
            r = _bounds(aircraft, factors, None if fixed == h else fixed, model, h)
            if not (r["symmetric"] and r["antisymmetric"]):
                raise RuntimeError(f"{aircraft} {factors} rho({fixed}) at {h:g} m: a class without a crossing in the grid")
            rows.append({**r, "config": _bounds_label(aircraft, factors, fixed)})
    return rows


#: The structure whose critical mode is the symmetric one (docs/flutter.md, density section): three densities.
SYM_STRUCTURE = ("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.7)))
#: C5 of docs/calibration.md §6: every factor within its bound (C3's wing, fuselage EI x 1.75), four densities.
C5_STRUCTURE = ("gtm_paper", (("wing.ei", 0.85), ("wing.gj", 1.04), ("fuselage.ei", 1.75)))


def density_symmetric_structure() -> str:
    """Both class boundaries on the symmetric-mode structure with the true density, rho(3048 m) and rho(0)."""
    import symmetric_mode

    a, f = SYM_STRUCTURE
    rows = _bounds_rows(((a, f, None, "US", PAPER_ALTITUDES_M[1:]), (a, f, 3048.0, "US", PAPER_ALTITUDES_M),
                         (a, f, 0.0, "US", PAPER_ALTITUDES_M[1:])))
    return "\n" + _minus(symmetric_mode.bounds_table(rows)) + "\n"


def calibration_c5() -> str:
    """C5's class boundaries (US p-k) with the true density and the linearised aerodynamics at rho(3048 m),
    rho(1524 m) and rho(0)."""
    import symmetric_mode

    a, f = C5_STRUCTURE
    rows = _bounds_rows(((a, f, None, "US", PAPER_ALTITUDES_M[1:]), (a, f, 3048.0, "US", PAPER_ALTITUDES_M[2:]),
                         (a, f, 1524.0, "US", (3048.0, 9144.0)), (a, f, 0.0, "US", PAPER_ALTITUDES_M[1:])))
    return "\n" + _minus(symmetric_mode.bounds_table(rows)) + "\n"


def strip_drag(level) -> str:
    """Drag and L/D of the strips alone (parasite drag off) in the quasi-steady trim at the US level flutter points
    (``level("US")``, the docs tool's rows) at sea level and 9144 m."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions
    from flexsim.trim import SteadyManoeuvre, trim

    model = AircraftModel(load_aircraft("gtm"), aero=AeroOptions("quasi-steady", parasite_drag=False))
    parts = []
    for h in (0.0, 9144.0):
        p = trim(model, SteadyManoeuvre.level(h, mach=level("US")[h]["mach"]))
        parts.append(f"{p.drag_n / 1e3:.1f} kN (L/D {p.lift_n / p.drag_n:.0f}) at {h:g} m")
    return " and ".join(parts)


# --- docs/calibration.md ----------------------------------------------------------------------------------------

def calibration_static_paper() -> str:
    """The trim columns of Tables 2-3 at the paper's own flight conditions (``python studies/paper_residuals.py
    --mass-factor 0.907 --incidence 1.81 2.7 --formulation paper --trim-at-paper``, calibrated gtm structure)."""
    import paper_residuals
    from manoeuvre_decomposition import configure

    ac = configure("gtm", None, 0.907, (1.81, 2.7), None)
    return "\n" + _minus(paper_residuals.trims_at_paper(ac, "paper")) + "\n"


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
    from flexsim.linear.modes import in_vacuo_modes
    from flexsim.model.aircraft_model import AircraftModel

    factors = tomllib.loads((ROOT / "tools" / "gtm_calibration.toml").read_text(encoding="utf-8"))["scaling"]
    gtm = load_aircraft("gtm")
    sections = {c.name: c.sections for c in gtm.components}
    wing, fuselage = sections["right_wing"], sections["fuselage"]
    modes = in_vacuo_modes(AircraftModel(gtm, gravity_m_s2=0.0)).modes

    def freq(label: str) -> str:
        hits = [m.frequency_rad_s for m in modes if m.dominant_dof == label]
        if not hits:
            raise RuntimeError(f"calibration-structure: no in-vacuo mode {label!r}")
        return f"{hits[0]:.1f}"

    return (f"wing GJ × {factors['wing_gj']:.3f}, wing EI × {factors['wing_ei']:.3f}, fuselage EI × "
            f"{factors['fuselage_ei']:.2f}; wing root EI {wing.ei_nm2[0] / 1e9:.2f} GN m², GJ {wing.gj_nm2[0] / 1e9:.3f} GN m², "
            f"fuselage EI peak {max(fuselage.ei_nm2) / 1e9:.1f} GN m². In-vacuo frequencies (`flexsim modes`): wing "
            f"bending 1 {freq('wings bending 1 (symmetric)')} (sym.) and {freq('wings bending 1 (antisymmetric)')} "
            f"(antisym.), fuselage bending 1 {freq('fuselage bending 1')}, wing torsion 1 "
            f"{freq('wings torsion 1 (symmetric)')} (sym.) and {freq('wings torsion 1 (antisymmetric)')} (antisym.) rad/s")


def calibration_damping(level) -> str:
    """What the assumed 1 % structural damping does: the undamped quasi-steady model at M 0.15 (sea level) and the
    undamped US flutter points against ``level("US")`` (the docs tool's damped rows)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.linear.study import MODELS, StudyCase, run_study
    from flexsim.trim import SteadyManoeuvre

    _, spec = FlutterAnalysis(load_aircraft("gtm"), MODELS["QS"], structural_damping=0.0).evaluate(
        SteadyManoeuvre.level(0.0, mach=0.15))
    crit = spec.critical("elastic")
    us = level("US")
    undamped = run_study([StudyCase("gtm", "US", h, structural_damping=0.0) for h in PAPER_ALTITUDES_M], workers=2,
                         progress=False)
    same, other = [], []
    for h, r in zip(PAPER_ALTITUDES_M, undamped):
        if "error" in r:
            raise RuntimeError(f"calibration-damping: no undamped US flutter point at {h:g} m: {r['error']}")
        if r["mode"] == us[h]["mode"]:
            same.append(f"{_num(100 * (us[h]['mach'] / r['mach'] - 1), '+.1f')} % at {h:g} m")
        else:
            other.append(f"at {h:g} m the undamped structure flutters first in another mode (dominant {r['mode']}, "
                         f"M {r['mach']:.4f}, {r['omega_rad_s']:.1f} rad/s)")
    return (f"Without damping the quasi-steady model is unstable already at M 0.15 at sea level in {crit.dominant_dof} "
            f"({crit.frequency_rad_s:.0f} rad/s, Re λ = {_num(crit.eigenvalue.real, '+.2f')} s⁻¹); 1 % structural damping "
            f"moves the US flutter Mach by {', '.join(same)}" + (f"; {'; '.join(other)}" if other else ""))


def calibration_speeds(level) -> str:
    """The paper's flutter speeds and dynamic pressures (Table 3, derived) against the US ones of the bundled gtm
    (``level("US")``, the docs tool's rows)."""
    from flexsim.atmosphere import isa_density, speed_of_sound
    from flexsim.linear.paper_data import TABLE_US

    paper = {row[0]: row[1] for row in TABLE_US}
    v_paper = [paper[h] * float(speed_of_sound(h)) for h in PAPER_ALTITUDES_M]
    q_paper = [0.5 * float(isa_density(h)) * v * v / 1e3 for h, v in zip(PAPER_ALTITUDES_M, v_paper)]
    us = level("US")
    v_ours = [us[h]["mach"] * float(speed_of_sound(h)) for h in PAPER_ALTITUDES_M]
    return (f"{', '.join(f'{v:.0f}' for v in v_paper)} m/s at 0-9144 m (M_F(9144)/M_F(0) = "
            f"{paper[9144.0] / paper[0.0]:.3f}; {paper[9144.0] / paper[3048.0]:.3f} from 3048 to 9144 m), while the dynamic "
            f"pressure at flutter falls from {q_paper[0]:.1f} to {q_paper[-1]:.1f} kPa. On the notional aircraft the flutter "
            f"point follows the dynamic pressure more closely ({', '.join(f'{v:.0f}' for v in v_ours)} m/s, US)")


def goland_pk_fs() -> str:
    """Peters N = 6 against Theodorsen p-k on the Goland wing (1.225 kg/m^3, its file's incompressible strips)."""
    from docs_figures_static import _goland

    (u_t, _), (u_p, _) = _goland("theodorsen", "none"), _goland("unsteady", "none")
    return f"{100 * abs(u_p / u_t - 1):.1f} %"


def calibration_summary(level) -> str:
    """What the calibration meets, from the level-flight rows ``level(model)`` of the docs tool (US, FS, QS)."""
    from flexsim.linear.paper_data import TABLE_US

    us, fs, qs = level("US"), level("FS"), level("QS")
    paper = {row[0]: row for row in TABLE_US}
    dm = {h: 100 * (us[h]["mach"] / paper[h][1] - 1) for h in PAPER_ALTITUDES_M}
    dw = [100 * (us[h]["omega_rad_s"] / paper[h][2] - 1) for h in PAPER_ALTITUDES_M[1:]]
    met = [h for h in PAPER_ALTITUDES_M if abs(dm[h]) <= 3.0]
    missed = [h for h in PAPER_ALTITUDES_M if abs(dm[h]) > 3.0]
    pkfs = max(abs(fs[h]["mach"] / us[h]["mach"] - 1) for h in PAPER_ALTITUDES_M)

    def at(hs) -> str:
        return ", ".join(f"{_num(dm[h], '+.2f')} % at {h:g} m" for h in hs) or "none"

    def span(key: str, fmt: str) -> str:
        lo, hi = (_num(f([us[h][key] for h in PAPER_ALTITUDES_M]), fmt) for f in (min, max))
        return lo if lo == hi else f"{lo} to {hi}"

    return (f"US M_F within 3 %: {at(met)}; outside: {at(missed)}. US ω_F {_num(min(dw), '+.1f')} to "
            f"{_num(max(dw), '+.1f')} % at 3048-9144 m (target 10 %). p-k and finite state within {100 * pkfs:.1f} % in M_F at "
            f"all four altitudes. Trim at the US flutter points: θ {span('theta_deg', '.1f')}°, thrust "
            f"{span('thrust_kN', '.0f')} kN, elevator {span('elevator_deg', '+.1f')}°")


# --- docs/validation.md -----------------------------------------------------------------------------------------

def typical_section_kf() -> str:
    """Reduced flutter frequency of the Theodorsen typical section and Peters N = 6's change of U_F."""
    from flexsim.aero.typical_section import TypicalSection, flutter_analysis

    section = TypicalSection(a=-0.2, e=-0.1, mu=20.0, r2=0.24, sigma=0.4)  # docs/validation.md, the case's section
    t, p = flutter_analysis(section, "theodorsen"), flutter_analysis(section, "peters", 6)
    return (f"k_F = {t.flutter_frequency / t.flutter_speed:.4f}; Peters' N = 6 approximation changes U_F by "
            f"{_num(100 * (p.flutter_speed / t.flutter_speed - 1), '+.2f')} %")


@functools.cache
def _phugoid(altitude_m: float = 6000.0, mach: float = 0.6, **switches):
    from flexsim.sim.validation import phugoid_point

    return phugoid_point(altitude_m, mach, **switches)


def validation_phugoid() -> str:
    """The ``phugoid-lanchester`` case's aircraft with the body moments and tail downwash on, against Lanchester."""
    p = _phugoid(body_moments=True, downwash=True)
    return (f"With them (static margin {100 * p.static_margin:.1f} % at this point) the frequency is "
            f"{100 * (1 - p.omega_rad_s / p.lanchester_omega_rad_s):.1f} % and the damping "
            f"{100 * (1 - p.damping_ratio / p.lanchester_damping_ratio):.0f} % below Lanchester's ({p.omega_rad_s:.5f} rad/s, "
            f"ζ = {p.damping_ratio:.4f} against {p.lanchester_omega_rad_s:.5f}, {p.lanchester_damping_ratio:.4f})")


#: Flight points of the phugoid survey of docs/validation.md: altitudes [m] and Mach numbers.
PHUGOID_ALTITUDES_M = (0.0, 3000.0, 6000.0)
PHUGOID_MACHS = (0.4, 0.5, 0.6, 0.7)


def validation_phugoid_range() -> str:
    """The case's phugoid against Lanchester over sea level to 6000 m and M 0.4-0.7, and without parasite drag."""
    from flexsim.trim.solver import TrimError

    d_omega, d_zeta, skipped = [], [], {}
    for h in PHUGOID_ALTITUDES_M:
        for mach in PHUGOID_MACHS:
            try:
                p = _phugoid(h, mach)
            except TrimError as exc:  # beyond a trim limit: the limits it names, in the error's order
                named = [q for q in ("angle of attack", "thrust", "aileron", "elevator", "rudder") if q in str(exc)]
                skipped.setdefault(" and ".join(named) or "a limit", []).append(f"{h:g} m M {mach:g}")
                continue
            d_omega.append(100 * (p.omega_rad_s / p.lanchester_omega_rad_s - 1))
            d_zeta.append(100 * (p.damping_ratio / p.lanchester_damping_ratio - 1))
    bare = _phugoid(parasite_drag=False)
    skip = ("; beyond the trim limits: " + ", ".join(f"{' and '.join(cases)} ({why})" for why, cases in skipped.items())
            if skipped else "")
    return (f"the frequency is within {_num(max(d_omega), '+.1f')} % to {_num(min(d_omega), '+.1f')} % of it at "
            f"{', '.join(f'{h:g}' for h in PHUGOID_ALTITUDES_M)} m and M {PHUGOID_MACHS[0]:g}–{PHUGOID_MACHS[-1]:g} "
            f"({len(d_omega)} points{skip}), the damping within {_num(max(d_zeta), '+.0f')} % to "
            f"{_num(min(d_zeta), '+.0f')} % (the speed derivative of the pitching moment, which Lanchester neglects, takes the "
            f"rest). Without the parasite drag (the paper's aircraft, L/D = {bare.lift_to_drag:.1f} at 6000 m, M 0.6) the "
            f"damping ratio is {bare.damping_ratio / bare.lanchester_damping_ratio:.2f} of Lanchester's")


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


def validation_phugoid_case() -> str:
    """L/D and static margin of the ``phugoid-lanchester`` case's trim (6000 m, M 0.6, strips only)."""
    p = _phugoid()
    return f"L/D = {p.lift_to_drag:.1f}; neutral point {100 * p.static_margin:.0f} % of the mean chord behind the CG"




# --- docs/flutter.md: the decomposition at 9144 m ----------------------------------------------------------------

def _decomposition_switches() -> tuple[str, ...]:
    """The default switches of ``studies/manoeuvre_decomposition.py`` (every one a term or a linearisation point of
    today's model)."""
    import manoeuvre_decomposition as md

    return tuple(md.SWITCHES)


@functools.cache
def _decomposition_gtm() -> tuple[dict, ...]:
    """``python studies/manoeuvre_decomposition.py --altitude 9144`` on the bundled gtm (US p-k, true density)."""
    import manoeuvre_decomposition as md

    ac = md.configure("gtm", None, 1.0, None, None)
    return tuple(md.run(ac, "gtm", 9144.0, _decomposition_switches(), 3048.0, 0.91))


def decomposition_gtm() -> str:
    """The decomposition table of the bundled gtm at 9144 m (every switch) and its summary."""
    import manoeuvre_decomposition as md

    rows = {r["switch"]: r for r in _decomposition_gtm()}
    ref = rows["none"]
    small = [s for s in ("rotation", "static_deformation", "thrust", "gravity")
             if abs(rows[s]["turn_dM"] - ref["turn_dM"]) <= 1.5e-4]
    damp, dens = rows["damping"], rows["density"]
    climbs = [r["climb_dM"] for s, r in rows.items() if s != "damping"]
    return ("\n" + _minus(md.table(list(rows.values()))) + "\n\n"
            f"The turn effect is {_num(ref['turn_dM'], '+.4f')}; {', '.join(small)} each change it by 0.0001 or less. "
            f"Without structural damping (`damping`) the critical mode is another one, at {damp['w_level']:.1f} rad/s "
            f"(M {damp['M_level']:.4f}), and the turn row compares different modes. With the linearised aerodynamics at "
            f"ρ(3048 m) (`density`) flutter moves to M {dens['M_level']:.2f} and the turn effect becomes "
            f"{_num(dens['turn_dM'], '+.4f')} ({_num(100 * (dens['turn_dM'] / ref['turn_dM'] - 1), '+.0f')} %). "
            f"M_F(+15°) − M_F(−15°) stays between {_num(min(climbs), '+.5f')} and {_num(max(climbs), '+.5f')} in every "
            f"row but `damping` ({_num(damp['climb_dM'], '+.5f')}, another mode).\n")


#: The figures of this module: name -> (function, fast). ``regenerate_docs_figures.py`` registers them.
STUDY_FIGURES = {
    "density-paper": (density_paper, True),
    "symmetric-census": (symmetric_census, True),
    "calibration-static-paper": (calibration_static_paper, True),
    "typical-section-kf": (typical_section_kf, True),
    "validation-phugoid-case": (validation_phugoid_case, True),
    "validation-phugoid": (validation_phugoid, True),
    "validation-phugoid-range": (validation_phugoid_range, True),
    "goland-lift-slope-085": (goland_lift_slope_085, True),
    "calibration-structure": (calibration_structure, True),
    "calibration-uncalibrated": (calibration_uncalibrated, True),
    "goland-pk-fs": (goland_pk_fs, True),
    "density-fixed": (density_fixed, False),
    "decomposition-gtm": (decomposition_gtm, False),
    "symmetric-bounds-us": (symmetric_bounds_us, False),
    "symmetric-bounds-more": (symmetric_bounds_more, False),
    "density-symmetric-structure": (density_symmetric_structure, False),
    "calibration-c5": (calibration_c5, False),
}
