"""Every column of the paper's Tables 2 and 3 for one configuration, with the residuals.

Configuration (study-level, all explicit on the command line and printed with the result):

* ``--aircraft`` and ``--scaling`` (a JSON object of :class:`flexsim.aircraft.calibration.StructuralScaling`
  factors applied on top of the file);
* ``--mass-factor``: every mass and inertia times k, stiffness unchanged (k = 0.907 is the paper's weight,
  889.4 kN = T_e / sin(theta) of all eight rows; below StructuralScaling's bound of 1, which
  keeps frequencies; here the frequencies rise by 1/sqrt(k));
* ``--incidence WING HTAIL``: rigging incidence [deg] of the wing and stabilizer strips (the paper's section
  angle of attack is W/U plus the elastic twist, eq. 28: no incidence from the Table 1 angles, whose dihedral
  about the swept axis tilts flexsim's streamwise chord by -1.81 deg (wing) and -2.7 deg (stabilizer));
* ``--fixed-density ALT``: the linearised aerodynamics of the flutter analysis at the density of altitude ALT,
  trim at the true density (``studies/density_finding.py``); default: the true density;
* ``--damping``: structural damping ratio.

For each model (US: Theodorsen p-k; QS: quasi-steady) and altitude the flutter crossing is tracked from a
starting Mach (``--starts-us``, ``--starts-qs``) by regula falsi (tolerance 5e-5), and the trim at the flutter
point gives theta, T_e, delta_e, the wing-tip deflection and twist. Printed: value / paper / relative difference,
the critical mode's symmetric energy share and |q_f1| / largest elastic coordinate. The paper's values are
printed beside the results, never used in them.

Run: python studies/paper_residuals.py --scaling '{"fuselage_ei": 1.75}' --mass-factor 0.907 --incidence 1.81 2.7 \
        --fixed-density 3048 --damping 0 [--models US QS] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from density_finding import ALTITUDES, run  # noqa: E402
from manoeuvre_decomposition import configure  # noqa: E402


#: Starting Mach of the crossing searches when ``--starts-us`` / ``--starts-qs`` are not given.
DEFAULT_START = 0.72
COLS = ("M_F", "omega_F", "theta_deg", "thrust_kN", "elevator_deg", "tip_deflection_m", "tip_twist_deg")


def residual_table(rows: list[dict]) -> str:
    out = ["| model | h [m] | " + " | ".join(COLS) + " | sym share / q_f1 ratio |", "|---" * (len(COLS) + 3) + "|"]
    for r in rows:
        cells = []
        for c in COLS:
            v, p = r[c], r.get("paper", {}).get(c)
            cells.append(f"{v:.4g} / {p:.4g} ({100 * (v / p - 1):+.1f} %)" if p else f"{v:.4g}")
        out.append(f"| {r['model']} | {r['altitude_m']:.0f} | " + " | ".join(cells) + f" | {r['sym_share']:.2f} / {r['qf1_ratio']:.2f} |")
    return "\n".join(out)


def trims_at_paper(ac, formulation: str) -> str:
    """Trim columns at the paper's own flight conditions (h, M_F of each row): the static model alone."""
    from manoeuvre_decomposition import Decomposition, Setup
    from flexsim.linear.paper_data import TABLE_QS, TABLE_US
    from flexsim.trimming import SteadyManoeuvre, trim

    model = Decomposition(Setup(ac, 0.0, "none", 0.0, formulation=formulation)).trim_model
    out = ["| table | h [m] | M | θ [°] | T_e [kN] | δ_e [°] | w_tip [m] | ψ_tip [°] |", "|---|---|---|---|---|---|---|---|"]
    for name, table in (("US", TABLE_US), ("QS", TABLE_QS)):
        for h, m, _, *paper in table:
            p = trim(model, SteadyManoeuvre.level(h, mach=m), check_limits=False)
            t = p.summary()
            ours = (t["theta_deg"], p.thrust_n / 1e3, t["elevator_deg"], t["tip_deflection_m"], t["tip_twist_deg"])
            out.append(f"| {name} | {h:.0f} | {m:.4f} | " + " | ".join(f"{v:.4g} / {q:.4g} ({100 * (v / q - 1):+.1f} %)" for v, q in zip(ours, paper)) + " |")
    return "\n".join(out)


