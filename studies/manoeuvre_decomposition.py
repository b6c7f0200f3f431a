"""What makes flutter depend on the manoeuvre: the decomposition of the turn and climb effects.

At one altitude (default 9144 m) the US (Theodorsen p-k) flutter Mach number of

* level flight, the level turns R = 5 km and R = 12 km (paper eqs. 36-37) and the climbs gamma = +-15 deg
  (eqs. 38-39)

is computed with the aircraft trimmed as usual (the one nonlinear model, true density) and the *linear model*
of the flutter analysis built with one ingredient switched off at a time. The switches modify the linearisation
point or the physical terms of the linear model (a field of :class:`flexsim.model.terms.Terms`, chosen when the
model is built), never the trim, and are listed in ``SWITCHES``:

======================  ===========================================================================================
``none``                the reference: linearised about the trim as in ``FlutterAnalysis``
``rotation``            body rotation rates omega := 0 in the linearisation point (centripetal and Coriolis terms
                        of eq. 33, dT/dq, and the steady rotation's contribution to the strip velocities)
``mass_matrix``         M(q), dT/dq and M_dot evaluated at the level-flight static deformation (same Mach) instead
                        of the manoeuvre's: the static deflection's effect on the inertia
                        (``Terms.inertia_q_offset_m`` = level q - manoeuvre q)
``static_deformation``  q, xi := level-flight static deformation in the whole linearisation point (inertia and
                        aerodynamics)
``force_resolution``    the trim-alpha terms of the strip force resolution removed from the linear model: the lift
                        tilt L a0 and the drag (c_n = -L, c_d = 0 in strip axes; eq. 28 with alpha_i0 = 0, d = 0;
                        ``Terms.force_resolution = "normal"``)
``aero_alpha``          the aerodynamics linearised about the level-flight body velocity (angle of attack and
                        sideslip of the level trim at the same Mach), structure about the manoeuvre
                        (``Terms.aero_velocity_offset_m_s`` = level v - manoeuvre v)
``thrust``              the thrust line's stiffness removed (its arm follows bending, eqs. 17-24:
                        ``Terms.thrust_follows_deflection = False``)
``gravity``             g := 0 in the linear model (eq. 32; ``Terms.gravity_m_s2``)
``prandtl_glauert``     the Prandtl-Glauert factor of the linear model frozen at the level flight's flutter Mach
                        (``Terms.compressibility_mach``)
``damping``             structural damping ratio 0 instead of the aircraft's (``Terms.structural_damping``)
``density``             the linearised aerodynamics at one density, rho(``--rho-altitude``, default 3048 m), trim at
                        the true density (the paper-replication hypothesis of docs/flutter.md); with
                        ``--fixed-density`` the reference is at the fixed density and this switch restores the true
                        one (``Terms.aero_density_kg_m3``)
``fin_normal``          (not in the default set) the fin's lift without tilt or drag in the linear model: c_n = -L,
                        c_d = 0 on the fin's strips (bounds any resolution of the fin's lift, eq. 31;
                        ``Terms.force_resolution = "fin-normal"``)
``fin_drag<k>``         (not in the default set) the paper's fin, eqs. 29-31: section drag *linear* in the fin's
                        angle, d_v = q c C_Dav a_v = k l_v with k = C_Dav / C_Lav (the paper gives no value; e.g.
                        ``fin_drag+0.1``; the sign of the paper's y_v relative to the chord is not stated, so both
                        signs are run), resolved with the fin's flow angle, in the linear model
                        (``Terms.fin_drag_per_lift``)
======================  ===========================================================================================

Every row records the terms of its linear model (``terms``: the fields of :class:`Terms` that differ from the full
model; the offsets, which differ from case to case, as the switch's name).

``--formulation paper`` uses the library's force resolution of the paper (``AeroOptions(formulation="paper")``,
docs/design.md "Force resolution": eq. 28 with alpha_i0 = W/U and d = l alpha_i0, no body-x component of a wing or
stabilizer strip force, in trim and in the linear model; T_e = W sin(theta)). Under it the ``force_resolution``
switch is a no-op (there are no trim-alpha terms left to remove).

The flutter Mach of each case is found by a secant/bisection search on the largest real part of the elastic
modes, started from the level-flight flutter Mach of the same switch (tolerance 5e-5 in Mach), which is cheaper
than a full grid search and finds the same crossing when it is continuous in the manoeuvre parameter (it is,
here: all crossings lie within 0.01 of the level one).

Prints a markdown table (and writes JSON with ``--json``). Run (about 3-6 min per switch set on a loaded 2-core
machine; 1 BLAS thread)::

    python studies/manoeuvre_decomposition.py --aircraft gtm --altitude 9144 [--switches none rotation ...]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from flexsim.aircraft.calibration import StructuralScaling  # noqa: E402
from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.atmosphere import isa_density, speed_of_sound  # noqa: E402
from flexsim.linear.stability import spectrum  # noqa: E402
from flexsim.model.aircraft_model import AircraftModel  # noqa: E402
from flexsim.model.coupling import AeroOptions  # noqa: E402
from flexsim.model.terms import Terms  # noqa: E402
from flexsim.structure.mirror import ranked  # noqa: E402
from flexsim.trimming import SteadyManoeuvre, trim  # noqa: E402

SWITCHES = ("none", "rotation", "mass_matrix", "static_deformation", "force_resolution", "aero_alpha", "thrust",
            "gravity", "prandtl_glauert", "damping", "density")
#: Study switches of the paper's fin model (eqs. 29-31), not in the default set: ``fin_normal`` (the fin's lift without
#: tilt or drag) and ``fin_drag<kappa>`` (section drag linear in the fin's angle, d_v = kappa l_v, e.g. ``fin_drag+0.1``).
FIN_SWITCHES = ("fin_normal", "fin_drag+0.1", "fin_drag-0.1", "fin_drag+0.3", "fin_drag-0.3")
#: Switches that leave the level-flight linear model unchanged (the level case is then taken from ``none``).
LEVEL_NEUTRAL = ("rotation", "mass_matrix", "static_deformation", "aero_alpha")
CASES = {"level": (math.inf, 0.0), "R5km": (5000.0, 0.0), "R12km": (12000.0, 0.0),
         "g+15": (math.inf, 15.0), "g-15": (math.inf, -15.0)}


def configure(name: str, scaling: dict | None, mass_factor: float, incidence: tuple[float, float] | None,
              damping: float | None):
    """The study aircraft: ``name`` with StructuralScaling factors, every mass and inertia times ``mass_factor``
    (stiffness unchanged), rigging incidence [deg] of the wing and stabilizer strips, structural damping.

    ``mass_factor`` = 0.907 gives the paper's weight, 889.4 kN (= T_e / sin(theta) in all eight rows of Tables 2-3);
    incidence (1.81, 2.7) deg puts the streamwise chords parallel to body x (the paper's section angle of attack is
    W/U plus the elastic twist, eq. 28; the Table 1 dihedral about the swept axis tilts them by -1.81 and -2.7 deg).
    """
    ac = load_aircraft(name)
    if scaling:
        ac = StructuralScaling(**scaling).apply(ac)
    comps = []
    for c in ac.components:
        if incidence is not None and c.aero is not None:
            inc = incidence[0] if "wing" in c.name else incidence[1] if "htail" in c.name else None
            if inc is not None:
                c = replace(c, aero=replace(c.aero, incidence_rad=math.radians(inc)))
        if mass_factor != 1.0:
            s = c.sections
            c = replace(c, sections=replace(s, mass_kg_per_m=s.mass_kg_per_m * mass_factor,
                                            torsional_inertia_kg_m=s.torsional_inertia_kg_m * mass_factor))
        comps.append(c)
    k = mass_factor
    ac = replace(ac, components=tuple(comps),
                 lumped_masses=tuple(replace(m, mass_kg=m.mass_kg * k, inertia_kg_m2=m.inertia_kg_m2 * k) for m in ac.lumped_masses),
                 engines=tuple(replace(e, mass_kg=e.mass_kg * k, inertia_kg_m2=e.inertia_kg_m2 * k) for e in ac.engines))
    if damping is not None:
        ac = replace(ac, structural_damping_ratio=damping)
    return ac


@dataclass
class Setup:
    aircraft: object
    altitude_m: float
    switch: str
    rho_altitude_m: float
    mach_pg: float | None = None  # level flutter Mach for the prandtl_glauert switch
    model: str = "US"  # "US" (Theodorsen p-k, the paper's Table 3), "FS" (finite state) or "QS" (quasi-steady, Table 2)
    base_rho_altitude_m: float | None = None  # None: the reference linear model uses the true density
    formulation: str = "physical"  # or "paper": the library's force resolution of eq. 28 (AeroOptions.formulation)
    mode_class: str = "any"  # "symmetric" / "antisymmetric": only modes with more than half their energy in that class


class Decomposition:
    """Trim with the true model, eigen-analysis (p-k) with the switched linear model."""

    def __init__(self, setup: Setup):
        self.s = setup
        ac = setup.aircraft
        self.trim_model = AircraftModel(ac, aero=AeroOptions("quasi-steady", formulation=setup.formulation))
        self._trim_guess = {}
        self.last_terms = None  # the terms of the last evaluation's linear model

    def terms(self, point, level_point) -> Terms:
        """The physical terms of the linear models at ``point`` (the trim of a case; ``level_point``: the level trim
        at the same speed): the reference's, with the one term of the switch changed (:class:`Terms`)."""
        s = self.s
        kw = {}
        if s.switch == "gravity":
            kw["gravity_m_s2"] = 0.0
        if s.switch == "damping":
            kw["structural_damping"] = 0.0
        fixed = s.base_rho_altitude_m
        if s.switch == "density":  # the density switch toggles between the true and one fixed density
            fixed = s.rho_altitude_m if fixed is None else None
        if fixed is not None:
            kw["aero_density_kg_m3"] = float(isa_density(fixed))
        if s.switch == "prandtl_glauert":
            kw["compressibility_mach"] = s.mach_pg
        if s.switch == "force_resolution" and s.formulation == "physical":
            kw["force_resolution"] = "normal"
        if s.switch == "fin_normal":
            kw["force_resolution"] = "fin-normal"
        if s.switch.startswith("fin_drag"):  # fin_drag+0.1: the paper's fin drag with kappa = C_Dav/C_Lav = +0.1
            kw["fin_drag_per_lift"] = float(s.switch[len("fin_drag"):])
        if s.switch == "thrust":
            kw["thrust_follows_deflection"] = False
        lay = self.trim_model.layout
        if s.switch == "aero_alpha":
            kw["aero_velocity_offset_m_s"] = tuple(level_point.x[lay.velocity][0:3] - point.x[lay.velocity][0:3])
        if s.switch == "mass_matrix":
            kw["inertia_q_offset_m"] = tuple(level_point.x[lay.q] - point.x[lay.q])
        return Terms(aero=AeroOptions("quasi-steady", formulation=s.formulation), **kw)

    def _linear_models(self, point, level_point):
        """The quasi-steady and finite-state models of the eigen-analysis and the linearisation point (x, u)."""
        s = self.s
        terms = self.terms(point, level_point)
        qs = AircraftModel(s.aircraft, terms=terms)
        fs = AircraftModel(s.aircraft, terms=replace(terms, aero=AeroOptions("unsteady", 6, formulation=s.formulation)))
        x, u = point.x.copy(), point.u.copy()
        lay = self.trim_model.layout
        if s.switch == "rotation":
            x[lay.velocity.start + 3: lay.velocity.start + 6] = 0.0
        if s.switch == "static_deformation":
            x[lay.q] = level_point.x[lay.q]
            x[lay.xi] = level_point.x[lay.xi]
        return qs, fs, x, u

    def g(self, case: str, mach: float) -> tuple[float, object]:
        """Largest real part of the elastic modes [1/s] at ``mach`` in ``case`` (and the critical mode)."""
        radius, gamma_deg = CASES[case]
        a = speed_of_sound(self.s.altitude_m)
        man = SteadyManoeuvre(mach * a, self.s.altitude_m, turn_radius_m=radius, climb_angle_rad=math.radians(gamma_deg))
        point = trim(self.trim_model, man, guess=self._trim_guess.get(case), check_limits=False)
        self._trim_guess[case] = point
        level = point
        if case != "level" and self.s.switch in LEVEL_NEUTRAL:
            level = trim(self.trim_model, SteadyManoeuvre.level(self.s.altitude_m, speed_m_s=mach * a),
                         guess=self._trim_guess.get("level"), check_limits=False)
        qs, fs, x, u = self._linear_models(point, level)
        if self.s.model == "QS":
            spec = spectrum(qs, x, u, aero_model="quasi-steady")
        elif self.s.model == "FS":  # finite-state state space, inflow states at zero in the steady trim
            spec = spectrum(fs, np.concatenate([x, np.zeros(fs.layout.n_inflow)]), u, aero_model="unsteady")
        else:
            spec = spectrum(qs, x, u, aero_model="theodorsen", pk_model=fs)
        self.last = (point, spec, qs)
        self.last_terms = qs.terms
        if self.s.mode_class == "any":
            return spec.max_real("elastic"), spec.critical("elastic")
        want = self.s.mode_class == "symmetric"
        cands = [m for m in spec.of_kind("elastic") if m.frequency_rad_s >= 0.5
                 and (mode_info(qs, m)["sym_share"] > 0.5) == want]
        crit = max(cands, key=lambda m: m.eigenvalue.real)
        return crit.eigenvalue.real, crit

    def flutter_mach(self, case: str, start: float, tol: float = 5e-5) -> tuple[float, float, int]:
        """Secant with bisection safeguard from ``start``; returns (M_F, omega_F, evaluations)."""
        n = 0
        m0 = start
        g0, _ = self.g(case, m0)
        n += 1
        step = -0.004 if g0 > 0 else 0.004
        m1 = m0 + step
        g1, _ = self.g(case, m1)
        n += 1
        while g0 * g1 > 0:  # widen until bracketed
            step *= 2.0
            m0, g0 = m1, g1
            m1 = m1 + step
            if not 0.3 < m1 < 0.97:
                raise RuntimeError(f"{case}: no crossing near M {start:.4f}")
            g1, _ = self.g(case, m1)
            n += 1
        lo, glo, hi, ghi = (m0, g0, m1, g1) if m0 < m1 else (m1, g1, m0, g0)
        while hi - lo > tol:
            m = hi - ghi * (hi - lo) / (ghi - glo)  # regula falsi (Illinois) safeguarded
            if not lo < m < hi:
                m = 0.5 * (lo + hi)
            gm, _ = self.g(case, m)
            n += 1
            if gm > 0:
                hi, ghi = m, gm
                glo *= 0.5
            else:
                lo, glo = m, gm
                ghi *= 0.5
            if abs(gm) < 1e-6:
                lo = hi = m
        mf = 0.5 * (lo + hi)
        _, mode = self.g(case, mf)
        self.mode = mode
        return mf, mode.frequency_rad_s, n + 1


