"""Figures of docs/flutter.md that were recorded study output, for ``regenerate_docs_figures.py``.

Each function returns the text of one ``<!-- figures:NAME -->`` region; the registry is ``RECORD_FIGURES`` at the
end (all of them are long studies): the studies' own functions (``symmetric_mode.bounds``,
``manoeuvre_decomposition.run``, ``options_effects``'s aircraft options, imported from ``studies/``, never copied)
on today's library. Every switch of ``studies/manoeuvre_decomposition.py`` is a physical term of the current model
(:class:`flexsim.model.terms.Terms`) or a change of the linearisation point; one checkpoint per switch.

Where a paragraph reads the numbers, the function writes the paragraph and raises ``RuntimeError`` naming the
claim when a qualitative statement of it no longer holds (the prose must then be rewritten by hand).
"""

from __future__ import annotations

import functools
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "studies"))
sys.path.insert(0, str(ROOT / "tools"))
from docs_figures_core import Figure, checkpoint  # noqa: E402
from docs_figures_static import _num  # noqa: E402
from docs_figures_studies import MORE_BOUNDS, PAPER_ALTITUDES_M, _bounds, _bounds_label, _class_bounds, _minus  # noqa: E402

#: The class-boundary grid of ``symmetric_mode.py`` (its default) [Mach]: low, high, step.
GRID = (0.55, 0.95, 0.025)


def _grid(lo: float, hi: float, step: float):
    import numpy as np

    return np.arange(lo, hi + 1e-9, step)


@functools.cache
def _bounds_row(aircraft: str, factors: tuple[tuple[str, float], ...], model: str, altitude_m: float,
                formulation: str | None = None, grid: tuple[float, float, float] = GRID) -> dict:
    """One row of ``python studies/symmetric_mode.py bounds --aircraft NAME [--factor N=V ...] [--formulation F]
    --model MODEL --altitudes H [--grid LO HI STEP]`` (true density), checkpointed (one piece per row)."""

    def compute() -> dict:
        import symmetric_mode
        from manoeuvre_decomposition import configure

        ac = configure(aircraft, None, 1.0, None, None)
        for name, value in factors:
            ac = symmetric_mode.apply_factor(ac, name, value)
        (row,) = symmetric_mode.bounds(ac, "", model, formulation or ac.formulation, None, [altitude_m], _grid(*grid))
        return row

    return checkpoint("symmetric-bounds", {"aircraft": aircraft, "factors": [list(f) for f in factors], "model": model,
                                           "altitude_m": altitude_m, "formulation": formulation, "grid": list(grid)},
                      compute)


def _both(row: dict, what: str) -> tuple[dict, dict]:
    s, a = row["symmetric"], row["antisymmetric"]
    if not (s and a and "omega_F" in s and "omega_F" in a):
        raise RuntimeError(f"{what}: at {row['altitude_m']:g} m a mirror class has no crossing inside the grid")
    return s, a


# --- the finite-state class boundaries ---------------------------------------------------------------------------

def symmetric_bounds_fs() -> str:
    """``python studies/symmetric_mode.py bounds --aircraft gtm|gtm_paper --model FS`` at 3048-9144 m."""
    import symmetric_mode

    rows = []
    for aircraft in ("gtm", "gtm_paper"):
        for h in PAPER_ALTITUDES_M[1:]:
            r = _bounds_row(aircraft, (), "FS", h)
            _both(r, "symmetric-bounds-fs")
            rows.append({**r, "config": _bounds_label(aircraft, (), None)})
    table = symmetric_mode.bounds_table(rows).split("\n\n")[0]
    gaps = {a: [r["gap_sym_minus_anti"] for r in rows if r["config"] == f"`{a}`"] for a in ("gtm", "gtm_paper")}
    us = {a: [r["gap_sym_minus_anti"] for r in _class_bounds(a)] for a in ("gtm", "gtm_paper")}
    if not all(g > 0 for g in gaps["gtm"] + gaps["gtm_paper"]):
        raise RuntimeError("symmetric-bounds-fs: a finite-state gap is not positive (the prose says the symmetric "
                           "boundary lies above the antisymmetric one)")
    order = all(a > b for a, b in zip(gaps["gtm"], gaps["gtm_paper"]))
    diff = max(abs(f - u) for a in gaps for f, u in zip(gaps[a], us[a]))
    return ("\n" + _minus(table) + "\n\nThe finite-state model " + ("confirms" if order else "does not confirm") +
            " the order of the gaps (`gtm` above `gtm_paper` at every altitude) and their size: its gaps differ from "
            f"the p-k ones above by {diff:.4f} at most.\n")


# --- the paper's force resolution's share of the gap --------------------------------------------------------------

def symmetric_force_resolution() -> str:
    """``gtm_paper`` with ``--formulation physical`` (US): both class boundaries against ``gtm_paper``'s own."""
    hs = PAPER_ALTITUDES_M[1:]
    phys = [_both(_bounds_row("gtm_paper", (), "US", h, "physical"), "symmetric-force-resolution") for h in hs]
    phys_rows = [_bounds_row("gtm_paper", (), "US", h, "physical") for h in hs]
    paper = {r["altitude_m"]: r for r in _class_bounds("gtm_paper")}
    anti_change = max(abs(a["M_F"] - paper[h]["antisymmetric"]["M_F"]) for h, (_, a) in zip(hs, phys))
    share = [r["gap_sym_minus_anti"] - paper[h]["gap_sym_minus_anti"] for h, r in zip(hs, phys_rows)]
    worst = max(share, key=abs)
    role = (f"the paper's force resolution (`gtm_paper`'s own) does not make the gap (it moves it by "
            f"{max(map(abs, share)):.4f} or less)" if abs(worst) < 5e-4 else
            f"the paper's force resolution changes the gap by {_num(-worst, '+.4f')} at {hs[share.index(worst)]:g} m "
            "(its largest change)")
    return (f"{role} — `gtm_paper` with `--formulation physical` has the symmetric boundary at "
            f"{' / '.join(format(s['M_F'], '.4f') for s, _ in phys)} "
            f"(gap {' / '.join(_num(r['gap_sym_minus_anti'], '+.4f') for r in phys_rows)}) and the antisymmetric one "
            f"at {' / '.join(format(a['M_F'], '.4f') for _, a in phys)} (within {anti_change:.4f} of `gtm_paper`'s) at "
            f"{' / '.join(f'{h:g}' for h in hs)} m")


# --- the paper's 17.8 rad/s sea-level mode: a softer wing torsion -------------------------------------------------

#: ``python studies/symmetric_mode.py vary --aircraft gtm_paper --altitude 0 --grid 0.30 0.80 0.025 --vary wing.gj
#: 0.3 0.5``: the grid [Mach] and the factors.
GJ_GRID = (0.30, 0.80, 0.025)
GJ_FACTORS = (0.3, 0.5)


def _qf1(crossing: dict) -> str:
    """``q_f1 the largest linear coordinate`` or ``q_f1 0.72 of the largest linear coordinate (NAME)``."""
    if crossing["largest"] == "fuselage bending 1":
        return "q_f1 the largest linear coordinate"
    return f"q_f1 {crossing['qf1_ratio']:.2f} of the largest linear coordinate ({crossing['largest']})"


