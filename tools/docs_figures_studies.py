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
                     f"{_join([x['V2PG_k'] for x in r], '.3g')} | {ratio[key]:.3f} |")
    paper_v2 = []
    from flexsim.atmosphere import speed_of_sound

    for h, m, *_ in TABLE_US:
        v = m * float(speed_of_sound(h))
        paper_v2.append(v * v / math.sqrt(1 - m * m) / 1e3)
    lines.append(f"| paper (Table 3) | {_join([p[1] for p in TABLE_US], '.4f')} | {_join([p[2] for p in TABLE_US], '.2f')} | "
                 f"{_join(paper_v2, '.3g')} | {TABLE_US[3][1] / TABLE_US[1][1]:.3f} |")
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


# --- docs/calibration.md ----------------------------------------------------------------------------------------

def calibration_static_paper() -> str:
    """The trim columns of Tables 2-3 at the paper's own flight conditions (``python studies/paper_residuals.py
    --mass-factor 0.907 --incidence 1.81 2.7 --formulation paper --trim-at-paper``, calibrated gtm structure)."""
    import paper_residuals
    from manoeuvre_decomposition import configure

    ac = configure("gtm", None, 0.907, (1.81, 2.7), None)
    return "\n" + _minus(paper_residuals.trims_at_paper(ac, "paper")) + "\n"


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

    d_omega, d_zeta, skipped = [], [], []
    for h in PHUGOID_ALTITUDES_M:
        for mach in PHUGOID_MACHS:
            try:
                p = _phugoid(h, mach)
            except TrimError:
                skipped.append(f"{h:g} m M {mach:g}")
                continue
            d_omega.append(100 * (p.omega_rad_s / p.lanchester_omega_rad_s - 1))
            d_zeta.append(100 * (p.damping_ratio / p.lanchester_damping_ratio - 1))
    bare = _phugoid(parasite_drag=False)
    skip = f"; {', '.join(skipped)} does not trim within the elevator's limits" if skipped else ""
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
}
