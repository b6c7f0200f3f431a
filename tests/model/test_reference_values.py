"""With every term on, the model gives the values of the recorded reference (``data/reference_values.json``).

The recorded reference was produced by ``tests/model/reference_cases.py`` (its docstring gives the command) with the
model as it was before its physics was split into one module per term: state derivatives of twelve GTM models
(free, restrained, quasi-rigid; quasi-steady and unsteady aerodynamics; the paper's force resolution, the
bending-incidence coupling, no compressibility / drag / downwash / bodies, vacuum, no gravity, structural damping, a
fixed aerodynamic density, a wind tunnel) at three seeded near-trim states each, in still air, a 1-cos gust, Dryden
turbulence and batched; four trims (level, turn, climb, glide); US and QS flutter points in level flight.

Tolerances: the recorded values came from the same algebra in another order, which rounds differently by about
1e-15 of the largest entry; LAPACK's and OpenBLAS's kernels for another CPU core type (the trims' and searches' linear
solves and eigenvalues) add their own rounding. Largest differences measured across CPU targets
(``python tools/reference_spread.py``: OpenBLAS core types Haswell, Zen, Sandybridge, SkylakeX, Prescott and numba's
``NUMBA_CPU_NAME=generic``; 2026-12-04): state derivatives 1.6e-13 of the largest entry of the vector, trims 3.6e-13
of the largest entry of each block (position, attitude, q, xi, velocity; thrust, surfaces), flutter Mach number and
frequency 2.1e-9 relative (the searches' brentq iterates move with the last bits of the eigenvalues). Tolerances
about 5x those: 1e-12, 2e-12 and 1e-8.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from tests.model import reference_cases as cases

DATA = json.loads((Path(__file__).parent / "data" / "reference_values.json").read_text())
RHS_TOL = 1e-12
TRIM_TOL = 2e-12
FLUTTER_TOL = 1e-8


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def _rel(new, old) -> float:
    new, old = np.asarray(new, float), np.asarray(old, float)
    assert new.shape == old.shape
    return float(np.max(np.abs(new - old)) / np.max(np.abs(old)))


def test_rhs_equals_the_recorded_reference(gtm):
    new = cases.rhs_values(gtm, DATA["rhs_inputs"])
    worst = 0.0
    for name, by_wind in DATA["rhs"].items():
        for wind, rows in by_wind.items():
            for s, old in enumerate(rows):
                d = _rel(new[name][wind][s], old)
                worst = max(worst, d)
                assert d <= RHS_TOL, (name, wind, s, d)
    print(f"rhs: largest difference / max |x_dot| {worst:.2e}")


def test_trims_equal_the_recorded_reference(gtm):
    """Block by block (position, attitude, q, xi, velocity; thrust, surfaces), each against its own largest entry."""
    from flexsim.model.aircraft_model import AircraftModel

    lay = AircraftModel(gtm, aero="quasi-steady").layout
    blocks = {"x": (lay.position, lay.euler, lay.q, lay.xi, lay.velocity), "u": (slice(0, 1), slice(1, 4))}
    new = cases.trim_values(gtm)
    worst = 0.0
    for name, old in DATA["trims"].items():
        for key, parts in blocks.items():
            for part in parts:
                a, b = np.asarray(new[name][key])[part], np.asarray(old[key])[part]
                d = float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))
                worst = max(worst, d)
                assert d <= TRIM_TOL, (name, key, part, d)
    print(f"trims: largest difference / max |entry| {worst:.2e}")


def test_flutter_points_equal_the_recorded_reference(gtm):
    new = cases.flutter_values(gtm)
    worst = 0.0
    for name, old in DATA["flutter"].items():
        for key in ("mach", "frequency_rad_s"):
            d = abs(new[name][key] - old[key]) / abs(old[key])
            worst = max(worst, d)
            assert d <= FLUTTER_TOL, (name, key, new[name][key], old[key])
    print(f"flutter: largest relative difference {worst:.2e}")