def symmetric_soft_torsion() -> str:
    """Both class boundaries of ``gtm_paper`` at sea level with the wing GJ x 0.3 and x 0.5 (US)."""
    (s3, a3), (s5, a5) = (_both(_bounds_row("gtm_paper", (("wing.gj", f),), "US", 0.0, None, GJ_GRID),
                                "symmetric-soft-torsion") for f in GJ_FACTORS)
    if not (s3["M_F"] < a3["M_F"] and s5["M_F"] > a5["M_F"]):
        raise RuntimeError("symmetric-soft-torsion: the symmetric mode is no longer critical at wing GJ x 0.3 only "
                           f"(x 0.3: {s3['M_F']} against {a3['M_F']}; x 0.5: {s5['M_F']} against {a5['M_F']})")
    return (f"at sea level, a symmetric mode critical at M {s3['M_F']:.4f} and {s3['omega_F']:.2f} rad/s with wing GJ "
            f"× {GJ_FACTORS[0]:g} ({_qf1(s3)}; antisymmetric {a3['M_F']:.4f} at "
            f"{a3['omega_F']:.2f} rad/s), while at × {GJ_FACTORS[1]:g} the symmetric one is at {s5['omega_F']:.2f} rad/s "
            f"and M {s5['M_F']:.4f}, above the antisymmetric {a5['M_F']:.4f}")


# --- the body moments and downwash, p-k (docs/flutter.md, options) -------------------------------------------------

@functools.cache
def _level_pk(bodies: bool, altitude_m: float) -> float:
    """US (Theodorsen p-k) level-flight flutter Mach of the bundled gtm, with its fuselage/nacelle moments and tail
    downwash (``bodies``) or without them (``options_effects._with(gtm, bodies=(), downwash_gradient=0.0)``), the
    search of ``flexsim flutter`` (M 0.5-0.95)."""
    from options_effects import _with

    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trim import SteadyManoeuvre

    gtm = load_aircraft("gtm")
    ac = gtm if bodies else _with(gtm, bodies=(), downwash_gradient=0.0)
    return FlutterAnalysis(ac, "theodorsen").search(SteadyManoeuvre.level(altitude_m, mach=0.5),
                                                     mach_range=(0.5, 0.95)).mach


def options_body_moments_pk() -> str:
    """The change of the US level flutter Mach when the body moments and tail downwash are switched on, 0 and 3048 m."""
    parts, pairs = [], []
    for h in PAPER_ALTITUDES_M[:2]:
        on, off = _level_pk(True, h), _level_pk(False, h)
        parts.append(f"{_num(100 * (on / off - 1), '+.2f')} % at {h:g} m")
        pairs.append(f"{on:.5f} against {off:.5f}")
    return f"{', '.join(parts)}: {', '.join(pairs)}"


# --- the decomposition of docs/flutter.md ------------------------------------------------------------------------

class Decomposition(tuple):
    """The options of one ``python studies/manoeuvre_decomposition.py`` command (all but the switches), as a hashable
    tuple of (flag, value) pairs in the script's own spelling, e.g. ``(("--aircraft", "gtm_paper"),)``."""

    def get(self, flag: str, default=None):
        return dict(self).get(flag, default)

    def args(self, switches) -> list[str]:
        out = []
        for flag, value in self:
            out += [flag, *value.split()] if flag == "--incidence" else [flag, value]
        return out + ["--switches", *switches]

    def command(self, switches) -> str:
        import shlex

        return "python studies/manoeuvre_decomposition.py " + shlex.join(self.args(switches))


def _config(**options) -> Decomposition:
    return Decomposition(tuple((f"--{k.replace('_', '-')}", str(v)) for k, v in options.items()))


#: The bundled gtm at 9144 m (the decomposition's default).
GTM = _config(altitude=9144)
#: The paper's fin (eqs. 29-31) on gtm_paper with the paper's force resolution.
GTM_PAPER = _config(aircraft="gtm_paper", formulation="paper", altitude=9144)
#: C1 of docs/calibration.md §6 (paper weight and formulation, zero-incidence chords, rho(3048 m), zeta = 0.01), the
#: symmetric mode.
C1 = _config(scaling='{"fuselage_ei":1.587,"wing_gj":0.816,"wing_ei":0.635,"fuselage_gj":0.907,'
                     '"htail_stiffness":0.907,"vtail_stiffness":0.907}', mass_factor=0.907, incidence="1.81 2.7",
             formulation="paper", fixed_density=3048, damping=0.01, mode_class="symmetric", altitude=9144, start=0.77)
#: C4: gtm_paper, fuselage EI x 2, wing EI x 0.7, zero-incidence chords, rho(3048 m), the symmetric mode.
C4 = _config(aircraft="gtm_paper", scaling='{"fuselage_ei":2.0,"wing_ei":0.7}', formulation="paper",
             incidence="1.81 2.7", fixed_density=3048, mode_class="symmetric", altitude=9144, start=0.82)
#: C5: gtm_paper with every factor within its bound (C3's wing, fuselage EI x 1.75), true density, the symmetric mode.
C5 = _config(aircraft="gtm_paper", scaling='{"wing_ei":0.85,"wing_gj":1.04,"fuselage_ei":1.75}', formulation="paper",
             mode_class="symmetric", altitude=9144, start=0.92)
#: The paper's mode: gtm_paper, fuselage EI x 2 (Fig. 4's peak), wing EI x 0.8, true density, the symmetric mode.
PAPER_MODE = _config(aircraft="gtm_paper", scaling='{"wing_ei":0.8,"fuselage_ei":2.0}', formulation="paper",
                     mode_class="symmetric", altitude=9144, start=0.92)


def _options(config: Decomposition) -> dict:
    """``manoeuvre_decomposition.run``'s keyword arguments and aircraft for ``config``."""
    import manoeuvre_decomposition as md

    g = config.get
    scaling = json.loads(g("--scaling")) if g("--scaling") else None
    incidence = tuple(float(v) for v in g("--incidence").split()) if g("--incidence") else None
    damping = float(g("--damping")) if g("--damping") else None
    fixed = float(g("--fixed-density")) if g("--fixed-density") else None
    ac = md.configure(g("--aircraft", "gtm"), scaling, float(g("--mass-factor", 1.0)), incidence, damping)
    return dict(ac=ac, aircraft_name=g("--aircraft", "gtm"), altitude_m=float(g("--altitude", 9144.0)),
                rho_altitude_m=3048.0, level_start=float(g("--start", 0.91)), base_rho_altitude_m=fixed,
                formulation=g("--formulation", "physical"), mode_class=g("--mode-class", "any"))


@functools.cache
def _current(config: Decomposition, switches: tuple[str, ...]) -> dict[str, dict]:
    """``config``'s decomposition on today's library (``manoeuvre_decomposition.run``), rows keyed by switch; one
    checkpoint per switch (the others start from the ``none`` row's level flutter point, as in one run)."""
    import manoeuvre_decomposition as md

    if switches[0] != "none":
        raise ValueError(f"switches {switches}: 'none' first")
    print(f"  {config.command(switches)}", flush=True)
    rows, ref = {}, None
    for sw in switches:
        def compute(sw=sw, ref=ref) -> dict:
            (row,) = md.run(switches=[sw], ref_level=ref, **_options(config))
            return row

        rows[sw] = checkpoint("decomposition", {"config": [list(o) for o in config], "switch": sw, "ref_level": ref},
                              compute)
        if sw == "none":
            ref = (rows[sw]["M_level"], rows[sw]["w_level"])
    return rows


def _table(rows) -> str:
    import manoeuvre_decomposition as md

    return _minus(md.table(list(rows)))


def _pg_slope(mach: float) -> float:
    """d[1/sqrt(1 - M^2)]/dM = M / (1 - M^2)^1.5, the Prandtl-Glauert factor's slope [-]."""
    return mach / (1.0 - mach * mach) ** 1.5


