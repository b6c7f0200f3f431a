"""Regenerate the figures quoted in README.md and docs/*.md from the current code, or check them.

Each figure lives in a marked region of a document (HTML comments, invisible when rendered; inline or spanning
lines; one name may mark several regions): ``<!-- figures:NAME -->...<!-- /figures:NAME -->``. The script
recomputes each region's text (:data:`FIGURES`) and compares it with the document **at the precision printed**
(:func:`difference`): the text between the numbers must be equal, counts (integers) equal, and every other number
within one unit of its last printed digit (two correct roundings of values less than a unit apart differ by at most
one unit), or within the figure's ``rtol`` (adaptive integrators and searches, whose step or iteration sequence
round-off can move). A region that agrees is left alone; a stale one is rewritten (``--check``: named, exit 1).
Round-off residuals are never printed: a figure prints the bound it checks (``docs_figures_static.bound``). The
plain command also redraws ``docs/figures/flutter_turn*.png`` and ``flutter_climb*.png`` from the study run.

``fast`` figures (well under a minute together) are checked by the default test suite
(``tests/test_docs_figures.py``); the others (the turn and climb studies, the environments, the simulation
accuracy table: about 15 minutes on a quiet 2-core machine) under ``pytest -m slow``. From the repository root::

    python tools/regenerate_docs_figures.py                 # rewrite every stale region, redraw docs/figures
    python tools/regenerate_docs_figures.py --check         # exit 1 if a region is stale
    python tools/regenerate_docs_figures.py --check --fast  # the fast figures only
    python tools/regenerate_docs_figures.py --only readme-calibration
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import re
import sys
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_static import (_num, goland_compressible, goland_incompressible_102,  # noqa: E402
                                 options_bending_incidence, options_coordinated_turn, options_effects_flutter,
                                 options_glide, options_lift_drag, options_paper_turn,
                                 options_static_margin, options_which_bank, validation_table)
from docs_figures_studies import STUDY_FIGURES, calibration_speeds, calibration_summary, flutter_mode_frequencies  # noqa: E402
from docs_figures_usage import USAGE_FIGURES  # noqa: E402
from docs_figures_simulation import SIMULATION_FIGURES  # noqa: E402

REGION = re.compile(r"<!-- figures:(?P<name>[\w-]+) -->(?P<body>.*?)<!-- /figures:(?P=name) -->", re.DOTALL)
#: A number as the docs print it: a sign (ASCII or typographic minus), digits (thousands separated by commas),
#: decimals, an exponent. Not inside a word: the digits of ``DOP853``, ``C1``, ``v0`` are text.
NUMBER = re.compile(r"(?<![\w.])[+\-−]?(?:\d{1,3}(?:,\d{3})+(?!\d)|\d+)(?:\.\d+)?(?:[eE][+\-−]?\d+)?")
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FIGURE_DIR = ROOT / "docs" / "figures"
#: Altitudes of the study tables quoted in docs/flutter.md [m].
TABLE_ALTITUDES_M = (0.0, 9144.0)
#: Turn radii of the US turn table [m].
TABLE_RADII_M = (5000.0, 8000.0, 12000.0)
#: Brent tolerance in Mach of the tight climb search (the study's is 1e-4).
TIGHT_TOL = 1e-7


class Figure(NamedTuple):
    """A figure: the function computing its text; ``fast``: checked by the default test suite; ``study``: the study
    it reads ("turn", "climb": its plots are redrawn); ``rtol``: a tolerance beyond the printed precision."""

    compute: Callable[[], str]
    fast: bool = False
    study: str | None = None
    rtol: float = 0.0


def _value(number: str) -> tuple[float, float, str]:
    """A printed number's value, the unit of its last digit and its kind: "count", "fixed" or "e<exponent>"."""
    text = number.replace("−", "-").replace(",", "")
    mantissa, e, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    kind = f"e{int(exponent)}" if e else "fixed" if "." in mantissa else "count"
    return float(text), 10.0 ** (int(exponent or 0) - decimals), kind


