"""Regenerate the figures quoted in README.md and docs/*.md (or check them): one command for all of them.

Each quoted figure lives in a marked region of a document::

    <!-- figures:NAME -->...<!-- /figures:NAME -->

(HTML comments: invisible on rendered pages; regions may be inline, e.g. inside a table cell, or span lines; one
name may mark several regions, which then hold the same text). This script recomputes the text of every region
from the code and rewrites it, redraws the agents' learning curves from their runs' ``result.json``
(``docs_figures_envs.AGENT_CURVES``) and the study figures of ``docs/figures/`` (``flutter_turn*.png``,
``flutter_climb*.png``) from the same run; ``--check`` only compares the text and exits 1 naming every region that
differs (it draws nothing). ``tests/test_docs_figures.py`` checks that every region names a known figure, runs
``--check --fast`` in the default suite and the full ``--check`` under ``pytest -m slow``.

Figures (name: document, what; ``fast`` ones take well under a minute on a quiet 2-core machine, the rest share
one flutter study of 120 points, about 3-5 minutes, plus about a minute each for the m = n table and the tight
climb search, and about 4 minutes for the baselines table):

* ``readme-calibration`` (fast): README.md, US (Theodorsen p-k) flutter Mach of the bundled gtm against the
  paper's Table 3 at 0, 3048, 6096, 9144 m, as ``flexsim flutter --models US`` prints it;
* ``flutter-level`` (fast): docs/flutter.md, US level-flight M_F / omega_F at 0 and 9144 m;
* ``flutter-level-table``, ``calibration-level-us``, ``calibration-level-qs``: docs/flutter.md and
  docs/calibration.md §4, level flight US, FS, QS against the paper's Tables 2-3;
* ``flutter-glide`` (fast): docs/flutter.md, the direct glide trim at 9144 m (thrust zero, gamma unknown), US;
* ``flutter-turn``, ``flutter-turn-trend``, ``flutter-turn-omega``, ``flutter-turn-tight``, ``flutter-turn-12km``,
  ``turn-effect-us``: docs/flutter.md (and docs/calibration.md), the turn study (``flexsim sweep --turn``'s
  default: QS and US, 0-9144 m, R = 5-12 km) — US table, trends, tight-turn effect, R -> level flight;
* ``flutter-climb``, ``flutter-climb-change``, ``flutter-climb-omega``, ``flutter-climb-tip``,
  ``flutter-glide-climb``: docs/flutter.md, the climb study (``flexsim sweep --climb``'s default: gamma =
  -15..15 deg) at 9144 m and 0 m, and the glide interpolated on its US curve;
* ``flutter-climb-tight``: docs/flutter.md, the climb effect on M_F with a Brent tolerance of 1e-7 (finite state);
* ``convergence-mn``: docs/flutter.md, finite-state level flutter with m = n = 2, 3, 4 (copies of gtm.toml);
* ``options-static-margin``, ``options-lift-drag``, ``options-glide`` (fast): docs/options.md, the cruise trim at
  9144 m, M 0.78 (``flexsim trim gtm --json``) with the body options on and off: static margin, L/D, glide;
* ``validation-table`` (fast): docs/validation.md, every check of ``flexsim validate --json``;
* ``options-coordinated-turn``, ``options-which-bank``, ``options-paper-turn`` (fast): docs/options.md, the
  coordinated and the paper's turn at 9144 m, M 0.78, R = 5 km (``studies/coordinated_turn.py``'s trim);
* ``options-bending-incidence`` (fast): docs/options.md, static aeroelastic figures with the bending incidence
  off and on (``studies/options_effects.py --skip-flutter``);
* ``options-effects-flutter`` (fast): docs/flutter.md, sea-level finite-state flutter with each option beyond the paper switched
  (``studies/options_effects.py``'s cases; about 15 s);
* ``goland-compressible``, ``goland-incompressible-102`` (fast): docs/validation.md, docs/options.md,
  docs/design.md, the Goland wing with the Prandtl-Glauert factor on (1.225 kg/m^3) and off (1.02 kg/m^3);
* ``simulation-accuracy``: docs/simulation.md, the default integrator, the previous default and Radau against
  DOP853 (rtol 1e-9) on every named manoeuvre (``tools/docs_figures_simulation.py``, ``flexsim.sim.accuracy``;
  about 3-6 minutes);
* ``symmetric-bounds-fs``, ``symmetric-force-resolution``, ``symmetric-vary``, ``symmetric-vary-reading``,
  ``symmetric-bounds-reading``, ``symmetric-soft-torsion``, ``decomposition-reading``, ``decomposition-fin``,
  ``decomposition-c1``, ``decomposition-c4``, ``decomposition-c5``, ``decomposition-paper-mode``,
  ``options-body-moments-pk`` (long): docs/flutter.md's formerly recorded study output, the class boundaries of
  ``studies/symmetric_mode.py`` and the decompositions of ``studies/manoeuvre_decomposition.py``, every switch a
  term of the current model (``tools/docs_figures_records.py``; checkpointed per row and switch);
* ``design-lift-slope``, ``design-lift-slope-total`` (fast): docs/design.md, the strips' lift slope against the
  vortex lattice's on the exposed surfaces, and the whole lattice's (``tools/docs_figures_design.py``);
* ``flutter-study-evaluations`` (the turn and climb studies' evaluation counts, docs/flutter.md), ``options-margin-change``
  (fast, docs/flutter.md), ``design-cla-peak`` (fast), ``design-reliability-census`` (docs/design.md: the counts of
  ``studies/reliability_census.py aircraft|cli|logs --quick``, about 30 s of CPU);
* ``env-baselines``: docs/environments.md, the baseline and random returns of every environment over seeds 0-9
  (``examples/agents/evaluate_baselines.py --episodes 10``);
* ``calibration-c1-c2``, ``calibration-c3``, ``calibration-c4``, ``calibration-scorecard-c1``,
  ``calibration-scorecard-c4``: docs/calibration.md §6-7, the paper-replication configurations (every column of
  Tables 2-3, ``studies/paper_residuals.py``) and their trend scorecards (``studies/manoeuvre_decomposition.py``),
  ``tools/docs_figures_calibration.py`` (about a CPU-minute together, 2-8 minutes wall on a loaded machine;
  checkpointed), with the inline figures
  ``calibration-c1-us-mach``, ``calibration-c1-qs-mach``, ``calibration-c4-us-mach``, ``calibration-c1-elevator``,
  ``calibration-c1-theta``, ``calibration-c1-v2pg`` read from them, ``calibration-c5-trim`` (C5's symmetric trim at
  3048 m, from ``calibration-c5``'s study), ``calibration-paper-mode-lead``, ``-omega``, ``-anti3048``, ``-fixed``,
  ``-mach`` (the paper's mode within the bounds, from docs/flutter.md's ``symmetric-bounds-more`` rows), and
  ``calibration-c1-fuselage`` (fast), ``calibration-c5-ratio-3048``, and ``calibration-variants`` (§5: M_F(9144)/M_F(0) of the notional
  structure's variants, finite state);
* ``calibration-robust-fit`` (fast): docs/calibration.md §3, the fit that made gtm.toml, read from its output
  ``tools/gtm_calibration.toml``;
* long: ``calibration-plain-fit`` (docs/calibration.md §3: the first fit's procedure with today's code, ``python
  studies/calibrate_gtm.py --damping 0 --loss linear``, 14 minutes on 2 loaded cores), ``calibration-aft-axis`` (§1: the
  quasi-steady spectrum of the ``gtm.toml`` of 67cf98a, the elastic axis at 0.625 c, on today's code).

The trim, validation and Goland figures are computed in ``tools/docs_figures_static.py``; the figures of the
``studies/`` scripts quoted in docs/flutter.md, docs/calibration.md and docs/validation.md (density, class
boundaries, census, decomposition, calibration, phugoid) in ``tools/docs_figures_studies.py`` (its
``STUDY_FIGURES``; the slow ones take 2-8 min each); those of docs/options.md, docs/logs.md and docs/design.md in
``tools/docs_figures_usage.py`` and of docs/environments.md (agent runs from their ``docs/figures/agent_*_result.json``,
flutter tasks, baselines) in ``tools/docs_figures_envs.py`` (``USAGE_FIGURES``; the slow ones, which fly the envs,
take up to about a minute each). ``benchmarks/`` figures (docs/performance.md, speed tables) are dated, not
regenerated.

**Long studies** (``Figure(..., long=True)``, ``tools/docs_figures_core.py``): the figures that take 10 minutes
to an hour each (the recorded rows of docs/flutter.md and docs/calibration.md). The plain command regenerates them
with everything else (it is the one command); ``--skip-long`` leaves them out (and ``--fast`` never includes
them). They compute their points through ``docs_figures_core.checkpoint``: every finished piece (one
configuration at one altitude) is stored as JSON under ``~/.cache/flexsim/docs-figures`` (outside the
repository; ``FLEXSIM_DOCS_FIGURES_CACHE`` moves it), keyed by the piece's arguments and the SHA-256 of the
source of ``flexsim/`` and ``studies/``, so an interrupted run resumes where it stopped and a code change
recomputes. To register one: ``NAME: Figure(compute, long=True)`` in a module's figure dict, added to
``FIGURES`` below (``docs_figures_core``'s docstring has an example); slow figures may use the checkpoints
too. Tests: the default suite checks that every
region names a registered figure and that the checkpoints resume and key by content; ``pytest -m slow`` runs
``--check --skip-long`` (about 15 minutes); the long figures are checked by the plain command only.

Run from the repository root::

    python tools/regenerate_docs_figures.py                 # rewrite every region, redraw docs/figures
    python tools/regenerate_docs_figures.py --check         # exit 1 if a region is stale
    python tools/regenerate_docs_figures.py --check --fast  # the fast figures only
    python tools/regenerate_docs_figures.py --skip-long     # everything but the long studies
    python tools/regenerate_docs_figures.py --only readme-calibration
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import re
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_static import (_num, goland_compressible, goland_incompressible_102,  # noqa: E402
                                 options_bending_incidence, options_coordinated_turn, options_effects_flutter,
                                 options_glide, options_lift_drag, options_paper_turn, options_static_margin,
                                 options_which_bank, validation_table)
from docs_figures_studies import (STUDY_FIGURES, calibration_damping, calibration_speeds,  # noqa: E402
                                  calibration_summary, strip_drag)
from docs_figures_usage import USAGE_FIGURES  # noqa: E402
from docs_figures_simulation import SIMULATION_FIGURES  # noqa: E402
from docs_figures_design import DESIGN_FIGURES  # noqa: E402
from docs_figures_core import Figure  # noqa: E402
from docs_figures_calibration import CALIBRATION_FIGURES  # noqa: E402
from docs_figures_calibration_text import TEXT_FIGURES as CALIBRATION_TEXT_FIGURES  # noqa: E402
from docs_figures_records import RECORD_FIGURES, flutter_mode_frequencies, flutter_study_evaluations  # noqa: E402

REGION = re.compile(r"<!-- figures:(?P<name>[\w-]+) -->(?P<body>.*?)<!-- /figures:(?P=name) -->", re.DOTALL)
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
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


def flutter_turn_omega() -> str:
    """US omega_F from R = 5 to 12 km at the table altitudes."""
    pairs = {h: (_turn(h, 5000.0)["omega_rad_s"], _turn(h, 12000.0)["omega_rad_s"]) for h in TABLE_ALTITUDES_M}
    return _direction(pairs, "ω_F", "R", " rad/s", 3)


def flutter_turn_tight() -> str:
    """The tightest turn (R = 5 km) against level flight: its trim at 9144 m and its M_F change."""
    level = _level_us()
    r, lv = _turn(9144.0, 5000.0), level[9144.0]
    rise = " and ".join(f"{100 * (_turn(h, 5000.0)['mach'] / level[h]['mach'] - 1):+.2f} % ({h:g} m)"
                        for h in TABLE_ALTITUDES_M)
    return (f"bank {r['phi_deg']:.1f}°, tip deflection {_num(r['tip_deflection_m'], '.3f')} m against "
            f"{_num(lv['tip_deflection_m'], '.3f')} m, twist {r['tip_twist_deg']:.2f}° against {lv['tip_twist_deg']:.2f}° "
            f"at 9144 m) changes M_F by {rise} at R = 5 km against level flight")


def flutter_turn_12km() -> str:
    """Largest |M_F(R = 12 km) / M_F(level) - 1| over the altitudes of the study."""
    level = _level_us()
    worst = max(abs(_turn(h, 12000.0)["mach"] / level[h]["mach"] - 1) for h in _altitudes("turn"))
    return f"within {100 * worst:.2f} %"


def turn_effect_us() -> str:
    """US M_F(5 km) - M_F(12 km) at every altitude of the study, and whether it grows with altitude."""
    hs = _altitudes("turn")
    effect = [_turn(h, 5000.0)["mach"] - _turn(h, 12000.0)["mach"] for h in hs]
    grows = all(b > a for a, b in zip(effect[:-1], effect[1:]))
    return (f"{' / '.join(f'{e:.4f}' for e in effect)} at {' / '.join(f'{h:g}' for h in hs)} m, "
            f"{'growing' if grows else 'not growing'} monotonically with altitude")


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


def flutter_climb_tip() -> str:
    """Relative change of the US tip deflection from gamma = -15 to +15 deg at 9144 m."""
    a, b = _climb(9144.0, -15.0)["tip_deflection_m"], _climb(9144.0, 15.0)["tip_deflection_m"]
    return f"{100 * abs(b / a - 1):.0f} %"


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


def convergence_mn() -> str:
    """Finite-state level flutter with m = n = 2, 3, 4 bending and torsion modes per component (copies of gtm.toml)."""
    from flexsim.aircraft.toml_loader import load_aircraft, resolve_aircraft_path
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.linear.study import MODELS, StudyCase, run_case
    from flexsim.trim import SteadyManoeuvre

    source = resolve_aircraft_path("gtm").read_text(encoding="utf-8")
    res: dict[tuple[int, float], dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        def variant(n: int) -> str:
            path = Path(tmp) / f"gtm_m{n}.toml"
            text, count = re.subn(r"(?m)^(bending_modes|torsion_modes) = \d+", rf"\1 = {n}", source)
            if count == 0:
                raise RuntimeError("convergence-mn: no bending_modes/torsion_modes lines in gtm.toml")
            path.write_text(text, encoding="utf-8")
            return str(path)

        for n in (2, 3, 4):
            for h in TABLE_ALTITUDES_M:
                t0 = time.perf_counter()
                res[n, h] = run_case(StudyCase(variant(n), "FS", h))
                print(f"  m = n = {n}, {h:g} m: {time.perf_counter() - t0:.1f} s per flutter point", flush=True)
                if "error" in res[n, h]:
                    raise RuntimeError(f"convergence-mn: m = n = {n}, {h:g} m: {res[n, h]['error']}")
        undamped3 = run_case(StudyCase(variant(3), "FS", 0.0, structural_damping=0.0))
        low = 0.3
        analysis4 = FlutterAnalysis(load_aircraft(variant(4)), MODELS["FS"], structural_damping=0.0)
        _, spec = analysis4.evaluate(SteadyManoeuvre.level(0.0, mach=low))
        crit4 = spec.critical("elastic")
    lines = ["", "| m = n | sea level | 9144 m |", "|---|---|---|"]
    for n in (2, 3, 4):
        cells = []
        for h in TABLE_ALTITUDES_M:
            r = res[n, h]
            step = "" if n == 2 else f" ({_num(100 * (r['mach'] / res[n - 1, h]['mach'] - 1), '+.1f')} %)"
            cells.append(f"{r['mach']:.4f}{step}, {r['omega_rad_s']:.2f} rad/s")
        lines.append(f"| {n} | {' | '.join(cells)} |")
    modes = {r["mode"] for r in res.values()}
    over = " and ".join(f"{100 * (res[2, h]['mach'] / res[4, h]['mach'] - 1):.1f} % at {h:g} m" for h in TABLE_ALTITUDES_M)
    mode_text = (f"Same critical mode ({modes.pop()}) throughout" if len(modes) == 1 else
                 f"The critical mode changes ({', '.join(sorted(modes))})")
    undamped = (f"m = n = 3 gives {undamped3['mach']:.4f} at sea level" if "mach" in undamped3 else
                f"m = n = 3 has no flutter point at sea level ({undamped3['error']})")
    stable4 = crit4.eigenvalue.real <= 0.0
    m4 = (f"m = n = 4 is stable at M {low} at sea level" if stable4 else
          f"m = n = 4 is unstable already at M {low} at sea level in {crit4.dominant_dof} "
          f"({crit4.frequency_rad_s:.0f} rad/s)")
    inc = {h: [res[n, h]["mach"] - res[n - 1, h]["mach"] for n in (3, 4)] for h in TABLE_ALTITUDES_M}
    shrink = ("the increments shrink" if all(abs(b) < abs(a) for a, b in inc.values()) else
              "the increments do not shrink at every altitude")
    return ("\n".join(lines) + f"\n\n{mode_text}; {shrink}, and m = n = 2 overestimates M_F against m = n = 4 by {over}. "
            f"Without structural damping {m4}; {undamped}.\n")




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
    "flutter-turn-omega": Figure(flutter_turn_omega, study="turn"),
    "flutter-turn-tight": Figure(flutter_turn_tight, study="turn"),
    "flutter-turn-12km": Figure(flutter_turn_12km, study="turn"),
    "turn-effect-us": Figure(turn_effect_us, study="turn"),
    "flutter-climb": Figure(flutter_climb, study="climb"),
    "flutter-climb-change": Figure(flutter_climb_change, study="climb"),
    "flutter-climb-omega": Figure(flutter_climb_omega, study="climb"),
    "flutter-climb-tip": Figure(flutter_climb_tip, study="climb"),
    "flutter-glide-climb": Figure(flutter_glide_climb, study="climb"),
    "flutter-climb-tight": Figure(flutter_climb_tight),
    "convergence-mn": Figure(convergence_mn),
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
    "env-baselines": Figure(env_baselines),
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in USAGE_FIGURES.items()},
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in SIMULATION_FIGURES.items()},
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in DESIGN_FIGURES.items()},
    **{name: Figure(compute, fast=fast) for name, (compute, fast) in STUDY_FIGURES.items()},
    **CALIBRATION_FIGURES,
    **CALIBRATION_TEXT_FIGURES,
    **RECORD_FIGURES,
    "calibration-summary": Figure(lambda: calibration_summary(_level)),
    "calibration-damping": Figure(lambda: calibration_damping(_level)),
    "calibration-speeds": Figure(lambda: calibration_speeds(_level), fast=True),
    "flutter-strip-drag": Figure(lambda: strip_drag(_level), fast=True),
    "flutter-mode-frequencies": Figure(lambda: flutter_mode_frequencies(_level), fast=True),
    "flutter-study-evaluations": Figure(lambda: flutter_study_evaluations(_study)),
}


def regions(text: str) -> list[re.Match]:
    """The marked regions of a document."""
    return list(REGION.finditer(text))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     epilog="Figures: " + ", ".join(FIGURES))
    parser.add_argument("--check", action="store_true", help="compare only; exit 1 if a region is stale")
    parser.add_argument("--only", action="append", choices=list(FIGURES), metavar="NAME",
                        help=f"regenerate this figure only (repeatable; one of {', '.join(FIGURES)})")
    parser.add_argument("--fast", action="store_true",
                        help=f"only the fast figures ({', '.join(n for n, f in FIGURES.items() if f.fast)})")
    parser.add_argument("--skip-long", action="store_true",
                        help=f"leave out the long studies ({', '.join(n for n, f in FIGURES.items() if f.long) or 'none'})")
    args = parser.parse_args(argv)
    wanted = args.only or list(FIGURES)
    if args.fast:
        wanted = [name for name in wanted if FIGURES[name].fast]
    if args.skip_long:
        wanted = [name for name in wanted if not FIGURES[name].long]
    values: dict[str, str] = {}
    stale = []
    for doc in DOCUMENTS:
        text = doc.read_text(encoding="utf-8")
        found = [m for m in regions(text) if m.group("name") in wanted]
        for m in found:
            if m.group("name") not in values:
                print(f"computing {m.group('name')} ...", flush=True)
                values[m.group("name")] = FIGURES[m.group("name")].compute()
        new = REGION.sub(lambda m: m.group(0) if m.group("name") not in values else
                         f"<!-- figures:{m.group('name')} -->{values[m.group('name')]}<!-- /figures:{m.group('name')} -->", text)
        if new != text:
            stale += [f"{doc.relative_to(ROOT)}: {m.group('name')}" for m in found
                      if m.group("body") != values[m.group("name")]]
            if not args.check:
                doc.write_text(new, encoding="utf-8")
    missing = [name for name in wanted if name not in values]
    if missing:
        print(f"no region in the docs for: {', '.join(missing)}", file=sys.stderr)
        return 1
    studies = sorted({FIGURES[name].study for name in values} - {None})
    if not args.check and studies:
        for path in draw_study_figures(studies):
            print(f"drew {path.relative_to(ROOT)}")
    if not args.check and any(name.startswith("agent-") for name in values):
        from docs_figures_envs import draw_agent_curves

        for path in draw_agent_curves():
            print(f"drew {path.relative_to(ROOT)}")
    if stale:
        print(("stale: " if args.check else "rewritten: ") + "; ".join(stale))
        return 1 if args.check else 0
    print("all regions up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