def decomposition_reading() -> str:
    """The reading of the bundled gtm's decomposition table (``decomposition-gtm``, every switch on today's model)."""
    from docs_figures_studies import _decomposition_gtm

    rows = {r["switch"]: r for r in _decomposition_gtm()}
    ref, aa, pg, mm, fr, dens = (rows[s] for s in ("none", "aero_alpha", "prandtl_glauert", "mass_matrix",
                                                    "force_resolution", "density"))
    t0 = ref["turn_dM"]
    small = max(abs(mm["turn_dM"] - t0), abs(fr["turn_dM"] - t0))
    if small > 1.5e-4 or not pg["turn_dM"] > t0 or not abs(aa["turn_dM"]) < 0.5 * abs(t0):
        raise RuntimeError("decomposition-reading: the reading (aero_alpha carries the turn effect, P-G compresses "
                           "it, M(q) and the force resolution change it by 0.0001 or less) no longer holds: "
                           f"{ {s: r['turn_dM'] for s, r in rows.items()} }")
    share = 100 * (1 - aa["turn_dM"] / t0)
    carried = "**entirely**" if abs(aa["turn_dM"]) <= 1.5e-4 else f"**{share:.0f} %**"
    return (f"Reading: the turn effect is carried {carried} by the aerodynamics linearised about the turn's larger angle "
            f"of attack and its sideslip (`aero_alpha`: {_num(t0, '+.4f')} → {_num(aa['turn_dM'], '+.4f')}); "
            "rotation rates, the whole static deformation, thrust, gravity, the static deflection's effect on M(q) and "
            f"the force resolution's trim-α terms each change it by {small:.4f} or less. "
            f"The **Prandtl–Glauert factor compresses it** (frozen at the level flutter Mach the turn effect is "
            f"{_num(pg['turn_dM'], '+.4f')}, {pg['turn_dM'] / t0:.1f}× larger) — at M {ref['M_level']:.2f} the P-G "
            f"factor's slope (d[1/√(1−M²)]/dM = M/(1−M²)^1.5 = {_pg_slope(ref['M_level']):.1f}) makes the aerodynamic "
            "stiffness rise so fast with Mach that any destabilising change is met within a few thousandths in Mach. "
            f"The **density** of the linearised aerodynamics raises it (row `density`: flutter moves to M "
            f"{dens['M_level']:.2f}, where that slope is {_pg_slope(ref['M_level']) / _pg_slope(dens['M_level']):.1f}× "
            "smaller).")


#: The fin switches (the paper's fin, eqs. 29-31) with their reference row, on gtm_paper.
FIN_SWITCHES = ("none", "fin_normal", "fin_drag+0.3", "fin_drag-0.3")


def decomposition_fin() -> str:
    """The fin switches' rows on gtm_paper and how much they move the turn and climb effects."""
    rows = _current(GTM_PAPER, FIN_SWITCHES)
    ref = rows["none"]
    label = {**rows, "none": {**ref, "switch": "none (`gtm_paper`)"}}
    dm = max(abs(r[k] - ref[k]) for r in rows.values() for k in ("turn_dM", "climb_dM"))
    dw = max(abs(r[k] - ref[k]) for r in rows.values() for k in ("turn_dw", "climb_dw"))
    return ("\n" + _table(label.values()).replace("| switched off |", "| switched |") + "\n\n"
            "The fin's resolution and drag law move neither the turn effect nor the climb effect (changes of at most "
            f"{dm:.0e} in Mach and {dw:.3f} rad/s)").replace("e-0", "e-")


#: C1's switches.
C1_SWITCHES = ("none", "rotation", "static_deformation", "thrust", "gravity", "damping", "mass_matrix", "aero_alpha",
               "prandtl_glauert")


def decomposition_c1() -> str:
    """C1's decomposition on the symmetric mode and its reading."""
    from flexsim.linear.paper_data import TABLE_US

    cur = _current(C1, C1_SWITCHES)
    ref = cur["none"]
    paper = TABLE_US[3]
    table = _table(cur.values())
    table += f"\n| paper (Figs. 10, 15; glide point) | {paper[1]:.4f} / {paper[2]:.2f} | ≈ +0.03 … +0.1 | < 0 | ≈ +0.004 | < 0 |"
    t0 = ref["turn_dM"]
    aa, pg, rot, mm = cur["aero_alpha"], cur["prandtl_glauert"], cur["rotation"], cur["mass_matrix"]
    nothing = {"M(q)": mm["turn_dM"] - t0, "the static deformation": cur["static_deformation"]["turn_dM"] - t0,
               "the thrust line": cur["thrust"]["turn_dM"] - t0, "gravity": cur["gravity"]["turn_dM"] - t0}
    if not (t0 > 0 and aa["turn_dM"] < 0.5 * t0 and pg["turn_dM"] > t0 and max(map(abs, nothing.values())) < 2e-4):
        raise RuntimeError("decomposition-c1: the reading (aero_alpha carries most of the turn effect, P-G compresses "
                           "it, M(q), static deformation, thrust and gravity nothing) no longer holds")
    dw0, dw_sd = ref["turn_dw"], cur["static_deformation"]["turn_dw"]
    rises = "rises" if dw0 < 0 else "falls"
    sign = "the paper's sign" if dw0 < 0 else "not the paper's sign"
    left = t0 - (t0 - aa["turn_dM"]) - (t0 - rot["turn_dM"])
    damp = cur["damping"]
    climbs = [r["climb_dM"] for r in cur.values()]
    wrong = ", the wrong way" if ref["climb_dM"] - cur["thrust"]["climb_dM"] < 0 and ref["climb_dM"] - mm["climb_dM"] < 0 else ""
    reverse = "and no switch here reverses it" if max(climbs) <= 0 else "and a switch reverses it"
    fragile = (f"the turn's static deformation alone sets its sign ({_num(dw_sd, '+.3f')} rad/s without it)"
               if (dw_sd > 0) != (dw0 > 0) else f"without the static deformation it is {_num(dw_sd, '+.3f')} rad/s")
    return ("\n" + table + "\n\n"
            f"Reading: with the paper's settings and on the symmetric mode the turn effect is {_num(t0, '+.4f')} (M_F "
            f"{'falling' if t0 > 0 else 'rising'} as R grows, as in the paper, but {0.03 / t0:.0f}-{0.1 / t0:.0f}× smaller) "
            f"and ω_F {rises} with R ({_num(dw0, '+.3f')} rad/s from 5 to 12 km: {sign}). The aerodynamics linearised "
            f"about the turn's α and sideslip again carry most of it (`aero_alpha`: "
            f"{100 * (1 - aa['turn_dM'] / t0):.0f} %, {_num(t0, '+.4f')} → {_num(aa['turn_dM'], '+.4f')}); Prandtl–Glauert "
            f"still compresses it (frozen: {_num(pg['turn_dM'], '+.4f')}, at M {ref['M_level']:.2f} its slope is "
            f"{_pg_slope(0.91) / _pg_slope(ref['M_level']):.1f}× smaller than at M 0.91). The rotation-rate terms carry "
            f"{100 * (1 - rot['turn_dM'] / t0):.0f} % ({_num(rot['turn_dM'], '+.4f')} without them); "
            f"{', '.join(nothing)} change it by {max(map(abs, nothing.values())):.4f} or less; about {left:.4f} is left to "
            f"the interaction of the switched terms. The small ω_F trend is fragile: {fragile}. The paper's undamped "
            f"structure (ζ = 0) flutters {ref['M_level'] - damp['M_level']:.3f} "
            f"{'lower' if damp['M_level'] < ref['M_level'] else 'higher'} in Mach ({damp['M_level']:.4f}, "
            f"{_num(100 * (damp['M_level'] / ref['M_level'] - 1), '+.1f')} %) with a turn effect of "
            f"{_num(damp['turn_dM'], '+.4f')}. The climb effect stays at {_num(ref['climb_dM'], '+.4f')} (the paper's sign "
            f"is +; {_num(damp['climb_dM'], '+.4f')} with ζ = 0); the thrust line contributes "
            f"{_num(ref['climb_dM'] - cur['thrust']['climb_dM'], '+.5f')} and M(q) "
            f"{_num(ref['climb_dM'] - mm['climb_dM'], '+.5f')} of it{wrong}, {reverse}.")


