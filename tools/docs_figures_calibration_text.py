"""The numbers of docs/calibration.md's text (every figure quoted is generated), for
``regenerate_docs_figures.py`` (:data:`TEXT_FIGURES`): checks on the paper's own data (§1, §4, §6), readings of the
static table at the paper's flight conditions, of C3-C5 and of the scorecards (§6-7), and the best-residual table
(§6). Each is computed from the same checkpoints as the tables it reads (``docs_figures_calibration``), never typed.
"""

from __future__ import annotations

import functools
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_calibration import (ALTITUDES_M, _diff, _minus, _mode, _paper_mode, _residuals,  # noqa: E402
                                      calibration_c5_trim, flutter_row, glide_gamma, scorecard_row)
from docs_figures_core import Figure  # noqa: E402


# ---: every number of the page generated; read from the checkpoints above) ----------

def _span_of(values, fmt: str = ".1f", unit: str = "", signed: bool = False) -> str:
    """``a-b`` (or ``a`` when equal) of the rounded values, with ``unit``."""
    lo, hi = (format(v, ("+" if signed else "") + fmt) for v in (min(values), max(values)))
    sep = " to " if signed else "-"
    return _minus(lo if lo == hi else f"{lo}{sep}{hi}") + unit


def calibration_paper_qs_us() -> str:
    """§1: the paper's QS flutter Mach (Table 2) against its US one (Table 3), altitude by altitude (the paper's data
    only: ``flexsim.linear.paper_data``)."""
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    diff = [(us[0], 100 * (qs[1] / us[1] - 1)) for qs, us in zip(TABLE_QS, TABLE_US)]
    near = [(h, d) for h, d in diff if abs(d) <= 2.0]
    far = [(h, d) for h, d in diff if abs(d) > 2.0]
    text = (f"within {max(abs(d) for _, d in near):.1f} % of the US ones at {' and '.join(f'{h:g}' for h, _ in near)} m"
            if near else "more than 2 % from the US ones at every altitude")
    if far:
        text += (f"; {' and '.join(format(d, '+.1f') + ' %' for _, d in far)} at "
                 f"{' and '.join(f'{h:g}' for h, _ in far)} m")
    return _minus(text)


def calibration_paper_thrust() -> str:
    """§4: the paper's thrust column against T_e = W sin θ (one W for all eight rows of Tables 2-3) and against an
    induced drag ∝ 1/q (T_e q constant); the paper's data and the ISA only."""
    import math

    from flexsim.atmosphere import isa
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    rows = [*TABLE_QS, *TABLE_US]
    weights = [r[4] / math.sin(math.radians(r[3])) for r in rows]  # [kN]
    w = sum(weights) / len(weights)
    dev = max(abs(x / w - 1) for x in weights) * 100
    tq = []
    for r in rows:
        atm = isa(r[0])
        q = 0.5 * atm.density * (r[1] * atm.speed_of_sound) ** 2
        tq.append(r[4] * q)
    mean_tq = 0.5 * (max(tq) + min(tq))
    spread = 100 * (max(tq) - min(tq)) / 2 / mean_tq
    return (f"T_e = {w:.1f} kN × sin θ in all {len(rows)} rows of Tables 2-3 (to {dev:.3f} %; an induced drag growing as "
            f"1/q would keep T_e·q constant, which varies by ±{spread:.0f} %): its aerodynamic resultant has no body-x "
            f"component and its aircraft weighs {w:.1f} kN ({w / 9.80665:.1f} t)")


def calibration_lift_slopes() -> str:
    """§6: the incompressible strip lift slopes of the bundled gtm (its vortex lattice, ``flexsim.aero.lift_slopes``)
    on the wing and the horizontal stabilizer."""
    import numpy as np

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel

    strips = AircraftModel(load_aircraft("gtm")).aero.strips
    comp = np.array(strips.component)
    parts = []
    for label, key in (("wing", "wing"), ("stabilizer", "htail")):
        s = strips.lift_slope0[np.char.find(comp.astype(str), key) >= 0]
        if s.size == 0:
            raise RuntimeError(f"calibration-lift-slopes: no {key} strips")
        parts.append(f"{label} {s.min():.1f}-{s.max():.1f}")
    return ", ".join(parts) + " per radian"


