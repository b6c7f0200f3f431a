"""Figures of the flutter points of the bundled gtm in level flight, turns and climbs (docs/flutter.md,
docs/calibration.md, docs/replication.md, README.md): ``flexsim.linear.study`` runs them, each at most once per
process; the turn and climb figures read the default studies of ``flexsim sweep``, whose plots the docs tool redraws."""

from __future__ import annotations

import functools
import math
from pathlib import Path

from figure_text import ROOT, figure, num, table

FIGURE_DIR = ROOT / "docs" / "figures"
#: Altitudes of the study tables quoted in docs/flutter.md [m].
TABLE_ALTITUDES_M = (0.0, 9144.0)
#: Turn radii of the US turn table [m].
TABLE_RADII_M = (5000.0, 8000.0, 12000.0)
#: Brent tolerance in Mach of the tight climb search (the study's is 1e-4).
TIGHT_TOL = 1e-7


def _sci(x: float) -> str:
    """``x`` as ``−2.2e-5`` (one decimal, signed, short exponent), ``0`` for zero."""
    if x == 0.0:
        return "0"
    mantissa, exponent = f"{x:+.1e}".split("e")
    return f"{num(float(mantissa), '+.1f')}e{int(exponent)}"


@functools.cache
def _level(model: str) -> dict[float, dict]:
    """Level-flight flutter rows (``flexsim flutter --models MODEL``) of the bundled gtm at the paper's altitudes,
    keyed by altitude [m]."""
    from flexsim.linear.paper_data import TABLE_US
    from flexsim.linear.study import StudyCase, run_study

    altitudes = [row[0] for row in TABLE_US]
    rows = run_study([StudyCase("gtm", model, h) for h in altitudes], workers=2, progress=False)
    for row in rows:
        if "error" in row:
            raise RuntimeError(f"no {model} level flutter point at {row['altitude_m']:g} m: {row['error']}")
    return {row["altitude_m"]: row for row in rows}


@functools.cache
def _study(kind: str) -> tuple[dict, ...]:
    """The default ``flexsim sweep --turn`` / ``--climb`` study of the bundled gtm (QS and US, 4 altitudes)."""
    from flexsim.linear.study import climb_cases, run_study, turn_cases

    print(f"  running the {kind} study (the default of flexsim sweep --{kind}) ...", flush=True)
    cases = turn_cases("gtm") if kind == "turn" else climb_cases("gtm")
    rows = run_study(cases, workers=2, progress=True)
    bad = [r for r in rows if "error" in r]
    if bad:
        raise RuntimeError(f"{kind} study: {len(bad)} points without a flutter point, e.g. {bad[0]['error']}")
    return tuple(rows)


def _pick(rows, model: str, altitude_m: float, key: str, value: float) -> dict:
    (row,) = [r for r in rows if r["model"] == model and r["altitude_m"] == altitude_m and r[key] == value]
    return row


def _turn(h: float, radius_m: float, model: str = "US") -> dict:
    return _pick(_study("turn"), model, h, "turn_radius_m", radius_m)


def _climb(h: float, gamma_deg: float, model: str = "US") -> dict:
    return _pick(_study("climb"), model, h, "climb_angle_deg", gamma_deg)


def _altitudes(kind: str) -> list[float]:
    return sorted({r["altitude_m"] for r in _study(kind)})


def _draw_study_figures(kinds) -> list[Path]:
    """Redraw docs/figures/flutter_<kind>.png and its trim figure at the top altitude for each study kind."""
    from flexsim.linear.study import plot_study, plot_trim

    out = []
    for kind in kinds:
        rows = list(_study(kind))
        top = max(_altitudes(kind))
        out.append(plot_study(rows, kind, FIGURE_DIR / f"flutter_{kind}.png"))
        out.append(plot_trim(rows, kind, FIGURE_DIR / f"flutter_{kind}_trim_{top:.0f}m.png", altitude_m=top))
    return out


# --- the figures ----------------------------------------------------------------------------------------------