def _reference(row: dict) -> str:
    """``level M / omega rad/s, turn effect ... (dw ...), climb effect ...`` of a decomposition's row."""
    dw = row["turn_dw"]
    return (f"level {row['M_level']:.4f} / {row['w_level']:.2f} rad/s, turn effect {_num(row['turn_dM'], '+.4f')} "
            f"(Δω_F {_num(dw, '+.3f')} rad/s: ω_F {'rises' if dw < 0 else 'falls'} with R, "
            f"{'the' if dw < 0 else 'not the'} paper's sign), climb effect {_num(row['climb_dM'], '+.5f')} "
            f"(Δω_F {_num(row['climb_dw'], '+.4f')} rad/s)")


def decomposition_c4() -> str:
    """C4's reference row (symmetric mode, rho(3048 m))."""
    return _reference(_current(C4, ("none",))["none"])


def _with_aero_alpha(config: Decomposition, figure: str, extra: tuple[str, ...] = ()) -> str:
    cur = _current(config, ("none", "aero_alpha", *extra))
    aa, href = cur["aero_alpha"]["turn_dM"], cur["none"]["turn_dM"]
    text = (_reference(cur["none"]) + f"; with `aero_alpha` the turn effect drops to {_num(aa, '+.4f')} — "
            f"{100 * (1 - aa / href):.0f} % of it is "
            "again the aerodynamics linearised about the turn's angle of attack and sideslip")
    for sw in extra:
        text += f"; `{sw}`: {_num(cur[sw]['turn_dM'], '+.4f')}"
    return text


def decomposition_c5() -> str:
    """C5's reference row (symmetric mode, every factor within its bound, true density) and its aero_alpha row."""
    return _with_aero_alpha(C5, "decomposition-c5")


def decomposition_paper_mode() -> str:
    """The paper's mode (fuselage EI x 2, wing EI x 0.8, true density): reference, aero_alpha and rotation rows."""
    return _with_aero_alpha(PAPER_MODE, "decomposition-paper-mode", ("rotation",))


# --- what moves the gap: one factor at a time on gtm_paper at 3048 m (US) ------------------------------------------

FE, WE, WG = "fuselage.ei", "wing.ei", "wing.gj"
#: C3's wing (the static columns' values, docs/calibration.md §6).
C3_WING = ((WE, 0.85), (WG, 1.04))
#: ``python studies/symmetric_mode.py vary --aircraft gtm_paper --altitude 3048 --vary NAME F1 F2 ...`` (and the same
#: with ``--factor`` for the pairs): the rows of docs/flutter.md's table, (label, factor sets).
VARY_ROWS = (
    ("fuselage EI × 1.5", (((FE, 1.5),),)),
    ("fuselage EI × 2", (((FE, 2.0),),)),
    ("fuselage EI × 3", (((FE, 3.0),),)),
    ("fuselage mass × 0.7 / × 1.3", ((("fuselage.mass", 0.7),), (("fuselage.mass", 1.3),))),
    ("lumped masses (not engines) × 0.5 / × 2", ((("lumped.mass", 0.5),), (("lumped.mass", 2.0),))),
    ("wing EI × 0.7 / × 1.3", (((WE, 0.7),), ((WE, 1.3),))),
    ("wing GJ × 0.8 / × 1.2", (((WG, 0.8),), ((WG, 1.2),))),
    ("engine mass × 0.5 / × 1.5", ((("engine.mass", 0.5),), (("engine.mass", 1.5),))),
    ("stabilizer stiffness × 0.5 / × 2", ((("htail.stiffness", 0.5),), (("htail.stiffness", 2.0),))),
    ("fuselage EI × 2, wing EI × 0.6 / 0.7 / 0.8", tuple(((FE, 2.0), (WE, w)) for w in (0.6, 0.7, 0.8))),
    ("fuselage EI × 1.5 / 1.75 / 2.25 / 2.5, wing EI × 0.7", tuple(((FE, f), (WE, 0.7)) for f in (1.5, 1.75, 2.25, 2.5))),
    ("fuselage EI × 1.25 / 1.5 / 1.75 / 2, wing EI × 0.85, GJ × 1.04 (static columns, §6 C3)",
     tuple((*C3_WING, (FE, f)) for f in (1.25, 1.5, 1.75, 2.0))),
)
VARY_ALTITUDE_M = 3048.0


def _vary(factors) -> dict:
    return _bounds_row("gtm_paper", tuple(factors), "US", VARY_ALTITUDE_M)


def _joined(cells: list[str]) -> str:
    return cells[0] if len(set(cells)) == 1 else "; ".join(cells)


def symmetric_vary() -> str:
    """The table of docs/flutter.md's "What moves the gap" (US, gtm_paper, 3048 m)."""
    base = {r["altitude_m"]: r for r in _class_bounds("gtm_paper")}[VARY_ALTITUDE_M]
    lines = [f"`gtm_paper` itself: gap {_num(base['gap_sym_minus_anti'], '+.4f')}, q_f1 ratio "
             f"{base['symmetric']['qf1_ratio']:.2f}.", "",
             "| factor (× `gtm_paper`) | SYM M_F / ω_F / q_f1 ratio | ANTI M_F / ω_F | M_sym − M_anti |",
             "|---|---|---|---|"]
    for label, sets in VARY_ROWS:
        rows = [_vary(f) for f in sets]
        both = [_both(r, f"symmetric-vary ({label})") for r in rows]
        sym = "; ".join(f"{s['M_F']:.4f} / {s['omega_F']:.2f} / {s['qf1_ratio']:.2f}" for s, _ in both)
        anti = [f"{a['M_F']:.4f} / {a['omega_F']:.2f}" for _, a in both]
        anti_cell = _joined(anti) if len(rows) == 1 or len(set(anti)) == 1 else "; ".join(f"{a['M_F']:.4f}" for _, a in both)
        gaps = "; ".join(_num(r["gap_sym_minus_anti"], "+.4f") for r in rows)
        lines.append(f"| {label} | {sym} | {anti_cell} | {gaps} |")
    return "\n" + "\n".join(lines) + "\n"


def _span(values, fmt: str, sep: str = "-") -> str:
    lo, hi = _num(min(values), fmt), _num(max(values), fmt)
    return lo if lo == hi else f"{lo}{sep}{hi}"