def difference(old: str, new: str, rtol: float = 0.0) -> str | None:
    """How ``old`` differs from ``new`` at the printed precision (None: they agree): equal text and counts, other
    numbers within one unit of the coarser last digit (same exponent: ``1e-12`` is not ``1e-11``) or ``rtol``."""
    old_text, new_text = NUMBER.split(old), NUMBER.split(new)
    if old_text != new_text:
        a, b = next(((a, b) for a, b in zip(old_text, new_text) if a != b), (old_text[-1], new_text[-1]))
        return f"text {a.strip()[:60]!r} against {b.strip()[:60]!r}" if a != b else "a different count of numbers"
    for a, b in zip(NUMBER.findall(old), NUMBER.findall(new)):
        (x, unit_a, kind_a), (y, unit_b, kind_b) = _value(a), _value(b)
        scientific = kind_a.startswith("e") or kind_b.startswith("e")
        digits = kind_a == kind_b if scientific else "fixed" in (kind_a, kind_b)
        if abs(x - y) > max(max(unit_a, unit_b) * (1 + 1e-9) if digits else 0.0, rtol * max(abs(x), abs(y))):
            return f"{a} against {b}"
    return None


def _sci(x: float) -> str:
    """``x`` as ``−2.2e-5`` (one decimal, signed, short exponent), ``0`` for zero."""
    if x == 0.0:
        return "0"
    mantissa, exponent = f"{x:+.1e}".split("e")
    return f"{_num(float(mantissa), '+.1f')}e{int(exponent)}"


# --- shared computations (each runs at most once per process) -------------------------------------------------

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


def _level_us() -> dict[float, dict]:
    return _level("US")


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


def draw_study_figures(kinds) -> list[Path]:
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

def readme_calibration() -> str:
    """US M_F of the bundled gtm against paper Table 3, e.g. ``+0.1 %, +1.2 %, +11.6 % and +17.1 % at 0, ...``."""
    from flexsim.linear.paper_data import TABLE_US

    level = _level_us()
    altitudes = [row[0] for row in TABLE_US]
    diffs = [f"{100 * (level[h]['mach'] / ref[1] - 1):+.1f} %" for h, ref in zip(altitudes, TABLE_US)]
    return (f"US M_F {', '.join(diffs[:-1])} and {diffs[-1]} against the paper at "
            f"{', '.join(f'{h:g}' for h in altitudes[:-1])} and {altitudes[-1]:g} m")


def flutter_level_table() -> str:
    """Level flight against the paper's Tables 2-3: US (p-k) with its difference, FS, and QS, at 4 altitudes."""
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    us, fs, qs = _level("US"), _level("FS"), _level("QS")
    lines = ["", "| h [m] | paper US M_F / ω_F | flexsim US (p-k) | FS | paper QS | flexsim QS |", "|---|---|---|---|---|---|"]
    for pu, pq in zip(TABLE_US, TABLE_QS):
        h = pu[0]
        lines.append(f"| {h:g} | {pu[1]:.4f} / {pu[2]:.3f} | {us[h]['mach']:.4f} / {us[h]['omega_rad_s']:.2f} "
                     f"({100 * (us[h]['mach'] / pu[1] - 1):+.1f} %) | {fs[h]['mach']:.4f} | {pq[1]:.4f} / {pq[2]:.3f} | "
                     f"{qs[h]['mach']:.4f} / {qs[h]['omega_rad_s']:.2f} |")
    worst = max(abs(fs[h]["mach"] / us[h]["mach"] - 1) for h in us)
    modes = sorted({r["mode"] for r in (*us.values(), *fs.values())})
    return ("\n".join(lines) + f"\n\nTheodorsen p-k and finite state agree within {100 * worst:.1f} % in M_F "
            f"(acceptance: 2 %); dominant coordinate of the critical mode (US, FS): {', '.join(modes)}.\n")


def calibration_level_us() -> str:
    """docs/calibration.md §4: US and FS level flight with frequency, tip deflection and twist against Table 3."""
    from flexsim.linear.paper_data import TABLE_US

    us, fs = _level("US"), _level("FS")
    lines = ["", "| h [m] | paper US M_F | flexsim US (p-k) | ΔM | FS | paper ω_F | flexsim ω_F | Δω | tip w [m] ours / paper | "
             "twist [°] ours / paper |", "|---|---|---|---|---|---|---|---|---|---|"]
    for h, mach, omega, _, _, _, tip, twist in TABLE_US:
        r = us[h]
        lines.append(f"| {h:g} | {mach:.4f} | {r['mach']:.4f} | {100 * (r['mach'] / mach - 1):+.1f} % | {fs[h]['mach']:.4f} | "
                     f"{omega:.3f} | {r['omega_rad_s']:.2f} | {100 * (r['omega_rad_s'] / omega - 1):+.1f} % | "
                     f"{_num(r['tip_deflection_m'], '.3f')} / {_num(tip, '.4f')} | {r['tip_twist_deg']:.2f} / {twist:.4f} |")
    return "\n".join(lines) + "\n"