@functools.cache
def _static_paper_rows() -> list[dict]:
    """The rows of ``calibration-static-paper`` (``paper_residuals.trims_at_paper`` at the paper's own flight
    conditions, calibrated gtm structure): ``{"table", "h", col: (value, paper, diff %)}``."""
    from docs_figures_studies import calibration_static_paper

    cols = ("theta", "thrust", "elevator", "w_tip", "psi_tip")
    num = r"([−+-]?[\d.]+)"
    cell = re.compile(num + r" / " + num + r" \(" + num + r" %\)")
    out = []
    for line in calibration_static_paper().replace("−", "-").splitlines():
        parts = [p.strip() for p in line.strip().strip("|").split("|")]
        if len(parts) != 8 or parts[0] not in ("US", "QS"):
            continue
        row = {"table": parts[0], "h": float(parts[1])}
        for name, text in zip(cols, parts[3:]):
            m = cell.fullmatch(text)
            if not m:
                raise RuntimeError(f"calibration-static-paper: cannot read {text!r}")
            row[name] = tuple(float(g) for g in m.groups())
        out.append(row)
    if len(out) != 8:
        raise RuntimeError(f"calibration-static-paper: {len(out)} rows, expected 8")
    return out


def _static_fit() -> tuple[float, float]:
    """θ_flexsim = a θ_paper + b through the US rows at 3048 and 9144 m of the static table."""
    pts = {r["h"]: r["theta"][:2] for r in _static_paper_rows() if r["table"] == "US" and r["h"] in (3048.0, 9144.0)}
    (t1, p1), (t2, p2) = pts[3048.0], pts[9144.0]
    a = (t2 - t1) / (p2 - p1)
    return a, t1 - a * p1


def calibration_static_theta() -> str:
    """§6-7: the range of θ's (and T_e's) excess at the paper's own flight conditions (every row of the table)."""
    d = [r[c][2] for r in _static_paper_rows() for c in ("theta", "thrust")]
    return _minus(f"{min(d):+.0f} to {max(d):+.0f} %")


def calibration_static_fit() -> str:
    """§7: the lift slope and offset read from θ at the paper's conditions."""
    a, b = _static_fit()
    return _minus(f"lift slope {100 * (1 / a - 1):+.0f} % and a {b:.2f}° offset")


def calibration_static_tips() -> str:
    """§6: the calibrated wing's tip deflection and twist at the paper's conditions (US, 3048 and 9144 m)."""
    rows = {r["h"]: r for r in _static_paper_rows() if r["table"] == "US"}
    twist = [rows[h]["psi_tip"][2] for h in (3048.0, 9144.0)]
    return _minus(f"w_tip {rows[3048.0]['w_tip'][2]:+.0f} % / {rows[9144.0]['w_tip'][2]:+.0f} % (3048 / 9144 m, too "
                  f"stiff in bending) and ψ_tip {_span_of(twist, '.0f', ' %', signed=True)}")


def calibration_static_summary() -> str:
    """§6: what the static table shows (elevator, twist, θ, tip deflection; θ's linear fit)."""
    rows = _static_paper_rows()
    el = max(abs(r["elevator"][2]) for r in rows)
    tw = max(abs(r["psi_tip"][2]) for r in rows)
    w = [abs(r["w_tip"][2]) for r in rows]
    a, b = _static_fit()
    return (f"the elevator (within {el:.1f} %) and the tip twist (within {tw:.1f} %) agree in every row; θ (and with it "
            f"T_e) stays {calibration_static_theta().replace(' to ', ' … ')} high — a lift-curve slope about "
            f"{100 * (1 - 1 / a):.0f} % below the paper's plus a {b:.2f}° offset (θ_flexsim ≈ {a:.2f} θ_paper + {b:.2f}° "
            f"through 3048 and 9144 m) —; the tip deflection is {min(w):.0f}-{max(w):.0f} % small")


