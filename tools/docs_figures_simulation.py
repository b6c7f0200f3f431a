"""Figures of docs/simulation.md, for ``regenerate_docs_figures.py``.

Each function returns the text of one ``<!-- figures:NAME -->`` region; the registry and the command are in
``tools/regenerate_docs_figures.py``. Speeds are not regenerated here (they depend on the machine and its load):
``benchmarks/bench_simulate.py`` prints them, and the docs quote them with their date.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from flexsim.sim.accuracy import (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE,  # noqa: E402
                                  manoeuvre_errors)
from flexsim.sim.manoeuvres import manoeuvre_names  # noqa: E402

def _label(name: str, duration_s: float) -> str:
    """The manoeuvre column: name, the compared duration and what sets the run apart (the turn's bank read from the
    setup's description, the gust's U_ds an input of the manoeuvre, the compared window of the flutter onset)."""
    import re

    from flexsim.sim.accuracy import RUN_OPTIONS
    from flexsim.sim.manoeuvres import build_manoeuvre

    t = RUN_OPTIONS.get(name, {}).get("t_end_s", duration_s)
    extra = ""
    if name == "level-turn-entry":
        bank = re.search(r"bank (-?[\d.]+) deg", build_manoeuvre(name).description)
        if not bank:
            raise RuntimeError("simulation-accuracy: no bank angle in level-turn-entry's description")
        extra = f", bank {float(bank.group(1)):.0f} deg"
    elif name == "gust-encounter":
        extra = ", U_ds 10 m/s"
    elif name == "flutter-onset":
        extra = ", growing"
    return f"`{name}` ({t:g} s{extra})"


def _cell(e, rigid_parts: bool) -> str:
    tip = f"tip {e.tip_m:.1e} m ({e.tip_relative:.1e})"
    if e.altitude_m is None or not rigid_parts:
        return tip if e.altitude_m is None else f"{e.altitude_m:.1e} m / {tip}"
    return f"{e.altitude_m:.1e} m / {e.airspeed_m_s:.1e} m/s / {e.bank_deg:.1e} deg / {tip}"


def simulation_accuracy() -> str:
    """The table of the default, the previous default and Radau against DOP853 (rtol 1e-9) on every named manoeuvre."""
    choices = (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE)
    lines = ["", f"| manoeuvre | default, {DEFAULT_CHOICE.name}: altitude / airspeed / bank / tip | previous default, "
             f"{PREVIOUS_CHOICE.name}: altitude / tip | {RADAU_CHOICE.name}: altitude / airspeed / bank / tip |",
             "|---|---|---|---|"]
    for name in manoeuvre_names():
        default, previous, radau = manoeuvre_errors(name, choices)
        label = _label(name, default.duration_s)
        lines.append(f"| {label} | {_cell(default, True)} | {_cell(previous, False)} | {_cell(radau, True)} |")
    return "\n".join(lines) + "\n"


def simulation_goland_flutter() -> str:
    """The clamped Goland wing's flutter speed and frequency with this model (``wind_tunnel_flutter``, Peters N = 6
    inflow and quasi-steady) and the tunnel speed of ``flutter-onset`` (its setup's metadata)."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.linear.flutter import wind_tunnel_flutter
    from flexsim.sim.manoeuvres import build_manoeuvre

    goland = load_aircraft("goland_wing")
    v, w = wind_tunnel_flutter(goland, aero_model="unsteady")
    v_qs, _ = wind_tunnel_flutter(goland, aero_model="quasi-steady")
    meta = build_manoeuvre("flutter-onset").metadata
    tunnel, flutter = float(meta["tunnel_speed_m_s"]), float(meta["flutter_speed_m_s"])
    return (f"{v:.1f} m/s at {w:.1f} rad/s with Peters N = 6 inflow, {v_qs:.1f} m/s quasi-steady; `flutter-onset` "
            f"flies at {tunnel / flutter:.2f} x {flutter:.1f} = {tunnel:.1f} m/s for either aerodynamic model")


def simulation_structural_limits() -> str:
    """The default structural limit (``STRUCTURAL_LIMIT_FRACTION`` x the wing's length) on the two bundled
    aircraft with wings."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.sim.simulate import STRUCTURAL_LIMIT_FRACTION

    def limit(name: str) -> float:
        return STRUCTURAL_LIMIT_FRACTION * load_aircraft(name).component("right_wing").length_m

    return (f"{STRUCTURAL_LIMIT_FRACTION:g} x the wing's length: {limit('gtm'):.2f} m on the GTM, "
            f"{limit('goland_wing'):.2f} m on the Goland wing")


@functools.cache
def _gtm_trim_jacobian():
    """The Jacobian of the unsteady GTM (m = n = 2, N = 6) at the named manoeuvres' level trim (9144 m, M 0.75)."""
    from flexsim.model.jacobian import jacobian
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("elevator-doublet")
    return jacobian(setup.model, setup.initial.x, setup.initial.u)[0]


def simulation_eigenvalues() -> str:
    """The stiff end of the linearised unsteady GTM's spectrum at the level trim: the most negative real part and
    the largest |lambda|."""
    import numpy as np

    lam = np.linalg.eigvals(_gtm_trim_jacobian())
    big = lam[np.argmax(np.abs(lam))]
    return (f"{lam.size} states) has well-damped aero-lag eigenvalues down to {lam.real.min():.0f} s^-1 and |lambda| "
            f"up to {abs(big):.0f} s^-1 ({big.real:.0f} +- {abs(big.imag):.0f}j)")


def simulation_phi_scaling() -> str:
    """The scaling of ``flexsim.sim.fixed_step``'s matrix functions for the GTM at the default step: the balanced
    1-norm ||Z|| against alpha_4 = max(||Z^4||^(1/4), ||Z^5||^(1/5)) (Al-Mohy & Higham 2009), the doublings each
    needs, and the largest difference of the scaled result to the augmented ``expm`` (relative to its largest
    entry)."""
    import math

    import numpy as np
    from scipy.linalg import matrix_balance

    from flexsim.sim.fixed_step import phi_functions
    from flexsim.sim.simulate import DEFAULT_MAX_STEP

    jac = _gtm_trim_jacobian()
    h = DEFAULT_MAX_STEP["ETD2RK"]
    zb, _ = matrix_balance(h * jac, permute=False, separate=True)
    norm = lambda a: float(np.abs(a).sum(axis=0).max())  # noqa: E731
    z4 = np.linalg.matrix_power(zb, 4)
    alpha = max(norm(z4) ** 0.25, norm(z4 @ zb) ** 0.2)
    scaled = phi_functions(jac, h)
    reference = phi_functions(jac, h, method="augmented")
    diff = max(float(np.abs(a - b).max() / np.abs(b).max()) for a, b in zip(scaled, reference))
    return (f"{alpha:.0f} against ||Z|| = {norm(zb):.0f} for the GTM at {1e3 * h:g} ms: "
            f"{math.ceil(math.log2(alpha))} doublings instead of {math.ceil(math.log2(norm(zb)))}) with the Taylor "
            f"polynomial by Paterson-Stockmeyer (equal to the {3 * jac.shape[0]} x {3 * jac.shape[0]} augmented `expm` "
            f"to {diff:.0e}")


@functools.cache
def _flutter_onset(limit_m: float | None, t_end_s: float | None, method: str | None = None, rtol: float | None = None):
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("flutter-onset")
    options = {} if t_end_s is None else {"t_end_s": t_end_s}
    if method is not None:
        options.update(method=method, rtol=rtol)
    return setup.simulate(structural_limit_m=limit_m, **options)


def simulation_flutter_onset_events() -> str:
    """The structural-limit event of ``flutter-onset`` with DOP853 at rtol 1e-9, the default and Radau at rtol 1e-3
    (a grazing peak moves the event by half a period of the flutter frequency)."""
    import math

    from flexsim.sim.manoeuvres import build_manoeuvre

    runs = {"DOP853": _flutter_onset(None, None, "DOP853", 1e-9), "default": _flutter_onset(None, None),
            "Radau": _flutter_onset(None, None, "Radau", 1e-3)}
    for name, r in runs.items():
        if r.status != "structural_limit":
            raise RuntimeError(f"simulation-flutter-onset-events: {name} ended with {r.status}")
    t = {name: r.t[-1] for name, r in runs.items()}
    from flexsim.linear.flutter import wind_tunnel_flutter

    _, omega = wind_tunnel_flutter(build_manoeuvre("flutter-onset").model.aircraft, aero_model="unsteady")
    half = math.pi / omega
    shift = (t["Radau"] - t["DOP853"]) / half
    note = (f" — {'one half period' if abs(shift - 1) < 0.15 else f'{shift:.2f} half periods'} later —"
            if abs(shift) > 0.15 else "")
    return (f"{t['DOP853']:.4f} s with DOP853 at rtol 1e-9 and {t['default']:.4f} s with the default ETD2RK, "
            f"{t['Radau']:.4f} s{note} with Radau at rtol 1e-3")


def simulation_flutter_onset_stop() -> str:
    """When the default integrator's ``flutter-onset`` run stops (the structural-limit event)."""
    r = _flutter_onset(None, None)
    if r.status != "structural_limit":
        raise RuntimeError(f"simulation-flutter-onset-stop: the run ended with {r.status}")
    return f"{r.t[-1]:.1f} s with the default integrator"


def simulation_flutter_onset_growth() -> str:
    """The tip amplitude of the growing Goland oscillation over the accuracy comparison's window (no structural
    limit, ``flexsim.sim.accuracy.RUN_OPTIONS``)."""
    import numpy as np

    from flexsim.sim.accuracy import RUN_OPTIONS

    opts = RUN_OPTIONS["flutter-onset"]
    r = _flutter_onset(opts["structural_limit_m"], opts["t_end_s"])
    tip = np.abs(r.tip_deflection_m("right_wing"))
    return f"grows to {tip.max():.2f} m in {opts['t_end_s']:g} s"


def simulation_ground_contact() -> str:
    """The ground-contact case of ``tests/sim/test_simulate.py`` (quasi-steady GTM trimmed level at 9144 m, M 0.75,
    put 30 m above the ground sinking at 40 m/s, only the ground event): when the default, ETD2RK with 10 ms steps
    and Radau at rtol 1e-6 reach the ground."""
    from flexsim.aircraft.toml_loader import load_aircraft
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.sim.simulate import simulate
    from flexsim.trim import SteadyManoeuvre, trim

    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.75))
    x0 = point.x.copy()
    x0[model.layout.position.start + 2] = -30.0
    x0[model.layout.v.start + 2] += 40.0

    def t_ground(**options) -> float:
        r = simulate(model, x0, 5.0, controls=point.u, events=["ground"], **options)
        if r.status != "ground_contact":
            raise RuntimeError(f"simulation-ground-contact: {options or 'default'} ended with {r.status}")
        return r.t[-1]

    default, fine = t_ground(), t_ground(method="ETD2RK", max_step=0.01)
    radau = t_ground(method="Radau", rtol=1e-6)
    return (f"ETD2RK reaches the ground at {fine:.3f} s with 10 ms steps and at {default:.3f} s with the default (20 ms, "
            f"halved where the steps left the model's range), Radau at rtol 1e-6 at {radau:.3f} s")


#: name -> (function, fast)
SIMULATION_FIGURES = {"simulation-accuracy": (simulation_accuracy, False),
                      "simulation-goland-flutter": (simulation_goland_flutter, True),
                      "simulation-structural-limits": (simulation_structural_limits, True),
                      "simulation-eigenvalues": (simulation_eigenvalues, True),
                      "simulation-phi-scaling": (simulation_phi_scaling, True),
                      "simulation-flutter-onset-stop": (simulation_flutter_onset_stop, True),
                      "simulation-flutter-onset-growth": (simulation_flutter_onset_growth, True),
                      "simulation-ground-contact": (simulation_ground_contact, False),
                      "simulation-flutter-onset-events": (simulation_flutter_onset_events, False)}