def changed_terms(terms: Terms) -> dict:
    """The fields of ``terms`` that differ from the full model's (:meth:`Terms.record`; the aerodynamic options in
    full); offsets, which depend on the case, as ``"level minus case"``."""
    full = Terms(aero=terms.aero).record()
    out = {"aero": full["aero"]}
    for name, value in terms.record().items():
        if value != full[name]:
            out[name] = "level minus case" if name.endswith("_offset_m") or name.endswith("_offset_m_s") else value
    return out


def mode_info(model: AircraftModel, mode) -> dict:
    """Symmetric share of the mode's kinetic energy (M(0); the library's mirror operator,
    :mod:`flexsim.structure.mirror`), |q_f1| / largest linear elastic displacement (bending coordinates, as the
    paper's Figs. 11/16 rank them) and that coordinate."""
    labels = model.structure.dofs.labels
    m0 = model.structure.inertia.mass_matrix(np.zeros(model.structure.dofs.nq))
    phi = mode.shape
    share = model.structure.mirror.symmetric_fraction(np.asarray(phi, dtype=complex), m0)
    disp = np.abs(phi / mode.eigenvalue)
    linear = [i for i, lab in enumerate(labels) if "bending" in lab]  # the linear elastic displacements [m]
    qf1 = labels.index("fuselage bending 1")
    big = ranked(disp, model.structure.mirror, candidates=linear)[0]  # mirror ties: the right half first
    return {"sym_share": round(share, 3), "qf1_ratio": round(float(disp[qf1] / disp[big]), 3),
            "largest": labels[big]}


