"""The symmetric and the antisymmetric flutter boundaries apart, and what would make the paper's mode critical.

The paper's flutter mode is symmetric with the fuselage's first vertical bending q_f1 its largest linear
coordinate (Figs. 11 and 16); flexsim's critical mode is an antisymmetric wing bending/torsion
mode. In symmetric flight the linear model commutes with the left-right mirror P of the coordinates
(:mod:`flexsim.structure.mirror`), so its modes split exactly into a symmetric class (P V = V) and an
antisymmetric one (P V = -V). This study computes, from one spectrum per Mach number, the largest real part of
the elastic modes of each class (a mode belongs to the class holding more than half its kinetic energy, M(0))
and so the flutter boundary of each class alone:

* ``bounds``: per altitude and class, the flutter Mach, frequency, |q_f1| / largest linear elastic coordinate
  (bending coordinates, as the paper's figures rank them) and that coordinate; the gap M_sym - M_anti;
* ``census``: every elastic mode at one (altitude, Mach): frequency, real part, damping ratio, class, q_f1 ratio
  and the largest coordinate (used for the paper's 17.8 rad/s sea-level mode);
* ``vary``: the two class boundaries at one altitude while one parameter is multiplied by each of a list of
  factors (fuselage/wing/tail stiffness, fuselage/engine mass, ...), for the sensitivity of the gap.

Models: ``US`` (Theodorsen p-k, the paper's Table 3), ``FS`` (finite-state state space, m = n = 2, N = 6),
``QS`` (quasi-steady). The configuration options are those of ``paper_residuals.py`` (aircraft file,
StructuralScaling, paper weight, incidence, force resolution, fixed density of the linearised aerodynamics,
damping); ``--factor NAME=VALUE`` multiplies one more table without StructuralScaling's bounds (a study, to find
how far a parameter would have to move; the bounds are argued in docs/calibration.md):

==========================  ======================================================================================
``fuselage.ei``             EI of the fuselage (both planes)
``fuselage.gj``             GJ of the fuselage
``fuselage.mass``           mass per length and torsional inertia of the fuselage sections (not the lumped masses)
``wing.ei``, ``wing.gj``    EI, GJ of both wing halves
``wing.mass``               mass per length and torsional inertia of both wing halves
``htail.stiffness``         EI and GJ of both stabilizer halves
``vtail.stiffness``         EI and GJ of the fin
``engine.mass``             mass and inertia of both engines (their thrust line is unchanged)
``lumped.mass``             mass and inertia of every lumped mass that is not an engine (payload, fuel, systems)
==========================  ======================================================================================

Each class crossing is bracketed on the Mach grid (``--grid LO HI STEP``) and refined by regula falsi on that
class's largest real part (tolerance 2e-4 in Mach). Run (about 1 min per altitude and model, 1 BLAS thread)::

    python studies/symmetric_mode.py bounds --aircraft gtm --model US --altitudes 3048 6096 9144
    python studies/symmetric_mode.py census --aircraft gtm --altitude 0 --mach 0.6742
    python studies/symmetric_mode.py vary --aircraft gtm --altitude 9144 --vary fuselage.ei 1 1.5 2 3
    python studies/symmetric_mode.py table run1.json run2.json        # reprint the table of earlier --json outputs
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
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from manoeuvre_decomposition import Decomposition, Setup, configure, mode_info  # noqa: E402

CLASSES = ("symmetric", "antisymmetric")
FACTORS = ("fuselage.ei", "fuselage.gj", "fuselage.mass", "wing.ei", "wing.gj", "wing.mass", "htail.stiffness",
           "vtail.stiffness", "engine.mass", "lumped.mass")


def apply_factor(ac, name: str, value: float):
    """``ac`` with one table multiplied by ``value`` (names in the module docstring; no bounds: a study)."""
    if name not in FACTORS:
        raise ValueError(f"--factor {name}: must be one of {', '.join(FACTORS)}")
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"--factor {name}={value}: must be a positive number")
    part, what = name.split(".")
    if part in ("engine", "lumped"):
        want_engine = part == "engine"
        masses = tuple(replace(m, mass_kg=m.mass_kg * value, inertia_kg_m2=m.inertia_kg_m2 * value)
                       if (m in ac.engines) == want_engine else m for m in ac.lumped_masses)
        engines = tuple(replace(e, mass_kg=e.mass_kg * value, inertia_kg_m2=e.inertia_kg_m2 * value) if want_engine else e
                        for e in ac.engines)
        return replace(ac, lumped_masses=masses, engines=engines)
    comps = []
    for c in ac.components:
        if part in c.name:
            s = c.sections
            if what in ("ei", "stiffness"):
                s = replace(s, ei_nm2=s.ei_nm2 * value)
            if what in ("gj", "stiffness"):
                s = replace(s, gj_nm2=s.gj_nm2 * value)
            if what == "mass":
                s = replace(s, mass_kg_per_m=s.mass_kg_per_m * value, torsional_inertia_kg_m=s.torsional_inertia_kg_m * value)
            c = replace(c, sections=s)
        comps.append(c)
    return replace(ac, components=tuple(comps))


class ClassBoundary:
    """Trim and one spectrum per Mach; the largest real part of each mirror class's elastic modes."""

    def __init__(self, aircraft, altitude_m: float, model: str, formulation: str, fixed_density_alt_m: float | None):
        self.dec = Decomposition(Setup(aircraft, altitude_m, "none", 0.0, model=model, formulation=formulation,
                                       base_rho_altitude_m=fixed_density_alt_m))
        self.cache: dict[float, dict] = {}

    def classes(self, mach: float) -> dict:
        """{class: (largest real part [1/s], mode, mode_info)} at ``mach`` (level flight)."""
        key = round(mach, 7)
        if key not in self.cache:
            self.dec.g("level", mach)
            point, spec, lin_model = self.dec.last
            ts = point.summary()
            out = {"trim": {"theta_deg": round(ts["theta_deg"], 3), "thrust_kN": round(point.thrust_n / 1e3, 2),
                            "elevator_deg": round(ts["elevator_deg"], 3), "tip_deflection_m": round(ts["tip_deflection_m"], 4),
                            "tip_twist_deg": round(ts["tip_twist_deg"], 4)}}
            for cls in CLASSES:
                best = None
                for m in spec.of_kind("elastic"):
                    if m.frequency_rad_s < 0.5:
                        continue
                    info = mode_info(lin_model, m)
                    if (info["sym_share"] > 0.5) == (cls == "symmetric") and (best is None or m.eigenvalue.real > best[0]):
                        best = (m.eigenvalue.real, m, info)
                out[cls] = best
            self.cache[key] = out
        return self.cache[key]

    def crossing(self, cls: str, grid: np.ndarray, tol: float = 2e-4) -> dict | None:
        """First crossing of class ``cls`` on ``grid``, refined by regula falsi; None if stable on the grid."""
        prev = None
        for m in grid:
            g = self.classes(float(m))[cls][0]
            if g > 0:
                if prev is None:
                    return {"M_F": float(m), "note": "unstable at the grid's lower end"}
                lo, glo, hi, ghi = prev[0], prev[1], float(m), g
                while hi - lo > tol:
                    mid = hi - ghi * (hi - lo) / (ghi - glo)
                    if not lo + 0.1 * tol < mid < hi - 0.1 * tol:
                        mid = 0.5 * (lo + hi)
                    gm = self.classes(mid)[cls][0]
                    if gm > 0:
                        hi, ghi = mid, gm
                        glo *= 0.5
                    else:
                        lo, glo = mid, gm
                        ghi *= 0.5
                at = self.classes(hi)
                _, mode, info = at[cls]
                return {"M_F": round(0.5 * (lo + hi), 5), "omega_F": round(mode.frequency_rad_s, 3),
                        "qf1_ratio": info["qf1_ratio"], "largest": info["largest"], "sym_share": info["sym_share"],
                        **at["trim"]}
            prev = (float(m), g)
        return None