def symmetric_vary_reading() -> str:
    """The reading of the "What moves the gap" table and of the stiffness variants' class boundaries."""
    from manoeuvre_decomposition import configure

    from flexsim.linear.modes import in_vacuo_modes
    from flexsim.linear.paper_data import TABLE_US
    from flexsim.model.aircraft_model import AircraftModel

    singles = [f for _, sets in VARY_ROWS for f in sets if len(f) == 1]
    pairs = [f for _, sets in VARY_ROWS for f in sets if len(f) > 1]
    gap = {f: _vary(f)["gap_sym_minus_anti"] for f in singles + pairs}
    if min(gap[f] for f in singles) <= 0:
        raise RuntimeError("symmetric-vary-reading: a single factor makes the symmetric mode critical; rewrite the reading")
    fe = {v: gap[((FE, v),)] for v in (1.5, 2.0, 3.0)}
    if not (fe[1.5] < fe[2.0] < fe[3.0] and fe[1.5] == min(gap[f] for f in singles)):
        raise RuntimeError(f"symmetric-vary-reading: the fuselage EI is no longer the strongest lever with an optimum "
                           f"near x 1.5 ({fe})")
    ac = configure("gtm_paper", None, 1.0, None, None)
    modes = in_vacuo_modes(AircraftModel(ac, gravity_m_s2=0.0)).modes
    fus = [m.frequency_rad_s for m in modes if m.dominant_dof == "fuselage bending 1"]
    if not fus:
        raise RuntimeError("symmetric-vary-reading: no in-vacuo fuselage bending 1 mode")
    crit = [f for f in pairs if gap[f] < 0]
    value = lambda f, name: dict(f)[name]  # noqa: E731
    q_largest = [f for f in pairs if _vary(f)["symmetric"]["qf1_ratio"] >= 0.995]
    if any(gap[f] < 0 for f in q_largest):
        raise RuntimeError("symmetric-vary-reading: the symmetric mode is critical with q_f1 the largest coordinate at "
                           "3048 m; rewrite the reading")
    peak = max(c.sections.ei_nm2.max() for c in ac.components if c.name == "fuselage")
    # Fuselage EI factors of the table beyond Fig. 4's peak (x 2), and C4's tip deflection against the paper's
    # (docs/calibration.md §6; the paper's value printed beside, never used in the result).
    beyond = min(v for f in pairs for name, v in f if name == FE and v > 2.0)
    from docs_figures_calibration import flutter_row

    c4_tip = [100 * (flutter_row("C4", "US", h)["tip_deflection_m"] / paper_h[6] - 1)
              for h, paper_h in ((row[0], row) for row in TABLE_US) if h >= VARY_ALTITUDE_M]
    nearest = [_bounds("gtm_paper", MORE_BOUNDS[0][1], None, "US", h) for h in MORE_BOUNDS[0][4]]
    c3 = _vary((*C3_WING, (FE, 1.75)))
    c3_crit = c3["symmetric"] if c3["gap_sym_minus_anti"] < 0 else c3["antisymmetric"]
    paper_tip = {row[0]: row[6] for row in TABLE_US}[VARY_ALTITUDE_M]
    paper_w = TABLE_US[1][2]
    w_near = [r["symmetric"]["omega_F"] for r in nearest]
    if not all(r["gap_sym_minus_anti"] < 0 for r in nearest):
        raise RuntimeError("symmetric-vary-reading: fuselage EI x 2, wing EI x 0.7 no longer has the symmetric mode "
                           "critical at 3048-9144 m")
    return (f"Reading: no single parameter makes the symmetric mode critical — every factor from × 0.5 to × 3 leaves the "
            f"gap positive; the fuselage EI is the strongest lever and has an optimum (× 1.5: {_num(fe[1.5], '+.4f')}) "
            f"where the fuselage's first bending ({fus[0]:.2f} rad/s in vacuo on `gtm_paper`; it scales with √EI) comes "
            f"up to the flutter frequency. Two factors together do it: the fuselage EI at × "
            f"{_span([value(f, FE) for f in crit], 'g')} **and** a softer wing bending (× "
            f"{_span([value(f, WE) for f in crit], 'g')}). But the two features of the paper's mode pull apart: q_f1 "
            f"becomes the largest coordinate only when the fuselage bending frequency rises *above* the flutter "
            f"frequency (rows with q_f1 ratio 1.00: fuselage EI × {_span([value(f, FE) for f in q_largest], 'g')} at wing "
            f"EI × {_span([value(f, WE) for f in q_largest], 'g')}), and there the symmetric mode is no longer critical "
            f"({_span([gap[f] for f in q_largest], '+.4f', ' to ')}); where it is critical q_f1 is "
            f"{_span([_vary(f)['symmetric']['qf1_ratio'] for f in crit], '.2f')} of the wing's first bending. The two twins "
            f"stay within ±{max(abs(gap[f]) for f in crit):.4f} in Mach where the symmetric one is critical, and their "
            f"order is decided by details far below the notional structure's accuracy. The bounds: fuselage EI × 2 on "
            f"`gtm_paper` is {2 * peak / 1e9:.0f} GN m² at its peak, the top of Fig. 4's fuselage panel (the only "
            f"published stiffness; × {beyond:g} leaves it by {100 * (beyond / 2.0 - 1):.0f} %); wing EI × 0.7 gives tip "
            f"deflections {_span(c4_tip, '.0f')} % {'above' if min(c4_tip) > 0 else 'off'} the paper's at "
            f"{VARY_ALTITUDE_M:g}-9144 m (`docs/calibration.md` §6, C4), while C3's wing (EI × 0.85, GJ × 1.04) gives "
            f"{_num(c3_crit['tip_deflection_m'], '.4f')} m at the {VARY_ALTITUDE_M:g} m flutter point with fuselage EI "
            f"× 1.75 (paper {_num(paper_tip, '.3f')} m). The nearest joint point found — fuselage EI × 2 (Fig. 4's peak), "
            f"wing EI × 0.7 (about {min(abs(t) for t in c4_tip) - 10:.0f} points outside a 10 % tip-deflection band) — "
            f"makes the symmetric mode critical at "
            f"3048-9144 m (by {_span([-r['gap_sym_minus_anti'] for r in nearest], '.4f')}, true density) with q_f1 "
            f"{_span([r['symmetric']['qf1_ratio'] for r in nearest], '.2f')} of the largest coordinate, at "
            f"{_span(w_near, '.1f')} rad/s (paper {paper_w:.1f}, {_num(100 * (sum(w_near) / len(w_near) / paper_w - 1), '+.0f')} %). "
            f"Within every bound (C3's wing, fuselage EI × 1.75) the symmetric mode is "
            + (f"critical at {VARY_ALTITUDE_M:g} m by {-c3['gap_sym_minus_anti']:.4f}" if c3["gap_sym_minus_anti"] < 0
               else f"not critical at {VARY_ALTITUDE_M:g} m ({_num(c3['gap_sym_minus_anti'], '+.4f')})")
            + f" with q_f1 {c3['symmetric']['qf1_ratio']:.2f} (other altitudes: C5 in `docs/calibration.md` §6).")


def symmetric_bounds_reading() -> str:
    """The reading of the stiffness variants' class boundaries at 6096-9144 m (``MORE_BOUNDS``' rows)."""
    from flexsim.linear.paper_data import TABLE_US

    fe2_08, fe2_08_rho, c3_fe2 = MORE_BOUNDS[1], MORE_BOUNDS[2], MORE_BOUNDS[3]
    rows = {h: _bounds(fe2_08[0], fe2_08[1], None, "US", h) for h in fe2_08[4]}
    rho = {h: _bounds(fe2_08_rho[0], fe2_08_rho[1], fe2_08_rho[2], "US", h) for h in fe2_08_rho[4]}
    c3 = {h: _bounds(c3_fe2[0], c3_fe2[1], None, "US", h) for h in c3_fe2[4]}
    high = (6096.0, 9144.0)
    paper = {row[0]: row for row in TABLE_US}
    sym_q = all(rows[h]["gap_sym_minus_anti"] < 0 and rows[h]["symmetric"]["qf1_ratio"] >= 0.995 for h in high)
    if not (sym_q and rows[3048.0]["gap_sym_minus_anti"] > 0 and all(rho[h]["gap_sym_minus_anti"] > 0 for h in high)
            and all(c3[h]["gap_sym_minus_anti"] < 0 for h in high)):
        raise RuntimeError("symmetric-bounds-reading: the paper's mode (symmetric, q_f1 largest) is no longer critical "
                           "at 6096-9144 m only with the true density; rewrite the reading")
    crit = {h: min(rows[h]["symmetric"]["M_F"], rows[h]["antisymmetric"]["M_F"]) for h in rows}
    crit_rho = {3048.0: crit[3048.0], **{h: min(rho[h]["symmetric"]["M_F"], rho[h]["antisymmetric"]["M_F"]) for h in high}}
    w = [rows[h]["symmetric"]["omega_F"] for h in high]
    return (f"with the fuselage EI at Fig. 4's peak (× 2) and the wing EI at the value the static columns want (× 0.8), "
            f"the critical mode at 6096 and 9144 m is **symmetric with q_f1 the largest linear coordinate** (critical by "
            f"{' and '.join(format(-rows[h]['gap_sym_minus_anti'], '.4f') for h in high)}, true density), at "
            f"{_span(w, '.1f')} rad/s (paper {paper[9144.0][2]:.1f}, "
            f"{_num(100 * (sum(w) / len(w) / paper[9144.0][2] - 1), '+.0f')} %); at 3048 m the antisymmetric twin still "
            f"leads by {rows[3048.0]['gap_sym_minus_anti']:.4f} (q_f1 {rows[3048.0]['symmetric']['qf1_ratio']:.2f} in the "
            f"symmetric one). With C3's wing (EI × 0.85 and GJ × 1.04) the symmetric mode leads at 6096-9144 m with q_f1 "
            f"{_span([c3[h]['symmetric']['qf1_ratio'] for h in high], '.2f')}. But the boundary is then the true-density "
            f"one (M_F {' and '.join(_num(100 * (crit[h] / paper[h][1] - 1), '+.1f') + ' %' for h in high)} against the "
            f"paper; trend {crit[9144.0] / crit[3048.0]:.3f}): with one density for the linearised aerodynamics, which "
            f"gives the paper's trend (ρ(3048 m): {crit_rho[9144.0] / crit_rho[3048.0]:.3f}), the antisymmetric twin leads "
            f"again at 6096-9144 m, by {_span([rho[h]['gap_sym_minus_anti'] for h in high], '.4f')}")