def calibration_c3_summary() -> str:
    """§6: what C3's rows show (with ρ(0), and with ρ(3048 m) at 3048 m)."""
    import math

    r0 = [flutter_row("C3", "US", h) for h in (3048.0, 9144.0)]
    r3 = flutter_row("C3, ρ(3048 m)", "US", 3048.0)
    static = max(abs(_diff(r, k)) for r in r0 for k in ("tip_deflection_m", "tip_twist_deg"))
    mach = max(abs(_diff(r, "M_F")) for r in r0)
    theta = [_diff(r, "theta_deg") for r in r0]
    fast = max(abs(_diff(r3, k)) for k in ("theta_deg", "thrust_kN", "tip_deflection_m", "tip_twist_deg"))
    return _minus(f"With ρ(0) C3 meets the static columns within {math.ceil(static)} % (w_tip, ψ_tip) and M_F within "
                  f"{math.ceil(mach)} %, but θ is {min(theta):.0f}-{max(theta):.0f} % high at those slow flutter points; "
                  f"at the faster flutter point of ρ(3048 m) θ, T_e, w_tip and ψ_tip all fall within {math.ceil(fast)} % "
                  f"while M_F is {_diff(r3, 'M_F'):.1f} % {'high' if _diff(r3, 'M_F') > 0 else 'low'} and δ_e "
                  f"{abs(_diff(r3, 'elevator_deg')):.0f} % {'low' if _diff(r3, 'elevator_deg') < 0 else 'high'}")


def calibration_c4_faster() -> str:
    """§6-7: how much faster than the paper C4 flutters at 3048-9144 m (critical mode)."""
    return _span_of([_diff(flutter_row("C4", "US", h), "M_F") for h in ALTITUDES_M[1:]], ".1f", " %")


def calibration_c4_tip() -> str:
    """§6: C4's tip deflection at its flutter points, 3048-9144 m."""
    return _span_of([_diff(flutter_row("C4", "US", h), "tip_deflection_m") for h in ALTITUDES_M[1:]], ".0f", " %",
                    signed=True)


def _c5(fixed: float | None, h: float) -> dict:
    from docs_figures_studies import C5_STRUCTURE, _bounds

    aircraft, factors = C5_STRUCTURE
    return _bounds(aircraft, factors, None if fixed == h else fixed, "US", h)


def _crit(r: dict) -> dict:
    return min((r["symmetric"], r["antisymmetric"]), key=lambda c: c["M_F"])