def bounds(ac, label: str, model: str, formulation: str, fixed: float | None, altitudes, grid) -> list[dict]:
    rows = []
    for h in altitudes:
        t0 = time.time()
        cb = ClassBoundary(ac, h, model, formulation, fixed)
        row = {"config": label, "model": model, "altitude_m": h}
        for cls in CLASSES:
            row[cls] = cb.crossing(cls, grid)
        s, a = row["symmetric"], row["antisymmetric"]
        row["gap_sym_minus_anti"] = round(s["M_F"] - a["M_F"], 5) if s and a else None
        row["seconds"] = round(time.time() - t0, 1)
        rows.append(row)
        print(json.dumps(row), flush=True)
    return rows


def bounds_table(rows: list[dict]) -> str:
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US

    out = ["| config | model | h [m] | SYM M_F / ω_F / q_f1 ratio (largest) | ANTI M_F / ω_F (largest) | M_sym − M_anti | paper M_F / ω_F (printed only) |",
           "|---|---|---|---|---|---|---|"]
    for r in rows:
        s, a = r["symmetric"], r["antisymmetric"]
        sc = f"{s['M_F']:.4f} / {s.get('omega_F', float('nan')):.2f} / {s.get('qf1_ratio', float('nan')):.2f} ({s.get('largest')})" if s else "none"
        ac_ = f"{a['M_F']:.4f} / {a.get('omega_F', float('nan')):.2f} ({a.get('largest')})" if a else "none"
        gap = f"{r['gap_sym_minus_anti']:+.4f}" if r["gap_sym_minus_anti"] is not None else "—"
        paper = [row for row in (TABLE_QS if r["model"] == "QS" else TABLE_US) if abs(row[0] - r["altitude_m"]) < 1]
        pc = f"{paper[0][1]:.4f} / {paper[0][2]:.2f}" if paper else "—"
        out.append(f"| {r['config']} | {r['model']} | {r['altitude_m']:.0f} | {sc} | {ac_} | {gap} | {pc} |")
    by_config: dict[str, dict[float, float]] = {}
    for r in rows:
        crit = [c["M_F"] for c in (r["symmetric"], r["antisymmetric"]) if c]
        if crit:
            by_config.setdefault(r["config"], {})[r["altitude_m"]] = min(crit)
    for cfg, m in by_config.items():
        if 3048.0 in m and 9144.0 in m:
            out.append(f"\n{cfg or 'config'}: critical M_F(9144 m) / M_F(3048 m) = {m[9144.0] / m[3048.0]:.3f}")
    return "\n".join(out)


