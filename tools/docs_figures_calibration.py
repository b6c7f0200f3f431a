"""Figures of docs/calibration.md, for ``regenerate_docs_figures.py`` (:data:`CALIBRATION_FIGURES`): §6-7 (issue
15 d: the paper-replication configurations C1-C4, their trend scorecards and the figures the text reads from them;
slow, about a CPU-minute together), §5 (the structure variants' altitude ratio; slow), §3 (the fits: the robust
one from its output file, fast; the first one's procedure rerun with today's code, long) and §1 (the quasi-steady
spectrum of the gtm.toml with the elastic axes at 0.625 c, today's code, long). The
numbers of the text come from the same checkpoints: ``docs_figures_calibration_text.py``.

The computations are the studies' own functions, imported from ``studies/`` (never copied):
``manoeuvre_decomposition.configure`` builds each configuration, ``paper_residuals.flutter_rows`` and
``paper_residuals.glide`` give every column of Tables 2-3 at its flutter points (``python
studies/paper_residuals.py ...``), ``manoeuvre_decomposition.run`` and ``scorecard`` the trend scorecards
(``python studies/manoeuvre_decomposition.py --switches none --mode-class symmetric ...`` and ``--scorecard``).
Every flutter point (one configuration, model and altitude) and every scorecard altitude is one checkpoint
(``docs_figures_core.checkpoint``), so an interrupted regeneration resumes.

Configurations (factors relative to the aircraft file; C1-C3 on ``gtm`` with every mass and inertia × 0.907, the
paper's 889.4 kN, and the stiffness factors × 0.907 too; C4 on ``gtm_paper``, which has that weight from the
centre tank): :data:`CONFIGS`.
"""

from __future__ import annotations

import functools
import os
import re
import sys
from pathlib import Path
from typing import NamedTuple

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_core import Figure, checkpoint  # noqa: E402
from docs_figures_studies import _minus  # noqa: E402

#: Altitudes of Tables 2-3 [m].
ALTITUDES_M = (0.0, 3048.0, 6096.0, 9144.0)


class Config(NamedTuple):
    """One study configuration: the arguments of ``paper_residuals.py`` / ``manoeuvre_decomposition.py``."""

    aircraft: str
    scaling: dict | None
    mass_factor: float
    incidence_deg: tuple[float, float] | None
    damping: float | None
    formulation: str
    fixed_density_alt_m: float | None

    def aircraft_model(self):
        from manoeuvre_decomposition import configure

        return configure(self.aircraft, self.scaling, self.mass_factor, self.incidence_deg, self.damping)

    def args(self) -> dict:
        return self._asdict()

    def command(self, script: str = "paper_residuals.py") -> str:
        import json

        parts = [f"python studies/{script}"]
        if self.aircraft != "gtm":
            parts.append(f"--aircraft {self.aircraft}")
        if self.scaling:
            parts.append(f"--scaling '{json.dumps(self.scaling, separators=(',', ':'))}'")
        if self.mass_factor != 1.0:
            parts.append(f"--mass-factor {self.mass_factor:g}")
        if self.incidence_deg:
            parts.append(f"--incidence {self.incidence_deg[0]:g} {self.incidence_deg[1]:g}")
        parts.append(f"--formulation {self.formulation}")
        if self.fixed_density_alt_m is not None:
            parts.append(f"--fixed-density {self.fixed_density_alt_m:g}")
        if self.damping is not None:
            parts.append(f"--damping {self.damping:g}")
        return " ".join(parts)


#: C1: the probe's best structure (fuselage EI × 1.75, wing GJ × 0.9, wing EI × 0.7), made frequency-equivalent at
#: the paper's weight (every factor × 0.907), the linearised aerodynamics at rho(3048 m).
_C1_SCALING = {"fuselage_ei": 1.587, "wing_gj": 0.816, "wing_ei": 0.635, "fuselage_gj": 0.907, "htail_stiffness": 0.907,
               "vtail_stiffness": 0.907}