def calibration_c5_summary() -> str:
    """§6: what C5's class boundaries (``calibration-c5``) show, with the trim at its 3048 m symmetric flutter point."""
    from flexsim.linear.paper_data import TABLE_US

    paper = {r[0]: r for r in TABLE_US}
    true = {h: _c5(None, h) for h in ALTITUDES_M[1:]}
    fixed = {h: _c5(3048.0, h) for h in ALTITUDES_M[1:]}
    low = {h: _c5(1524.0, h) for h in (3048.0, 9144.0)}
    zero = {h: _c5(0.0, h) for h in ALTITUDES_M[1:]}

    def where(rows, sym: bool) -> list[float]:
        return [h for h, r in rows.items() if (r["gap_sym_minus_anti"] < 0) == sym]

    def alts(hs) -> str:
        return f"{hs[0]:g}" if len(hs) == 1 else f"{hs[0]:g}-{hs[-1]:g}"

    sym_true, sym_fixed, anti_fixed = where(true, True), where(fixed, True), where(fixed, False)
    sym_rows = [r["symmetric"] for rows in (true, fixed) for r in rows.values()]
    ratio = {k: _crit(v[9144.0])["M_F"] / _crit(v[3048.0])["M_F"] for k, v in
             (("true", true), ("3048", fixed), ("1524", low), ("0", zero))}
    p_ratio = paper[9144.0][1] / paper[3048.0][1]
    level = [100 * (_crit(low[h])["M_F"] / paper[h][1] - 1) for h in (3048.0, 9144.0)]
    anti_low = [r["antisymmetric"]["omega_F"] for r in low.values()]
    crit_low = all(r["gap_sym_minus_anti"] > 0 for r in low.values())
    text = (f"Within the justified bounds the **symmetric mode is critical** at {alts(sym_true)} m with the true density "
            f"and at {alts(sym_fixed)} m with ρ(3048 m)"
            + (f" (at {', '.join(f'{h:g}' for h in anti_fixed)} m the antisymmetric twin by "
               f"{', '.join(format(fixed[h]['gap_sym_minus_anti'], '.4f') for h in anti_fixed)})" if anti_fixed else "")
            + f"; the trim at its 3048 m flutter point has {calibration_c5_trim()}. But q_f1 is "
            f"{_span_of([s['qf1_ratio'] for s in sym_rows], '.2f')} of the wing's first bending (not the largest), the "
            f"frequency {_span_of([s['omega_F'] for s in sym_rows], '.1f')} rad/s (paper {paper[3048.0][2]:.1f}), M_F "
            f"{100 * (true[3048.0]['symmetric']['M_F'] / paper[3048.0][1] - 1):+.0f} % at 3048 m, and the trend is that of "
            f"the density used (critical M_F(9144)/M_F(3048) {ratio['true']:.3f} true, {ratio['3048']:.3f} with ρ(3048 m), "
            f"{ratio['1524']:.3f} with ρ(1524 m), {ratio['0']:.3f} with ρ(0); paper {p_ratio:.3f}). With ρ(1524 m) this "
            f"in-bounds structure puts the critical M_F at {_crit(low[3048.0])['M_F']:.4f} and "
            f"{_crit(low[9144.0])['M_F']:.4f} (3048 and 9144 m) — within {max(abs(x) for x in level):.1f} % of the "
            "paper's level and trend — but the critical mode is then the "
            + (f"antisymmetric twin at {_span_of(anti_low, '.1f')} rad/s, the symmetric one "
               f"{_span_of([r['gap_sym_minus_anti'] for r in low.values()], '.4f')} above" if crit_low else
               "symmetric one at some altitude")
            + f": the densities that fit the level favour the antisymmetric mode (gap "
            f"{_span_of([r['gap_sym_minus_anti'] for r in zero.values()], '.4f', signed=True)} with ρ(0)), the lower ones "
            "the symmetric mode.")
    return _minus(text)