def _level_rows(*cells: str) -> list[list[str]]:
    """Rows of a level-flight table at the paper's altitudes: each cell a template of the fields below (``pm_``,
    ``pw_``: M_F, omega_F of Tables 3 and 2; ``dm_``, ``dw_``: flexsim's differences from them)."""
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    def diff(a: float, b: float) -> str:
        return f"{num(100 * (a / b - 1), '+.1f')} %"

    rows = []
    for (h, m_us, w_us, _, _, _, tip, twist), (_, m_qs, w_qs, *_) in zip(TABLE_US, TABLE_QS):
        us, fs, qs = (_level(model)[h] for model in ("US", "FS", "QS"))
        fields = {"h": f"{h:g}", "pm_us": f"{m_us:.4f}", "pw_us": f"{w_us:.3f}", "pm_qs": f"{m_qs:.4f}",
                  "pw_qs": f"{w_qs:.3f}", "us_m": f"{us['mach']:.4f}", "us_w": f"{us['omega_rad_s']:.2f}",
                  "qs_m": f"{qs['mach']:.4f}", "qs_w": f"{qs['omega_rad_s']:.2f}", "fs_m": f"{fs['mach']:.4f}",
                  "dm_us": diff(us["mach"], m_us), "dw_us": diff(us["omega_rad_s"], w_us), "dm_qs": diff(qs["mach"], m_qs),
                  "tip": f"{num(us['tip_deflection_m'], '.3f')} / {num(tip, '.4f')}",
                  "twist": f"{us['tip_twist_deg']:.2f} / {twist:.4f}", "mode": qs["mode"]}
        rows.append([cell.format(**fields) for cell in cells])
    return rows


def readme_calibration() -> str:
    """US M_F of the bundled gtm against paper Table 3, e.g. ``+0.1 %, +1.2 %, +11.6 % and +17.1 % at 0, ...``."""
    from flexsim.linear.paper_data import TABLE_US

    diffs = [f"{100 * (_level('US')[h]['mach'] / mach - 1):+.1f} %" for h, mach, *_ in TABLE_US]
    heights = [f"{row[0]:g}" for row in TABLE_US]
    return (f"US M_F {', '.join(diffs[:-1])} and {diffs[-1]} against the paper at {', '.join(heights[:-1])} and "
            f"{heights[-1]} m")


@figure(fast=False)
def flutter_level_table() -> str:
    """Level flight against the paper's Tables 2-3: US (p-k) with its difference, FS, and QS, at 4 altitudes."""
    us, fs = _level("US"), _level("FS")
    worst = max(abs(fs[h]["mach"] / us[h]["mach"] - 1) for h in us)
    modes = sorted({r["mode"] for r in (*us.values(), *fs.values())})
    return (table("| h [m] | paper US M_F / ω_F | flexsim US (p-k) | FS | paper QS | flexsim QS |",
                  _level_rows("{h}", "{pm_us} / {pw_us}", "{us_m} / {us_w} ({dm_us})", "{fs_m}", "{pm_qs} / {pw_qs}",
                              "{qs_m} / {qs_w}"))
            + f"\nTheodorsen p-k and finite state agree within {100 * worst:.1f} % in M_F "
            f"(acceptance: 2 %); dominant coordinate of the critical mode (US, FS): {', '.join(modes)}.\n")


@figure(fast=False)
def calibration_level_us() -> str:
    """docs/calibration.md §4: US and FS level flight with frequency, tip deflection and twist against Table 3."""
    return table("| h [m] | paper US M_F | flexsim US (p-k) | ΔM | FS | paper ω_F | flexsim ω_F | Δω | "
                 "tip w [m] ours / paper | twist [°] ours / paper |",
                 _level_rows("{h}", "{pm_us}", "{us_m}", "{dm_us}", "{fs_m}", "{pw_us}", "{us_w}", "{dw_us}", "{tip}", "{twist}"))


@figure(fast=False)
def calibration_level_qs() -> str:
    """docs/calibration.md §4: QS level flight against Table 2, with the critical mode."""
    return table("| h [m] | paper QS M_F / ω_F (Table 2) | flexsim QS | ΔM | critical mode (largest coordinate) |",
                 _level_rows("{h}", "{pm_qs} / {pw_qs}", "{qs_m} / {qs_w}", "{dm_qs}", "{mode}"))


