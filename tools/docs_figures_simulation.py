"""Figures of docs/simulation.md, for ``regenerate_docs_figures.py``.

Each function returns the text of one ``<!-- figures:NAME -->`` region; the registry and the command are in
``tools/regenerate_docs_figures.py``. Speeds are not regenerated here (they depend on the machine and its load):
``benchmarks/bench_simulate.py`` prints them, and the docs quote them with their date.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from flexsim.sim.accuracy import (DEFAULT_CHOICE, PREVIOUS_CHOICE, RADAU_CHOICE,  # noqa: E402
                                  manoeuvre_errors)
from flexsim.sim.manoeuvres import manoeuvre_names  # noqa: E402

_DURATION = {"level-turn-entry": "10 s, bank 28 deg", "climb": "10 s", "elevator-doublet": "6 s", "aileron-roll": "6 s",
             "gust-encounter": "5 s, U_ds 10 m/s", "flutter-onset": "3.1 s, growing"}


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
        label = f"`{name}` ({_DURATION.get(name, f'{default.duration_s:g} s')})"
        lines.append(f"| {label} | {_cell(default, True)} | {_cell(previous, False)} | {_cell(radau, True)} |")
    return "\n".join(lines) + "\n"


#: name -> (function, fast)
SIMULATION_FIGURES = {"simulation-accuracy": (simulation_accuracy, False)}