def run(ac, aircraft_name: str, altitude_m: float, switches, rho_altitude_m: float, level_start: float,
        cases=tuple(CASES), ref_level: tuple[float, float] | None = None, base_rho_altitude_m: float | None = None,
        formulation: str = "physical", mode_class: str = "any") -> list[dict]:
    rows = []
    for sw in switches:
        t0 = time.time()
        setup = Setup(ac, altitude_m, sw, rho_altitude_m, base_rho_altitude_m=base_rho_altitude_m, formulation=formulation,
                      mode_class=mode_class)
        dec = Decomposition(setup)
        res = {}
        if sw in LEVEL_NEUTRAL and ref_level is not None:
            (m_lvl, w_lvl), n = ref_level, 0  # the switch does nothing in level flight
        else:
            m_lvl, w_lvl, n = dec.flutter_mach("level", level_start if ref_level is None or sw == "density" else ref_level[0])
        if sw == "none":
            ref_level = (m_lvl, w_lvl)
        setup.mach_pg = m_lvl
        res["level"] = (m_lvl, w_lvl)
        evals = n
        for case in cases:
            if case == "level":
                continue
            mf, wf, n = dec.flutter_mach(case, m_lvl)
            res[case] = (mf, wf)
            evals += n
        row = {"switch": sw, "aircraft": aircraft_name, "altitude_m": altitude_m, "evaluations": evals,
               "seconds": round(time.time() - t0, 1), "terms": None if dec.last_terms is None else changed_terms(dec.last_terms)}
        for case, (mf, wf) in res.items():
            row[f"M_{case}"] = round(mf, 5)
            row[f"w_{case}"] = round(wf, 4)
        if "R5km" in res and "R12km" in res:
            row["turn_dM"] = round(res["R5km"][0] - res["R12km"][0], 5)
            row["turn_dw"] = round(res["R5km"][1] - res["R12km"][1], 4)
        if "g+15" in res and "g-15" in res:
            row["climb_dM"] = round(res["g+15"][0] - res["g-15"][0], 5)
            row["climb_dw"] = round(res["g+15"][1] - res["g-15"][1], 4)
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