# --- the density section: which twin each density makes critical ------------------------------------------------

def _critical(row: dict) -> dict:
    """The critical crossing of a class-boundary row (the lower Mach) with its class."""
    s, a = _both(row, "density-symmetric-findings")
    return {**(s if s["M_F"] < a["M_F"] else a), "class": "symmetric" if s["M_F"] < a["M_F"] else "antisymmetric"}


def _where(rows: dict[float, dict], symmetric: bool) -> str:
    hs = [h for h, r in sorted(rows.items()) if (r["gap_sym_minus_anti"] < 0) == symmetric]
    if not hs:
        return "nowhere"
    return f"at {hs[0]:g}-{hs[-1]:g} m" if len(hs) > 1 else f"at {hs[0]:g} m"


def density_symmetric_findings() -> str:
    """The three findings on the symmetric-mode structure and C5 (the density section's class-boundary rows,
    ``docs_figures_studies._bounds_rows``' configurations, shared with density-symmetric-structure and
    calibration-c5)."""
    from docs_figures_studies import C5_STRUCTURE, SYM_STRUCTURE

    from flexsim.atmosphere import isa_density
    from flexsim.linear.paper_data import TABLE_US

    paper = {row[0]: row for row in TABLE_US}
    paper_ratio = paper[9144.0][1] / paper[3048.0][1]

    def rows(structure, fixed, altitudes) -> dict[float, dict]:
        a, f = structure
        return {h: _bounds(a, f, None if fixed == h else fixed, "US", h) for h in altitudes}

    def ratio(r: dict[float, dict]) -> float:
        return _critical(r[9144.0])["M_F"] / _critical(r[3048.0])["M_F"]

    high = PAPER_ALTITUDES_M[1:]
    true, r3048, r0 = (rows(SYM_STRUCTURE, None, high), rows(SYM_STRUCTURE, 3048.0, PAPER_ALTITUDES_M),
                       rows(SYM_STRUCTURE, 0.0, high))
    c_lo, c_hi = _critical(r0[3048.0])["M_F"], _critical(r3048[3048.0])["M_F"]
    p3048 = paper[3048.0][1]
    if not (c_lo < p3048 < c_hi and min(abs(c_lo / p3048 - 1), abs(c_hi / p3048 - 1)) > 0.03):
        raise RuntimeError("density-symmetric-findings: the paper's 3048 m level is no longer bracketed by rho(0) and "
                           "rho(3048 m), or one of them meets 3 %; rewrite finding (2)")
    grows = all(all(b["gap_sym_minus_anti"] > a["gap_sym_minus_anti"] for a, b in zip(list(r.values())[:-1],
                                                                                         list(r.values())[1:]))
                for r in (r3048, r0))
    omegas = [r["symmetric"]["omega_F"] for rr in (true, r3048, r0) for r in rr.values()]
    c5_true, c5_1524 = rows(C5_STRUCTURE, None, high), rows(C5_STRUCTURE, 1524.0, (3048.0, 9144.0))
    crit = {h: _critical(r) for h, r in c5_1524.items()}
    off = max([abs(crit[h]["M_F"] / paper[h][1] - 1) for h in crit] + [abs(ratio(c5_1524) / paper_ratio - 1)])
    classes = {c["class"] for c in crit.values()}
    sym_above = [r["gap_sym_minus_anti"] for r in c5_1524.values()]
    twin = (f"in the antisymmetric twin ({_span([c['omega_F'] for c in crit.values()], '.1f')} rad/s; the symmetric "
            f"mode {_span(sym_above, '.4f')} above)" if classes == {"antisymmetric"} else
            f"in the {' and '.join(sorted(classes))} twin")
    return (f"(1) The trend again follows from any single density ({ratio(r3048):.3f} with ρ(3048 m), {ratio(r0):.3f} "
            f"with ρ(0); true density {ratio(true):.3f}; the paper {paper_ratio:.3f}), on this structure as on the bundled "
            f"one. (2) The level brackets the density: with ρ(3048 m) the critical M_F at 3048 m is {c_hi:.4f}, with ρ(0) "
            f"{c_lo:.4f}, and the paper's {p3048:.4f} lies between — a density between {float(isa_density(3048.0)):.3f} "
            f"and {float(isa_density(0.0)):.3f} kg/m³; neither natural value (the flight's at 3048 m, or sea level's from "
            "a linearisation about Z = 0) meets 3 % at 3048 m on this structure. (3) **The density decides which twin "
            "is critical**: the symmetric mode gains on the antisymmetric one as the density of the perturbation "
            f"aerodynamics falls (true density, falling with altitude: symmetric critical {_where(true, True)}; one "
            f"density: the gap {'grows' if grows else 'does not grow monotonically'} with altitude, ρ(3048 m) leaves the "
            f"symmetric mode critical only {_where(r3048, True)}, ρ(0) {_where(r0, True)}). So no single density and "
            "structure found gives the paper's trend *and* its symmetric mode at 3048-9144 m; the densities that match "
            f"the level put the antisymmetric twin first, and the symmetric mode flutters at {_span(omegas, '.1f')} rad/s "
            f"(paper {paper[3048.0][2]:.1f}) in every row. The same holds on the structure with every factor inside its "
            f"bound (C5 of `docs/calibration.md` §6: C3's wing, fuselage EI × 1.75): ρ(1524 m) = "
            f"{float(isa_density(1524.0)):.3f} kg/m³ gives the critical M_F {crit[3048.0]['M_F']:.4f} / "
            f"{crit[9144.0]['M_F']:.4f} at 3048 / 9144 m, within {100 * off:.1f} % of the paper's level and trend (ratio "
            f"{ratio(c5_1524):.3f}), but {twin}, while the true density makes the symmetric mode critical "
            f"{_where(c5_true, True)} with the true-density trend ({ratio(c5_true):.3f})")


# --- the density section: which density the level and the frequency point to -------------------------------------