@dataclass(frozen=True)
class CensusMode:
    """One mode of the census at a flight point (rigid-body or elastic, positive frequency)."""

    frequency_rad_s: float  #: damped frequency [rad/s]
    real_1_s: float  #: real part of the eigenvalue [1/s]
    damping_ratio: float  #: [-]
    kind: str  #: "rigid" or "elastic"
    sym_share: float  #: symmetric share of the kinetic energy [-] (> 0.5: the symmetric class)
    qf1_ratio: float  #: |q_f1| / largest linear elastic coordinate [-]
    largest: str  #: the largest linear elastic coordinate
    dominant: str  #: the dominant degree of freedom (energy)

    @property
    def symmetric(self) -> bool:
        return self.sym_share > 0.5


def census_modes(ac, model: str, formulation: str, fixed: float | None, altitude: float, mach: float,
                 fmax: float) -> tuple[CensusMode, ...]:
    """Every rigid-body and elastic mode up to ``fmax`` [rad/s] in level flight at (``altitude`` [m], ``mach``),
    by frequency (aerodynamic lag modes and the elastic modes' zero-frequency roots left out)."""
    cb = ClassBoundary(ac, altitude, model, formulation, fixed)
    cb.dec.g("level", mach)
    _, spec, lin_model = cb.dec.last
    out = []
    for m in sorted(spec.modes, key=lambda m: m.frequency_rad_s):
        if m.kind == "aerodynamic" or m.frequency_rad_s > fmax or m.eigenvalue.imag < 0 or (m.kind == "elastic" and m.frequency_rad_s < 0.5):
            continue
        info = mode_info(lin_model, m)
        out.append(CensusMode(float(m.frequency_rad_s), float(m.eigenvalue.real), float(m.damping_ratio), m.kind,
                              info["sym_share"], info["qf1_ratio"], info["largest"], m.dominant_dof))
    return tuple(out)