def flutter_rows(ac, label: str, model: str, altitudes, starts, fixed_density_alt_m: float | None = None,
                 formulation: str = "physical", mode_class: str = "any") -> list[dict]:
    """Every column of Tables 2-3 (flutter point and the trim at it) of the configured aircraft ``ac`` for one
    model at ``altitudes``, the crossing tracked from ``starts`` (one Mach per altitude); the linearised
    aerodynamics at the density of ``fixed_density_alt_m`` (None: the true density). Rows as
    ``density_finding.run`` prints them (``M_F``, ``omega_F``, ``theta_deg``, ..., ``sym_share``, ``qf1_ratio``,
    ``paper``); an altitude without a crossing has no row."""
    dens = ["true"] if fixed_density_alt_m is None else [str(fixed_density_alt_m)]
    return run(ac, label, model, dens, list(starts), list(altitudes), formulation, mode_class)


def glide(ac, formulation: str, altitude_m: float, mach: float) -> dict:
    """The glide (thrust zero, gamma unknown) of ``ac`` at ``altitude_m`` and ``mach``: the trim summary
    (``gamma_deg``, ``alpha_deg``, ...)."""
    from manoeuvre_decomposition import Decomposition, Setup
    from flexsim.trimming import SteadyManoeuvre, trim

    dec = Decomposition(Setup(ac, altitude_m, "none", 0.0, formulation=formulation))
    return trim(dec.trim_model, SteadyManoeuvre.glide(altitude_m, mach=mach), check_limits=False).summary()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--aircraft", default="gtm")
    ap.add_argument("--scaling", default=None, help="JSON object of StructuralScaling factors")
    ap.add_argument("--mass-factor", type=float, default=1.0)
    ap.add_argument("--incidence", type=float, nargs=2, default=None, metavar=("WING", "HTAIL"))
    ap.add_argument("--fixed-density", type=float, default=None, metavar="ALT")
    ap.add_argument("--damping", type=float, default=None)
    ap.add_argument("--formulation", default="physical", choices=("physical", "paper"),
                    help="the library's force resolution (AeroOptions.formulation): paper = eq. 28, T_e = W sin(theta)")
    ap.add_argument("--models", nargs="+", default=["US", "QS"], choices=("US", "QS"))
    ap.add_argument("--altitudes", type=float, nargs="+", default=list(ALTITUDES))
    ap.add_argument("--starts-us", type=float, nargs="+", default=None)
    ap.add_argument("--starts-qs", type=float, nargs="+", default=None)
    ap.add_argument("--mode-class", default="any", choices=("any", "symmetric", "antisymmetric"),
                    help="track the crossing of the most unstable mode of this class only")
    ap.add_argument("--trim-at-paper", action="store_true",
                    help="only trim at the paper's (h, M_F) of every row of Tables 2-3 and print the trim columns")
    ap.add_argument("--json", type=Path, default=None)
    a = ap.parse_args()
    scaling = json.loads(a.scaling) if a.scaling else None
    ac = configure(a.aircraft, scaling, a.mass_factor, tuple(a.incidence) if a.incidence else None, a.damping)
    label = json.dumps({"aircraft": a.aircraft, "scaling": scaling, "mass_factor": a.mass_factor, "incidence_deg": a.incidence,
                        "fixed_density_alt_m": a.fixed_density, "damping": a.damping, "formulation": a.formulation})
    print("#", label, flush=True)
    if a.trim_at_paper:
        print(trims_at_paper(ac, a.formulation))
        return
    rows = []
    for model in a.models:
        starts = (a.starts_us if model == "US" else a.starts_qs) or [DEFAULT_START] * len(a.altitudes)
        rows += flutter_rows(ac, label, model, a.altitudes, starts, a.fixed_density, a.formulation, a.mode_class)
    print(residual_table(rows))
    for r in rows:  # the glide (thrust zero, gamma unknown) at the US flutter Mach of 9144 m (paper: -3.12 deg)
        if r["model"] == "US" and abs(r["altitude_m"] - 9144.0) < 1:
            g = glide(ac, a.formulation, 9144.0, r["M_F"])
            print(f"glide at 9144 m, M {r['M_F']:.4f}: gamma {g['gamma_deg']:.3f} deg, alpha {g['alpha_deg']:.3f} deg (paper -3.12 deg)")
    if a.json:
        a.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
