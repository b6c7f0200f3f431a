"""Printing flexsim's flutter results beside Tuzcu & Nguyen (2014): tables, critical mode, trend scorecard.

The paper's values (:mod:`flexsim.linear.paper_data`) are printed beside the results and kept under a
separate ``paper`` key in JSON; every computed field comes from the study rows
(:mod:`flexsim.linear.study`, :mod:`flexsim.linear.scorecard`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from flexsim.linear.paper_data import GLIDE_9144, PAPER_TREND_SIGNS, TABLE_QS, TABLE_US, paper_crossover_altitude_m
from flexsim.linear.scorecard import crossover_altitude, critical_altitude, trend_signs
from flexsim.linear.study import MODELS, glide_from_climb

__all__ = ["RunSettings", "PAPER_REPLICATION", "physical_settings", "flutter_report", "flutter_table", "sweep_report", "mode_matches_paper"]

#: The paper's critical mode (Figs. 11, 16 text), printed beside flexsim's.
PAPER_MODE = "symmetric, q_f1 (fuselage bending 1) the largest linear coordinate"


@dataclass(frozen=True)
class RunSettings:
    """One labelled set of settings of a flutter run.

    Attributes
    ----------
    label : str
        ``"physical"``, ``"paper-replication"`` or ``"as given"``.
    aircraft : str
        Bundled name or TOML path.
    formulation : {"physical", "paper"} or None
        None: the aircraft file's.
    linear_density_altitude_m : float or None
        Density of the linearised aerodynamics fixed at this altitude's ISA value [m]; None: true density.
    """

    label: str
    aircraft: str
    formulation: str | None = None
    linear_density_altitude_m: float | None = None

    def describe(self) -> str:
        """One line: aircraft, force resolution, density of the linearised aerodynamics."""
        dens = ("the flight's true density" if self.linear_density_altitude_m is None
                else f"the ISA density of {self.linear_density_altitude_m:.0f} m")
        form = self.formulation or "the aircraft file's"
        return f"{self.label}: aircraft {self.aircraft}, {form} force resolution, linearised aerodynamics at {dens}"


#: The paper-replication settings: the paper's weight and force resolution (gtm_paper). The density of the
#: linearised aerodynamics stays the true one: docs/flutter.md finds the paper's altitude trend implies one
#: fixed density but does not identify its value (--linear-density-altitude-m H sets one).
PAPER_REPLICATION = RunSettings("paper-replication", "gtm_paper", "paper", None)


def physical_settings(aircraft: str = "gtm") -> RunSettings:
    """The physical settings on ``aircraft``: physical force resolution, true density."""
    return RunSettings("physical", aircraft, "physical", None)


def mode_matches_paper(row: dict) -> bool:
    """True when the row's critical mode is symmetric with q_f1 the largest linear coordinate (as the paper's)."""
    linear = [p for p in row.get("participation", []) if p["kind"] == "linear"]
    return row.get("mode_symmetry") == "symmetric" and bool(linear) and linear[0]["label"] == "fuselage bending 1"


def _mode_text(row: dict) -> str:
    linear = [p for p in row.get("participation", []) if p["kind"] == "linear"]
    lead = f", largest linear {linear[0]['label']}" if linear else ""
    return f"{row['mode']}{lead}"  # the mode's name carries its symmetry


#: Width of the text report [characters]: every line of :func:`flutter_report` fits a terminal this wide.
REPORT_WIDTH = 100

_HEAD = (f"{'':<18} {'h':>5} {'M_F':>7} {'w_F':>7} {'theta':>6} {'T_e':>6} {'d_e':>6} {'w_tip':>7} {'psi_tip':>7}  "
         f"{'vs paper [%]':>12}",
         f"{'settings':<18} {'[m]':>5} {'[-]':>7} {'[rad/s]':>7} {'[deg]':>6} {'[kN]':>6} {'[deg]':>6} {'[m]':>7} {'[deg]':>7}  "
         f"{'M_F':>5} {'w_F':>6}")


def _values(label: str, h: float, v: tuple) -> str:
    """One table row: label, altitude and (M_F, w_F, theta, T_e, d_e, w_tip, psi_tip)."""
    return (f"{label:<18} {h:5.0f} {v[0]:7.4f} {v[1]:7.3f} {v[2]:6.3f} {v[3]:6.2f} {v[4]:6.3f} {v[5]:7.4f} {v[6]:7.4f}")


def _wrapped(lines: list[str], width: int = REPORT_WIDTH) -> list[str]:
    """``lines`` with every line longer than ``width`` wrapped at spaces, continued with its own indent + 4."""
    import textwrap

    out = []
    for line in lines:
        if len(line) <= width:
            out.append(line)
            continue
        indent = " " * (len(line) - len(line.lstrip()) + 4)
        out += textwrap.wrap(line, width, subsequent_indent=indent, break_on_hyphens=False)
    return out


def _where(rows: list[tuple[float, str]], n_settings: int) -> str:
    """Where a critical mode was found: its altitudes, and its settings unless all of them."""
    hs = sorted({h for h, _ in rows})
    labels = sorted({s for _, s in rows})
    text = f"{', '.join(f'{h:.0f}' for h in hs)} m"
    if len(labels) < n_settings or len(rows) < len(hs) * n_settings:
        text += " (" + ", ".join(f"{h:.0f} m {s}" for h, s in rows) + ")" if len(labels) > 1 else f" ({labels[0]})"
    return text


def _span(values: list[float]) -> str:
    lo, hi = min(values), max(values)
    return f"{lo:+.1f} %" if abs(hi - lo) < 0.05 else f"{lo:+.1f} to {hi:+.1f} %"


def flutter_report(rows: list[dict], settings: list[RunSettings], models: list[str]) -> tuple[list[str], dict]:
    """Text lines (at most :data:`REPORT_WIDTH` characters each) and the JSON document of ``flexsim flutter`` (level
    flight, paper Tables 2-3).

    The text opens with a one-line summary (each model's flutter Mach against the paper's, in %, and how many rows
    have the paper's critical mode), then per model a table of the flutter points with the paper's row below each
    altitude and one column comparing M_F and w_F with the paper's, and the critical modes below the table. The
    differences of every quantity are in the JSON rows' ``vs_paper_percent``. Rows must carry a ``settings`` label
    (one of ``settings``' labels).
    """
    paper = {"QS": TABLE_QS, "US": TABLE_US, "FS": TABLE_US}
    keys = ("mach", "omega_rad_s", "theta_deg", "thrust_kN", "elevator_deg", "tip_deflection_m", "tip_twist_deg")
    for row in rows:  # every quantity against the paper's row of the same model and altitude (JSON)
        ref = {p[0]: p for p in paper.get(row["model"], ())}.get(row["altitude_m"])
        if ref and "mach" in row:
            row["vs_paper_percent"] = {k: 100 * (row[k] / ref[i + 1] - 1) for i, k in enumerate(keys)}
    found = [r for r in rows if "mach" in r]
    summary = []
    for key in models:
        d = [r["vs_paper_percent"]["mach"] for r in found if r["model"] == key and "vs_paper_percent" in r]
        if d:
            summary.append(f"{key} {_span(d)}")
    n_mode = sum(mode_matches_paper(r) for r in found)
    lines = [f"M_F vs the paper's: {', '.join(summary) or 'no flutter point'}; the paper's critical mode in "
             f"{n_mode}/{len(found)} rows"]
    lines += ["", "Flutter in steady level flight beside Tuzcu & Nguyen (2014) Tables 2-3; the bundled GTM is notional "
              "(structure from public data, calibrated to Table 3: docs/calibration.md). Settings:"]
    lines += [f"  {s.label}: aircraft {s.aircraft}, {s.formulation or 'the file' + chr(39) + 's'} force resolution, "
              + ("true density" if s.linear_density_altitude_m is None else f"density of {s.linear_density_altitude_m:.0f} m")
              for s in settings]
    lines.append("  paper's critical mode: symmetric, fuselage bending 1 (q_f1) the largest linear (Figs. 11, 16)")
    searched: dict[tuple[float, float], list[float]] = {}
    for r in rows:
        hs = searched.setdefault((r["mach_min"], r["mach_max"]), [])
        if r["altitude_m"] not in hs:
            hs.append(r["altitude_m"])
    lines += [f"  searched M {lo:.3f}-{hi:.3f} at {', '.join(f'{h:.0f}' for h in sorted(hs))} m" for (lo, hi), hs in searched.items()]
    for key in models:
        lines += ["", f"{key} ({MODELS[key]}) beside paper Table {'2' if key == 'QS' else '3'}", *_HEAD]
        table = {p[0]: p for p in paper[key]}
        modes: dict[str, list[str]] = {}
        for h in sorted({r["altitude_m"] for r in rows if r["model"] == key}):
            for s in settings:
                for row in [r for r in rows if r["model"] == key and r["altitude_m"] == h and r["settings"] == s.label]:
                    if "error" in row:
                        lines.append(f"{s.label:<18} {h:5.0f}  no flutter point: {row['error'][:70]}")
                        continue
                    line = _values(s.label, h, tuple(row[k] for k in keys))
                    d = row.get("vs_paper_percent")
                    lines.append(line + (f"  {d['mach']:+5.1f} {d['omega_rad_s']:+6.1f}" if d else ""))
                    modes.setdefault(_mode_text(row), []).append((h, s.label))
            ref = table.get(h)
            if ref:
                lines.append(_values(f"paper Table {'2' if key == 'QS' else '3'}", h, ref[1:8]))
        if modes:
            lines.append("critical mode:")
        for text, where in modes.items():
            same = text.startswith("symmetric") and "fuselage bending 1" in text.split("largest linear")[-1]
            lines.append(f"  {_where(where, len(settings))}: {text}{'' if same else ' [not the paper' + chr(39) + 's]'}")
    score = []
    if "QS" in models and "US" in models:
        lines += ["", "QS/US crossover altitude (where M_F(US) - M_F(QS) changes sign) [m]:"]
        for s in settings:
            sel = [r for r in rows if r["settings"] == s.label]
            h_x = crossover_altitude(sel)
            diffs = _us_minus_qs(sel)
            score.append({"settings": s.label, "crossover_altitude_m": h_x, "us_minus_qs": diffs})
            lines.append(f"  {s.label:<18} {'none' if h_x is None else f'{h_x:.0f}'}   (US - QS: "
                         + ", ".join(f"{h:.0f} m {d:+.4f}" for h, d in diffs) + ")")
        lines.append(f"  {'paper':<18} {paper_crossover_altitude_m():.0f}   (Tables 2-3: US below QS at 0-3048 m, above at 6096-9144 m)")
    doc = {"rows": rows, "scorecard": score, "settings": [s.__dict__ for s in settings],
           "paper": {"table_qs": TABLE_QS, "table_us": TABLE_US, "crossover_altitude_m": paper_crossover_altitude_m(),
                     "critical_mode": PAPER_MODE}}
    return _wrapped(lines), doc


_TABLE_HEADER = (f"{'settings':<18} {'h [m]':>6} {'M_F [-]':>8} {'V_F [m/s]':>9} {'w_F [rad/s]':>11} {'theta [deg]':>11} "
                 f"{'phi [deg]':>9} {'gamma [deg]':>11} {'T_e [kN]':>9} {'d_e [deg]':>9} {'w_tip [m]':>9}  critical mode")


def flutter_table(rows: list[dict], settings: list[RunSettings], models: list[str], condition: str) -> tuple[list[str], dict]:
    """Text lines and the JSON document of ``flexsim flutter`` for any aircraft and manoeuvre (no paper columns).

    Every row names the Mach range searched (``search_range``, from :func:`flexsim.linear.envelope.search_range`);
    a row without a flutter point says that none was found in that range, with the search's reason.
    """
    from flexsim.atmosphere import speed_of_sound

    lines = [f"Flutter in {condition}. Settings:"]
    lines += [f"  {s.describe()}" for s in settings]
    lines.append("Searched (Mach range per altitude; [envelope] of the aircraft file, --mach-min/--mach-max, or the estimates "
                 "of docs/aircraft-format.md):")
    seen = set()
    for r in rows:
        key = (r["settings"], r["altitude_m"])
        if key not in seen:
            seen.add(key)
            lines.append(f"  {r['settings']:<18} {r['search_range']}")
    for key in models:
        lines += ["", f"{key} ({MODELS[key]})", _TABLE_HEADER]
        for r in [r for r in rows if r["model"] == key]:
            h = r["altitude_m"]
            if "error" in r:
                lines.append(f"{r['settings']:<18} {h:6.0f}  no flutter found in M {r['mach_min']:.3f}-{r['mach_max']:.3f} "
                             f"(V {r['mach_min'] * speed_of_sound(h):.1f}-{r['mach_max'] * speed_of_sound(h):.1f} m/s): {r['error']}")
                continue
            lines.append(f"{r['settings']:<18} {h:6.0f} {r['mach']:8.4f} {r['mach'] * speed_of_sound(h):9.2f} {r['omega_rad_s']:11.3f} "
                         f"{r['theta_deg']:11.3f} {r['phi_deg']:9.3f} {r['gamma_deg']:11.3f} {r['thrust_kN']:9.3f} "
                         f"{r['elevator_deg']:9.3f} {r['tip_deflection_m']:9.4f}  {r['mode']}")
    doc = {"rows": rows, "settings": [s.__dict__ for s in settings], "condition": condition}
    return lines, doc


def _us_minus_qs(rows: list[dict]) -> list[tuple[float, float]]:
    qs = {r["altitude_m"]: r["mach"] for r in rows if r["model"] == "QS" and "mach" in r}
    us = {r["altitude_m"]: r["mach"] for r in rows if r["model"] == "US" and "mach" in r}
    return [(h, us[h] - qs[h]) for h in sorted(set(qs) & set(us))]


def _sign(s: int | None) -> str:
    return {1: "+", -1: "-", 0: "0", None: "n/a"}[s]


def sweep_report(rows: list[dict], kind: str, paper_aircraft: bool = True) -> tuple[list[str], dict]:
    """Text lines and the JSON scorecard of ``flexsim sweep --turn|--climb`` beside the paper's trends.

    ``paper_aircraft=False`` (any aircraft but the paper's): the trends and glide points alone, nothing of the paper."""
    signs = trend_signs(rows, kind)
    if not paper_aircraft:
        signs = [replace(t, paper_sign=None, match=None) for t in signs]
    per = "km" if kind == "turn" else "deg"
    x = "R" if kind == "turn" else "gamma"
    lines = ["", f"Trend scorecard ({kind}; sign of the least-squares slope over the study, 0 = change over the range below the "
             "search resolution, 1e-4 in M_F or rad/s; change = slope x range, [-] or [rad/s]; paper: its text to Figs. 7-10, 12-15)",
             f"{'model':<6} {'h [m]':>6} {'quantity':<16} {'slope':>12} {'unit':<12} {'change':>10} {'sign':>5} {'paper':>6}  match"]
    if not paper_aircraft:
        lines[1] = lines[1].split("; paper:")[0] + ")"
        lines[2] = lines[2].split(" paper")[0].rstrip()
    for t in signs:
        mark = "" if t.match is None else ("yes" if t.match else "NO")
        unit = f"1/{per}" if t.quantity.startswith("dM_F") else f"rad/s/{per}"
        line = f"{t.model:<6} {t.altitude_m:6.0f} {t.quantity:<16} {t.slope:12.4e} {unit:<12} {t.change:+10.5f} {_sign(t.sign):>5}"
        lines.append(line + (f" {_sign(t.paper_sign):>6}  {mark}" if paper_aircraft else ""))
    score: dict = {"kind": kind, "trends": [t.as_dict() for t in signs]}
    for model in sorted({t.model for t in signs}):
        judged = [t for t in signs if t.model == model and t.match is not None]
        if judged:
            n = sum(t.match for t in judged)
            score[f"matches_{model}"] = [n, len(judged)]
            lines.append(f"{model}: {n} of {len(judged)} trend signs as the paper's")
    paper: dict = {"trend_signs": {f"{k[0]} {k[1]}/d{x} {k[2]} {k[3]:.0f} m": v for k, v in PAPER_TREND_SIGNS.items() if k[0] == kind}}
    if kind == "turn":
        h_c = critical_altitude(signs)
        score["critical_altitude_m"] = h_c
        paper["critical_altitude"] = "between 0 and 3048 m (US dM_F/dR changes sign)"
        lines.append(f"critical altitude (US dM_F/dR changes sign) [m]: {'none' if h_c is None else f'{h_c:.0f}'}; "
                     f"paper: {paper['critical_altitude']}")
    else:
        glides = []
        for model in sorted({r["model"] for r in rows}):
            for h in sorted({r["altitude_m"] for r in rows}):
                g = glide_from_climb(rows, model=model, altitude_m=h)
                if g:
                    glides.append({"model": model, "altitude_m": h, **g})
                    lines.append(f"glide at {h:.0f} m (T_e = 0 on the {model} climb curve): gamma = {g['gamma_deg']:.2f} deg, "
                                 f"M_F = {g['mach']:.4f}, omega_F = {g['omega_rad_s']:.3f} rad/s")
        score["glide"] = glides
        paper["glide_9144_US"] = {"gamma_deg": GLIDE_9144[0], "mach": GLIDE_9144[1], "omega_rad_s": GLIDE_9144[2]}
        lines.append(f"paper glide at 9144 m (US): gamma = {GLIDE_9144[0]} deg, M_F = {GLIDE_9144[1]}, omega_F = {GLIDE_9144[2]} rad/s")
    if not paper_aircraft:
        lines = [ln for ln in lines if "paper" not in ln]
        return lines, {"scorecard": score}
    return lines, {"scorecard": score, "paper": paper}

