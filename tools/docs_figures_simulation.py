"""Figures of docs/simulation.md, for ``regenerate_docs_figures.py`` (speeds are measured by ``benchmarks/``)."""

from __future__ import annotations

import functools
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from flexsim.sim.accuracy import (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE, RUN_OPTIONS,  # noqa: E402
                                  manoeuvre_errors)
from flexsim.sim.manoeuvres import manoeuvre_names  # noqa: E402

#: Errors below this are printed as the bound: the reference itself (DOP853 at rtol 1e-9) does not resolve them,
#: and their digits are round-off (a symmetric manoeuvre's bank).
ERROR_FLOOR = 1e-6


def _e(x: float) -> str:
    return f"{x:.1e}" if abs(x) >= ERROR_FLOOR else f"< {ERROR_FLOOR:.0e}".replace("e-0", "e-")


def _cell(e, rigid_parts: bool) -> str:
    tip = f"tip {_e(e.tip_m)} m ({_e(e.tip_relative)})"
    if e.altitude_m is None or not rigid_parts:
        return tip if e.altitude_m is None else f"{_e(e.altitude_m)} m / {tip}"
    return f"{_e(e.altitude_m)} m / {_e(e.airspeed_m_s)} m/s / {_e(e.bank_deg)} deg / {tip}"


def simulation_accuracy() -> str:
    """The table of the default, the previous default and Radau against DOP853 (rtol 1e-9) on every named manoeuvre."""
    choices = (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE)
    lines = ["", f"| manoeuvre | default, {DEFAULT_CHOICE.name}: altitude / airspeed / bank / tip | previous default, "
             f"{PREVIOUS_CHOICE.name}: altitude / tip | {RADAU_CHOICE.name}: altitude / airspeed / bank / tip |",
             "|---|---|---|---|"]
    for name in manoeuvre_names():
        default, previous, radau = manoeuvre_errors(name, choices)
        label = f"`{name}` ({RUN_OPTIONS.get(name, {}).get('t_end_s', default.duration_s):g} s)"
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


@functools.cache
def _flutter_onset(limit_m: float | None, t_end_s: float | None, method: str | None = None, rtol: float | None = None):
    from flexsim.sim.manoeuvres import build_manoeuvre

    setup = build_manoeuvre("flutter-onset")
    options = {} if t_end_s is None else {"t_end_s": t_end_s}
    if method is not None:
        options.update(method=method, rtol=rtol)
    return setup.simulate(structural_limit_m=limit_m, **options)


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


#: name -> (function, fast, study, rtol): the accuracy table's errors of adaptive runs within a factor of 2 (their
#: step sequences follow error estimates that round-off moves).
SIMULATION_FIGURES = {"simulation-accuracy": (simulation_accuracy, False, None, 0.5),
                      "simulation-goland-flutter": (simulation_goland_flutter, True),
                      "simulation-structural-limits": (simulation_structural_limits, True),
                      "simulation-eigenvalues": (simulation_eigenvalues, True),
                      "simulation-flutter-onset-stop": (simulation_flutter_onset_stop, True),
                      "simulation-flutter-onset-growth": (simulation_flutter_onset_growth, True)}
