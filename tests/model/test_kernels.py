"""The compiled kernels of the right-hand side (flexsim._kernels): interpreted = compiled, batch = single,
in-kernel wind = the same wind called from Python, and closed forms of the small kernels.

* ``NUMBA_DISABLE_JIT=1`` runs the same kernel source as plain Python/numpy (numba's documented debugging
  switch); a subprocess evaluates rhs that way and must agree with the compiled kernel to round-off
  (1e-12 of the largest entry: the two differ only in the order of floating-point operations).
* Gust closed form (CS-25.341(a)): U(H) = U_ds, U(2H) = 0, U(H/2) = U_ds/2; Dryden interpolation returns the
  grid values at grid points and their mean half-way (linear interpolation, MIL-F-8785C field frozen on a grid).
* ``solve`` (Gaussian elimination with partial pivoting) against LAPACK on a well-conditioned system (1e-12).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from flexsim import _kernels as k
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.disturbances import DrydenTurbulence, OneMinusCosineGust, combine

ROOT = Path(__file__).resolve().parents[2]

_SCRIPT = r"""
import json, sys
import numpy as np
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.disturbances import OneMinusCosineGust
from flexsim import _kernels
assert not hasattr(_kernels.rhs, "py_func"), "NUMBA_DISABLE_JIT=1 should leave the kernels as Python functions"
gtm = load_aircraft("gtm").with_modes(1, 1)
out = {}
gust = OneMinusCosineGust(4.0, 20.0, front_position_ned_m=[-10.0, 0.0, 0.0])
for name, aero in (("unsteady", "unsteady"), ("vacuum", None)):
    model = AircraftModel(gtm, aero=aero)
    x = np.array(json.loads(sys.argv[1])[name])
    out[name] = model.rhs(0.1, x, np.array([3e4, 0.01, -0.02, 0.005]), gust).tolist()