@functools.cache
def _density_trade() -> dict:
    """The density-fixed rows (``docs_figures_studies._density_rows``, ``density_finding.py --fixed 0 3048``) read as
    power laws: V_F^2/sqrt(1-M^2) ~ rho^n on the bundled structure, the density the paper's level implies, and the
    one the paper's frequency implies after scaling the whole stiffness to match it."""
    import numpy as np
    from docs_figures_studies import _density_rows

    from flexsim.atmosphere import isa_density
    from flexsim.linear.paper_data import TABLE_US

    by = {}
    for r in _density_rows():
        by.setdefault(r["density"], {})[r["altitude_m"]] = r
    rho0, rho3 = float(isa_density(0.0)), float(isa_density(3048.0))
    hs = PAPER_ALTITUDES_M[1:]
    n = float(np.mean([math.log(by["rho(3048 m)"][h]["V2PG_k"] / by["rho(0 m)"][h]["V2PG_k"]) / math.log(rho3 / rho0)
                       for h in PAPER_ALTITUDES_M]))
    v2 = {k: float(np.mean([by[k][h]["V2PG_k"] for h in hs])) for k in ("rho(0 m)", "rho(3048 m)")}
    paper_v2 = float(np.mean([_paper_v2(h, m) for h, m, *_ in TABLE_US if h in hs]))
    rho_level = rho0 * (paper_v2 / v2["rho(0 m)"]) ** (1.0 / n)
    lo, hi = 0.0, 11000.0
    for _ in range(60):  # the ISA altitude of rho_level (isa_density falls with altitude)
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if float(isa_density(mid)) > rho_level else (lo, mid)
    omegas = [by[k][h]["omega_F"] for k in ("rho(0 m)", "rho(3048 m)") for h in PAPER_ALTITUDES_M]
    paper_w = float(np.mean([w for h, m, w, *_ in TABLE_US if h in hs]))
    ratio = paper_w / float(np.mean([by[k][h]["omega_F"] for k in ("rho(0 m)", "rho(3048 m)") for h in hs]))
    return {"n": n, "paper_v2": paper_v2, "rho_level": rho_level, "isa_alt": 0.5 * (lo + hi),
            "speed_rho0": math.sqrt(paper_v2 / v2["rho(0 m)"]) - 1, "speed_rho3048": math.sqrt(paper_v2 / v2["rho(3048 m)"]) - 1,
            "omegas": omegas, "paper_w": paper_w, "v_drop": [1 - paper_w / w for w in omegas],
            "rho_frequency": rho_level * ratio ** (-2.0 / n)}


def _paper_v2(altitude_m: float, mach: float) -> float:
    """V^2/sqrt(1-M^2) [10^3 m^2/s^2] of a row of the paper's Table 3."""
    from flexsim.atmosphere import speed_of_sound

    v = mach * float(speed_of_sound(altitude_m))
    return v * v / math.sqrt(1 - mach * mach) / 1e3


def density_which() -> str:
    """What the density-fixed rows say about the density the paper's level and frequency imply."""
    d = _density_trade()
    drop = sorted(100 * x for x in d["v_drop"])
    return (f"V_F²/√(1−M²) ∝ ρ^{_num(d['n'], '.1f')} between the two rows above, so the paper's "
            f"{d['paper_v2']:.0f}k m²/s² (3048-9144 m) corresponds to ρ ≈ {d['rho_level']:.1f} kg/m³ (ISA ≈ "
            f"{round(d['isa_alt'], -2):.0f} m), a value with no special meaning; ρ(0) needs a structure whose flutter "
            f"speed is {100 * d['speed_rho0']:.0f} % higher, ρ(3048 m) one {-100 * d['speed_rho3048']:.0f} % lower. "
            f"Matching ω_F as well ({d['paper_w']:.1f} against flexsim's {_span(d['omegas'], '.1f')} rad/s) by scaling "
            f"the whole stiffness (ω_F and V_F ∝ √k at a fixed density) lowers V_F by {drop[0]:.0f}-{drop[-1]:.0f} %, "
            f"which a lower density (V_F ∝ ρ^{_num(d['n'] / 2, '.2f')}) must restore: that points to")


def density_frequency_match() -> str:
    """The density the paper's frequency points to (``density_which``'s last step)."""
    return f"ρ ≈ {_density_trade()['rho_frequency']:.1f} kg/m³"


# --- the density section: what the static columns' structure (C3) says ---------------------------------------------

def _c3(config: str) -> dict:
    """C3's US flutter row at 3048 m (``docs_figures_calibration.flutter_row``, the rows of docs/calibration.md §6)."""
    from docs_figures_calibration import flutter_row

    row = flutter_row(config, "US", 3048.0)
    if row is None:
        raise RuntimeError(f"density-c3: {config} has no US crossing at 3048 m")
    return row


def _pct(row: dict, key: str) -> str:
    return f"{_num(100 * (row[key] / row['paper'][key] - 1), '+.1f')} %"


def density_c3() -> str:
    """C3 (the wing of the static columns) at 3048 m with the linearised aerodynamics at rho(0) and rho(3048 m)."""
    r0, r3 = _c3("C3"), _c3("C3, ρ(3048 m)")
    return (f"w_tip {_pct(r0, 'tip_deflection_m')}, ψ_tip {_pct(r0, 'tip_twist_deg')} at 3048 m); with that structure "
            f"the US flutter Mach at 3048 m is {r0['M_F']:.4f} ({_pct(r0, 'M_F')}) with the linearised aerodynamics at "
            f"ρ(0) and {r3['M_F']:.4f} ({_pct(r3, 'M_F')}) with ρ(3048 m)")


def density_c3_mode() -> str:
    """C3's frequency and mode class at 3048 m with rho(0)."""
    r0 = _c3("C3")
    return (f"{r0['omega_F']:.1f} rad/s ({_pct(r0, 'omega_F')}) and in the "
            f"{'symmetric' if r0['sym_share'] > 0.5 else 'antisymmetric'} mode")


def density_static_columns() -> str:
    """The density at which C3's US flutter Mach at 3048 m meets the paper's, interpolated in ln(rho)."""
    from flexsim.atmosphere import isa_density

    r0, r3 = _c3("C3"), _c3("C3, ρ(3048 m)")
    target = r0["paper"]["M_F"]
    if not min(r0["M_F"], r3["M_F"]) < target < max(r0["M_F"], r3["M_F"]):
        raise RuntimeError("density-static-columns: the paper's 3048 m flutter Mach is not between C3's with rho(0) "
                           "and rho(3048 m); rewrite the reading")
    s = (target - r0["M_F"]) / (r3["M_F"] - r0["M_F"])
    ln_rho = math.log(float(isa_density(0.0))) + s * (math.log(float(isa_density(3048.0))) - math.log(float(isa_density(0.0))))
    return f"≈ {math.exp(ln_rho):.1f} kg/m³"


# --- the density section: what the paper's own tables imply (fast: printed values only) ------------------------

def _paper(table: str) -> dict[float, dict]:
    """``density_finding.paper_quantities`` of Table 2 ("QS") or 3 ("US"), keyed by altitude [m]."""
    import density_finding

    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    return {r["altitude_m"]: r for r in density_finding.paper_quantities(TABLE_QS if table == "QS" else TABLE_US)}


def _spread(values) -> float:
    """max / min - 1 of positive values [-]."""
    return max(values) / min(values) - 1


def density_paper_boundary() -> str:
    """The paper's US boundary from 3048 to 9144 m: V^2/sqrt(1-M^2) and omega_F nearly constant while the density
    and the scaled dynamic pressure halve."""
    us = _paper("US")
    hs = PAPER_ALTITUDES_M[1:]
    a, b = us[hs[0]], us[hs[-1]]
    return (f"keeps V²/√(1−M²) within {100 * _spread([us[h]['V2PG_k'] for h in hs]):.0f} % and ω_F within "
            f"{100 * _spread([us[h]['omega_F'] for h in hs]):.2f} % ({' / '.join(format(us[h]['omega_F'], '.3f') for h in hs)} rad/s) "
            f"while the air density falls from {a['rho']:.3f} to {b['rho']:.3f} kg/m³ (× {b['rho'] / a['rho']:.2f}) and "
            f"the Prandtl–Glauert-scaled dynamic pressure from {a['qPG_kPa']:.1f} to {b['qPG_kPa']:.1f} kPa "
            f"(× {b['qPG_kPa'] / a['qPG_kPa']:.2f})")