_PAPER = {"mass_factor": 0.907, "incidence_deg": (1.81, 2.7), "damping": 0.01, "formulation": "paper"}
CONFIGS = {
    "C1": Config("gtm", _C1_SCALING, fixed_density_alt_m=3048.0, **_PAPER),
    # C2: C1's wing EI raised by 14 % towards the tip deflections.
    "C2": Config("gtm", {**_C1_SCALING, "wing_ei": 0.726}, fixed_density_alt_m=3048.0, **_PAPER),
    # C3: C1 with the wing EI and GJ of the static columns, the linearised aerodynamics at rho(0) and rho(3048 m).
    "C3": Config("gtm", {**_C1_SCALING, "wing_gj": 1.04, "wing_ei": 0.85}, fixed_density_alt_m=0.0, **_PAPER),
    "C3, ρ(3048 m)": Config("gtm", {**_C1_SCALING, "wing_gj": 1.04, "wing_ei": 0.85}, fixed_density_alt_m=3048.0,
                            **_PAPER),
    # C4: gtm_paper with fuselage EI x 2 (Fig. 4's peak) and wing EI x 0.7, zero-incidence chords, rho(3048 m).
    "C4": Config("gtm_paper", {"fuselage_ei": 2.0, "wing_ei": 0.7}, 1.0, (1.81, 2.7), None, "paper", 3048.0),
}
#: Starting Mach of the crossing searches (paper_residuals.py's default, C4's ``--starts-us``).
STARTS = {"C4": {"US": (0.76, 0.78, 0.80, 0.82)}}
#: The level search's start of the scorecards (manoeuvre_decomposition.py's ``--start`` default).
SCORECARD_START = 0.91


def _label(config: str) -> str:
    import json

    return json.dumps({"config": config, **CONFIGS[config].args()})


def flutter_row(config: str, model: str, altitude_m: float, mode_class: str = "any") -> dict | None:
    """Every column of Tables 2-3 at one flutter point of a configuration (``paper_residuals.flutter_rows``), or
    None where the search finds no crossing; one checkpoint."""
    import paper_residuals

    c = CONFIGS[config]
    start = STARTS.get(config, {}).get(model, (paper_residuals.DEFAULT_START,) * 4)[ALTITUDES_M.index(altitude_m)]
    args = {"config": c.args(), "model": model, "altitude_m": altitude_m, "start": start, "mode_class": mode_class}

    def compute():
        rows = paper_residuals.flutter_rows(c.aircraft_model(), _label(config), model, [altitude_m], [start],
                                            c.fixed_density_alt_m, c.formulation, mode_class)
        return rows[0] if rows else None

    return checkpoint("paper-residuals", args, compute)


def glide_gamma(config: str, mach: float) -> dict:
    """The glide of a configuration at 9144 m and ``mach`` (``paper_residuals.glide``); one checkpoint."""
    import paper_residuals

    c = CONFIGS[config]
    return checkpoint("paper-residuals-glide", {"config": c.args(), "altitude_m": 9144.0, "mach": mach},
                      lambda: paper_residuals.glide(c.aircraft_model(), c.formulation, 9144.0, mach))


def _cell(value: float, paper: float | None) -> str:
    text = f"{value:.4g}"
    return text if not paper else f"{text} ({100 * (value / paper - 1):+.1f} %)"


def _mode(row: dict) -> str:
    return f"{'sym' if row['sym_share'] > 0.5 else 'anti'}, q_f1 {row['qf1_ratio']:.2f}"