def calibration_level_qs() -> str:
    """docs/calibration.md §4: QS level flight against Table 2, with the critical mode."""
    from flexsim.linear.paper_data import TABLE_QS

    qs = _level("QS")
    lines = ["", "| h [m] | paper QS M_F / ω_F (Table 2) | flexsim QS | ΔM | critical mode (largest coordinate) |",
             "|---|---|---|---|---|"]
    for h, mach, omega, *_ in TABLE_QS:
        r = qs[h]
        lines.append(f"| {h:g} | {mach:.4f} / {omega:.3f} | {r['mach']:.4f} / {r['omega_rad_s']:.2f} | "
                     f"{_num(100 * (r['mach'] / mach - 1), '+.1f')} % | {r['mode']} |")
    return "\n".join(lines) + "\n"


def flutter_level() -> str:
    """US level-flight M_F / omega_F at the table altitudes: ``0.6858 / 36.744 (0 m), ...``."""
    level = _level_us()
    return ", ".join(f"{level[h]['mach']:.4f} / {level[h]['omega_rad_s']:.3f} ({h:g} m)" for h in TABLE_ALTITUDES_M)


def flutter_glide() -> str:
    """The direct glide trim at 9144 m (thrust zero, gamma unknown), US."""
    from flexsim.linear.study import StudyCase, run_study

    (row,) = run_study([StudyCase("gtm", "US", 9144.0, climb_angle_deg=None)], workers=1, progress=False)
    if "error" in row:
        raise RuntimeError(f"flutter-glide: no glide flutter point: {row['error']}")
    gamma = row["gamma_deg"]
    return (f"γ = {_num(gamma, '.3f')}° (L/D {1.0 / math.tan(math.radians(-gamma)):.1f}), "
            f"M_F = {row['mach']:.5f}, ω_F = {row['omega_rad_s']:.3f} rad/s")