def calibration_target_symmetric() -> str:
    """§7: the symmetric-mode target's result cell (C5's class boundaries, C4's and C1's critical modes)."""
    true = {h: _c5(None, h) for h in ALTITUDES_M[1:]}
    fixed = {h: _c5(3048.0, h) for h in ALTITUDES_M[1:]}
    lead_true = [-r["gap_sym_minus_anti"] for r in true.values() if r["gap_sym_minus_anti"] < 0]
    sym_fixed = [h for h, r in fixed.items() if r["gap_sym_minus_anti"] < 0]
    anti_fixed = [h for h, r in fixed.items() if r["gap_sym_minus_anti"] >= 0]
    qf1 = [r["symmetric"]["qf1_ratio"] for rows in (true, fixed) for r in rows.values()]
    c4 = [flutter_row("C4", "US", h) for h in ALTITUDES_M]
    c4_sym = [h for h, r in zip(ALTITUDES_M, c4) if r["sym_share"] > 0.5]
    c1_gap = [flutter_row("C1", "US", h, "symmetric")["M_F"] - flutter_row("C1", "US", h)["M_F"] for h in (3048.0, 9144.0)]
    text = (f"C5 (all factors within bounds): symmetric mode critical by {_span_of(lead_true, '.4f')} at "
            f"{', '.join(f'{h:g}' for h, r in true.items() if r['gap_sym_minus_anti'] < 0)} m (true density; ρ(3048 m): by "
            f"{_span_of([-fixed[h]['gap_sym_minus_anti'] for h in sym_fixed], '.4f')} at "
            f"{', '.join(f'{h:g}' for h in sym_fixed)} m"
            + (f", antisymmetric by {_span_of([fixed[h]['gap_sym_minus_anti'] for h in anti_fixed], '.4f')} at "
               f"{', '.join(f'{h:g}' for h in anti_fixed)} m" if anti_fixed else "")
            + f"), q_f1 {_span_of(qf1, '.2f')} of wing bending 1; C4: symmetric at "
            f"{', '.join(f'{h:g}' for h in c4_sym)} m, q_f1 "
            f"{_span_of([r['qf1_ratio'] for r in c4 if r['sym_share'] > 0.5], '.2f')}; C1: antisymmetric by "
            f"{_span_of(c1_gap, '.4f')} at 3048 and 9144 m")
    return _minus(text)


def _scorecard_rows(config: str) -> list[dict]:
    return [scorecard_row(config, h) for h in ALTITUDES_M]


def _signs(config: str) -> str:
    import manoeuvre_decomposition

    m = re.search(r"(\d+)/(\d+) signs", manoeuvre_decomposition.scorecard(_scorecard_rows(config)))
    if not m:
        raise RuntimeError(f"calibration: no sign count in {config}'s scorecard")
    return f"{m.group(1)}/{m.group(2)}"


def calibration_target_signs() -> str:
    """§7: the trend-sign counts of C1's and C4's symmetric mode (their scorecards)."""
    return f"C1, symmetric mode: **{_signs('C1')}**; C4, symmetric mode: {_signs('C4')}"


def calibration_target_turn() -> str:
    """§7: the 9144 m turn effect M_F(5 km) − M_F(12 km) of C1's and C4's symmetric mode (their scorecards)."""
    c1, c4 = (_scorecard_rows(c)[-1] for c in ("C1", "C4"))
    falling = c1["M_R5km"] > c1["M_R12km"]
    return _minus(f"C1 symmetric mode: {c1['turn_dM']:+.4f} (falling with R {'✔' if falling else '✘'}, "
                  f"{0.02 / c1['turn_dM']:.0f}× below the target); C4 symmetric mode: {c4['turn_dM']:+.4f}")


def calibration_target_climb() -> str:
    """§7: the 9144 m climb effect M_F(+15°) − M_F(−15°) of C1's and C4's symmetric mode (their scorecards)."""
    c1, c4 = (_scorecard_rows(c)[-1] for c in ("C1", "C4"))
    return _minus(f"C1 symmetric mode: {c1['climb_dM']:+.4f}; C4 symmetric mode: {c4['climb_dM']:+.4f}")


def calibration_target_glide() -> str:
    """§7: the glide angles at the 9144 m flutter points (C1 symmetric class, C3, C4) and C1's distance to the
    paper's glide (``flexsim.linear.paper_data.GLIDE_9144``, printed beside)."""
    from flexsim.linear.paper_data import GLIDE_9144

    def gamma(config: str, mode_class: str = "any") -> tuple[float, float]:
        m = flutter_row(config, "US", 9144.0, mode_class)["M_F"]
        return glide_gamma(config, m)["gamma_deg"], m

    (g1, m1), (g3, _), (g4, m4) = gamma("C1", "symmetric"), gamma("C3"), gamma("C4")
    paper = GLIDE_9144[0]
    return _minus(f"C1: {g1:.2f}° at M {m1:.4f} (paper's formulation: T_e = 0 ⇔ θ = 0, γ = −α); C3 {g3:.2f}°; C4 "
                  f"{g4:.2f}° at M {m4:.4f}")