def density_paper_trim() -> str:
    """The paper's trims (both tables): q_F * theta nearly constant while q_F changes, and T_e / sin(theta)."""
    rows = [*_paper("QS").values(), *_paper("US").values()]
    qt = [r["q_theta"] for r in rows]
    w = [r["weight_kN"] for r in rows]
    return (f"q_F·θ (lift ≈ q·α) stays at {min(qt):.0f}-{max(qt):.0f} Pa·rad while q_F changes "
            f"{max(r['q_kPa'] for r in rows) / min(r['q_kPa'] for r in rows):.1f}-fold, and T_e = "
            f"{sum(w) / len(w):.1f} kN × sin θ in every row (within {max(w) - min(w):.2f} kN)")


def density_paper_speed() -> str:
    """The paper's US flutter speed and frequency change from 3048 to 9144 m."""
    us = _paper("US")
    a, b = us[3048.0], us[9144.0]
    return (f"V_F {a['V_F']:.1f} → {b['V_F']:.1f} m/s, ω_F {_num(100 * (b['omega_F'] / a['omega_F'] - 1), '+.2f')} %")


def density_paper_qs() -> str:
    """The paper's QS table from 3048 to 6096 m: V^2/sqrt(1-M^2) and omega_F."""
    qs = _paper("QS")
    a, b = qs[3048.0], qs[6096.0]
    return (f"V²/√(1−M²) {'drops' if b['V2PG_k'] < a['V2PG_k'] else 'rises'} by "
            f"{abs(100 * (b['V2PG_k'] / a['V2PG_k'] - 1)):.0f} % from 3048 to 6096 m at "
            f"{a['omega_F']:.2f} / {b['omega_F']:.2f} rad/s")


def density_paper_altitude() -> str:
    """The paper's US flutter speeds over 0-9144 m and its rise of M_F from 3048 to 9144 m."""
    us = _paper("US")
    v = [r["V_F"] for r in us.values()]
    return (f"({min(v):.0f}-{max(v):.0f} m/s) and the slow rise of M_F with altitude "
            f"({_num(100 * (us[9144.0]['M_F'] / us[3048.0]['M_F'] - 1), '+.1f')} % from 3048 to 9144 m)")


def density_true_rise() -> str:
    """The rise of the bundled gtm's US flutter Mach from 3048 to 9144 m with the true density (the density-fixed
    rows)."""
    from docs_figures_studies import _density_rows

    true = {r["altitude_m"]: r for r in _density_rows() if r["density"] == "true"}
    return f"{_num(100 * (true[9144.0]['M_F'] / true[3048.0]['M_F'] - 1), '+.0f')} %"


def density_turn_growth() -> str:
    """C1's symmetric-mode turn effect M_F(5 km) - M_F(12 km) at 0-9144 m (the scorecard rows of docs/calibration.md
    §7, ``docs_figures_calibration.scorecard_row``) and whether it grows monotonically with altitude."""
    from docs_figures_calibration import scorecard_row

    effect = [scorecard_row("C1", h)["turn_dM"] for h in PAPER_ALTITUDES_M]
    grows = all(b > a for a, b in zip(effect[:-1], effect[1:]))
    return (f"{'grows monotonically' if grows else 'does not grow monotonically'} with altitude, "
            f"{' / '.join(_num(e, '.4f') for e in effect)} at {' / '.join(f'{h:g}' for h in PAPER_ALTITUDES_M)} m")


# --- in-vacuo frequencies and the options table quoted in prose (fast) ---------------------------------------------

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


def flutter_mode_frequencies(level) -> str:
    """The US flutter frequencies of the bundled gtm (``level("US")``, the docs tool's rows) against its in-vacuo
    fuselage bending 1 and wing torsion 1."""
    w = [r["omega_rad_s"] for r in level("US").values()]
    fus, t_s, t_a = (_vacuo("gtm", k) for k in ("fuselage bending 1", "wings torsion 1 (symmetric)",
                                                "wings torsion 1 (antisymmetric)"))
    if not fus < min(w) <= max(w) < min(t_s, t_a):
        raise RuntimeError("flutter-mode-frequencies: the flutter frequency is no longer between the fuselage's first "
                           "bending and the wings' first torsion")
    return (f"{_span(w, '.1f')} rad/s (US), between the fuselage's first bending ({fus:.1f} rad/s in vacuo) and the "
            f"wings' first torsion ({t_s:.1f}/{t_a:.1f} rad/s, symmetric/antisymmetric)")


def flutter_study_evaluations(study) -> str:
    """Model evaluations (trim + linearisation + eigen-analysis) of the default turn and climb studies
    (``study("turn")``, ``study("climb")``: the docs tool's rows of ``flexsim sweep --turn`` / ``--climb``)."""
    rows = [r for kind in ("turn", "climb") for r in study(kind)]
    evaluations = [int(r["evaluations"]) for r in rows]
    chains = {(r["model"], r["altitude_m"]) for r in rows}
    return (f"the {len(rows)} points of the two studies ({len(chains)} chains of model and altitude per study) take "
            f"{sum(evaluations)} evaluations, {sum(evaluations) / len(rows):.1f} per point on average "
            f"({min(evaluations)}-{max(evaluations)})")


def symmetric_wing_bending_vacuo() -> str:
    """The in-vacuo frequency of gtm_paper's symmetric wing first bending."""
    return f"{_vacuo('gtm_paper', 'wings bending 1 (symmetric)'):.1f} rad/s in vacuo"


def options_paper_turn_effect() -> str:
    """The paper's turn (R = 5 km) against level flight at sea level (finite state; options-effects-flutter's points)."""
    from docs_figures_static import options_effects_points

    points = dict(options_effects_points())
    level, turn = points["level flight, bundled `gtm`"], points["turn R = 5 km, the paper's (heading on track)"]
    return f"{_num(100 * (turn.mach / level.mach - 1), '+.2f')} % at R = 5 km"


#: The figures of this module (all long studies; CPU on a quiet machine: the finite-state bounds about 2 min, the
#: vary table about 15-20 min, each decomposition switch about 30 s). ``regenerate_docs_figures.py`` registers them.
RECORD_FIGURES = {name: Figure(compute, long=True) for name, compute in {
    "symmetric-bounds-fs": symmetric_bounds_fs,
    "symmetric-force-resolution": symmetric_force_resolution,
    "symmetric-vary": symmetric_vary,
    "symmetric-vary-reading": symmetric_vary_reading,
    "symmetric-bounds-reading": symmetric_bounds_reading,
    "symmetric-soft-torsion": symmetric_soft_torsion,
    "decomposition-reading": decomposition_reading,
    "decomposition-fin": decomposition_fin,
    "decomposition-c1": decomposition_c1,
    "decomposition-c4": decomposition_c4,
    "decomposition-c5": decomposition_c5,
    "decomposition-paper-mode": decomposition_paper_mode,
    "options-body-moments-pk": options_body_moments_pk,
}.items()}
#: Slow, not long: it reads the class-boundary rows density-symmetric-structure and calibration-c5 compute.
RECORD_FIGURES["density-symmetric-findings"] = Figure(density_symmetric_findings)
RECORD_FIGURES["density-which"] = Figure(density_which)
RECORD_FIGURES["density-frequency-match"] = Figure(density_frequency_match)
RECORD_FIGURES["density-c3"] = Figure(density_c3)
RECORD_FIGURES["density-c3-mode"] = Figure(density_c3_mode)
RECORD_FIGURES["density-static-columns"] = Figure(density_static_columns)
RECORD_FIGURES["density-true-rise"] = Figure(density_true_rise)
RECORD_FIGURES["density-turn-growth"] = Figure(density_turn_growth)
RECORD_FIGURES.update({name: Figure(compute, fast=True) for name, compute in {
    "density-paper-boundary": density_paper_boundary, "density-paper-trim": density_paper_trim,
    "density-paper-speed": density_paper_speed, "density-paper-qs": density_paper_qs,
    "density-paper-altitude": density_paper_altitude, "symmetric-wing-bending-vacuo": symmetric_wing_bending_vacuo,
    "options-paper-turn-effect": options_paper_turn_effect}.items()})