def flutter_turn() -> str:
    """The markdown table of the US turn at the table altitudes and radii (the study's points)."""
    lines = ["", "| h [m] | R [km] | M_F | ω_F [rad/s] | φ [°] | θ [°] | T_e [kN] | δ_e [°] | tip w [m] | tip ψ [°] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for h in TABLE_ALTITUDES_M:
        for radius in TABLE_RADII_M:
            r = _turn(h, radius)
            lines.append(f"| {h:g} | {radius / 1e3:g} | {r['mach']:.4f} | {r['omega_rad_s']:.3f} | {r['phi_deg']:.1f} | "
                         f"{r['theta_deg']:.2f} | {r['thrust_kN']:.1f} | {_num(r['elevator_deg'], '+.2f')} | "
                         f"{_num(r['tip_deflection_m'], '.3f')} | {r['tip_twist_deg']:.2f} |")
    return "\n".join(lines) + "\n"


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


def flutter_turn_trend() -> str:
    """US M_F from R = 5 to 12 km at every altitude of the study, and whether a critical altitude exists."""
    pairs = {h: (_turn(h, 5000.0)["mach"], _turn(h, 12000.0)["mach"]) for h in _altitudes("turn")}
    text = _direction(pairs, "M_F", "R", "", 4) + ", R = 5 → 12 km"
    signs = {math.copysign(1.0, b - a) for a, b in pairs.values()}
    return text + ("; no critical altitude between these altitudes" if len(signs) == 1 else
                   "; the sign changes between these altitudes (a critical altitude)")


def flutter_turn_12km() -> str:
    """Largest |M_F(R = 12 km) / M_F(level) - 1| over the altitudes of the study."""
    level = _level_us()
    worst = max(abs(_turn(h, 12000.0)["mach"] / level[h]["mach"] - 1) for h in _altitudes("turn"))
    return f"within {100 * worst:.2f} %"


def flutter_climb() -> str:
    """The US climb at 9144 m from gamma = -15 to +15 deg: flutter point and trim."""
    a, b = _climb(9144.0, -15.0), _climb(9144.0, 15.0)
    allrows = [_climb(9144.0, g) for g in sorted({r["climb_angle_deg"] for r in _study("climb")})]
    twist = [r["tip_twist_deg"] for r in allrows]
    return (f"M_F = {a['mach']:.4f} → {b['mach']:.4f} and ω_F = {a['omega_rad_s']:.3f} → {b['omega_rad_s']:.3f} rad/s "
            f"from γ = −15° to +15°, θ {_num(a['theta_deg'], '.1f')} → {_num(b['theta_deg'], '.1f')}°, "
            f"T_e {_num(a['thrust_kN'], '+.0f')} → {_num(b['thrust_kN'], '+.0f')} kN, "
            f"δ_e {_num(a['elevator_deg'], '+.2f')} → {_num(b['elevator_deg'], '+.2f')}°, tip deflection "
            f"{_num(a['tip_deflection_m'], '.3f')} → {_num(b['tip_deflection_m'], '.3f')} m, twist "
            f"{min(twist):.2f}-{max(twist):.2f}°")


def flutter_climb_change() -> str:
    """US M_F(+15 deg) - M_F(-15 deg) of the study at the table altitudes."""
    return " and ".join(f"{_num(_climb(h, 15.0)['mach'] - _climb(h, -15.0)['mach'], '+.5f')} at {h:g} m"
                        for h in TABLE_ALTITUDES_M)


def flutter_climb_omega() -> str:
    """US omega_F from gamma = -15 to +15 deg at the table altitudes; the paper says it decreases."""
    pairs = {h: (_climb(h, -15.0)["omega_rad_s"], _climb(h, 15.0)["omega_rad_s"]) for h in reversed(TABLE_ALTITUDES_M)}
    mark = "✔" if all(b < a for a, b in pairs.values()) else "✘"
    return _direction(pairs, "ω_F", "γ", " rad/s", 4) + f" {mark}"


def flutter_glide_climb() -> str:
    """The glide interpolated where thrust is zero on the US climb curve at 9144 m."""
    from flexsim.linear.study import glide_from_climb

    glide = glide_from_climb(list(_study("climb")), "US", 9144.0)
    if glide is None:
        raise RuntimeError("flutter-glide-climb: the US climb curve at 9144 m has no thrust zero")
    angles = sorted({r["climb_angle_deg"] for r in _study("climb")})
    return (f"γ = {_num(glide['gamma_deg'], '.2f')}° (on the {len(angles)} angles {_num(angles[0], 'g')}..{angles[-1]:g}°) "
            f"with M_F {glide['mach']:.4f} and ω_F {glide['omega_rad_s']:.3f} rad/s")


def flutter_climb_tight() -> str:
    """Finite-state M_F(+15 deg) - M_F(-15 deg) with a Brent tolerance of 1e-7 in Mach, at the table altitudes."""
    from flexsim.linear.study import StudyCase
    from flexsim.trim import SteadyManoeuvre

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


def env_baselines() -> str:
    """The markdown table of baseline and random returns (seeds 0-9, full episodes, default settings)."""
    sys.path.insert(0, str(ROOT / "examples" / "agents"))
    from evaluate_baselines import evaluate

    from baselines import BASELINES

    lines = ["", "| id | baseline return | random return | random episodes end by |", "|---|---|---|---|"]
    for env_id in BASELINES:
        import gymnasium as gym

        limit = gym.spec(env_id).max_episode_steps
        result = evaluate(env_id, 10)
        base, rand = result["baseline"], result["random"]
        reasons = [r for r in rand["reasons"] if r]
        if not reasons:
            ending = "time limit"
        else:
            common = max(set(reasons), key=reasons.count)
            ending = f"{common.replace('_', ' ')} ({reasons.count(common)}/10), {rand['lengths'].mean():.0f} steps on average"
        label = env_id.removeprefix("FlexSim/GTM-").removesuffix("-v0")
        lines.append(f"| {label} (max {limit}) | {base['returns'].mean():.1f} +- {base['returns'].std():.1f} | "
                     f"{rand['returns'].mean():.1f} +- {rand['returns'].std():.1f} | {ending} |")
    return "\n".join(lines) + "\n"


FIGURES: dict[str, Figure] = {
    "readme-calibration": Figure(readme_calibration, fast=True),
    "flutter-level": Figure(flutter_level, fast=True),
    "flutter-level-table": Figure(flutter_level_table),
    "calibration-level-us": Figure(calibration_level_us),
    "calibration-level-qs": Figure(calibration_level_qs),
    "flutter-glide": Figure(flutter_glide, fast=True),
    "flutter-turn": Figure(flutter_turn, study="turn"),
    "flutter-turn-trend": Figure(flutter_turn_trend, study="turn"),
    "flutter-turn-12km": Figure(flutter_turn_12km, study="turn"),
    "flutter-climb": Figure(flutter_climb, study="climb"),
    "flutter-climb-change": Figure(flutter_climb_change, study="climb"),
    "flutter-climb-omega": Figure(flutter_climb_omega, study="climb"),
    "flutter-glide-climb": Figure(flutter_glide_climb, study="climb"),
    # a difference of two searches at TIGHT_TOL: 1e-7 in each M_F, 10 % of the smallest difference printed
    "flutter-climb-tight": Figure(flutter_climb_tight, rtol=0.1),
    "options-static-margin": Figure(options_static_margin, fast=True),
    "options-lift-drag": Figure(options_lift_drag, fast=True),
    "options-glide": Figure(options_glide, fast=True),
    "validation-table": Figure(validation_table, fast=True),
    "options-coordinated-turn": Figure(options_coordinated_turn, fast=True),
    "options-which-bank": Figure(options_which_bank, fast=True),
    "options-paper-turn": Figure(options_paper_turn, fast=True),
    "options-bending-incidence": Figure(options_bending_incidence, fast=True),
    "options-effects-flutter": Figure(options_effects_flutter, fast=True),
    "goland-compressible": Figure(goland_compressible, fast=True),
    "goland-incompressible-102": Figure(goland_incompressible_102, fast=True),
    # FlutterMargin-v0's episodes fly just past its flutter point: its baseline return is 989.3-989.7 on two builds
    "env-baselines": Figure(env_baselines, rtol=1e-3),
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in USAGE_FIGURES.items()},
    **{name: Figure(*spec) for name, spec in SIMULATION_FIGURES.items()},
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in STUDY_FIGURES.items()},
    "calibration-summary": Figure(lambda: calibration_summary(_level)),
    "flutter-mode-frequencies": Figure(lambda: flutter_mode_frequencies(_level), fast=True),
    "calibration-speeds": Figure(lambda: calibration_speeds(_level), fast=True),
}