def table(rows: list[dict]) -> str:
    out = ["| switched off | M_F level / ω_F [rad/s] | M_F(5 km) − M_F(12 km) | Δω_F turn [rad/s] | M_F(+15°) − M_F(−15°) | "
           "Δω_F climb [rad/s] |",
           "|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['switch']} | {r['M_level']:.4f} / {r['w_level']:.2f} | {r.get('turn_dM', float('nan')):+.4f} | "
                   f"{r.get('turn_dw', float('nan')):+.3f} | {r.get('climb_dM', float('nan')):+.5f} | {r.get('climb_dw', float('nan')):+.4f} |")
    return "\n".join(out)


#: The paper's trend signs (its text after Figs. 7-10 and 12-15): d/dR from R = 5 to 12 km, d/dgamma from -15 to +15 deg.
PAPER_SIGNS = {"dM/dR": {0.0: +1, 3048.0: -1, 6096.0: -1, 9144.0: -1}, "dw/dR": {0.0: -1, 3048.0: +1, 6096.0: +1, 9144.0: +1},
               "dM/dg": {h: +1 for h in (0.0, 3048.0, 6096.0, 9144.0)}, "dw/dg": {h: -1 for h in (0.0, 3048.0, 6096.0, 9144.0)}}
#: Differences below these count as unresolved (search tolerance 5e-5 in Mach): [-], [rad/s].
RESOLVED = {"M": 1e-4, "w": 1e-3}