def flutter_level() -> str:
    """US level-flight M_F / omega_F at the table altitudes: ``0.6858 / 36.744 (0 m), ...``."""
    level = _level("US")
    return ", ".join(f"{level[h]['mach']:.4f} / {level[h]['omega_rad_s']:.3f} ({h:g} m)" for h in TABLE_ALTITUDES_M)


def flutter_glide() -> str:
    """The direct glide trim at 9144 m (thrust zero, gamma unknown), US."""
    from flexsim.linear.study import StudyCase, run_study

    (row,) = run_study([StudyCase("gtm", "US", 9144.0, climb_angle_deg=None)], workers=1, progress=False)
    if "error" in row:
        raise RuntimeError(f"flutter-glide: no glide flutter point: {row['error']}")
    gamma = row["gamma_deg"]
    return (f"γ = {num(gamma, '.3f')}° (L/D {1.0 / math.tan(math.radians(-gamma)):.1f}), "
            f"M_F = {row['mach']:.5f}, ω_F = {row['omega_rad_s']:.3f} rad/s")


@figure(fast=False, study="turn")
def flutter_turn() -> str:
    """The markdown table of the US turn at the table altitudes and radii (the study's points)."""
    return table("| h [m] | R [km] | M_F | ω_F [rad/s] | φ [°] | θ [°] | T_e [kN] | δ_e [°] | tip w [m] | tip ψ [°] |",
                 [[f"{h:g}", f"{radius / 1e3:g}", f"{r['mach']:.4f}", f"{r['omega_rad_s']:.3f}", f"{r['phi_deg']:.1f}",
                   f"{r['theta_deg']:.2f}", f"{r['thrust_kN']:.1f}", num(r["elevator_deg"], "+.2f"),
                   num(r["tip_deflection_m"], ".3f"), f"{r['tip_twist_deg']:.2f}"]
                  for h in TABLE_ALTITUDES_M for radius in TABLE_RADII_M for r in [_turn(h, radius)]])


def _direction(pairs: dict[float, tuple[float, float]], quantity: str, variable: str, unit: str, digits: int) -> str:
    """``quantity decreases as variable increases at A and B (a → b at A, ...)``, grouped by sign."""
    groups: dict[str, list[float]] = {}
    for h, (a, b) in pairs.items():
        groups.setdefault("decreases" if b < a else "increases" if b > a else "does not change", []).append(h)
    parts = []
    for word, hs in groups.items():
        where = ", ".join(f"{h:g}" for h in hs[:-1]) + (" and " if len(hs) > 1 else "") + f"{hs[-1]:g} m"
        values = ", ".join(f"{pairs[h][0]:.{digits}f} → {pairs[h][1]:.{digits}f}{unit} at {h:g} m" for h in hs)
        parts.append(f"{quantity} {word} as {variable} increases at {where} ({values})")
    return "; ".join(parts)


@figure(fast=False, study="turn")
def flutter_turn_trend() -> str:
    """US M_F from R = 5 to 12 km at every altitude of the study, and whether a critical altitude exists."""
    pairs = {h: (_turn(h, 5000.0)["mach"], _turn(h, 12000.0)["mach"]) for h in _altitudes("turn")}
    text = _direction(pairs, "M_F", "R", "", 4) + ", R = 5 → 12 km"
    signs = {math.copysign(1.0, b - a) for a, b in pairs.values()}
    return text + ("; no critical altitude between these altitudes" if len(signs) == 1 else
                   "; the sign changes between these altitudes (a critical altitude)")


@figure(fast=False, study="turn")
def flutter_turn_12km() -> str:
    """Largest |M_F(R = 12 km) / M_F(level) - 1| of the US turn study over its altitudes."""
    level = _level("US")
    worst = max(abs(_turn(h, 12000.0)["mach"] / level[h]["mach"] - 1) for h in _altitudes("turn"))
    return f"within {100 * worst:.2f} %"