def regions(text: str) -> list[re.Match]:
    """The marked regions of a document."""
    return list(REGION.finditer(text))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0], epilog="Figures: " + ", ".join(FIGURES))
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 if a region is stale")
    parser.add_argument("--only", action="append", choices=list(FIGURES), metavar="NAME",
                        help="regenerate this figure only (repeatable)")
    parser.add_argument("--fast", action="store_true",
                        help=f"only the fast figures ({', '.join(n for n, f in FIGURES.items() if f.fast)})")
    args = parser.parse_args(argv)
    wanted = [name for name in args.only or FIGURES if FIGURES[name].fast or not args.fast]
    values: dict[str, str] = {}
    stale = []
    for doc in DOCUMENTS:
        text = doc.read_text(encoding="utf-8")
        changed = {}
        for m in regions(text):
            name = m.group("name")
            if name not in wanted:
                continue
            if name not in values:
                print(f"computing {name} ...", flush=True)
                values[name] = FIGURES[name].compute()
            why = difference(m.group("body"), values[name], FIGURES[name].rtol)
            if why is not None:
                stale.append(f"{doc.relative_to(ROOT)}: {name} ({why})")
                changed[m.start()] = values[name]
        if changed and not args.check:
            doc.write_text(REGION.sub(lambda m: m.group(0) if m.start() not in changed else
                                      f"<!-- figures:{m.group('name')} -->{changed[m.start()]}<!-- /figures:{m.group('name')} -->",
                                      text), encoding="utf-8")
    missing = [name for name in wanted if name not in values]
    if missing:
        print(f"no region in the docs for: {', '.join(missing)}", file=sys.stderr)
        return 1
    studies = sorted({FIGURES[name].study for name in values} - {None})
    if not args.check and studies:
        for path in draw_study_figures(studies):
            print(f"drew {path.relative_to(ROOT)}")
    if stale:
        print(("stale: " if args.check else "rewritten: ") + "; ".join(stale))
        return 1 if args.check else 0
    print("all regions up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