def scorecard(rows: list[dict]) -> str:
    """US trend signs against the paper's, from ``none`` rows at several altitudes (one row per altitude)."""
    out = ["| h [m] | dM_F/dR | dω_F/dR | dM_F/dγ | dω_F/dγ | level M_F / ω_F |", "|---|---|---|---|---|---|"]
    n_ok = n = 0
    for r in sorted(rows, key=lambda r: r["altitude_m"]):
        h = float(r["altitude_m"])
        vals = {"dM/dR": r["M_R12km"] - r["M_R5km"], "dw/dR": r["w_R12km"] - r["w_R5km"],
                "dM/dg": r["M_g+15"] - r["M_g-15"], "dw/dg": r["w_g+15"] - r["w_g-15"]}
        cells = []
        for key, val in vals.items():
            ok = abs(val) > RESOLVED[key[1]] and np.sign(val) == PAPER_SIGNS[key][h]
            n_ok, n = n_ok + ok, n + 1
            cells.append(f"{val:+.5f} {'✔' if ok else '✘'}")
        out.append(f"| {h:.0f} | " + " | ".join(cells) + f" | {r['M_level']:.4f} / {r['w_level']:.2f} |")
    out.append(f"\n{n_ok}/{n} signs as the paper (a difference below {RESOLVED['M']} in Mach or {RESOLVED['w']} rad/s counts as unresolved, ✘)")
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--aircraft", default="gtm")
    ap.add_argument("--altitude", type=float, default=9144.0)
    ap.add_argument("--switches", nargs="+", default=list(SWITCHES), choices=SWITCHES + FIN_SWITCHES)
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--rho-altitude", type=float, default=3048.0, help="altitude of the density of the 'density' switch [m]")
    ap.add_argument("--start", type=float, default=0.91, help="starting Mach of the level search")
    ap.add_argument("--damping", type=float, default=None, help="structural damping ratio (default: the aircraft's)")
    ap.add_argument("--scaling", default=None, help="JSON object of StructuralScaling factors")
    ap.add_argument("--mass-factor", type=float, default=1.0)
    ap.add_argument("--incidence", type=float, nargs=2, default=None, metavar=("WING", "HTAIL"))
    ap.add_argument("--formulation", default="physical", choices=("physical", "paper"))
    ap.add_argument("--mode-class", default="any", choices=("any", "symmetric", "antisymmetric"),
                    help="track the most unstable mode of this class only (energy share > 1/2)")
    ap.add_argument("--fixed-density", type=float, default=None, metavar="ALT",
                    help="reference linear model at the density of ALT (the 'density' switch then restores the true one)")
    ap.add_argument("--ref-level", type=float, nargs=2, default=None, metavar=("M_F", "OMEGA_F"),
                    help="level flutter point of the 'none' switch from an earlier run (for split runs)")
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--scorecard", type=Path, nargs="+", default=None, metavar="JSON",
                    help="only print the trend scorecard from earlier --json outputs (their 'none' rows, one per altitude)")
    a = ap.parse_args()
    if a.scorecard:
        rows = [r for f in a.scorecard for r in json.loads(f.read_text()) if r["switch"] == "none"]
        print(scorecard(rows))
        return
    scaling = json.loads(a.scaling) if a.scaling else None
    ac = configure(a.aircraft, scaling, a.mass_factor, tuple(a.incidence) if a.incidence else None, a.damping)
    label = json.dumps({"aircraft": a.aircraft, "scaling": scaling, "mass_factor": a.mass_factor, "incidence_deg": a.incidence,
                        "fixed_density_alt_m": a.fixed_density, "damping": a.damping, "formulation": a.formulation,
                        "mode_class": a.mode_class})
    print("#", label, flush=True)
    rows = run(ac, label, a.altitude, a.switches, a.rho_altitude, a.start, a.cases,
               tuple(a.ref_level) if a.ref_level else None, a.fixed_density, a.formulation, a.mode_class)
    print(table(rows))
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