def census(ac, model: str, formulation: str, fixed: float | None, altitude: float, mach: float, fmax: float) -> str:
    out = [f"elastic and rigid-body modes at h {altitude:.0f} m, M {mach:.4f} ({model}):",
           "| ω [rad/s] | Re [1/s] | ζ | class (sym share) | q_f1 ratio | largest linear coordinate | dominant (energy) |",
           "|---|---|---|---|---|---|---|"]
    for m in census_modes(ac, model, formulation, fixed, altitude, mach, fmax):
        cls = "sym" if m.symmetric else "anti"
        out.append(f"| {m.frequency_rad_s:.2f}{' (rigid)' if m.kind == 'rigid' else ''} | {m.real_1_s:+.3f} | {m.damping_ratio:+.3f} | {cls} ({m.sym_share:.2f}) | "
                   f"{m.qf1_ratio:.2f} | {m.largest} | {m.dominant} |")
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("what", choices=("bounds", "census", "vary", "table"))
    ap.add_argument("files", nargs="*", type=Path, help="table: --json outputs of earlier bounds/vary runs to reprint")
    ap.add_argument("--aircraft", default="gtm")
    ap.add_argument("--scaling", default=None, help="JSON object of StructuralScaling factors")
    ap.add_argument("--mass-factor", type=float, default=1.0)
    ap.add_argument("--incidence", type=float, nargs=2, default=None, metavar=("WING", "HTAIL"))
    ap.add_argument("--damping", type=float, default=None)
    ap.add_argument("--formulation", default=None, choices=("physical", "paper"),
                    help="force resolution (default: the aircraft file's)")
    ap.add_argument("--fixed-density", type=float, default=None, metavar="ALT",
                    help="linearised aerodynamics at the density of ALT [m] (trim at the true density)")
    ap.add_argument("--factor", action="append", default=[], metavar="NAME=VALUE", help="one more table factor (repeatable)")
    ap.add_argument("--model", default="US", choices=("US", "FS", "QS"))
    ap.add_argument("--altitudes", type=float, nargs="+", default=[3048.0, 6096.0, 9144.0])
    ap.add_argument("--altitude", type=float, default=9144.0, help="census / vary altitude [m]")
    ap.add_argument("--mach", type=float, default=0.78, help="census Mach")
    ap.add_argument("--fmax", type=float, default=60.0, help="census: highest frequency listed [rad/s]")
    ap.add_argument("--grid", type=float, nargs=3, default=[0.55, 0.95, 0.025], metavar=("LO", "HI", "STEP"))
    ap.add_argument("--vary", nargs="+", default=None, metavar="NAME F1", help="vary: factor name then values")
    ap.add_argument("--json", type=Path, default=None)
    a = ap.parse_args()
    if a.what == "table":
        rows = []
        for f in a.files:
            doc = json.loads(f.read_text())
            cfg = doc["config"]
            tag = [f"{cfg['aircraft']} ({cfg['formulation']})"] + [f"{k} × {v:g}" for k, v in (cfg.get("factors") or {}).items()]
            if cfg.get("fixed_density_alt_m") is not None:
                tag.append(f"ρ({cfg['fixed_density_alt_m']:.0f} m)")
            rows += [{**r, "config": ", ".join(tag + ([r["config"]] if r["config"] else [])), "_base": ", ".join(tag[:len(tag) - (cfg.get("fixed_density_alt_m") is not None)]),
                      "_rho_alt": cfg.get("fixed_density_alt_m")} for r in doc["rows"]]
        # a fixed density rho(h*) equals the true density at h*: take that altitude's row from the true-density run
        for r in [r for r in rows if r["_rho_alt"] is None]:
            for cfg_name in {q["config"] for q in rows if q["_base"] == r["config"] and q["_rho_alt"] == r["altitude_m"]}:
                if not any(q["config"] == cfg_name and q["altitude_m"] == r["altitude_m"] for q in rows):
                    rows.append({**r, "config": cfg_name, "_rho_alt": r["altitude_m"]})
        rows.sort(key=lambda q: (q["config"], q["altitude_m"]))
        print(bounds_table(rows))
        return
    scaling = json.loads(a.scaling) if a.scaling else None
    ac = configure(a.aircraft, scaling, a.mass_factor, tuple(a.incidence) if a.incidence else None, a.damping)
    extra = {}
    for f in a.factor:
        name, _, val = f.partition("=")
        extra[name] = float(val)
        ac = apply_factor(ac, name, float(val))
    formulation = a.formulation or ac.formulation
    label = json.dumps({"aircraft": a.aircraft, "scaling": scaling, "mass_factor": a.mass_factor, "incidence_deg": a.incidence,
                        "fixed_density_alt_m": a.fixed_density, "damping": a.damping, "formulation": formulation,
                        "factors": extra or None})
    print("#", label, flush=True)
    grid = np.arange(a.grid[0], a.grid[1] + 1e-9, a.grid[2])
    if a.what == "census":
        print(census(ac, a.model, formulation, a.fixed_density, a.altitude, a.mach, a.fmax))
        return
    if a.what == "bounds":
        rows = bounds(ac, "", a.model, formulation, a.fixed_density, a.altitudes, grid)
    else:
        name, values = a.vary[0], [float(v) for v in a.vary[1:]]
        rows = []
        for v in values:
            rows += bounds(apply_factor(ac, name, v), f"{name} × {v:g}", a.model, formulation, a.fixed_density, [a.altitude], grid)
    print(bounds_table(rows))
    if a.json:
        a.json.write_text(json.dumps({"config": json.loads(label), "rows": rows}, indent=1))


if __name__ == "__main__":
    main()