@figure(fast=False, study="climb")
def flutter_climb() -> str:
    """The US climb at 9144 m from gamma = -15 to +15 deg: flutter point and trim."""
    a, b = _climb(9144.0, -15.0), _climb(9144.0, 15.0)
    allrows = [_climb(9144.0, g) for g in sorted({r["climb_angle_deg"] for r in _study("climb")})]
    twist = [r["tip_twist_deg"] for r in allrows]
    return (f"M_F = {a['mach']:.4f} → {b['mach']:.4f} and ω_F = {a['omega_rad_s']:.3f} → {b['omega_rad_s']:.3f} rad/s "
            f"from γ = −15° to +15°, θ {num(a['theta_deg'], '.1f')} → {num(b['theta_deg'], '.1f')}°, "
            f"T_e {num(a['thrust_kN'], '+.0f')} → {num(b['thrust_kN'], '+.0f')} kN, "
            f"δ_e {num(a['elevator_deg'], '+.2f')} → {num(b['elevator_deg'], '+.2f')}°, tip deflection "
            f"{num(a['tip_deflection_m'], '.3f')} → {num(b['tip_deflection_m'], '.3f')} m, twist "
            f"{min(twist):.2f}-{max(twist):.2f}°")


@figure(fast=False, study="climb")
def flutter_climb_change() -> str:
    """US M_F(+15 deg) - M_F(-15 deg) of the study at the table altitudes."""
    return " and ".join(f"{num(_climb(h, 15.0)['mach'] - _climb(h, -15.0)['mach'], '+.5f')} at {h:g} m"
                        for h in TABLE_ALTITUDES_M)


@figure(fast=False, study="climb")
def flutter_climb_omega() -> str:
    """US omega_F from gamma = -15 to +15 deg at the table altitudes; the paper says it decreases."""
    pairs = {h: (_climb(h, -15.0)["omega_rad_s"], _climb(h, 15.0)["omega_rad_s"]) for h in reversed(TABLE_ALTITUDES_M)}
    mark = "✔" if all(b < a for a, b in pairs.values()) else "✘"
    return _direction(pairs, "ω_F", "γ", " rad/s", 4) + f" {mark}"


@figure(fast=False, study="climb")
def flutter_glide_climb() -> str:
    """The glide interpolated where thrust is zero on the US climb curve at 9144 m."""
    from flexsim.linear.study import glide_from_climb

    glide = glide_from_climb(list(_study("climb")), "US", 9144.0)
    if glide is None:
        raise RuntimeError("flutter-glide-climb: the US climb curve at 9144 m has no thrust zero")
    angles = sorted({r["climb_angle_deg"] for r in _study("climb")})
    return (f"γ = {num(glide['gamma_deg'], '.2f')}° (on the {len(angles)} angles {num(angles[0], 'g')}..{angles[-1]:g}°) "
            f"with M_F {glide['mach']:.4f} and ω_F {glide['omega_rad_s']:.3f} rad/s")


# a difference of two searches at TIGHT_TOL: 1e-7 in each M_F, 10 % of the smallest difference printed
@figure(fast=False, rtol=0.1)
def flutter_climb_tight() -> str:
    """Finite-state M_F(+15 deg) - M_F(-15 deg) with a Brent tolerance of 1e-7 in Mach, at the table altitudes."""
    from flexsim.linear.study import StudyCase
    from flexsim.trimming import SteadyManoeuvre

    parts = []
    for h in TABLE_ALTITUDES_M:
        analysis = StudyCase("gtm", "FS", h).analysis()
        start = SteadyManoeuvre.level(h, mach=0.5)
        mach, guess = {}, None
        for gamma in (-15.0, 15.0):
            man = SteadyManoeuvre(start.speed_m_s, h, math.inf, math.radians(gamma))
            mach[gamma] = analysis.search(man, mach_range=(0.5, 0.95), tol=TIGHT_TOL, mach_guess=guess).mach
            guess = mach[gamma]
        parts.append(f"{_sci(mach[15.0] - mach[-15.0])} at {h:g} m")
    return " and ".join(parts)