def config_table(pieces) -> str:
    """The markdown table of (config, model, mode class, altitudes) pieces: value (difference to the paper's
    Table 3 / Table 2 row) of every column, the critical mode's class and |q_f1| / largest."""
    cols = ("M_F", "omega_F", "theta_deg", "thrust_kN", "elevator_deg", "tip_deflection_m", "tip_twist_deg")
    lines = ["", "| config | model | h [m] | M_F | ω_F [rad/s] | θ [°] | T_e [kN] | δ_e [°] | w_tip [m] | ψ_tip [°] | "
             "mode, q_f1/largest |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for config, model, mode_class, altitudes in pieces:
        for h in altitudes:
            r = flutter_row(config, model, h, mode_class)
            label = model + (" sym-class" if mode_class == "symmetric" else "")
            if r is None:
                lines.append(f"| {config} | {label} | {h:.0f} | no crossing" + " |" * 8)
                continue
            cells = " | ".join(_cell(r[c], r.get("paper", {}).get(c)) for c in cols)
            lines.append(f"| {config} | {label} | {h:.0f} | {cells} | {_mode(r)} |")
    return _minus("\n".join(lines)) + "\n"


def commands(pieces) -> str:
    """The ``paper_residuals.py`` command of each piece (config, model, mode class, altitudes), as markdown lines."""
    import paper_residuals

    out = []
    for config, model, mode_class, altitudes in pieces:
        cmd = CONFIGS[config].command() + f" --models {model}"
        if altitudes != ALTITUDES_M:
            cmd += " --altitudes " + " ".join(f"{h:.0f}" for h in altitudes)
        starts = STARTS.get(config, {}).get(model)
        if starts:
            cmd += f" --starts-{model.lower()} " + " ".join(f"{m:g}" for m in starts)
        if mode_class != "any":
            cmd += f" --mode-class {mode_class}"
        if model == "US" and not starts and paper_residuals.DEFAULT_START != 0.72:
            raise RuntimeError("paper_residuals.DEFAULT_START changed: update the commands")
        out.append(f"* {config} {model}{' ' + mode_class + ' class' if mode_class != 'any' else ''}: `{cmd}`")
    return "\n".join(out)


def _config_region(pieces, glides) -> str:
    """Table, glides at the 9144 m flutter points of ``glides`` ((config, mode class) pairs) and commands."""
    text = config_table(pieces) + "\n"
    for config, mode_class in glides:
        r = flutter_row(config, "US", 9144.0, mode_class)
        g = glide_gamma(config, r["M_F"])
        text += (f"Glide of {config} at 9144 m, M {r['M_F']:.4f} (its US{' ' + mode_class + '-class' if mode_class != 'any' else ''} "
                 f"flutter point): γ {_minus(format(g['gamma_deg'], '.3f'))}° (α {g['alpha_deg']:.3f}°; paper −3.12°).\n")
    return text + "\nCommands (each prints these rows; the US ones the glide too):\n\n" + commands(pieces) + "\n"


def calibration_c1_c2() -> str:
    """C1 (US and QS at 0-9144 m, US symmetric class at 3048 and 9144 m) and C2 (US)."""
    return _config_region((("C1", "US", "any", ALTITUDES_M), ("C1", "QS", "any", ALTITUDES_M),
                           ("C1", "US", "symmetric", (3048.0, 9144.0)), ("C2", "US", "any", ALTITUDES_M)),
                          (("C1", "any"), ("C1", "symmetric")))


def calibration_c3() -> str:
    """C3 (US) at 3048 and 9144 m with the linearised aerodynamics at rho(0), and at 3048 m with rho(3048 m)."""
    return _config_region((("C3", "US", "any", (3048.0, 9144.0)), ("C3, ρ(3048 m)", "US", "any", (3048.0,))),
                          (("C3", "any"),))


def calibration_c4() -> str:
    """C4 (US) at 0-9144 m and its glide."""
    return _config_region((("C4", "US", "any", ALTITUDES_M),), (("C4", "any"),))


def scorecard_row(config: str, altitude_m: float) -> dict:
    """The ``none`` row of ``manoeuvre_decomposition.py --switches none --mode-class symmetric`` with the
    configuration's options at one altitude: level, R = 5 / 12 km and gamma = +-15 deg flutter points (symmetric
    class, US); one checkpoint."""
    import manoeuvre_decomposition

    c = CONFIGS[config]
    args = {"config": c.args(), "altitude_m": altitude_m, "start": SCORECARD_START, "mode_class": "symmetric",
            "cases": list(manoeuvre_decomposition.CASES)}

    def compute():
        (row,) = manoeuvre_decomposition.run(c.aircraft_model(), _label(config), altitude_m, ["none"], 3048.0,
                                             SCORECARD_START, tuple(manoeuvre_decomposition.CASES), None,
                                             c.fixed_density_alt_m, c.formulation, "symmetric")
        return row

    return checkpoint("calibration-scorecard", args, compute)


def _scorecard(config: str) -> str:
    import manoeuvre_decomposition

    rows = [scorecard_row(config, h) for h in ALTITUDES_M]
    text = manoeuvre_decomposition.scorecard(rows)
    effect = " / ".join(f"{r['turn_dM']:.4f}" for r in rows)
    grows = all(b["turn_dM"] > a["turn_dM"] for a, b in zip(rows[:-1], rows[1:]))
    return (_minus("\n" + text) + f".\n\nTurn effect M_F(5 km) − M_F(12 km) of {config}'s symmetric mode: "
            f"{_minus(effect)} at 0 / 3048 / 6096 / 9144 m ({'growing' if grows else 'not growing'} monotonically with "
            f"altitude).\n\nCommand: for h in 0 3048 6096 9144, `{CONFIGS[config].command('manoeuvre_decomposition.py')} "
            f"--altitude h --switches none --mode-class symmetric --json h.json`, then `python "
            f"studies/manoeuvre_decomposition.py --scorecard 0.json 3048.json 6096.json 9144.json`.\n")


def calibration_scorecard_c1() -> str:
    """C1's trend scorecard (symmetric mode)."""
    return _scorecard("C1")


def calibration_scorecard_c4() -> str:
    """C4's trend scorecard (symmetric mode)."""
    return _scorecard("C4")


def _diff(row: dict, key: str) -> float:
    """Relative difference [%] of a column to the paper's row (printed only, never used in the result)."""
    return 100 * (row[key] / row["paper"][key] - 1)


def _residuals(config: str, model: str, key: str = "M_F", altitudes=ALTITUDES_M) -> str:
    """``+5.9 / −1.6 / −1.0 / −1.4 %``: a column's differences to the paper at ``altitudes`` (critical mode)."""
    return _minus(" / ".join(f"{_diff(flutter_row(config, model, h), key):+.1f}" for h in altitudes)) + " %"


def _span(config: str, key: str, altitudes=ALTITUDES_M[1:]) -> str:
    """``+0.6 to +3.8 %``: the range of a column's US differences (critical mode) at ``altitudes``."""
    values = sorted(_diff(flutter_row(config, "US", h), key) for h in altitudes)
    return _minus(f"{values[0]:+.1f} to {values[-1]:+.1f} %")


#: The configurations take well under a minute each on a quiet 2-core machine (measured 04:20 UTC 2026-12-02 at
#: load 4-6: C1-C2 40 s wall / 18 s CPU, C3 18 / 6 s, C4 9 / 3 s, each scorecard 33-40 / 15 s), so they are slow
#: figures (``pytest -m slow``), not long ones. All of this module's slow figures together (with §5's variants):
#: 7 min 54 s wall, 2 min 50 s CPU at nice 19 and load 7, numba's recompilation after a kernel change included.
def calibration_c1_v2pg() -> str:
    """§6: V^2/sqrt(1-M^2) at C1's QS and US flutter points (the quantity one density keeps constant)."""
    qs = [flutter_row("C1", "QS", h)["V2PG_k"] for h in ALTITUDES_M]
    us = [flutter_row("C1", "US", h)["V2PG_k"] for h in ALTITUDES_M]
    return (f"≈ {sum(qs) / len(qs):.0f}k m²/s² on C1 against {sum(us) / len(us):.0f}k for the US model "
            f"({min(qs):.1f}-{max(qs):.1f}k and {min(us):.1f}-{max(us):.1f}k at 0-9144 m)")


def calibration_c5_trim() -> str:
    """§6: the trim at C5's symmetric US flutter point at 3048 m (true density), from the class-boundary row of
    ``calibration-c5`` (``docs_figures_studies._bounds``: ``symmetric_mode.py bounds``)."""
    from docs_figures_studies import C5_STRUCTURE, _bounds
    from flexsim.linear.paper_data import TABLE_US

    aircraft, factors = C5_STRUCTURE
    sym = _bounds(aircraft, factors, None, "US", 3048.0)["symmetric"]
    (paper,) = [row for row in TABLE_US if row[0] == 3048.0]
    return _minus(f"w_tip {sym['tip_deflection_m']:.4f} m, ψ_tip {sym['tip_twist_deg']:.3f}° (paper {paper[6]:.3f} m, "
                  f"{paper[7]:.3f}°)")


def calibration_c1_fuselage() -> str:
    """§6: C1's fuselage EI against the notional fuselage (factor 1) and its peak (C1's aircraft itself)."""
    import tomllib

    c1 = {c.name: c.sections for c in CONFIGS["C1"].aircraft_model().components}["fuselage"]
    gtm = tomllib.loads((ROOT / "tools" / "gtm_calibration.toml").read_text(encoding="utf-8"))["scaling"]["fuselage_ei"]
    return f"C1: {gtm * CONFIGS['C1'].scaling['fuselage_ei']:.2f}, peak {max(c1.ei_nm2) / 1e9:.1f} GN m²"


def calibration_c5_ratio_3048() -> str:
    """§6: C5's critical M_F(9144 m) / M_F(3048 m) with the linearised aerodynamics at rho(3048 m) (at 3048 m the
    true density), from ``calibration-c5``'s class-boundary rows."""
    from docs_figures_studies import C5_STRUCTURE, _bounds

    aircraft, factors = C5_STRUCTURE
    low, high = _bounds(aircraft, factors, None, "US", 3048.0), _bounds(aircraft, factors, 3048.0, "US", 9144.0)
    crit = [min(r["symmetric"]["M_F"], r["antisymmetric"]["M_F"]) for r in (low, high)]
    return f"{crit[1] / crit[0]:.3f}"


#: The paper's mode within the bounds (§6-7): gtm_paper with fuselage EI × 2 (Fig. 4's peak) and wing EI × 0.8 (the
#: static columns' value), the class-boundary rows of docs/flutter.md's ``symmetric-bounds-more``.
PAPER_MODE_STRUCTURE = ("gtm_paper", (("fuselage.ei", 2.0), ("wing.ei", 0.8)))


def _paper_mode(part: str) -> str:
    """One figure of the paper's-mode structure: ``lead`` (symmetric ahead by ... at 6096 and 9144 m, true density),
    ``omega``, ``anti3048`` (the antisymmetric lead at 3048 m), ``fixed`` (its lead with rho(3048 m) at 6096-9144 m),
    ``mach`` (the symmetric M_F against the paper's at 6096 / 9144 m)."""
    from docs_figures_studies import _bounds
    from flexsim.linear.paper_data import TABLE_US

    aircraft, factors = PAPER_MODE_STRUCTURE
    true = {h: _bounds(aircraft, factors, None, "US", h) for h in ALTITUDES_M[1:]}
    for h, r in true.items():
        if not (r["symmetric"] and r["antisymmetric"]):
            raise RuntimeError(f"paper's mode structure at {h:g} m: a class without a crossing")
    if part == "lead":
        return " and ".join(f"{-true[h]['gap_sym_minus_anti']:.4f}" for h in (6096.0, 9144.0))
    if part == "omega":
        return f"{sum(true[h]['symmetric']['omega_F'] for h in (6096.0, 9144.0)) / 2:.1f} rad/s"
    if part == "anti3048":
        return f"{true[3048.0]['gap_sym_minus_anti']:.4f}"
    if part == "mach":
        paper = {h: m for h, m, *_ in TABLE_US}
        return _minus(" / ".join(f"{100 * (true[h]['symmetric']['M_F'] / paper[h] - 1):+.1f}" for h in (6096.0, 9144.0))) + " %"
    fixed = [_bounds(aircraft, factors, 3048.0, "US", h)["gap_sym_minus_anti"] for h in (6096.0, 9144.0)]
    return f"{min(fixed):.4f}-{max(fixed):.4f}"


#: §5's variants of the notional structure (``gtm_uncalibrated`` with StructuralScaling factors, finite state, no
#: structural damping), rows of label and factor sets; the calibrated ``gtm`` (its damping) closes the table.
VARIANTS = (("wing GJ × 0.2 / 0.3 / 0.35", ({"wing_gj": 0.2}, {"wing_gj": 0.3}, {"wing_gj": 0.35})),
            ("GJ 0.3 with fuselage EI × 0.5 / × 2", ({"wing_gj": 0.3, "fuselage_ei": 0.5}, {"wing_gj": 0.3, "fuselage_ei": 2.0})),
            ("GJ 0.3 with wing EI × 0.5 / × 2", ({"wing_gj": 0.3, "wing_ei": 0.5}, {"wing_gj": 0.3, "wing_ei": 2.0})),
            ("GJ 0.3 with stabilizer stiffness × 0.5 / fuselage GJ × 0.5",
             ({"wing_gj": 0.3, "htail_stiffness": 0.5}, {"wing_gj": 0.3, "fuselage_gj": 0.5})),
            ("mass × 1.574 (option B, 157 t), GJ 0.40, EI 1.41, fuselage EI 1.15",
             ({"mass": 1.574, "wing_gj": 0.40, "wing_ei": 1.41, "fuselage_ei": 1.15},)))


#: The dominant coordinate "w" (body-axis vertical velocity) read as the mode's name.
HEAVE = "heave (w)"


def variant_point(factors: dict | None, altitude_m: float) -> dict:
    """``calibrate_gtm.flutter_point`` of ``gtm_uncalibrated`` × ``factors`` without structural damping (None: the
    calibrated ``gtm`` with its own); one checkpoint."""
    import calibrate_gtm

    def compute():
        from dataclasses import replace

        from flexsim.aircraft.calibration import StructuralScaling
        from flexsim.aircraft.toml_loader import load_aircraft

        if factors is None:
            return calibrate_gtm.flutter_point(load_aircraft("gtm"), altitude_m)
        ac = replace(StructuralScaling(**factors).apply(load_aircraft("gtm_uncalibrated")), structural_damping_ratio=0.0)
        return calibrate_gtm.flutter_point(ac, altitude_m)

    return checkpoint("calibration-variant", {"factors": factors, "altitude_m": altitude_m}, compute)


def calibration_variants() -> str:
    """§5: M_F at 0 / 9144 m, their ratio and the critical mode of each variant, against the paper's."""
    from flexsim.linear.paper_data import TABLE_US

    def cells(factor_sets):
        pts = [(variant_point(f, 0.0), variant_point(f, 9144.0)) for f in factor_sets]
        for f, (a, b) in zip(factor_sets, pts):
            if "error" in a or "error" in b:
                raise RuntimeError(f"calibration-variants: {f}: {a.get('error') or b.get('error')}")
        modes = []
        for a, b in pts:
            ma, mb = (HEAVE if m == "w" else m for m in (a["mode"], b["mode"]))
            m = ma if ma == mb else f"{ma} → {mb}"
            if m not in modes:
                modes.append(m)
        return (", ".join(f"{a['mach']:.3f} / {b['mach']:.3f}" for a, b in pts),
                ", ".join(f"{b['mach'] / a['mach']:.2f}" for a, b in pts), "; ".join(modes))

    lines = ["", "| variant (finite state, no structural damping) | M_F at 0 / 9144 m | ratio | critical mode (0 → 9144 m) |",
             "|---|---|---|---|"]
    ratios = []
    for label, factor_sets in VARIANTS:
        mach, ratio, mode = cells(factor_sets)
        ratios += [float(r) for r in ratio.split(", ")]
        lines.append(f"| {label} | {mach} | {ratio} | {mode} |")
    mach, ratio, mode = cells((None,))
    lines.append(f"| calibrated `gtm` (ζ = 0.01) | {mach} | {ratio} | {mode} |")
    paper = {h: m for h, m, *_ in TABLE_US}
    lines.append(f"| **paper** | {paper[0.0]:.3f} / {paper[9144.0]:.3f} | **{paper[9144.0] / paper[0.0]:.3f}** | |")
    return ("\n".join(lines) + f"\n\nThe ratio of the variants lies between {min(ratios):.2f} and {max(ratios):.2f} "
            f"(paper {paper[9144.0] / paper[0.0]:.3f}).\n")


# --- historical inputs (long figures: today's code on an input of an earlier commit) ------------------------------

#: The first calibration's procedure (df7ff6d: plain least squares, no structural damping) with today's code.
PLAIN_FIT_ARGV = ("studies/calibrate_gtm.py", "--damping", "0", "--loss", "linear")
#: The last commit with the research note's elastic-axis reading (0.25 b behind mid-chord, 0.625 c) in gtm.toml.
AFT_AXIS_COMMIT = "67cf98a"
#: The quasi-steady spectrum of that gtm (no structural damping, as then) in level flight: the most unstable
#: oscillatory elastic mode at each altitude and Mach.
AFT_AXIS_SNIPPET = """
import json
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import FlutterAnalysis
from flexsim.trim import SteadyManoeuvre
ac = load_aircraft("gtm")
ea = sorted({float(f) for c in ac.components if "wing" in c.name for f in c.sections.ea_fraction})
analysis = FlutterAnalysis(ac, "quasi-steady")
for h, mach in ((0.0, 0.3), (0.0, 0.45), (3048.0, 0.45), (6096.0, 0.45), (9144.0, 0.45)):
    _, spec = analysis.evaluate(SteadyManoeuvre.level(h, mach=mach))
    m = spec.critical("elastic")
    wing = max((w for w in spec.of_kind("elastic") if w.frequency_rad_s >= 0.5 and "wing" in w.dominant_dof),
               key=lambda w: w.eigenvalue.real)
    print(json.dumps({"altitude_m": h, "mach": mach, "real_1_s": m.eigenvalue.real, "omega_rad_s": m.frequency_rad_s,
                      "dof": m.dominant_dof, "wing_real_1_s": wing.eigenvalue.real,
                      "wing_omega_rad_s": wing.frequency_rad_s, "wing_dof": wing.dominant_dof, "wing_ea_fraction": ea}))
"""


def _fit_summary(text: str) -> tuple[dict[str, float], str]:
    """Factors and ``wing GJ × 0.399, ... (M_F ... %, ω_F ... %)`` of a ``calibrate_gtm.py --out`` file (the format
    of df7ff6d and of today's script)."""
    import json

    from flexsim.linear.paper_data import TABLE_US

    factors = {k: float(v) for k, v in re.findall(r"(?m)^(\w+) = ([\d.]+)$", text) if k != "structural_damping_ratio"}
    rows = [json.loads(line[2:]) for line in text.splitlines() if line.startswith("# {")]
    paper = {h: (m, w) for h, m, w, *_ in TABLE_US}
    dm = " / ".join(f"{100 * (r['mach'] / paper[r['altitude_m']][0] - 1):+.1f}" for r in rows)
    dw = [100 * (r["omega_rad_s"] / paper[r["altitude_m"]][1] - 1) for r in rows if r["altitude_m"] > 0]
    return factors, _minus(f"wing GJ × {factors['wing_gj']:.3f}, EI × {factors['wing_ei']:.3f}, fuselage EI × "
                           f"{factors['fuselage_ei']:.3f} (M_F {dm} % at 0-9144 m, ω_F {min(dw):+.1f} to {max(dw):+.1f} % "
                           f"at 3048-9144 m)")


def calibration_plain_fit() -> str:
    """§3: the first fit's procedure (df7ff6d: plain least squares, no structural damping) run with today's code:
    ``python studies/calibrate_gtm.py --damping 0 --loss linear --out fit.toml`` (about 40 evaluations of the four
    finite-state flutter points; 5-15 minutes on 2 idle cores). One checkpoint keyed by the source digest."""
    import json
    import os
    import subprocess
    import tempfile

    def compute() -> dict:
        with tempfile.TemporaryDirectory(prefix="flexsim-plain-fit-") as tmp:
            out = Path(tmp) / "fit.toml"
            env = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
            run = subprocess.run([sys.executable, *PLAIN_FIT_ARGV, "--out", str(out)], cwd=ROOT, env=env,
                                 capture_output=True, text=True, timeout=4 * 3600.0)
            if run.returncode != 0:
                raise RuntimeError(f"calibration-plain-fit: python {' '.join(PLAIN_FIT_ARGV)} failed "
                                   f"(exit {run.returncode}): {run.stderr.strip()[-2000:]}")
            return {"stdout": run.stdout, "fit": out.read_text(encoding="utf-8")}

    import calibrate_gtm
    from flexsim.linear.paper_data import TABLE_US

    out = checkpoint("calibration-plain-fit", {"argv": list(PLAIN_FIT_ARGV)}, compute)
    paper = {r[0]: r[2] for r in TABLE_US}
    rows = [json.loads(line[2:]) for line in out["fit"].splitlines() if line.startswith("# {")]
    worst = max(abs(r["omega_rad_s"] / paper[r["altitude_m"]] - 1) for r in rows
                if r["altitude_m"] > calibrate_gtm.FIT_FREQUENCY_ABOVE_M)
    tol = calibrate_gtm.TOL_FREQUENCY
    return (_fit_summary(out["fit"])[1] + f": the frequency target ({100 * tol:.0f} %) "
            + ("met" if worst <= tol else "missed"))


def calibration_robust_fit() -> str:
    """§3: the robust fit that made gtm.toml, from its output ``tools/gtm_calibration.toml`` (written by
    ``python studies/calibrate_gtm.py --out tools/gtm_calibration.toml`` at 2f53416; gtm.toml = gtm_uncalibrated ×
    its factors is tested in tests/aircraft/test_calibration.py). Not rerun: the file in the repository is that
    run's output, and a rerun at 2f53416 costs about 18 CPU-minutes (108 finite-state points of the numpy
    right-hand side, measured 2026-12-02)."""
    return _fit_summary((ROOT / "tools" / "gtm_calibration.toml").read_text(encoding="utf-8"))[1]


def _aft_axis_rows() -> list[dict]:
    """``AFT_AXIS_SNIPPET``'s rows on today's code with the aircraft file ``gtm.toml`` of ``AFT_AXIS_COMMIT`` (read
    from the repository's history with ``git show``: the data of that commit, not its code), checkpointed."""
    import json
    import subprocess
    import tempfile

    try:
        text = subprocess.run(["git", "-C", str(ROOT), "show", f"{AFT_AXIS_COMMIT}:flexsim/aircraft/data/gtm.toml"],
                              capture_output=True, text=True, timeout=60, check=True).stdout
    except (OSError, subprocess.SubprocessError) as exc:
        raise RuntimeError(f"calibration-aft-axis reads gtm.toml of {AFT_AXIS_COMMIT} from the git history, which this "
                           f"checkout lacks ({exc}); run the tool in a clone with full history, or --skip-long") from exc

    def compute() -> list[dict]:
        with tempfile.TemporaryDirectory(prefix="flexsim-aft-axis-") as tmp:
            path = Path(tmp) / "gtm.toml"
            path.write_text(text, encoding="utf-8")
            code = AFT_AXIS_SNIPPET.replace('load_aircraft("gtm")', f"load_aircraft({str(path)!r})")
            run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=3600,
                                 env={**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"})
            if run.returncode != 0:
                raise RuntimeError(f"calibration-aft-axis failed: {run.stderr.strip()[-2000:]}")
            return [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]

    return checkpoint("calibration-aft-axis", {"commit": AFT_AXIS_COMMIT, "file": text}, compute)


def calibration_aft_axis() -> str:
    """§1: the quasi-steady model with the elastic axis at 0.625 c (gtm.toml of 67cf98a, today's code)."""
    rows = _aft_axis_rows()
    ea = {f for r in rows for f in r["wing_ea_fraction"]}
    if ea != {0.625}:
        raise RuntimeError(f"calibration-aft-axis: gtm.toml at {AFT_AXIS_COMMIT} has the wing's elastic axis at {ea}")
    unstable = all(r["real_1_s"] > 0 for r in rows)
    low = min(r["mach"] for r in rows)
    names = {"wing": "the wing's", "htail": "the stabilizer's"}
    parts = []
    for key, name in names.items():  # "wing" is not in "left_htail ..."
        hits = [r for r in rows if key in r["dof"]]
        if hits:
            omegas = sorted({round(r["omega_rad_s"]) for r in hits})
            band = f"{omegas[0]}" + (f"-{omegas[-1]}" if len(omegas) > 1 else "")
            coords = sorted({r["dof"].split(" ", 1)[1] for r in hits})
            parts.append(f"{name} {' / '.join(coords)} ({band} rad/s) at "
                         + ", ".join(f"{r['altitude_m']:g} m M {r['mach']:g}" for r in hits))
    others = sorted({r["dof"] for r in rows if "wing" not in r["dof"] and "htail" not in r["dof"]})
    wing_unstable = [f"{r['altitude_m']:g}" for r in rows if r["wing_real_1_s"] > 0 and r["mach"] == 0.45]
    return (f"{'unstable' if unstable else 'not unstable everywhere'} already at M {low:g} at sea level and at M 0.45 at "
            f"all four altitudes (Re λ {_minus(format(min(r['real_1_s'] for r in rows), '+.2f'))} to "
            f"{_minus(format(max(r['real_1_s'] for r in rows), '+.2f'))} s⁻¹), most in " + "; ".join(parts)
            + (f"; {', '.join(others)}" if others else "")
            + f"; the wing's torsion alone is unstable at M 0.45 at {', '.join(wing_unstable) or 'no altitude'} m "
            f"(`gtm.toml` of {AFT_AXIS_COMMIT}, the last commit with that reading: wing and stabilizer axes at 0.625 c, "
            "the uncalibrated stiffness, no structural damping)")


CALIBRATION_FIGURES = {
    "calibration-c1-c2": Figure(calibration_c1_c2),
    "calibration-c3": Figure(calibration_c3),
    "calibration-c4": Figure(calibration_c4),
    "calibration-scorecard-c1": Figure(calibration_scorecard_c1),
    "calibration-scorecard-c4": Figure(calibration_scorecard_c4),
    # inline figures of §6's best-residual table and §7's targets (read from the same checkpoints)
    "calibration-c1-us-mach": Figure(lambda: _residuals("C1", "US")),
    "calibration-c1-qs-mach": Figure(lambda: _residuals("C1", "QS")),
    "calibration-c4-us-mach": Figure(lambda: _residuals("C4", "US")),
    "calibration-c1-elevator": Figure(lambda: _span("C1", "elevator_deg")),
    "calibration-c1-theta": Figure(lambda: _span("C1", "theta_deg")),
    "calibration-c1-v2pg": Figure(calibration_c1_v2pg),
    "calibration-c5-trim": Figure(calibration_c5_trim),
    **{f"calibration-paper-mode-{part}": Figure(functools.partial(_paper_mode, part))
       for part in ("lead", "omega", "anti3048", "fixed", "mach")},
    "calibration-c1-fuselage": Figure(calibration_c1_fuselage, fast=True),
    "calibration-c5-ratio-3048": Figure(calibration_c5_ratio_3048),
    "calibration-variants": Figure(calibration_variants),
    "calibration-plain-fit": Figure(calibration_plain_fit, long=True),
    "calibration-robust-fit": Figure(calibration_robust_fit, fast=True),
    "calibration-aft-axis": Figure(calibration_aft_axis, long=True),
}


for _gone in ("calibration-c5-trim", "calibration-c5-ratio-3048", "calibration-c1-elevator"):  # now cells of the
    del CALIBRATION_FIGURES[_gone]  # text figures' summaries (docs_figures_calibration_text.py)