print(json.dumps(out))
"""


def _state(model: AircraftModel, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    lay = model.layout
    x = 0.05 * rng.standard_normal(lay.n_states)
    x[lay.position] = [0.0, 0.0, -2000.0]
    x[lay.v] = [150.0, 1.0, 6.0]
    return x


def test_interpreted_kernels_equal_compiled():
    gtm = load_aircraft("gtm").with_modes(1, 1)
    gust = OneMinusCosineGust(4.0, 20.0, front_position_ned_m=[-10.0, 0.0, 0.0])
    u = np.array([3e4, 0.01, -0.02, 0.005])
    states, compiled = {}, {}
    for name, aero in (("unsteady", "unsteady"), ("vacuum", None)):
        model = AircraftModel(gtm, aero=aero)
        states[name] = _state(model, 3).tolist()
        compiled[name] = model.rhs(0.1, np.array(states[name]), u, gust)
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", PYTHONPATH=str(ROOT))
    run = subprocess.run([sys.executable, "-c", _SCRIPT, json.dumps(states)], env=env, capture_output=True, text=True,
                         timeout=600, cwd=ROOT)
    assert run.returncode == 0, run.stderr[-2000:]
    interpreted = json.loads(run.stdout.strip().splitlines()[-1])
    for name, dx in compiled.items():
        py = np.array(interpreted[name])
        assert np.max(np.abs(py - dx)) <= 1e-12 * np.max(np.abs(dx)), name


@pytest.fixture(scope="module")
def unsteady():
    return AircraftModel(load_aircraft("gtm"))


def test_batch_equals_single(unsteady):
    """rhs_batch (one compiled call for N aircraft, each with its own wind) equals rhs row by row, bit for bit."""
    xs = np.stack([_state(unsteady, s) for s in range(4)])
    us = np.tile([2e4, 0.0, -0.01, 0.0], (4, 1))
    winds = [DrydenTurbulence.mil_f_8785c(2000.0, "light", seed=1), None,
             OneMinusCosineGust(5.0, 25.0, front_position_ned_m=[-8.0, 0.0, 0.0]),
             combine(DrydenTurbulence.mil_f_8785c(2000.0, "light", seed=2), OneMinusCosineGust(3.0, 20.0))]
    batch = unsteady.rhs_batch(0.0, xs, us, unsteady.pack_winds(winds))
    np.testing.assert_array_equal(unsteady.rhs_batch(0.0, xs, us, winds), batch)
    for i in range(4):
        np.testing.assert_array_equal(batch[i], unsteady.rhs(0.0, xs[i], us[i], winds[i]))
    np.testing.assert_array_equal(unsteady.rhs_batch(0.0, xs, us)[1], unsteady.rhs(0.0, xs[1], us[1]))
    with pytest.raises(ValueError, match="winds\\[0\\]"):
        unsteady.pack_winds([lambda t, p: np.zeros_like(p)])


def test_wind_in_kernel_equals_python_callable(unsteady):
    """A field of flexsim.sim.disturbances is evaluated inside the kernel; the same field behind a plain
    Python callable goes through the callable path. Both must give the same derivative (round-off)."""
    wind = combine(OneMinusCosineGust(5.0, 25.0, front_position_ned_m=[-8.0, 0.0, 0.0], normal_ned=[1.0, 0.3, 0.0]),
                   DrydenTurbulence.mil_f_8785c(2000.0, "moderate", seed=2, heading_rad=0.2))
    assert wind.wind_data is not None
    x = _state(unsteady, 7)
    u = np.array([1e4, 0.0, 0.0, 0.0])
    inside = unsteady.rhs(0.3, x, u, wind)
    via_python = unsteady.rhs(0.3, x, u, lambda t, p: wind(t, p))
    still = unsteady.rhs(0.3, x, u)
    assert np.max(np.abs(inside - still)) > 1e-3 * np.max(np.abs(still))  # the wind matters here
    assert np.max(np.abs(inside - via_python)) <= 1e-13 * np.max(np.abs(inside))


def test_gust_and_dryden_closed_forms():
    u_ds, h = 7.0, 30.0
    s = np.array([-1.0, 0.0, h / 2, h, 2 * h, 2 * h + 1.0])
    np.testing.assert_allclose(k.gust_profiles(s, u_ds, h, False), [0.0, 0.0, u_ds / 2, u_ds, 0.0, 0.0], atol=1e-14)
    np.testing.assert_allclose(k.gust_profiles(s, u_ds, h, True), [0.0, 0.0, u_ds / 2, u_ds, u_ds, u_ds], atol=1e-14)
    grid = np.arange(12.0).reshape(3, 4)
    np.testing.assert_allclose(k.dryden_track(grid, 2.0, np.array([0.0, 2.0, 3.0, 8.0, -2.0])),
                               [[0, 4, 8], [1, 5, 9], [1.5, 5.5, 9.5], [0, 4, 8], [3, 7, 11]], atol=1e-14)


def test_solve_against_lapack():
    rng = np.random.default_rng(0)
    a = rng.standard_normal((30, 30)) + 10 * np.eye(30)
    b = rng.standard_normal(30)
    x = k.solve(a, b)
    np.testing.assert_allclose(x, np.linalg.solve(a, b), rtol=0, atol=1e-12 * np.max(np.abs(x)))
    with pytest.raises(ZeroDivisionError):
        k.solve(np.zeros((3, 3)), np.ones(3))


def test_replaced_part_is_refused():
    """The kernels use the arrays packed at construction: a part swapped in afterwards (a study's surgery through
    object.__setattr__ on the sealed model) would be ignored, so the model refuses to evaluate."""
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    x = _state(model, 1)
    model.rhs(0.0, x, np.zeros(4))
    object.__setattr__(model, "aero", AircraftModel(load_aircraft("gtm"), aero="quasi-steady").aero)
    with pytest.raises(RuntimeError, match="replaced after construction"):
        model.rhs(0.0, x, np.zeros(4))