def calibration_target_glide_met() -> str:
    """§7: C1's glide (symmetric-class 9144 m flutter point) against the paper's γ (printed beside)."""
    from flexsim.linear.paper_data import GLIDE_9144

    g1 = glide_gamma("C1", flutter_row("C1", "US", 9144.0, "symmetric")["M_F"])["gamma_deg"]
    return f"{abs(g1 - GLIDE_9144[0]):.2f}°"


def calibration_qs_share() -> str:
    """§6-7: the dynamic pressure (V²/√(1−M²)) of C1's QS flutter as a share of its US flutter's, mean over 0-9144 m."""
    qs = [flutter_row("C1", "QS", h)["V2PG_k"] for h in ALTITUDES_M]
    us = [flutter_row("C1", "US", h)["V2PG_k"] for h in ALTITUDES_M]
    return f"{100 * sum(qs) / sum(us):.0f} %"


def calibration_paper_v2pg() -> str:
    """§6: V²/√(1−M²) at the paper's QS and US flutter points (Tables 2-3 and the ISA), in k m²/s²."""
    import math

    from flexsim.atmosphere import isa
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    v = [(r[1] * isa(r[0]).speed_of_sound) ** 2 / math.sqrt(1 - r[1] ** 2) / 1e3 for r in (*TABLE_QS, *TABLE_US)]
    return f"{min(v):.0f}-{max(v):.0f}k"


def calibration_best_residuals() -> str:
    """§6: the best residual per column of Tables 2-3 over the configurations (C1 for the flutter columns, C3 for
    the static ones; 3048-9144 m unless noted), with each target (an input of the replication) and whether it is met."""
    from flexsim.linear.paper_data import TABLE_US

    upper = ALTITUDES_M[1:]

    def span(config, key, model="US", altitudes=upper, mode_class="any", fmt=".1f"):
        return _span_of([_diff(flutter_row(config, model, h, mode_class), key) for h in altitudes], fmt, " %",
                        signed=True)

    c1_sea = _diff(flutter_row("C1", "US", 0.0), "M_F")
    c1_up = [_diff(flutter_row("C1", "US", h), "M_F") for h in upper]
    low = {h: _c5(1524.0, h) for h in (3048.0, 9144.0)}
    paper = {r[0]: r for r in TABLE_US}
    c5_low = " / ".join(format(100 * (_crit(low[h])["M_F"] / paper[h][1] - 1), "+.1f") for h in low)
    c5_cls = {"antisymmetric twin" if r["gap_sym_minus_anti"] > 0 else "symmetric mode" for r in low.values()}
    c1_classes = {_mode(flutter_row("C1", "US", h)).split(",")[0] for h in upper}
    crit = "antisymmetric" if c1_classes == {"anti"} else "symmetric" if c1_classes == {"sym"} else "mixed"
    sea_w = flutter_row("C1", "US", 0.0)["omega_F"]
    qs = [_diff(flutter_row("C1", "QS", h), "M_F") for h in ALTITUDES_M]
    rows = [
        ("US M_F", f"{_span_of(c1_up, '.1f', ' %', signed=True)} (sea level {c1_sea:+.1f} %); C3 "
                   f"{span('C3', 'M_F', altitudes=(3048.0, 9144.0))}; C5 with ρ(1524 m) {c5_low} % at 3048 / 9144 m "
                   f"({' / '.join(sorted(c5_cls))})", "C1, C3, C5", "3 % at all four altitudes",
         f"3048-9144 m {'yes' if all(abs(x) <= 3 for x in c1_up) else 'no'}, sea level "
         f"{'yes' if abs(c1_sea) <= 3 else 'no'}"),
        ("US ω_F", f"{span('C1', 'omega_F')} (critical, {crit}); "
                   f"{span('C1', 'omega_F', altitudes=(3048.0, 9144.0), mode_class='symmetric')} (symmetric mode)", "C1",
         "—", f"sea level: {sea_w:.1f} against the paper's {paper[0.0][2]:.1f} rad/s (another mode)"),
        ("QS M_F", _span_of(qs, ".1f", " %", signed=True), "C1", "5 %",
         "yes" if all(abs(x) <= 5 for x in qs) else "no"),
        ("θ, T_e", f"{span('C1', 'theta_deg')} (C1); {span('C4', 'theta_deg')} (C4, at flutter points "
                   f"{calibration_c4_faster()} faster than the paper's); {calibration_static_theta()} at the paper's "
                   "own conditions, any structure", "C1, C4", "10 %", "only where the flutter Mach is too high"),
        ("δ_e", span("C1", "elevator_deg"), "C1", "—", ""),
        ("w_tip", span("C3", "tip_deflection_m", altitudes=(3048.0, 9144.0)),
         f"C3 (C1: {span('C1', 'tip_deflection_m', fmt='.0f')})", "—", ""),
        ("ψ_tip", span("C3", "tip_twist_deg", altitudes=(3048.0, 9144.0)),
         f"C3 (C1: {span('C1', 'tip_twist_deg', fmt='.0f')})", "—", ""),
        ("symmetric, q_f1-largest mode", calibration_target_symmetric().split("; C4")[0]
         + "; fuselage EI × 2, wing EI × 0.8 (bounds' edge and static value): symmetric **with q_f1 largest** at "
           f"6096-9144 m (true density), antisymmetric at 3048 m by {_paper_mode('anti3048')} and with ρ(3048 m)",
         "C5; fus. EI 2, wing EI 0.8", "symmetric, q_f1 largest", "at 6096-9144 m with the true density only"),
    ]
    lines = ["", "| column | best | config | target | met? |", "|---|---|---|---|---|"]
    lines += [f"| {' | '.join(r)} |" for r in rows]
    return _minus("\n".join(lines)) + "\n"


