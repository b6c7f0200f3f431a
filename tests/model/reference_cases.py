"""The cases of the recorded reference (``data/reference_values.json``) and the script that records them.

The recorded reference holds values of the right-hand side, of trims and of flutter points computed by the model
before its physics was split into one module per term; ``test_reference_values.py`` recomputes them with the current
code and compares (rhs and trims 1e-12 relative, flutter Mach and frequency 1e-8). The states and controls at which
the right-hand side is evaluated are stored in the file as well (JSON floats round-trip exactly), so the test
evaluates the current model at bit-identical inputs.

Recorded with (in a checkout of the code to record, 1 BLAS thread)::

    PYTHONPATH=<checkout> OMP_NUM_THREADS=1 python3 tests/model/reference_cases.py --write tests/model/data/reference_values.json

``--write`` runs the cases in the checkout found first on ``sys.path`` and stores what they return; the inputs
(states, controls) are derived from trims of that checkout with a seeded perturbation.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: Right-hand-side models: name -> keyword arguments of AircraftModel (AeroOptions given as a dict under "aero").
RHS_MODELS = {
    "free_qs": dict(aero=dict(model="quasi-steady")),
    "free_us": dict(aero=dict(model="unsteady")),
    "free_us_bending_incidence": dict(aero=dict(model="unsteady", bending_incidence=True)),
    "free_qs_paper": dict(aero=dict(model="quasi-steady", formulation="paper")),
    "free_qs_no_pg_no_drag": dict(aero=dict(model="quasi-steady", compressibility="none", parasite_drag=False,
                                            downwash=False, body_moments=False)),
    "free_vacuum": dict(aero=None),
    "free_qs_damped_fixed_density": dict(aero=dict(model="quasi-steady"), structural_damping=0.02,
                                         aero_density_kg_m3=0.9),
    "free_us_no_gravity": dict(aero=dict(model="unsteady", n_inflow=4), gravity_m_s2=0.0),
    "restrained_qs": dict(variant="restrained", aero=dict(model="quasi-steady"), restrained_velocity_m_s=[200.0, 0.0, 8.0],
                          restrained_euler_rad=[0.0, 0.04, 0.0], altitude_m=3000.0, structural_damping=0.02),
    "restrained_us_tunnel": dict(variant="restrained", aero=dict(model="unsteady"), restrained_velocity_m_s=[150.0, 0.0, 5.0],
                                 altitude_m=1000.0, air_density_kg_m3=1.1),
    "quasi_rigid_us": dict(variant="quasi-rigid", aero=dict(model="unsteady")),
    "quasi_rigid_qs_frozen": dict(variant="quasi-rigid", aero=dict(model="quasi-steady"), frozen="seed"),
}
#: Models whose states are also evaluated in one batched call (rhs_batch) in the gust.
BATCHED = ("free_qs", "free_us", "restrained_qs")
#: Trims on the GTM (quasi-steady model, the trim model of the flutter analysis): name -> SteadyManoeuvre factory.
TRIMS = {
    "level_3000_m0.6": ("level", dict(altitude_m=3000.0, mach=0.6)),
    "turn_3000_r5km_m0.6": ("turn", dict(altitude_m=3000.0, radius_m=5000.0, mach=0.6)),
    "climb_6096_g10_m0.7": ("climb", dict(altitude_m=6096.0, climb_angle_rad=math.radians(10.0), mach=0.7)),
    "glide_3000_m0.5": ("glide", dict(altitude_m=3000.0, mach=0.5)),
}
#: Flutter searches (FlutterAnalysis on the GTM, level flight): name -> (aero model, altitude [m]).
FLUTTER = {"US_9144": ("theodorsen", 9144.0), "QS_9144": ("quasi-steady", 9144.0), "US_0": ("theodorsen", 0.0)}


def _model(gtm, name: str):
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.model.coupling import AeroOptions

    kw = dict(RHS_MODELS[name])
    aero = kw.pop("aero")
    if kw.pop("frozen", None) == "seed":
        from flexsim.structure.model import structural_model

        d = structural_model(gtm).dofs
        rng = np.random.default_rng(7)
        kw["frozen_q"], kw["frozen_xi"] = 0.05 * rng.standard_normal(d.nq), 0.01 * rng.standard_normal(d.nxi)
    return AircraftModel(gtm, aero=None if aero is None else AeroOptions(**aero), **kw)


def _winds():
    from flexsim.sim.disturbances import DrydenTurbulence, OneMinusCosineGust

    return {"still": None,
            "gust": OneMinusCosineGust(6.0, 25.0, front_position_ned_m=[-8.0, 0.0, 0.0]),
            "dryden": DrydenTurbulence(sigma_m_s=[1.5, 1.0, 1.2], length_m=[300.0, 150.0, 150.0], seed=3, n_points=2**13)}


def rhs_inputs(gtm) -> dict:
    """Seeded states and controls of every rhs model near a GTM trim (recorded once, stored in the file)."""
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre, trim

    free = AircraftModel(gtm, aero="quasi-steady")
    base = trim(free, SteadyManoeuvre.level(3000.0, mach=0.6))
    out = {}
    for k, name in enumerate(RHS_MODELS):
        model = _model(gtm, name)
        lay = model.layout
        rng = np.random.default_rng(100 + k)
        states = []
        for s in range(3):
            x = model.pack(*free.unpack(base.x))  # the trim's blocks this variant has; inflow states zero
            x += 0.02 * rng.standard_normal(lay.n_states) * (1.0 + np.abs(x))
            if lay.rigid:
                x[lay.position] = [10.0 * s, 2.0 * s, -3000.0 - 50.0 * s]
            u = base.u * (1.0 + 0.05 * rng.standard_normal(4)) + np.array([0.0, 0.01, -0.01, 0.005]) * s
            states.append((x.tolist(), u.tolist()))
        out[name] = states
    return out


def rhs_values(gtm, inputs: dict) -> dict:
    """x_dot of every model at its stored states, in still air, a 1-cos gust and Dryden turbulence."""
    winds = _winds()
    out = {}
    for name, states in inputs.items():
        model = _model(gtm, name)
        out[name] = {w: [model.rhs(0.0, np.array(x), np.array(u), wind).tolist() for x, u in states]
                     for w, wind in winds.items()}
        if name in BATCHED:
            out[name]["batch_gust"] = model.rhs_batch(0.0, np.array([x for x, _ in states]), np.array([u for _, u in states]),
                                                      winds["gust"]).tolist()
    return out


def trim_values(gtm) -> dict:
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre, trim

    model = AircraftModel(gtm, aero="quasi-steady")
    out = {}
    for name, (kind, kw) in TRIMS.items():
        point = trim(model, getattr(SteadyManoeuvre, kind)(**kw), check_limits=False)
        out[name] = {"x": point.x.tolist(), "u": point.u.tolist()}
    return out


def flutter_values(gtm) -> dict:
    from flexsim.linear.flutter import FlutterAnalysis
    from flexsim.trimming import SteadyManoeuvre

    out = {}
    analyses = {}
    for name, (aero, altitude) in FLUTTER.items():
        fa = analyses.setdefault(aero, FlutterAnalysis(gtm, aero_model=aero))
        p = fa.search(SteadyManoeuvre.level(altitude, mach=0.5))
        out[name] = {"mach": p.mach, "frequency_rad_s": p.frequency_rad_s}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--write", type=Path, required=True)
    a = ap.parse_args()
    from flexsim.aircraft.toml_loader import load_aircraft

    gtm = load_aircraft("gtm")
    inputs = rhs_inputs(gtm)
    data = {"about": "the recorded reference: values of the model before its physics was split into terms "
                     "(tests/model/reference_cases.py, which says how it was produced)",
            "rhs_inputs": inputs, "rhs": rhs_values(gtm, inputs), "trims": trim_values(gtm), "flutter": flutter_values(gtm)}
    a.write.parent.mkdir(parents=True, exist_ok=True)
    a.write.write_text(json.dumps(data))
    print("wrote", a.write, a.write.stat().st_size, "bytes", file=sys.stderr)


if __name__ == "__main__":
    main()
