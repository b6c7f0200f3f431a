"""Does the paper's altitude trend follow from one density in its linearised aerodynamics?

For every altitude of Tables 2 and 3 (0, 3048, 6096, 9144 m) the level-flight flutter point is computed with the
aircraft trimmed at the true (ISA) density, and the linear model of the flutter analysis built with the
aerodynamics at

* ``true``: the flight's own density (flexsim's default, physical), or
* ``rho(h*)``: one fixed density, that of altitude h* (``--fixed 0 3048``), Mach and compressibility unchanged.

Printed per row: M_F, omega_F, V_F, V_F^2/sqrt(1-M_F^2) (the quantity the paper's US boundary keeps constant
within 2 % from 3048 to 9144 m), q_F/sqrt(1-M_F^2), the critical mode's symmetric energy share and
|q_f1|/largest elastic coordinate, and the paper's values beside it (printed only, never used).

The search tracks the crossing from ``--start`` Mach numbers (one per altitude) by regula falsi (tolerance
5e-5), as ``manoeuvre_decomposition.py`` does; the switch machinery is that script's ``density`` switch.

Run: python studies/density_finding.py [--aircraft gtm] [--model US|QS] [--damping 0] [--fixed 0 3048]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from manoeuvre_decomposition import Decomposition, Setup, mode_info  # noqa: E402

from flexsim.aircraft.toml_loader import load_aircraft  # noqa: E402
from flexsim.atmosphere import isa_density, speed_of_sound  # noqa: E402
from flexsim.linear.paper_data import TABLE_QS, TABLE_US  # noqa: E402

ALTITUDES = (0.0, 3048.0, 6096.0, 9144.0)


def paper_row(model: str, h: float):
    table = TABLE_US if model == "US" else TABLE_QS
    for row in table:
        if abs(row[0] - h) < 1:
            return row
    return None


def paper_quantities(table) -> list[dict]:
    """What one of the paper's Tables 2-3 implies per row (derived from the printed values only, ISA): altitude [m],
    M_F, omega_F [rad/s], V_F [m/s], rho [kg/m^3], V_F^2/sqrt(1-M^2) [10^3 m^2/s^2], q_F and q_F/sqrt(1-M^2) [kPa],
    q_F * theta [Pa rad] (trim lift ~ q alpha: follows the true density when constant) and T_e / sin(theta) [kN]
    (the paper's weight)."""
    rows = []
    for h, m, omega, theta, te, *_ in table:
        v = m * speed_of_sound(h)
        pg = 1.0 / math.sqrt(1.0 - m * m)
        q = 0.5 * isa_density(h) * v * v
        rows.append({"altitude_m": h, "M_F": m, "omega_F": omega, "V_F": float(v), "rho": float(isa_density(h)),
                     "V2PG_k": float(v * v * pg / 1e3), "q_kPa": float(q / 1e3), "qPG_kPa": float(q * pg / 1e3),
                     "q_theta": float(q * math.radians(theta)), "weight_kN": te / math.sin(math.radians(theta))})
    return rows


def paper_table() -> str:
    """What the paper's own Tables 2-3 imply (:func:`paper_quantities`), as a markdown table."""
    out = ["| table | h [m] | V_F [m/s] | V_F²/√(1−M²) [10³ m²/s²] | q_F/√(1−M²) [kPa] | q_F·θ [Pa rad] | T_e/sin θ [kN] |",
           "|---|---|---|---|---|---|---|"]
    for name, table in (("2 (QS)", TABLE_QS), ("3 (US)", TABLE_US)):
        for r in paper_quantities(table):
            out.append(f"| {name} | {r['altitude_m']:.0f} | {r['V_F']:.1f} | {r['V2PG_k']:.1f} | {r['qPG_kPa']:.1f} | "
                       f"{r['q_theta']:.0f} | {r['weight_kN']:.2f} |")
    return "\n".join(out)


def run(aircraft, label: str, model: str, densities, starts, altitudes=ALTITUDES, formulation: str = "physical",
        mode_class: str = "any") -> list[dict]:
    rows = []
    for dens in densities:
        for h, m0 in zip(altitudes, starts):
            t0 = time.time()
            fixed = dens != "true"
            setup = Setup(aircraft, h, "density" if fixed else "none", float(dens) if fixed else 0.0, model=model,
                          formulation=formulation, mode_class=mode_class)
            dec = Decomposition(setup)
            try:
                mf, wf, n = dec.flutter_mach("level", m0)
            except RuntimeError as err:
                print(f"# {label} {model} {dens} {h}: {err}", flush=True)
                continue
            v = mf * speed_of_sound(h)
            pg = 1.0 / math.sqrt(1.0 - mf * mf)
            rho_lin = isa_density(float(dens)) if fixed else isa_density(h)
            info = mode_info(dec.last[2], dec.mode)
            trim_point = dec.last[0]
            ts = trim_point.summary()
            info.update({"theta_deg": round(ts["theta_deg"], 3), "thrust_kN": round(trim_point.thrust_n / 1e3, 2),
                         "elevator_deg": round(ts["elevator_deg"], 3), "tip_deflection_m": round(ts["tip_deflection_m"], 4),
                         "tip_twist_deg": round(ts["tip_twist_deg"], 4)})
            row = {"aircraft": label, "model": model, "mode_class": mode_class, "density": "true" if not fixed else f"rho({float(dens):.0f} m)",
                   "altitude_m": h, "M_F": round(mf, 4), "omega_F": round(wf, 3), "V_F": round(v, 1),
                   "V2PG_k": round(v * v * pg / 1e3, 2), "qPG_kPa": round(0.5 * rho_lin * v * v * pg / 1e3, 2), **info,
                   "evaluations": n, "seconds": round(time.time() - t0, 1)}
            p = paper_row(model, h)
            if p is not None:  # printed beside the result, never used in it
                row["paper"] = dict(zip(("M_F", "omega_F", "theta_deg", "thrust_kN", "elevator_deg", "tip_deflection_m",
                                         "tip_twist_deg"), p[1:]))
            rows.append(row)
            print(json.dumps(row), flush=True)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--aircraft", default="gtm")
    ap.add_argument("--model", default="US", choices=("US", "QS"))
    ap.add_argument("--damping", type=float, default=None, help="structural damping ratio (default: the aircraft's)")
    ap.add_argument("--fixed", nargs="*", default=["0", "3048"], help="altitudes [m] of the fixed densities")
    ap.add_argument("--no-true", action="store_true", help="skip the true-density rows")
    ap.add_argument("--altitudes", type=float, nargs="+", default=list(ALTITUDES))
    ap.add_argument("--starts", type=float, nargs="+", default=None, help="starting Mach per altitude")
    ap.add_argument("--scaling", type=str, default=None, help="JSON of StructuralScaling factors applied to the aircraft")
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument("--paper", action="store_true", help="only print what the paper's tables imply, and exit")
    a = ap.parse_args()
    if a.paper:
        print(paper_table())
        return
    ac = load_aircraft(a.aircraft)
    label = a.aircraft
    if a.scaling:
        from flexsim.aircraft.calibration import StructuralScaling

        ac = StructuralScaling(**json.loads(a.scaling)).apply(ac)
        label += " " + a.scaling
    if a.damping is not None:
        ac = replace(ac, structural_damping_ratio=a.damping)
        label += f" zeta={a.damping}"
    dens = ([] if a.no_true else ["true"]) + list(a.fixed)
    starts = a.starts or [0.70] * len(a.altitudes)
    rows = run(ac, label, a.model, dens, starts, a.altitudes)
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