TEXT_FIGURES = {
    "calibration-paper-qs-us": Figure(calibration_paper_qs_us, fast=True),
    "calibration-paper-thrust": Figure(calibration_paper_thrust, fast=True),
    "calibration-paper-v2pg": Figure(calibration_paper_v2pg, fast=True),
    "calibration-lift-slopes": Figure(calibration_lift_slopes, fast=True),
    "calibration-static-theta": Figure(calibration_static_theta, fast=True),
    "calibration-static-fit": Figure(calibration_static_fit, fast=True),
    "calibration-static-tips": Figure(calibration_static_tips, fast=True),
    "calibration-static-summary": Figure(calibration_static_summary, fast=True),
    "calibration-c3-summary": Figure(calibration_c3_summary),
    "calibration-c3-us-mach": Figure(lambda: _residuals("C3", "US", altitudes=(3048.0, 9144.0))),
    "calibration-c4-theta": Figure(lambda: _residuals("C4", "US", "theta_deg", ALTITUDES_M[1:])),
    "calibration-c4-faster": Figure(calibration_c4_faster),
    "calibration-c4-tip": Figure(calibration_c4_tip),
    "calibration-c5-summary": Figure(calibration_c5_summary),
    "calibration-target-symmetric": Figure(calibration_target_symmetric),
    "calibration-target-signs": Figure(calibration_target_signs),
    "calibration-target-turn": Figure(calibration_target_turn),
    "calibration-target-climb": Figure(calibration_target_climb),
    "calibration-target-glide": Figure(calibration_target_glide),
    "calibration-target-glide-met": Figure(calibration_target_glide_met),
    "calibration-qs-share": Figure(calibration_qs_share),
    "calibration-best-residuals": Figure(calibration_best_residuals),
}
